#include "estimator/reporting/progress.hpp"

namespace ssid::estimator {

std::string ProgressEvent::text() const {
  std::string s = phase;
  if (counted()) s += " " + std::to_string(done) + "/" + std::to_string(total);
  else if (has_count()) s += " " + std::to_string(done);
  if (!detail.empty()) s += (s.empty() ? "" : ": ") + detail;
  return s;
}

void report(const Progress& p, const std::string& phase, double fraction) {
  if (!p) return;
  ProgressEvent e;
  e.phase = phase;
  e.fraction = fraction;
  p(e);
}

void report(const Progress& p, const std::string& phase, long done, long total, const std::string& detail,
            double fraction) {
  if (!p) return;
  ProgressEvent e;
  e.phase = phase;
  e.done = done;
  e.total = total;
  e.detail = detail;
  e.fraction = fraction;
  p(e);
}

}  // namespace ssid::estimator
