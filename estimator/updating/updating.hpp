#pragma once
/// \file updating.hpp
/// Iterative Bayesian model updating (the SSID analogue; STARS-ID paper
/// Eqs. (4)–(8)). Each cycle:
///  1. solve the model at r_i;
///  2. pair test and analysis modes: in the first cycle by MAC on the sensor
///     DOFs (and frequency), afterwards by tracking each partner from the
///     previous cycle (MAC on the tracking shapes), re-checked against the test
///     by MAC — a mode that loses its partner leaves the update and is reported;
///  3. measurements z and predictions u(r_i): frequencies f = √λ / 2π [Hz] and
///     unit-normalised shapes at the sensors (the test shape's arbitrary scale
///     and sign are removed: u = φ_s/‖φ_s‖, z = ±ψ/‖ψ‖ with the sign of ψᵀu);
///  4. sensitivities T = ∂u/∂r: ∂f = ∂λ / (8π² f),
///     ∂u_shape = (I − u uᵀ) ∂φ_s / ‖φ_s‖;
///  5. the step of Eq. (7) in parameters scaled by their prior standard
///     deviations (so E ≈ 7e10 and an area ≈ 1e-4 are equally well conditioned),
///     bounds honoured, posterior covariance of Eq. (8);
///  6. a safeguard where the linearisation overshoots: when J at the new point
///     exceeds J at the last accepted one (same test modes paired), or the new
///     point loses pairs, the step from the accepted point is recomputed with
///     Levenberg–Marquardt damping, (H + μ diag H) Δ = g, μ = 0.1, 1, 10, …
///     (at most 12 times); each point accepted at once divides μ by 10 (0
///     below 0.1), so near the answer the step is Eq. (7) again; a point
///     accepted after rejected trials keeps μ (lowering it at once had the
///     next trial rejected again). After two rejected trials, a third that
///     raises J by less than 1e-6 of it ends the iteration at the accepted
///     point, converged (approximate sensitivities point near, not at, J's
///     minimum; the iteration would otherwise trade rejected trials for
///     gains of 1e-7 of J until the cycle limit).
/// Stops when no parameter moves by more than `tolerance` prior standard
/// deviations. The result carries the posterior, the Laplace evidence, the
/// identifiability analysis and the history of every cycle.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "estimator/updating/bayes.hpp"
#include "estimator/correlation/measures.hpp"
#include "estimator/updating/modal_model.hpp"
#include "estimator/reporting/progress.hpp"

namespace ssid::estimator {

/// One measured mode. Either measurement may be left out (use_* false, or an
/// empty shape).
struct MeasuredMode {
  int id = 0;                    ///< test mode number, as the test reports it
  double frequency_hz = 0;
  double frequency_std_hz = 0;   ///< σ of the frequency measurement [Hz]
  Eigen::VectorXd shape;         ///< n_s components at the sensor DOFs (any scale)
  double shape_std = 0;          ///< σ of each component of the unit-normalised shape
  bool use_frequency = true;
  bool use_shape = true;
  /// The analyst's pair: the analysis mode (0-based, in ascending order of the
  /// model where the estimate starts) this test mode is paired with, whatever
  /// MAC says; −1: paired by MAC (or by frequency when it has no shape). The
  /// partner is then followed from cycle to cycle like any other, and kept even
  /// where its MAC with the test shape falls below `mac_min` (the seed's MPI
  /// reconciliation paired by hand where MAC failed: mid-strut nodes unmeasured).
  int fixed_partner = -1;
};

struct ParameterPrior {
  std::vector<std::string> names;
  Eigen::VectorXd mean;   ///< r₀
  Eigen::MatrixXd cov;    ///< S_rr
  Eigen::VectorXd lower;  ///< bounds (±inf allowed)
  Eigen::VectorXd upper;
};

struct UpdateOptions {
  int max_iterations = 20;
  double tolerance = 1e-4;       ///< convergence: max |Δr_j| / σ_j
  double mac_min = 0.6;          ///< a pair needs at least this MAC (sensor DOFs)
  double freq_tol_pct = 50.0;    ///< and a frequency error below this
  double track_mac_min = 0.5;    ///< cycle-to-cycle tracking MAC
  bool shape_derivatives = true; ///< use shapes in the update (needs ∂φ)
  /// Where the iteration starts (and the first pairing is made); empty: the
  /// prior mean. The prior itself is unchanged, so the estimate and evidence
  /// stay those of the same posterior — a start only helps reach it (e.g. a
  /// new mode placed near the test mode it should explain).
  Eigen::VectorXd start;
};

/// One test–analysis pair.
struct UpdatePair {
  int config = 0;         ///< configuration index
  int test = -1;          ///< index into the measured modes
  int fem = -1;           ///< analysis mode index (0-based)
  double mac = 0;
  double test_hz = 0, fem_hz = 0;
  double error_pct = 0;   ///< (f_fem − f_test) / f_test × 100
};

struct UpdateCycle {
  int cycle = 0;
  Eigen::VectorXd r;
  std::vector<UpdatePair> pairs;
  double objective = 0;    ///< J(r_i)
  double misfit = 0;       ///< data part of J
  double freq_rms_pct = 0; ///< RMS frequency error of the pairs
  double mean_mac = 0;
  bool clipped = false;
  int step_halvings = 0;   ///< trials rejected before this point (J had grown or pairs were lost), each retried with more damping
};

/// A test mode that left the update because its partner was lost.
struct DroppedMode {
  int config = 0;
  int test = -1;   ///< index into the configuration's measured modes
  int cycle = 0;
  std::string why;
};

struct UpdateResult {
  Eigen::VectorXd r;              ///< posterior mean
  Eigen::MatrixXd posterior_cov;  ///< Eq. (8)
  Eigen::VectorXd posterior_std;
  double log_evidence = 0;        ///< Laplace approximation at r
  Identifiability identifiability;
  bool converged = false;
  /// Empty when the iteration ran to its end (converged, or `max_iterations`
  /// reached); otherwise why it stopped early: interrupted through the progress
  /// callback (Interrupted), or a numerical failure after cycle 0. The result is
  /// then the last accepted cycle's (its r, posterior and pairs).
  std::string stopped;
  bool interrupted = false;          ///< stopped by Interrupted (`stopped` holds its message)
  std::vector<UpdateCycle> history;  ///< cycle 0 is the initial model; the last one the final model
  std::vector<std::string> notes;    ///< modes that lost their partner, bounds hit, …
  int measurements = 0;              ///< length of z in the final cycle
  std::vector<DroppedMode> dropped;  ///< test modes that lost their partner (also in notes)
  std::vector<ModalSolution> final_solutions;  ///< per configuration, at r
};

/// Pairs measured modes with analysis modes: first the analyst's pairs
/// (MeasuredMode::fixed_partner), then by MAC and frequency, greedily by
/// decreasing MAC, one partner each; modes without a shape pair by nearest
/// frequency among the remaining ones. A fixed partner beyond the solved modes
/// throws formats::InputError.
std::vector<UpdatePair> pair_for_update(const std::vector<MeasuredMode>& test, const ModalSolution& fem,
                                 const UpdateOptions& options);

/// One tested configuration (bare, with added mass, …): its model and its
/// measured modes. All configurations share the parameter vector.
struct Configuration {
  std::string name;
  ModalModel* model = nullptr;
  std::vector<MeasuredMode> test;
};

/// Estimates the parameters from all configurations together. Reports each
/// cycle through `progress` (phase "cycle", counted against the iteration limit,
/// the detail giving J, the frequency error and the pairs). When `progress`
/// throws Interrupted, or a cycle after the first fails with a NumericalError,
/// the result of the last accepted cycle comes back with `stopped` set; before
/// any cycle was accepted the exception passes.
UpdateResult update(const std::vector<Configuration>& configurations, const ParameterPrior& prior,
                    const UpdateOptions& options = {}, const Progress& progress = {});

/// One configuration.
UpdateResult update(ModalModel& model, const std::vector<MeasuredMode>& test, const ParameterPrior& prior,
                    const UpdateOptions& options = {}, const Progress& progress = {});

/// Recursive estimation: the posterior of one test is the prior of the next
/// (same names and bounds; mean and covariance from the result).
ParameterPrior posterior_as_prior(const UpdateResult& result, const ParameterPrior& prior);

}  // namespace ssid::estimator
