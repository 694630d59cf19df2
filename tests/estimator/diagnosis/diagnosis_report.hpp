#pragma once
// A diagnosis as text for test failure messages: summary, evidence findings,
// every ranked hypothesis (score, RMS, pairs) and the notes.
#include <string>

#include "estimator/diagnosis/diagnosis.hpp"

namespace ssid::test_support {

inline std::string ranking(const estimator::diagnosis::Diagnosis& d) {
  std::string s = d.summary + "\n";
  for (const auto& f : d.evidence.findings) s += "  evidence: " + f + "\n";
  for (const auto& h : d.ranking)
    s += "  " + h.kind + " @ " + h.location.text + ": score " + std::to_string(h.score) + ", rms " +
         std::to_string(h.after.freq_rms_pct) + " %, paired " + std::to_string(h.after.paired) + "\n";
  for (const auto& n : d.notes) s += "  note: " + n + "\n";
  return s;
}

}  // namespace ssid::test_support
