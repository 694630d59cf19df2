#pragma once
/// \file progress.hpp
/// The library never prints: long computations report through this callback,
/// which the CLI turns into progress lines (with the time left) and uses to stop
/// a run on Ctrl-C.
///
/// A report names the phase and, where the phase is a count of like items
/// (cycles, candidates, solves), how many are done of how many: the caller can
/// then estimate the time left from the phase's own pace. The callback may throw
/// Interrupted to stop the computation; functions that can return what they have
/// so far (an update's last accepted cycle, a diagnosis's hypotheses tested so
/// far) catch it, mark their result as stopped early and return it; the others
/// let it pass.
#include <functional>
#include <stdexcept>
#include <string>

namespace ssid::estimator {

/// One progress report.
struct ProgressEvent {
  std::string phase;       ///< what is being done, e.g. "screening candidates"
  long done = -1;          ///< items of the phase done (−1: the phase is not counted)
  long total = -1;         ///< items of the phase in all (≤ 0 with done ≥ 0: a count without a known end)
  bool total_is_bound = false;  ///< `total` is an upper bound (an iteration limit), not the count
  std::string detail;      ///< the item at hand or its outcome, e.g. "missing_mass at GRID 12"
  double fraction = -1.0;  ///< of the whole computation, in [0, 1]; < 0 when unknown
  /// A heartbeat (a solve starting): nothing new to show, but a chance for the
  /// caller to stop the run (throw Interrupted) between reports far apart.
  bool tick = false;

  /// Items done of a known total (the time left can be estimated).
  bool counted() const { return done >= 0 && total > 0; }
  /// Items done, with or without a known total.
  bool has_count() const { return done >= 0; }
  /// "phase", "phase 3/20", "phase 3", "phase 3/20: detail" or "phase: detail".
  std::string text() const;
};

/// The reporting callback; empty: no reports.
using Progress = std::function<void(const ProgressEvent& event)>;

/// Thrown by a Progress callback to stop the computation (the CLI does on
/// SIGINT). `what()` says why ("interrupted (Ctrl-C)").
class Interrupted : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Calls `p` when set, with a phase that is not counted.
void report(const Progress& p, const std::string& phase, double fraction = -1.0);

/// Calls `p` when set: item `done` of `total` of `phase` (done = 0 at the start;
/// total ≤ 0 when not known).
void report(const Progress& p, const std::string& phase, long done, long total, const std::string& detail = {},
            double fraction = -1.0);

}  // namespace ssid::estimator
