#pragma once
/// \file deck_study.hpp
/// Model updating end to end (the SSID analogue of the seed report): a deck
/// whose DESVARs are the parameters, measured real normal modes from a
/// universal file (dataset 55, nodes from 15/2411), and an optional study file
/// overriding the defaults. Three phases, one function each:
///
///   read_study / parse_study   the study file (JSON, docs/estimation.md);
///   prepare_problem            decks assembled, test nodes mapped to grids,
///                              test modes selected, priors and weights set —
///                              or, from a problem file (formats/problem_file),
///                              imported operators with their Taylor model;
///   run_problem                the iterative Bayesian update of
///                              estimator/updating/updating.hpp (Eqs. (7)–(8)) with mode
///                              tracking, then the correlation at the answer;
///   result_json                the result as `ssid estimate --json` writes it.
///
/// Defaults (every one can be overridden by the study):
///  - prior mean: DESVAR XINIT; prior σ: half the distance from XINIT to the
///    nearer DESVAR bound (the bounds then lie at 2σ or more), or 30 % of |XINIT|
///    when both bounds are open (|bound| ≥ 1e20), or 1 when XINIT is 0;
///  - frequency σ: 1 % of the measured frequency; shape σ (each component of
///    the unit-normalised test shape): 0.05/√n_s with n_s sensor DOFs;
///  - pairing: MAC ≥ 0.6 within ±50 % in frequency; tracking MAC ≥ 0.5;
///  - analysis modes: 2 n_test + 6 (at most the number of analysis DOFs − 1);
///  - at most 20 cycles, stop when no parameter moves by 1e-4 prior σ.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <cstdint>
#include <limits>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "estimator/updating/modal_model.hpp"
#include "estimator/reporting/progress.hpp"
#include "estimator/updating/updating.hpp"
#include "formats/problem_file.hpp"
#include "translators/assembly/parameter_units.hpp"
#include "translators/measurement/sensor_mapping.hpp"

namespace ssid::estimator {

/// A prior given in the study for one parameter (by DESVAR label).
struct PriorSetting {
  std::optional<double> mean;     ///< default: DESVAR XINIT
  std::optional<double> std;      ///< absolute standard deviation
  std::optional<double> std_pct;  ///< standard deviation in % of |mean|
};

/// One tested configuration: a deck and its measured modes (paths relative to
/// the study file's folder; empty: the command line's DECK / MEASURED).
struct StudyConfiguration {
  std::string name;
  std::string deck;
  std::string measured;
  std::optional<int> analysis_modes;
};

/// Which test modes enter the update.
struct ModeSelection {
  std::vector<int> modes;           ///< test mode numbers to use; empty: all
  std::vector<int> exclude;         ///< test mode numbers to leave out
  double min_hz = 0;                ///< modes below are left out (e.g. suspension modes)
  double max_hz = std::numeric_limits<double>::infinity();
  std::vector<int> frequency_only;  ///< use only the frequency of these modes
  std::vector<int> shape_only;      ///< use only the shape of these modes
};

enum class OperatorUpdate {
  Exact,  ///< re-assemble the deck at each cycle's parameters
  Taylor  ///< first-order Taylor model of K and M about the prior mean
};

struct Study {
  std::string source = "<defaults>";  ///< study file path (messages, relative paths)
  std::string title;
  std::vector<std::string> parameters;  ///< DESVAR labels to estimate; empty: every DESVAR
  std::map<std::string, PriorSetting> priors;
  double frequency_std_pct = 1.0;
  std::optional<double> shape_std;  ///< default 0.05/√n_s
  bool use_shapes = true;
  double mac_min = 0.6;
  double frequency_window_pct = 50.0;
  double track_mac_min = 0.5;
  translators::MapBy map_by = translators::MapBy::Id;
  double map_tolerance = 0;
  ModeSelection modes;
  std::vector<StudyConfiguration> configurations;  ///< empty: one, from the command line
  int max_iterations = 20;
  double tolerance = 1e-4;
  bool recursive = false;  ///< configurations one after the other, posterior → prior
  ShapeDerivative shape_derivative = ShapeDerivative::Nelson;
  OperatorUpdate operators = OperatorUpdate::Exact;
  std::optional<int> analysis_modes;
  /// Krylov iteration of the eigen-solver ("auto", "spectra", "block-lanczos";
  /// eigen_solver.hpp): the eigen-solve dominates a cycle on large models.
  std::string eigen_method = "auto";
  double uninformed_ratio = 0.9;     ///< posterior σ / prior σ above this: not informed by the data
  double strong_correlation = 0.9;   ///< |posterior correlation| above this: reported as a pair
};

/// Parses a study from JSON; unknown keys and wrong types are errors naming
/// `source` and the key path ("study.json: priors.STRUTA.std: expected a
/// positive number, got \"x\""). Throws std::invalid_argument.
Study parse_study(const nlohmann::json& j, const std::string& source);
/// Reads and parses a study file; JSON syntax errors name the file and byte offset.
Study read_study(const std::string& path);

/// One configuration ready to estimate.
struct PreparedConfiguration {
  std::string name, deck, measured;
  std::vector<int> test_numbers;                 ///< UFF mode number of each measured mode
  std::vector<MeasuredMode> test;
  std::vector<std::string> sensor_labels;        ///< "grid:direction" per sensor row
  std::vector<std::pair<std::int64_t, int>> dofs;  ///< analysis (a-set) DOFs
  Eigen::SparseMatrix<double> sensors;           ///< n_s × n_a
  int analysis_modes = 0;
  std::shared_ptr<ModalModel> model;
  /// K, M, ∂K, ∂M at given parameters (exact re-assembly, or the imported
  /// operators' Taylor model): what the model solves, and what a problem file stores.
  OperatorModel::Assemble assemble;
  std::vector<std::string> notes;                ///< unmapped nodes, dropped DOFs, left-out modes
};

struct EstimationProblem {
  std::string title;
  ParameterPrior prior;
  std::vector<std::int64_t> desvar_ids;
  /// Per parameter: what it designs and its unit (translators/assembly/parameter_units.hpp);
  /// empty for a problem file, which carries no deck.
  std::vector<translators::ParameterUnit> units;
  /// Where the units come from: the deck's "$ units:" comment, or why they are "deck units".
  std::string units_note;
  UpdateOptions options;
  bool recursive = false;
  double uninformed_ratio = 0.9, strong_correlation = 0.9;
  std::string operators = "exact";  ///< "exact" | "taylor"
  std::vector<PreparedConfiguration> configurations;
  std::vector<std::string> notes;
};

/// Builds the problem from decks and measured universal files. `deck` and
/// `measured` are the command line's (used by configurations that name none).
/// Throws std::invalid_argument / ParseError / ModelError with the file named.
EstimationProblem prepare_problem(const Study& study, const std::string& deck, const std::string& measured);

/// The problem as a problem file (operators at the prior mean).
formats::ProblemFile to_problem_file(const EstimationProblem& problem);
/// A problem from a problem file: imported operators with their first-order
/// Taylor model (options.operators "taylor", what `ssid translate` writes), or,
/// for "exact", the deck each configuration names re-assembled every cycle (it
/// must still have the file's DESVAR ids and analysis DOFs).
EstimationProblem problem_from_file(const formats::ProblemFile& file);

/// A strongly correlated pair of parameters in the posterior.
struct CorrelatedPair {
  int a = 0, b = 0;
  double rho = 0;
};

struct EstimationResult {
  UpdateResult update;                ///< the final (joint, or last recursive) estimate
  std::vector<UpdateResult> stages;   ///< recursive mode: one per configuration
  Eigen::VectorXd initial;            ///< prior mean of the first stage
  Eigen::VectorXd prior_std;          ///< of the first stage
  std::vector<int> uninformed;        ///< parameters with posterior σ / prior σ > uninformed_ratio
  std::vector<CorrelatedPair> correlated;
  /// Per configuration at the answer: MAC (test × analysis), analysis frequencies (Hz).
  std::vector<Eigen::MatrixXd> mac;
  std::vector<Eigen::VectorXd> fe_hz;
  /// Empty when the result is complete (every stage converged); otherwise why it
  /// is partial: not converged within the iteration limit, stopped by a
  /// numerical failure, or interrupted (then `interrupted`; recursive stages not
  /// reached are missing from `stages`). A partial result is the last accepted
  /// cycle's: usable to look at, not to trust.
  std::string partial_reason;
  bool interrupted = false;
  bool partial() const { return !partial_reason.empty(); }
};

/// Runs the estimation (joint, or recursive), reporting each cycle (and each
/// recursive stage) through `progress`. When `progress` throws Interrupted the
/// result so far comes back marked partial (EstimationResult::partial_reason);
/// before the first cycle was accepted, Interrupted passes to the caller.
EstimationResult run_problem(EstimationProblem& problem, const Progress& progress = {});

/// The result as JSON: {"converged", "partial" (and "partial_reason" when
/// true), "iterations", "parameters", "correlation", "pairs", "unpaired_test",
/// "unpaired_fe", "identifiability", "notes", ...}.
nlohmann::json result_json(const EstimationProblem& problem, const EstimationResult& result);

/// A readable summary (parameters, pairs, identifiability, notes).
std::string format_summary(const EstimationProblem& problem, const EstimationResult& result);

}  // namespace ssid::estimator
