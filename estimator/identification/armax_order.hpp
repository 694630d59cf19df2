#pragma once
/// \file armax_order.hpp
/// The ARMAX paper's model-order rule (seed report, Appendix A, "ARMAX
/// Identification of Vibrating Structures", section "Model Order Estimation";
/// docs/armax.md): identify with all p response records at an order s larger than
/// needed, then again with subsets of p/d records at order d·s (the same number
/// p·s of poles); the frequencies, dampings and shapes common to every
/// identification are the structure's, the others belong to the measurement noise.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "estimator/identification/armax.hpp"

namespace ssid::estimator::identification {

/// One identification of the rule: which response records, at which orders.
struct ArmaxRun {
  std::vector<int> outputs;  ///< 0-based columns of the response records used
  ArmaxOptions options;      ///< orders s and m for this subset
};

/// The paper's runs: all p records at `all_outputs` (s, m), then each record alone
/// at (p·s, p·m) (paper: s = 6, m = 45 for p = 2 and s = 12, m = 90 for p = 1).
std::vector<ArmaxRun> single_output_runs(int outputs, const ArmaxOptions& all_outputs);

/// Matching of poles across runs.
struct RecurrenceOptions {
  /// Two poles are the same mode when their frequencies differ by at most this
  /// fraction (the paper's structural frequencies agree to 0.02 %; its close noise
  /// pair 3011.31/3016.43 Hz differs by 0.17 % and is told apart by damping).
  double hz_tolerance = 1e-3;
  /// … and their damping ratios by at most this fraction of the larger one (the
  /// paper's pair above: 1.2e-3 against 1.8e-2).
  double zeta_tolerance = 0.25;
  /// Poles within this fraction of the Nyquist frequency (|arg z| ≥ (1 − margin)·π)
  /// are rejected: a mode there cannot be told from its alias, and the noise puts
  /// near-real negative roots there in every run.
  double nyquist_margin = 0.02;
};

/// A mode found in every run.
struct RecurringMode {
  double hz_mean = 0, hz_std = 0;      ///< Hz, over the runs (sample standard deviation)
  double zeta_mean = 0, zeta_std = 0;  ///< damping ratio, over the runs
  /// Shape at the reference run's outputs (the first run), largest component 1.
  Eigen::VectorXcd shape;
  std::vector<int> outputs;            ///< the reference run's outputs, rows of `shape`
  std::vector<std::size_t> pole;       ///< index of the mode's pole in each run's model
};

/// A pole the rule rejects, with the reason.
struct RejectedPole {
  std::size_t run = 0;    ///< index of the run
  ArmaxPole pole;
  std::string reason;     ///< e.g. "real root", "not found in run 2 (outputs 2)"
};

/// The runs, the structure's modes (ascending frequency) and the noise poles.
struct ArmaxOrderResult {
  std::vector<ArmaxRun> runs;
  std::vector<ArmaxModel> models;   ///< one per run
  std::vector<RecurringMode> modes; ///< the model order is modes.size()
  std::vector<RejectedPole> rejected;
};

/// Clusters the poles of several identifications: a pole of the first model is a
/// structural mode when every other model has a pole within the tolerances; each
/// model's pole is used at most once, closest pairs first (distance
/// |Δf|/(f·tol_f) + |Δζ|/(ζ_max·tol_ζ)). Every pole not in a mode is listed as rejected.
/// `outputs` names the first model's outputs (copied into each mode).
std::vector<RecurringMode> recurring_modes(const std::vector<ArmaxModel>& models,
                                           const std::vector<std::vector<int>>& outputs,
                                           const RecurrenceOptions& options,
                                           std::vector<RejectedPole>& rejected);

/// Runs identify_armax once per run on the chosen columns of `outputs` (r × p
/// responses; `inputs` r × q forces, dt in s), then recurring_modes.
/// Throws formats::InputError when there are fewer than two runs or a run names a
/// column that does not exist.
ArmaxOrderResult armax_model_order(const Eigen::Ref<const Eigen::MatrixXd>& outputs,
                                   const Eigen::Ref<const Eigen::MatrixXd>& inputs, double dt,
                                   const std::vector<ArmaxRun>& runs, const RecurrenceOptions& options);

}  // namespace ssid::estimator::identification
