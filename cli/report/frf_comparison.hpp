#pragma once
/// \file frf_comparison.hpp
/// Measured FRFs against the FRFs of the analysis model, for `--report` of
/// `correlate` and `estimate` (the seed's Figures 6–9: FRFs of the test, of the
/// pretest model and of the updated model laid over each other). The analysis FRFs
/// are the modal superposition of the deck's mass-normalised modes (the seed's Eq. 2,
/// frf_synthesis.hpp) observed at the measured FRFs' response and reference DOFs
/// through the test-node mapping (sensor_mapping.hpp: a signed basic direction at
/// the grid the node maps to), each mode damped as the test mode it stands for.
/// Like report_data.hpp, it adds to the command's JSON what the report draws.
#include <Eigen/Core>
#include <cstddef>
#include <optional>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "cli/cli_util.hpp"
#include "estimator/diagnosis/diagnosis.hpp"
#include "estimator/study/deck_study.hpp"
#include "formats/uff.hpp"
#include "translators/assembly/fe_model.hpp"
#include "translators/measurement/mode_set.hpp"
#include "translators/measurement/sensor_mapping.hpp"

namespace ssid::cli::report {

/// The options --frf FILE, --frf-damping Z, --frf-max N (correlate, estimate, diagnose);
/// `frf_help` says what --frf lays over what.
void add_frf_options(po::options_description& desc, const std::string& frf_help);

/// --frf-damping (NaN when not given) and --frf-max, checked.
struct FrfOptions {
  double zeta_fallback;
  std::size_t max_frfs;
};
/// Prints what is wrong and returns nullopt for --frf-damping outside [0, 1) or --frf-max < 1.
std::optional<FrfOptions> frf_options(const po::variables_map& vm);

/// One analysis whose FRFs are drawn ("analysis", "prior mean", "estimate"): a deck's
/// model (not owned: it outlives the call) and its modes.
struct FrfAnalysis {
  std::string label;
  const translators::FeModel* model = nullptr;
  Eigen::VectorXd eigenvalue;  ///< ω_r², (rad/s)²
  Eigen::MatrixXd a_modes;     ///< a-set modes, mass-normalised (φᵀMφ = 1), one column per mode
};

/// The analysis of `model` with stiffness and mass `op` (a-set): the modes correlate
/// solves (the deck's EIGRL, else every mode of a small model, else the lowest ten),
/// mass-normalised whatever the deck's NORM. The solver's warnings go to `problems`.
FrfAnalysis deck_analysis(const std::string& label, const translators::FeModel& model,
                          const translators::FeOperators& op, std::vector<std::string>& problems);

/// What gives each analysis mode its damping: the test modes' own (dataset 55's viscous
/// damping ratio; `test_hz`/`test_zeta`, those > 0 only), the nearest within
/// `pair_tolerance` (relative) lending it (damping_partners); the others take `fallback`
/// (the command's --frf-damping), or, when none was given (NaN), the test modes' mean.
struct FrfDamping {
  std::vector<double> test_hz, test_zeta;
  std::vector<int> test_numbers;  ///< as the test file numbers them
  double fallback = 0;            ///< NaN: none given
  double pair_tolerance = 0.1;
};

/// The FRF comparison: every measured FRF of `measured` (dataset 58, function type 4)
/// whose response and reference nodes map to grids of the first analysis's model (through `nodes` — the
/// test file's nodes, to which the FRF file's own are added — by `map`; with map by id a
/// node nobody lists maps to the grid of its id), drive points first, at most `max_frfs`,
/// against each analysis of `analyses`. Returns {"file", "frfs": [{"response": [node,
/// dir], "reference": [node, dir], "response_grid", "reference_grid", "at" (file:line),
/// "quantity" (from the ordinate's data type 8, 11, 12; else receptance, with a note),
/// "unit", "hz" (the measured lines above 0 Hz), "measured": {"re", "im"} (as the file
/// holds them: the analysis is observed along the same signed directions),
/// "analyses": [{"label", "re", "im", "frac"}]}], "analyses": [{"label", "modes": [{"mode", "hz", "zeta", "zeta_from"}]}],
/// "left_out": [why, ...] (FRFs not drawn)}. Notes about what was left out go to
/// `problems`. Throws formats::InputError when no FRF can be drawn or no damping is known.
nlohmann::json frf_comparison_json(const formats::uff::UffFile& measured, std::vector<translators::TestNode> nodes,
                                   const translators::NodeMapOptions& map, const std::vector<FrfAnalysis>& analyses, const FrfDamping& damping,
                                   std::size_t max_frfs, std::vector<std::string>& problems);

/// `ssid estimate --frf`: the measured FRFs against those of the first configuration's
/// deck at the prior mean ("prior mean") and at the estimate ("estimate") — the seed's
/// before-and-after FRF figures; the modes those correlate solves (the deck's EIGRL, every
/// mode of a small model), each test mode lending its damping (`zeta_fallback`:
/// --frf-damping, NaN when not given). Throws formats::InputError when the
/// configuration has no deck (a problem file's run) or frf_comparison_json does.
nlohmann::json estimate_frf_comparison(const formats::uff::UffFile& measured,
                                       const estimator::PreparedConfiguration& configuration,
                                       const Eigen::VectorXd& prior_mean, const Eigen::VectorXd& estimate,
                                       double zeta_fallback, std::size_t max_frfs, std::vector<std::string>& problems);

/// `ssid diagnose --frf`: the measured FRFs against those of the deck as given ("deck"),
/// of the ordinary update ("parameters updated": the "parameter" hypothesis's deck at its
/// estimate) and, when an extension is named, of the extended, updated deck ("cause:
/// KIND"). `configuration` is the first configuration (its measured modes lend the
/// damping, its nodes the mapping).
nlohmann::json diagnosis_frf_comparison(const formats::uff::UffFile& measured,
                                        const estimator::diagnosis::ConfigurationInput& configuration,
                                        const estimator::diagnosis::Diagnosis& diagnosis,
                                        const translators::NodeMapOptions& map, double zeta_fallback,
                                        std::size_t max_frfs, std::vector<std::string>& problems);

/// The comparison as text: one line per FRF with its FRAC against each analysis.
std::string frf_comparison_text(const nlohmann::json& comparison);

}  // namespace ssid::cli::report
