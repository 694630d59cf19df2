#pragma once
/// \file progress_lines.hpp
/// What a long command prints while it runs, and how Ctrl-C stops it.
///
/// The library reports through estimator::Progress; ProgressLines turns the
/// reports into lines on stderr, with counts and the time left estimated from
/// the phase's own pace:
///   ssid diagnose: screening candidates 120/480, 35 s elapsed, ~1 min 45 s left
/// (nothing with --quiet). Ctrl-C (SIGINT) sets a flag (InterruptFlag); the next
/// report throws estimator::Interrupted, the library returns what it has marked
/// partial, and the command writes it and exits 130 (kExitInterrupted).
#include <chrono>
#include <string>

#include "estimator/reporting/progress.hpp"

namespace ssid::cli {

/// While alive, SIGINT sets a flag instead of ending the process; the handler
/// is one-shot, so a second Ctrl-C ends the process at once (a run that does
/// not reach a report soon enough can still be stopped).
class InterruptFlag {
 public:
  InterruptFlag();
  ~InterruptFlag();
  InterruptFlag(const InterruptFlag&) = delete;
  InterruptFlag& operator=(const InterruptFlag&) = delete;
  /// Ctrl-C was pressed since construction.
  static bool raised();
};

/// "12 s", "1 min 45 s", "2 h 5 min".
std::string duration_text(double seconds);

class ProgressLines {
 public:
  /// `prefix` starts each line ("ssid diagnose"). Counted reports of one phase
  /// are printed at most every `min_interval_s` seconds (0: all), the last of
  /// the phase always; other reports always; ticks never. Nothing is printed in
  /// the first `silent_s` seconds (a quick run stays quiet; a long one speaks
  /// from then on).
  ProgressLines(std::string prefix, bool quiet, double min_interval_s, double silent_s = 0.0);
  /// The library's callback: prints, and throws estimator::Interrupted
  /// ("interrupted (Ctrl-C)") once Ctrl-C was pressed. Refers to this object.
  estimator::Progress callback();
  /// The line for `e` at `elapsed_s` seconds into its phase (what callback() prints).
  std::string line(const estimator::ProgressEvent& e, double elapsed_s) const;

 private:
  using Clock = std::chrono::steady_clock;
  void on_event(const estimator::ProgressEvent& e);
  std::string m_prefix;
  bool m_quiet = false;
  double m_min_interval = 0, m_silent = 0;
  Clock::time_point m_start = Clock::now();
  std::string m_phase;             ///< the phase of the last report
  Clock::time_point m_phase_start;
  std::string m_printed_phase;     ///< the phase of the last line printed
  Clock::time_point m_printed_at;
  std::string m_last_line;
};

}  // namespace ssid::cli
