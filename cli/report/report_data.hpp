#pragma once
/// \file report_data.hpp
/// What a `--report` shows that a command's JSON did not hold yet, added to
/// that JSON (the report is a view of the JSON, never a second source of
/// numbers; docs/report.md): the run (command, inputs with SHA-256, version,
/// date), the deck's geometry as lines, and mode shapes at the grids.
#include <Eigen/Core>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli/commands.hpp"
#include "cli/report/projection.hpp"
#include "translators/assembly/fe_model.hpp"
#include "translators/measurement/sensor_mapping.hpp"

namespace ssid::cli::report {

/// {"command": "ssid NAME ARGS...", "inputs": [{"path", "sha256", "bytes"}],
/// "version", "date"}: the date in UTC (ISO 8601), or SOURCE_DATE_EPOCH's when
/// that is set (reproducible reports).
nlohmann::json run_json(const std::string& subcommand, const Args& args, const std::vector<std::string>& inputs);

/// A pretest sensor record ({"grid", "component", "label", ...}, cmd_pretest):
/// how it is named ("T2", or a given direction's cosines) and its component as
/// text ("" for a sensor along a given direction, whose "component" is null).
std::string sensor_label(const nlohmann::json& sensor);
std::string sensor_component(const nlohmann::json& sensor);

/// The test's wire frame on `test_grids`: each test grid joined to the (at most
/// three) nearest test grids (straight distance) that a path along `lines`
/// through non-test grids reaches, each line (smaller id, larger id) once, sorted.
/// A path never passes another test grid, so a line stands for a stretch of the
/// structure between two sensors; test grids without a position in `grids` are skipped.
Lines test_wire_frame(const Lines& lines, const Points& grids, const std::vector<std::int64_t>& test_grids);

/// The deck drawn as lines: {"grids": [[id, x, y, z]] (basic), "lines": [[g1, g2]]
/// (CROD, CONROD, CBAR, CBEAM, CBUSH, CELAS1/2 between two grids, RBAR, RBE2 legs),
/// "test_lines": [[n1, n2]]}: the test's wire frame (test_wire_frame; the deck's
/// geometry seen by the sensors; a test file's own trace lines, dataset 82, are not read yet).
nlohmann::json geometry_json(const translators::FeModel& model, const std::vector<translators::GridPosition>& grids,
                             const std::vector<std::int64_t>& test_grids);

/// The a-set modes (columns of `a_modes`) at every grid of `grids`, in basic
/// X, Y, Z (expanded through the model's reduction, rotated out of each grid's
/// displacement frame): per mode [[id, dx, dy, dz], ...].
std::vector<nlohmann::json> grid_shapes_json(const translators::FeModel& model,
                                             const std::vector<translators::GridPosition>& grids,
                                             const Eigen::MatrixXd& a_modes);

/// A shape at measured DOFs (node, direction ±1..3 in basic; rotations are
/// skipped) times `scale`, as [[node, dx, dy, dz], ...] in first-seen order.
nlohmann::json dof_shape_json(const std::vector<translators::MeasuredDof>& dofs, const Eigen::VectorXd& values,
                              double scale);

/// The least-squares factor taking `test` onto `fe` (fe·test / test·test; 0 for a zero test shape).
double scale_onto(const Eigen::VectorXd& fe, const Eigen::VectorXd& test);

/// Test–analysis cross-orthogonality X = φ_aᵀ M_r φ_e (measures.hpp's cross_orthogonality,
/// each mode at unit generalised mass under M_r), with the analysis mass reduced to the test
/// DOFs by SEREP from the analysis modes themselves: for mass-orthogonal modes Φᵀ M Φ =
/// diag(m), SEREP's M_r = Tᵀ M T with T = Φ Φ_a⁺ is Φ_a⁺ᵀ diag(m) Φ_a⁺, so the shapes at
/// the test DOFs (`fe`, columns numbered `fe_numbers`) and their generalised masses
/// `modal_mass` suffice. The basis is every analysis mode when they are independent at the
/// test DOFs, else the analysis modes of `pairs` ((analysis, test) numbers). Returns
/// {"reduction", "basis", "fe_modes", "test_modes", "matrix" (|X|: a test shape's sign is
/// arbitrary), "min_diagonal" 0.9, "max_off_diagonal" 0.1, "pairs": [{"fe_mode",
/// "test_mode", "xor", "largest_off_diagonal" (in the pair's row and column), "accepted"}]},
/// or {"unavailable": why}.
nlohmann::json cross_orthogonality_json(const Eigen::MatrixXd& fe, const std::vector<double>& modal_mass,
                                        const std::vector<int>& fe_numbers, const Eigen::MatrixXd& test,
                                        const std::vector<int>& test_numbers,
                                        const std::vector<std::pair<int, int>>& pairs);

/// The same object for a test-analysis model's reduced mass `Mr` on the test DOFs (in
/// the rows' order of `fe` and `test`): every analysis mode of `fe` (its shapes at the
/// test DOFs) against every test mode, "reduction" saying which TAM, "basis" every
/// analysis mode.
nlohmann::json cross_orthogonality_json(const Eigen::MatrixXd& fe, const Eigen::MatrixXd& Mr,
                                        const std::vector<int>& fe_numbers, const Eigen::MatrixXd& test,
                                        const std::vector<int>& test_numbers,
                                        const std::vector<std::pair<int, int>>& pairs, const std::string& reduction);

/// Writes the HTML report of `j` (html_report.hpp) to `path`. Throws InputError when it cannot.
void write_report(const std::string& path, const nlohmann::json& j);

}  // namespace ssid::cli::report

namespace ssid::cli::report {

/// One pair whose shapes the report draws.
struct ShapePair {
  int fe_mode = 0, test_mode = 0;  ///< as the JSON's "pairs" number them
  double fe_hz = 0, test_hz = 0, mac = 0;
  Eigen::Index fe_column = 0;      ///< column of the a-set modes
  Eigen::VectorXd fe_at_dofs, test_at_dofs;  ///< both shapes at `dofs`
};

/// Adds "geometry" (geometry_json) and "shapes" to `j`: per pair {"fe_mode", "test_mode",
/// "fe_hz", "test_hz", "mac", "fe" (every grid), "test" (the measured nodes, scaled onto
/// the analysis shape by scale_onto), "test_scale", "mems" (mems_json of the analysis
/// shape against `test_set`)}. `test_set` holds every test shape at `dofs` (columns),
/// numbered `test_numbers`. `test_lines`: the test's own wire frame (a test file's trace
/// lines, dataset 82, in grid ids), drawn instead of the one derived from the deck when
/// not empty; "geometry"'s "test_lines_from" says which.
void add_shapes(nlohmann::json& j, const translators::FeModel& model, const Eigen::MatrixXd& a_modes,
                const std::vector<translators::MeasuredDof>& dofs, const std::vector<ShapePair>& pairs,
                const Eigen::MatrixXd& test_set, const std::vector<int>& test_numbers, const Lines& test_lines = {});

/// The seed's MEMS and error mode (reconciliation paper Eqs. 2–3, its Figure 4) of
/// one analysis shape `fe` (the reference φ_a, at `dofs`) against every test shape
/// (columns of `test_set`, each scaled to unit norm: the paper's remedy for the
/// arbitrary test scaling): {"comparison", "alpha": [[test mode, α]], "error_squared"
/// (e², Eq. 2), "mac_superposition" (squared MAC of φ_a and Σ α_i φ_e_i), "error" (ê,
/// Eq. 3, at the measured nodes, in the analysis shape's units), "pair_error_squared"
/// (e² with the pair's test shape alone: 1 − MAC)}.
nlohmann::json mems_json(const std::vector<translators::MeasuredDof>& dofs, const Eigen::VectorXd& fe,
                         const Eigen::VectorXd& pair_test, const Eigen::MatrixXd& test_set,
                         const std::vector<int>& test_numbers);

/// Measured DOFs from the estimator's sensor labels ("grid:direction").
std::vector<translators::MeasuredDof> dofs_of_labels(const std::vector<std::string>& labels);

}  // namespace ssid::cli::report

#include <boost/program_options/variables_map.hpp>

#include "estimator/study/deck_study.hpp"

namespace ssid::cli::report {

/// The a-set K and M of configuration `c`'s deck at parameters `r` (its exact
/// re-assembly), as the deck-side code takes them: what the estimate's FRF overlays and
/// TAMs are computed from. `c.assemble` must be set (a deck's configuration).
translators::FeOperators operators_at(const estimator::PreparedConfiguration& c, const Eigen::VectorXd& r);

/// `ssid estimate --report`: adds "run" (inputs: deck, measured file, study or
/// problem file, FRF file), the first configuration's "geometry" and the "shapes" of its
/// pairs at the estimate (one more eigen-solve) to `j`, each later configuration's as
/// "configuration_shapes": [{"configuration" (its name), "geometry", "shapes"}], and
/// writes the report. Shapes need the deck: a problem file's run (or a deck no longer
/// there) gets none.
void write_estimate_report(const std::string& path, const Args& args, const boost::program_options::variables_map& vm,
                           const estimator::EstimationProblem& problem, const estimator::EstimationResult& result,
                           nlohmann::json& j);

/// `ssid diagnose --report`: adds "run" (inputs: the deck, the measured file, the
/// study) and the deck's "geometry" to `j`, and writes the report.
void write_diagnosis_report(const std::string& path, const Args& args, const boost::program_options::variables_map& vm,
                            nlohmann::json& j);

}  // namespace ssid::cli::report
