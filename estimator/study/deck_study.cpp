#include "estimator/study/deck_study.hpp"
#include "estimator/study/study_reader.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <set>
#include <sstream>
#include <stdexcept>

#include "estimator/correlation/measures.hpp"
#include "estimator/eigen/eigen_solver.hpp"
#include "estimator/identification/modal_indicators.hpp"
#include "estimator/reporting/number_text.hpp"
#include "formats/bulk_model.hpp"
#include "formats/parse_error.hpp"
#include "formats/uff.hpp"
#include "translators/assembly/fe_model.hpp"
#include "translators/measurement/mode_set.hpp"
#include "formats/text_util.hpp"

namespace ssid::estimator {

namespace {

using json = nlohmann::json;

std::string folder_of(const std::string& path) {
  const auto slash = path.find_last_of('/');
  return slash == std::string::npos ? "" : path.substr(0, slash + 1);
}

std::string relative_to(const std::string& base_file, const std::string& path) {
  if (path.empty() || path[0] == '/' || base_file == "<defaults>") return path;
  return folder_of(base_file) + path;
}

bool contains(const std::vector<int>& v, int x) { return std::find(v.begin(), v.end(), x) != v.end(); }

// ---------------------------------------------------------------------------
// Decks and measured data.

struct LoadedDeck {
  std::shared_ptr<formats::Deck> deck;
  std::shared_ptr<translators::FeModel> fe;
};

LoadedDeck load_deck(const std::string& path) {
  LoadedDeck l;
  l.deck = std::make_shared<formats::Deck>(formats::read_deck(path));
  l.fe = translators::assemble_deck(*l.deck, path);
  return l;
}

/// A deck held in memory (`name`: INCLUDEs resolve from its folder; messages).
LoadedDeck load_deck_text(const std::string& text, const std::string& name) {
  LoadedDeck l;
  l.deck = std::make_shared<formats::Deck>(formats::read_deck_text(text, name));
  l.fe = translators::assemble_deck(*l.deck, name);
  return l;
}

/// Where the parameters' units come from, for the summary.
std::string units_note(const translators::DeckUnits& du) {
  if (du.source.empty())
    return "deck units: the deck states no unit system (a comment \"$ units: SI\" would name them)";
  if (du.si) return "SI, as the deck states (" + du.source + ": \"$ units: " + du.text + "\")";
  return "deck units: the deck states \"" + du.text + "\" (" + du.source + "), which ssid does not name";
}

/// Default prior σ from XINIT and the DESVAR bounds (see the header).
double default_prior_std(double x, double lo, double hi) {
  const bool lo_open = lo <= -1e19, hi_open = hi >= 1e19;
  double room = std::numeric_limits<double>::infinity();
  if (!lo_open) room = std::min(room, x - lo);
  if (!hi_open) room = std::min(room, hi - x);
  if (std::isfinite(room) && room > 0) return room / 2.0;
  return x != 0 ? 0.3 * std::abs(x) : 1.0;
}

/// The eigen-solve the estimator uses: the CHOLMOD shift-invert Lanczos,
/// analysis kept between cycles (the sparsity never changes). The lowest
/// `nmodes`; when they stop below `band_hz`, the lowest `max_modes` instead
/// (models with many local modes below and among the tested global ones).
OperatorModel::EigenSolve make_eigen_solve(const std::string& who, const std::string& method = "auto",
                                           double band_hz = 0, int max_modes = 0) {
  auto solver = std::make_shared<EigenSolver>();
  if (method == "spectra") solver->options().method = EigenMethod::Spectra;
  if (method == "block-lanczos") solver->options().method = EigenMethod::BlockLanczos;
  return [solver, who, band_hz, max_modes](const SparseMatrix& K, const SparseMatrix& M, int nmodes) {
    solver->options().nd = nmodes;
    EigenResult r = solver->solve(K, M);
    if (r.ok() && r.size() >= nmodes && r.cycles(r.size() - 1) < band_hz && nmodes < max_modes) {
      solver->options().nd = max_modes;
      r = solver->solve(K, M);
    }
    if (!r.ok()) throw_solve_failure(r, who + ": eigen-solve failed: " + r.message);
    if (r.size() < nmodes)
      throw formats::NumericalError(who + ": eigen-solve returned " + std::to_string(r.size()) + " of " +
                               std::to_string(nmodes) + " modes");
    return std::make_pair(Eigen::VectorXd(r.eigenvalues), Eigen::MatrixXd(r.modes));
  };
}

/// Operators of the selected parameters from the deck's full DESVAR vector.
OperatorModel::Assemble exact_assembly(std::shared_ptr<translators::FeModel> fe, Eigen::VectorXd x_fixed,
                                       std::vector<std::size_t> index) {
  return [fe, x_fixed, index](const Eigen::VectorXd& r) {
    Eigen::VectorXd x = x_fixed;
    for (std::size_t j = 0; j < index.size(); ++j) x(static_cast<Eigen::Index>(index[j])) = r(static_cast<Eigen::Index>(j));
    translators::FeOperators op = fe->operators(x, true);
    Operators out;
    out.K = std::move(op.K);
    out.M = std::move(op.M);
    for (std::size_t j : index) {
      out.dK.push_back(op.dK[j]);
      out.dM.push_back(op.dM[j]);
    }
    return out;
  };
}

}  // namespace

// ---------------------------------------------------------------------------

Study parse_study(const json& j, const std::string& source) {
  const StudyReader rd(source);
  Study s;
  s.source = source;
  rd.keys(j, "", {"title", "parameters", "priors", "measurement", "pairing", "pairs", "mapping", "modes", "configurations",
                  "convergence", "recursive", "sensitivity", "operators", "analysis_modes", "eigen_method", "identifiability",
                  "prior_std_pct", "diagnosis", "comment"});
  if (j.contains("title")) s.title = rd.text(j["title"], "title");
  if (j.contains("parameters")) {
    const auto& p = j["parameters"];
    if (!p.is_array()) rd.fail("parameters", "expected an array of DESVAR labels, got " + StudyReader::shown(p));
    for (std::size_t i = 0; i < p.size(); ++i)
      s.parameters.push_back(formats::detail::upper(rd.text(p[i], "parameters[" + std::to_string(i) + "]")));
  }
  if (j.contains("priors")) {
    const auto& pr = j["priors"];
    if (!pr.is_object()) rd.fail("priors", "expected an object {\"LABEL\": {\"mean\", \"std\" | \"std_pct\"}}");
    for (const auto& [label, v] : pr.items()) {
      const std::string path = "priors." + label;
      rd.keys(v, path, {"mean", "std", "std_pct"});
      PriorSetting ps;
      if (v.contains("mean")) ps.mean = rd.number(v["mean"], path + ".mean");
      if (v.contains("std")) ps.std = rd.number(v["std"], path + ".std", true);
      if (v.contains("std_pct")) ps.std_pct = rd.number(v["std_pct"], path + ".std_pct", true);
      if (ps.std && ps.std_pct) rd.fail(path, "give \"std\" or \"std_pct\", not both");
      s.priors[formats::detail::upper(label)] = ps;
    }
  }
  if (j.contains("prior_std_pct")) s.prior_std_pct = rd.number(j["prior_std_pct"], "prior_std_pct", true);
  if (j.contains("measurement")) {
    const auto& m = j["measurement"];
    rd.keys(m, "measurement", {"frequency_std_pct", "shape_std", "shape_std_pct", "use_shapes", "frequencies_only",
                               "std_from", "frequency_std_floor_pct", "shape_std_floor_pct"});
    if (m.contains("std_from"))
      s.std_from = rd.choice(m["std_from"], "measurement.std_from", {"identification", "study"}) == "study"
                       ? MeasurementStd::Study
                       : MeasurementStd::Identification;
    if (m.contains("frequency_std_floor_pct"))
      s.frequency_std_floor_pct = rd.number(m["frequency_std_floor_pct"], "measurement.frequency_std_floor_pct", true);
    if (m.contains("shape_std_floor_pct"))
      s.shape_std_floor_pct = rd.number(m["shape_std_floor_pct"], "measurement.shape_std_floor_pct", true);
    if (m.contains("frequency_std_pct"))
      s.frequency_std_pct = rd.number(m["frequency_std_pct"], "measurement.frequency_std_pct", true);
    if (m.contains("shape_std")) s.shape_std = rd.number(m["shape_std"], "measurement.shape_std", true);
    if (m.contains("shape_std_pct")) s.shape_std_pct = rd.number(m["shape_std_pct"], "measurement.shape_std_pct", true);
    if (m.contains("shape_std") && m.contains("shape_std_pct"))
      rd.fail("measurement", "give \"shape_std\" or \"shape_std_pct\", not both");
    if (m.contains("use_shapes")) s.use_shapes = rd.boolean(m["use_shapes"], "measurement.use_shapes");
    if (m.contains("frequencies_only"))
      s.frequencies_only = rd.boolean(m["frequencies_only"], "measurement.frequencies_only");
  }
  if (j.contains("pairs")) {
    const auto& p = j["pairs"];
    if (!p.is_array())
      rd.fail("pairs", "expected an array of {\"test_mode\", \"fe_mode\"} (and \"configuration\"), got " +
                           StudyReader::shown(p));
    for (std::size_t i = 0; i < p.size(); ++i) {
      const std::string path = "pairs[" + std::to_string(i) + "]";
      rd.keys(p[i], path, {"configuration", "test_mode", "fe_mode", "comment"});
      FixedPair fp;
      if (p[i].contains("configuration")) fp.configuration = rd.text(p[i]["configuration"], path + ".configuration");
      if (!p[i].contains("test_mode")) rd.fail(path, "needs \"test_mode\" (the measured mode number)");
      if (!p[i].contains("fe_mode")) rd.fail(path, "needs \"fe_mode\" (the analysis mode, 1-based)");
      fp.test_mode = rd.integer(p[i]["test_mode"], path + ".test_mode", 0);
      fp.fe_mode = rd.integer(p[i]["fe_mode"], path + ".fe_mode", 1);
      for (const auto& q : s.pairs)
        if (q.configuration == fp.configuration && (q.test_mode == fp.test_mode || q.fe_mode == fp.fe_mode))
          rd.fail(path, "test mode " + std::to_string(fp.test_mode) + " or analysis mode " + std::to_string(fp.fe_mode) +
                            " is paired twice");
      s.pairs.push_back(fp);
    }
  }
  if (j.contains("pairing")) {
    const auto& p = j["pairing"];
    rd.keys(p, "pairing", {"mac_min", "frequency_window_pct", "track_mac_min", "track_on"});
    if (p.contains("track_on"))
      s.track_on_sensors = rd.choice(p["track_on"], "pairing.track_on", {"sensors", "all"}) == "sensors";
    if (p.contains("mac_min")) s.mac_min = rd.number(p["mac_min"], "pairing.mac_min", false, true);
    if (p.contains("frequency_window_pct"))
      s.frequency_window_pct = rd.number(p["frequency_window_pct"], "pairing.frequency_window_pct", true);
    if (p.contains("track_mac_min")) s.track_mac_min = rd.number(p["track_mac_min"], "pairing.track_mac_min", false, true);
    if (s.mac_min > 1) rd.fail("pairing.mac_min", "a MAC lies in [0, 1]");
    if (s.track_mac_min > 1) rd.fail("pairing.track_mac_min", "a MAC lies in [0, 1]");
  }
  if (j.contains("mapping")) {
    const auto& m = j["mapping"];
    rd.keys(m, "mapping", {"by", "tolerance"});
    if (m.contains("by")) {
      const std::string by = rd.choice(m["by"], "mapping.by", {"id", "position", "id-then-position"});
      s.map_by = by == "id" ? translators::MapBy::Id
                 : by == "position" ? translators::MapBy::Position
                                    : translators::MapBy::IdThenPosition;
    }
    if (m.contains("tolerance")) s.map_tolerance = rd.number(m["tolerance"], "mapping.tolerance", true);
    if (s.map_by != translators::MapBy::Id && !(s.map_tolerance > 0))
      rd.fail("mapping", "mapping by position needs a positive \"tolerance\" (model length units)");
  }
  if (j.contains("modes")) {
    const auto& m = j["modes"];
    rd.keys(m, "modes", {"use", "exclude", "min_hz", "max_hz", "frequency_only", "shape_only"});
    if (m.contains("use")) s.modes.modes = rd.integers(m["use"], "modes.use");
    if (m.contains("exclude")) s.modes.exclude = rd.integers(m["exclude"], "modes.exclude");
    if (m.contains("min_hz")) s.modes.min_hz = rd.number(m["min_hz"], "modes.min_hz", false, true);
    if (m.contains("max_hz")) s.modes.max_hz = rd.number(m["max_hz"], "modes.max_hz", true);
    if (m.contains("frequency_only")) s.modes.frequency_only = rd.integers(m["frequency_only"], "modes.frequency_only");
    if (m.contains("shape_only")) s.modes.shape_only = rd.integers(m["shape_only"], "modes.shape_only");
  }
  if (j.contains("configurations")) {
    const auto& c = j["configurations"];
    if (!c.is_array() || c.empty())
      rd.fail("configurations", "expected a non-empty array of {\"name\", \"deck\", \"measured\"}");
    std::set<std::string> names;
    for (std::size_t i = 0; i < c.size(); ++i) {
      const std::string path = "configurations[" + std::to_string(i) + "]";
      rd.keys(c[i], path, {"name", "deck", "measured", "analysis_modes"});
      StudyConfiguration sc;
      sc.name = c[i].contains("name") ? rd.text(c[i]["name"], path + ".name") : "config" + std::to_string(i + 1);
      if (!names.insert(sc.name).second) rd.fail(path + ".name", "configuration \"" + sc.name + "\" is given twice");
      if (c[i].contains("deck")) sc.deck = relative_to(source, rd.text(c[i]["deck"], path + ".deck"));
      if (c[i].contains("measured")) sc.measured = relative_to(source, rd.text(c[i]["measured"], path + ".measured"));
      if (c[i].contains("analysis_modes")) sc.analysis_modes = rd.integer(c[i]["analysis_modes"], path + ".analysis_modes");
      s.configurations.push_back(sc);
    }
  }
  if (j.contains("convergence")) {
    const auto& c = j["convergence"];
    rd.keys(c, "convergence", {"max_iterations", "tolerance"});
    if (c.contains("max_iterations")) s.max_iterations = rd.integer(c["max_iterations"], "convergence.max_iterations", 0);
    if (c.contains("tolerance")) s.tolerance = rd.number(c["tolerance"], "convergence.tolerance", true);
  }
  if (j.contains("recursive")) s.recursive = rd.boolean(j["recursive"], "recursive");
  if (j.contains("sensitivity"))
    s.shape_derivative = rd.choice(j["sensitivity"], "sensitivity", {"nelson", "modal-sum"}) == "nelson"
                             ? ShapeDerivative::Nelson
                             : ShapeDerivative::ModalSum;
  if (j.contains("operators"))
    s.operators = rd.choice(j["operators"], "operators", {"exact", "taylor"}) == "exact" ? OperatorUpdate::Exact
                                                                                      : OperatorUpdate::Taylor;
  if (j.contains("analysis_modes")) s.analysis_modes = rd.integer(j["analysis_modes"], "analysis_modes");
  if (j.contains("eigen_method"))
    s.eigen_method = rd.choice(j["eigen_method"], "eigen_method", {"auto", "spectra", "block-lanczos"});
  if (j.contains("diagnosis")) {
    if (!j["diagnosis"].is_object()) rd.fail("diagnosis", "expected an object, got " + StudyReader::shown(j["diagnosis"]));
    s.diagnosis = j["diagnosis"];
  }
  if (j.contains("identifiability")) {
    const auto& i = j["identifiability"];
    rd.keys(i, "identifiability", {"uninformed_ratio", "strong_correlation"});
    if (i.contains("uninformed_ratio")) s.uninformed_ratio = rd.number(i["uninformed_ratio"], "identifiability.uninformed_ratio", true);
    if (i.contains("strong_correlation"))
      s.strong_correlation = rd.number(i["strong_correlation"], "identifiability.strong_correlation", true);
  }
  return s;
}

Study read_study(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw formats::InputError(path + ": cannot open the study file");
  std::stringstream ss;
  ss << in.rdbuf();
  json j;
  try {
    j = json::parse(ss.str());
  } catch (const json::parse_error& e) {
    throw formats::InputError(path + ": not valid JSON (byte " + std::to_string(e.byte) + "): " + e.what());
  }
  return parse_study(j, path);
}

// ---------------------------------------------------------------------------
// The estimation problem, one phase per function: the study's options, the
// configurations' files, the estimated parameters and their prior, the sensors
// (test nodes onto grids, measured DOFs onto analysis DOFs), the measured modes
// chosen, the analysis model. prepare_problem runs them in that order.

namespace {

void set_options(const Study& study, EstimationProblem& problem) {
  problem.title = study.title;
  problem.recursive = study.recursive;
  problem.uninformed_ratio = study.uninformed_ratio;
  problem.strong_correlation = study.strong_correlation;
  problem.operators = study.operators == OperatorUpdate::Exact ? "exact" : "taylor";
  problem.options.max_iterations = study.max_iterations;
  problem.options.tolerance = study.tolerance;
  problem.options.mac_min = study.mac_min;
  problem.options.freq_tol_pct = study.frequency_window_pct;
  problem.options.track_mac_min = study.track_mac_min;
  problem.options.shape_derivatives = study.use_shapes && !study.frequencies_only;
}

/// The estimated parameters' labels (upper case): the study's list, or every
/// DESVAR of the first deck. Every prior must name one of them.
std::vector<std::string> estimated_labels(const Study& study, const std::vector<translators::DesignParameter>& params) {
  std::vector<std::string> labels;
  if (study.parameters.empty())
    for (const auto& p : params) labels.push_back(formats::detail::upper(p.label));
  else
    labels = study.parameters;
  for (const auto& [label, ps] : study.priors)
    if (std::find(labels.begin(), labels.end(), label) == labels.end())
      throw formats::InputError(study.source + ": priors." + label + ": no such parameter is estimated (" +
                                  (study.parameters.empty() ? "the deck's DESVAR labels" : "study \"parameters\"") +
                                  " hold none of that name)");
  return labels;
}

/// Each label's index among the deck's parameters.
std::vector<std::size_t> parameter_indices(const std::vector<std::string>& labels,
                                           const std::vector<translators::DesignParameter>& params,
                                           const std::string& deck) {
  std::vector<std::size_t> index;
  for (const auto& l : labels) {
    std::size_t found = params.size();
    for (std::size_t j = 0; j < params.size(); ++j)
      if (formats::detail::upper(params[j].label) == l) found = j;
    if (found == params.size()) {
      std::string have;
      for (const auto& p : params) have += (have.empty() ? "" : ", ") + p.label;
      throw formats::InputError(deck + ": parameter '" + l + "' is no DESVAR label of this deck (it has: " + have + ")");
    }
    index.push_back(found);
  }
  return index;
}

/// The prior (mean, σ, bounds from DESVAR and the study's priors), the DESVAR
/// ids and each parameter's unit, from the first configuration's deck.
void set_prior(const Study& study, const std::vector<std::string>& labels, const std::vector<std::size_t>& index,
               const LoadedDeck& ld, EstimationProblem& problem) {
  const translators::FeModel& fe = *ld.fe;
  const auto& params = fe.parameters();
  const auto p = static_cast<Eigen::Index>(labels.size());
  problem.prior.names = labels;
  problem.prior.mean.resize(p);
  problem.prior.lower.resize(p);
  problem.prior.upper.resize(p);
  Eigen::VectorXd sd(p);
  for (Eigen::Index j = 0; j < p; ++j) {
    const auto& d = params[index[static_cast<std::size_t>(j)]];
    problem.desvar_ids.push_back(d.id);
    double mean = d.initial, s = default_prior_std(d.initial, d.lower, d.upper);
    if (study.prior_std_pct && d.initial != 0) s = *study.prior_std_pct / 100.0 * std::abs(d.initial);
    if (auto it = study.priors.find(labels[static_cast<std::size_t>(j)]); it != study.priors.end()) {
      if (it->second.mean) mean = *it->second.mean;
      if (it->second.std) s = *it->second.std;
      else if (it->second.std_pct) s = *it->second.std_pct / 100.0 * std::abs(mean);
      else if (it->second.mean) s = default_prior_std(mean, d.lower, d.upper);
      if (!(s > 0))
        throw formats::InputError(study.source + ": priors." + labels[static_cast<std::size_t>(j)] +
                                    ": the prior standard deviation is 0 (a std_pct of a zero mean?)");
    }
    if (mean < d.lower || mean > d.upper)
      throw formats::InputError(study.source + ": prior mean " + significant(mean, 6) + " of " + d.label +
                                  " lies outside its DESVAR bounds [" + significant(d.lower, 6) + ", " +
                                  significant(d.upper, 6) + "]");
    problem.prior.mean(j) = mean;
    problem.prior.lower(j) = d.lower <= -1e19 ? -INFINITY : d.lower;
    problem.prior.upper(j) = d.upper >= 1e19 ? INFINITY : d.upper;
    sd(j) = s;
  }
  problem.prior.cov = sd.array().square().matrix().asDiagonal();
  const translators::DeckUnits du = translators::deck_units(*ld.deck);
  for (std::size_t j = 0; j < index.size(); ++j)
    problem.units.push_back(translators::parameter_unit(params[index[j]], du, fe.bulk()));
  problem.units_note = units_note(du);
}

/// Which row of the measured shapes each sensor row of pc.sensors holds.
using ShapeRows = std::vector<Eigen::Index>;

/// Test nodes onto grids, measured DOFs onto analysis DOFs: pc.sensors (the
/// observation matrix on the a-set, rows that see an analysis DOF only), their
/// labels and grids. Returns the measured shapes' row of each sensor. Data
/// without shapes has no sensors.
ShapeRows map_sensors(const Study& study, const ConfigurationSource& sc, const translators::FeModel& fe,
                      PreparedConfiguration& pc) {
  const translators::ModeSet& set = sc.data.modes;
  const auto na = static_cast<Eigen::Index>(fe.reduction().a_to_g.size());
  pc.node_map = {study.map_by, study.map_tolerance};
  pc.test_nodes = sc.data.nodes;
  if (set.dofs.empty()) {
    pc.sensors = SparseMatrix(0, na);
    return {};
  }
  std::vector<translators::GridPosition> grids;
  for (const auto& g : fe.geometry().grids()) grids.push_back({g.id, g.x, g.frame});
  std::vector<translators::TestNode> nodes = sc.data.nodes;
  std::set<std::int64_t> shape_nodes;
  for (const auto& d : set.dofs) shape_nodes.insert(d.node);
  if (nodes.empty()) {
    if (study.map_by != translators::MapBy::Id)
      throw formats::InputError(sc.measured + ": mapping by position needs the test node positions (dataset 15 or 2411)");
    for (auto id : shape_nodes) nodes.push_back({id, Eigen::Vector3d::Zero(), 0});
  }
  const translators::NodeMapping mapping = translators::map_test_nodes(nodes, grids, pc.node_map);
  pc.test_lines = translators::segments_in_grids(sc.data.trace_lines, mapping);
  for (const auto& pr : mapping.problems) pc.notes.push_back(sc.measured + ": " + pr);
  const translators::Observation obs = translators::observe(set.dofs, mapping, grids);
  if (obs.rows.empty())
    throw formats::InputError(sc.measured + ": none of the " + std::to_string(shape_nodes.size()) +
                                " measured nodes maps to a grid of " + sc.deck +
                                (study.map_by == translators::MapBy::Id
                                     ? " by id; map them by position (study \"mapping\": {\"by\": \"position\", "
                                       "\"tolerance\": ...})"
                                     : " within the position tolerance"));
  // A measured node that maps nowhere is an error, not a sensor left out;
  // identified modes name the shape entry that brings it.
  for (const auto& [node, key] : sc.data.node_keys)
    if (!mapping.grid_of(node)) {
      const auto why = mapping.why_unmapped.find(node);
      throw formats::InputError(sc.measured + ": " + key + ": test node " + std::to_string(node) + ": " +
                                (why != mapping.why_unmapped.end() ? why->second : "no grid with this id") +
                                " in the deck " + sc.deck);
    }
  translators::require_mapped(set.dofs, mapping, sc.measured, "the deck " + sc.deck);
  const SparseMatrix Cg = translators::observation_matrix(obs, fe.geometry().gset());
  const SparseMatrix Ca_all = Cg * fe.reduction().T;
  // Keep the rows that see the analysis DOFs (a measured direction on a
  // constrained DOF measures nothing the model can move).
  std::vector<Eigen::Index> keep_rows;
  ShapeRows shape_rows;
  std::map<std::pair<std::int64_t, int>, Eigen::Index> dof_row;
  for (std::size_t i = 0; i < set.dofs.size(); ++i)
    dof_row[{set.dofs[i].node, set.dofs[i].direction}] = static_cast<Eigen::Index>(i);
  std::size_t constrained = 0;
  for (std::size_t i = 0; i < obs.rows.size(); ++i) {
    const auto& md = obs.rows[i].measured;
    if (Ca_all.row(static_cast<Eigen::Index>(i)).norm() == 0.0) {
      ++constrained;
      continue;
    }
    keep_rows.push_back(static_cast<Eigen::Index>(i));
    shape_rows.push_back(dof_row.at({md.node, md.direction}));
    const std::int64_t grid = *mapping.grid_of(md.node);
    pc.sensor_labels.push_back(std::to_string(grid) + ":" + std::to_string(md.direction));
    pc.sensor_grids.push_back(grid);
  }
  if (constrained)
    pc.notes.push_back(sc.measured + ": " + std::to_string(constrained) +
                       " measured DOF(s) on constrained analysis DOFs left out of the shapes");
  std::vector<Eigen::Triplet<double>> t;
  // Row selection as a product (S picks rows of Ca_all).
  SparseMatrix S(static_cast<Eigen::Index>(keep_rows.size()), Ca_all.rows());
  for (std::size_t r = 0; r < keep_rows.size(); ++r) t.emplace_back(static_cast<int>(r), static_cast<int>(keep_rows[r]), 1.0);
  S.setFromTriplets(t.begin(), t.end());
  pc.sensors = S * Ca_all;
  pc.sensors.makeCompressed();
  return shape_rows;
}

/// The analyst's pairs of configuration `sc` (index `k`): test mode number →
/// analysis mode (0-based).
std::map<int, int> fixed_pairs_of(const Study& study, const ConfigurationSource& sc, std::size_t k) {
  std::map<int, int> out;
  for (const auto& fp : study.pairs)
    if (fp.configuration == sc.name || (fp.configuration.empty() && k == 0)) out[fp.test_mode] = fp.fe_mode - 1;
  return out;
}

/// Measured mode `m` of `set` at the sensor rows, with the study's σ.
MeasuredMode measured_mode(const Study& study, const translators::ModeSet& set, std::size_t m, const ShapeRows& shape_rows) {
  const auto ns = static_cast<Eigen::Index>(shape_rows.size());
  MeasuredMode mm;
  mm.id = m < set.numbers.size() ? set.numbers[m] : static_cast<int>(m + 1);
  mm.frequency_hz = set.frequency_hz[m];
  mm.frequency_std_hz = study.frequency_std_pct / 100.0 * mm.frequency_hz;
  mm.shape.resize(ns);
  for (Eigen::Index r = 0; r < ns; ++r) mm.shape(r) = set.shapes(shape_rows[static_cast<std::size_t>(r)], static_cast<Eigen::Index>(m));
  if (ns == 0 || mm.shape.norm() == 0) mm.shape.resize(0);
  const double root_ns = std::sqrt(static_cast<double>(std::max<Eigen::Index>(ns, 1)));
  mm.shape_std = study.shape_std ? *study.shape_std : (ns ? study.shape_std_pct / 100.0 / root_ns : 0.0);
  mm.use_shape = study.use_shapes && mm.shape.size() > 0;
  // The identification's σ replaces the study's where it has one, floored and
  // scaled (Study::std_from, frequency_std_floor_pct, identified_*_scale).
  if (study.std_from != MeasurementStd::Study) {
    if (m < set.frequency_std_hz.size() && std::isfinite(set.frequency_std_hz[m]))
      mm.frequency_std_hz = study.identified_frequency_std_scale *
                            std::max(set.frequency_std_hz[m], study.frequency_std_floor_pct / 100.0 * mm.frequency_hz);
    if (m < set.shape_std.size() && std::isfinite(set.shape_std[m]) && ns)
      mm.shape_std = study.identified_shape_std_scale * std::max(set.shape_std[m], study.shape_std_floor_pct / 100.0 / root_ns);
  }
  return mm;
}

/// Whether mode `m` of `set` takes its σ from the identification (measured_mode).
bool identified_std(const Study& study, const translators::ModeSet& set, std::size_t m) {
  return study.std_from != MeasurementStd::Study && m < set.frequency_std_hz.size() && std::isfinite(set.frequency_std_hz[m]);
}

/// The measured modes the study's selection keeps, at the sensor rows, with
/// their σ and fixed partners (pc.test, pc.test_numbers).
void select_measured_modes(const Study& study, const ConfigurationSource& sc, std::size_t k, const std::string& who,
                           const ShapeRows& shape_rows, PreparedConfiguration& pc) {
  const translators::ModeSet& set = sc.data.modes;
  if (study.std_from == MeasurementStd::Identification && set.frequency_std_hz.empty())
    throw formats::InputError(study.source + ": measurement.std_from: \"identification\", but " + sc.measured +
                              " carries no σ of its own (the JSON of ssid identify modes does; UFF 55 and frequency "
                              "lists do not)");
  const auto& sel = study.modes;
  const std::map<int, int> fixed = fixed_pairs_of(study, sc, k);
  std::vector<int> left_out;
  for (std::size_t m = 0; m < set.frequency_hz.size(); ++m) {
    const int number = m < set.numbers.size() ? set.numbers[m] : static_cast<int>(m + 1);
    const double f = set.frequency_hz[m];
    const bool chosen = (sel.modes.empty() || contains(sel.modes, number)) && !contains(sel.exclude, number) &&
                        f >= sel.min_hz && f <= sel.max_hz;
    if (!chosen) {
      left_out.push_back(number);
      continue;
    }
    if (!(f > 0)) {
      pc.notes.push_back(sc.measured + ": test mode " + std::to_string(number) + " has frequency " + significant(f, 6) +
                         " Hz: left out (rigid-body or bad data)");
      continue;
    }
    MeasuredMode mm = measured_mode(study, set, m, shape_rows);
    mm.id = number;
    mm.use_frequency = !contains(sel.shape_only, number);
    mm.use_shape = mm.use_shape && !contains(sel.frequency_only, number);
    if (auto it = fixed.find(number); it != fixed.end()) mm.fixed_partner = it->second;
    pc.test.push_back(mm);
    pc.test_numbers.push_back(number);
    pc.test_damping.push_back(m < set.damping.size() ? set.damping[m] : 0.0);
    pc.std_from.push_back(identified_std(study, set, m) ? "identification" : "study");
  }
  for (int n : sel.modes)
    if (!contains(set.numbers, n))
      throw formats::InputError(study.source + ": modes.use: " + sc.measured + " has no mode " + std::to_string(n));
  for (const auto& [n, j] : fixed)
    if (!contains(pc.test_numbers, n))
      throw formats::InputError(study.source + ": pairs: test mode " + std::to_string(n) + " is not among the modes of " +
                                sc.measured + " the estimate uses");
  if (!left_out.empty()) {
    std::string l;
    for (int n : left_out) l += " " + std::to_string(n);
    pc.notes.push_back(sc.measured + ": test modes left out by the mode selection:" + l);
  }
  if (pc.test.empty()) throw formats::InputError(who + ": no measured mode is left after the mode selection");
}

/// The analysis DOFs, the number of analysis modes, and the modal model at
/// parameter values (exact re-assembly or the Taylor operators).
void attach_model(const Study& study, const ConfigurationSource& sc, const std::string& who, const LoadedDeck& ld,
                  const std::vector<std::size_t>& index, const EstimationProblem& problem, PreparedConfiguration& pc) {
  const translators::FeModel& fe = *ld.fe;
  const translators::DofMap& gset = fe.geometry().gset();
  for (std::size_t a : fe.reduction().a_to_g) {
    const auto& d = gset.at(a);
    pc.dofs.emplace_back(d.point, d.component);
  }
  const int na = static_cast<int>(pc.dofs.size());
  int fixed_max = 0;
  for (const auto& t : pc.test) fixed_max = std::max(fixed_max, t.fixed_partner + 1);
  const bool given = sc.analysis_modes || study.analysis_modes;
  int nmodes = sc.analysis_modes    ? *sc.analysis_modes
               : study.analysis_modes ? *study.analysis_modes
                                      : 2 * static_cast<int>(pc.test.size()) + study.extra_analysis_modes;
  nmodes = std::min(std::max(nmodes, fixed_max), na - 1);
  if (nmodes < static_cast<int>(pc.test.size()))
    pc.notes.push_back("only " + std::to_string(nmodes) + " analysis modes for " + std::to_string(pc.test.size()) +
                       " test modes");
  if (nmodes < 1) throw formats::InputError(sc.deck + ": the model has too few analysis DOFs (" + std::to_string(na) + ")");
  if (fixed_max > nmodes)
    throw formats::InputError(study.source + ": pairs: analysis mode " + std::to_string(fixed_max) + " of " + who +
                              " does not exist (the model has " + std::to_string(na) + " analysis DOFs)");
  pc.analysis_modes = nmodes;
  // The band rule only where the study does not name the number of modes.
  double f_max = 0;
  for (const auto& t : pc.test) f_max = std::max(f_max, t.frequency_hz);
  const double band_hz = given ? 0.0 : study.analysis_band_factor * f_max;
  const int max_modes = std::min(na - 1, std::max(study.max_analysis_modes, nmodes));

  Eigen::VectorXd x_fixed = fe.initial_parameters();
  for (std::size_t j = 0; j < index.size(); ++j)
    x_fixed(static_cast<Eigen::Index>(index[j])) = problem.prior.mean(static_cast<Eigen::Index>(j));
  OperatorModel::Assemble exact = exact_assembly(ld.fe, x_fixed, index);
  // Keep the deck alive as long as the assembly refers to the model.
  auto deck_keep = ld.deck;
  OperatorModel::Assemble assemble = [exact, deck_keep](const Eigen::VectorXd& r) { return exact(r); };
  if (study.operators == OperatorUpdate::Taylor) assemble = taylor_operators(exact(problem.prior.mean), problem.prior.mean);
  pc.assemble = assemble;
  pc.model = std::make_shared<OperatorModel>(assemble, make_eigen_solve(who, study.eigen_method, band_hz, max_modes),
                                             pc.sensors, nmodes, study.shape_derivative);
  pc.model->set_tracking_on_sensors(study.track_on_sensors);
  if (pc.sensors.rows() == 0)
    pc.notes.push_back(sc.measured + ": no measured shapes: pairs " + (study.pairs.empty() ? "" : "as fixed, else ") +
                       "by frequency; modes followed by their shapes at every analysis DOF");
  pc.fe = ld.fe;
  for (const auto& n : fe.notes()) pc.notes.push_back(sc.deck + ": " + n);
}

/// The summary's words for where the σ of `configs` come from.
std::string measurement_std_text(const Study& study, const std::vector<PreparedConfiguration>& configs) {
  std::string from_id, from_study;
  for (const auto& c : configs)
    for (std::size_t i = 0; i < c.std_from.size(); ++i)
      (c.std_from[i] == "identification" ? from_id : from_study) +=
          " " + (configs.size() > 1 ? c.name + ":" : std::string()) + std::to_string(c.test_numbers[i]);
  const std::string shape_pct =
      study.shape_std ? significant(*study.shape_std, 3) + " on the unit shape" : significant(study.shape_std_pct, 3) + " % of the RMS shape component";
  const std::string studys = "the study's " + significant(study.frequency_std_pct, 3) + " % of each frequency, " + shape_pct;
  std::string scale;
  if (study.identified_frequency_std_scale != 1.0 || study.identified_shape_std_scale != 1.0)
    scale = ", times the noise scale the data imply (frequencies " + significant(study.identified_frequency_std_scale, 3) +
            ", shapes " + significant(study.identified_shape_std_scale, 3) + ")";
  const std::string ident = "from the identification (per mode: its hz_std, and its shape_std where given, else " + shape_pct +
                            "), floored at " + significant(study.frequency_std_floor_pct, 3) + " % of the frequency and " +
                            significant(study.shape_std_floor_pct, 3) + " % of the RMS shape component" + scale;
  if (from_study.empty()) return ident;
  if (from_id.empty()) return studys;
  return ident + " for test modes" + from_id + "; " + studys + " for test modes" + from_study;
}

}  // namespace

std::vector<MeasuredMode> measured_at_sensors(const Study& study, const translators::ModeSet& set,
                                              const PreparedConfiguration& pc) {
  std::vector<MeasuredMode> out;
  for (std::size_t m = 0; m < set.frequency_hz.size(); ++m) out.push_back(measured_mode(study, set, m, pc.shape_rows));
  return out;
}

// ---------------------------------------------------------------------------
// Measured data.

translators::ModeSet parse_frequency_list(const std::string& text, const std::string& name, bool is_json) {
  translators::ModeSet set;
  auto add = [&](int number, double hz, const std::string& where) {
    if (!std::isfinite(hz) || !(hz > 0))
      throw formats::InputError(where + ": expected a positive frequency [Hz], got " + significant(hz, 6));
    if (contains(set.numbers, number)) throw formats::InputError(where + ": mode " + std::to_string(number) + " is given twice");
    set.numbers.push_back(number);
    set.frequency_hz.push_back(hz);
  };
  if (is_json) {
    json j;
    try {
      j = json::parse(text);
    } catch (const json::parse_error& e) {
      throw formats::InputError(name + ": not valid JSON (byte " + std::to_string(e.byte) + "): " + e.what());
    }
    const StudyReader rd(name);
    if (!j.is_array() || j.empty())
      rd.fail("(top level)", "expected a non-empty array of frequencies [Hz] or of {\"mode\", \"hz\"}");
    for (std::size_t i = 0; i < j.size(); ++i) {
      const std::string path = "[" + std::to_string(i) + "]";
      if (j[i].is_object()) {
        rd.keys(j[i], path, {"mode", "hz", "comment"});
        if (!j[i].contains("hz")) rd.fail(path, "needs \"hz\"");
        const int number = j[i].contains("mode") ? rd.integer(j[i]["mode"], path + ".mode", 0) : static_cast<int>(i + 1);
        add(number, rd.number(j[i]["hz"], path + ".hz", true), name + ": " + path);
      } else {
        add(static_cast<int>(i + 1), rd.number(j[i], path, true), name + ": " + path);
      }
    }
    return set;
  }
  std::istringstream in(text);
  std::string line;
  int line_no = 0;
  bool header_allowed = true;
  while (std::getline(in, line)) {
    ++line_no;
    const std::string where = name + ":" + std::to_string(line_no);
    if (const auto hash = line.find('#'); hash != std::string::npos) line.resize(hash);
    std::vector<std::string> fields;
    std::string field;
    std::istringstream ls(line);
    while (std::getline(ls, field, ',')) {
      const auto b = field.find_first_not_of(" \t\r"), e = field.find_last_not_of(" \t\r");
      fields.push_back(b == std::string::npos ? "" : field.substr(b, e - b + 1));
    }
    if (fields.size() == 1 && fields[0].empty()) continue;
    if (fields.empty()) continue;
    auto as_number = [&](const std::string& f, double& x) {
      std::size_t used = 0;
      try {
        x = std::stod(f, &used);
      } catch (const std::exception&) {
        return false;
      }
      return used == f.size();
    };
    double a = 0, b = 0;
    const bool first_numeric = as_number(fields[0], a);
    if (!first_numeric && header_allowed) {  // a header line
      header_allowed = false;
      continue;
    }
    header_allowed = false;
    if (fields.size() > 2)
      throw formats::InputError(where + ": expected \"HZ\" or \"MODE, HZ\", got " + std::to_string(fields.size()) + " fields");
    if (!first_numeric)
      throw formats::InputError(where + ": expected a number, got \"" + fields[0] + "\"");
    if (fields.size() == 1) {
      add(static_cast<int>(set.frequency_hz.size() + 1), a, where);
    } else {
      if (!as_number(fields[1], b)) throw formats::InputError(where + ": expected a frequency [Hz], got \"" + fields[1] + "\"");
      if (a != std::floor(a) || a < 0) throw formats::InputError(where + ": expected a mode number, got \"" + fields[0] + "\"");
      add(static_cast<int>(a), b, where);
    }
  }
  if (set.frequency_hz.empty()) throw formats::InputError(name + ": no frequency in the list");
  return set;
}

MeasuredData parse_identified_modes(const json& j, const std::string& name) {
  const StudyReader rd(name);
  const json& modes = j.at("modes");
  if (!modes.is_array() || modes.empty())
    rd.fail("modes", "expected a non-empty array of identified modes, got " + StudyReader::shown(modes));
  MeasuredData d;
  translators::ModeSet& set = d.modes;
  std::map<std::pair<std::int64_t, int>, Eigen::Index> row_of;  // (node, direction) → row
  std::vector<Eigen::VectorXd> shapes;
  bool any_std = false;
  for (std::size_t i = 0; i < modes.size(); ++i) {
    const std::string path = "modes[" + std::to_string(i) + "]";
    const json& m = modes[i];
    if (!m.is_object()) rd.fail(path, "expected an object {\"hz\", \"hz_std\", \"shape\", ...}, got " + StudyReader::shown(m));
    if (!m.contains("hz")) rd.fail(path, "needs \"hz\" (the mode's frequency [Hz])");
    const int number = m.contains("mode") ? rd.integer(m["mode"], path + ".mode", 0) : static_cast<int>(i + 1);
    if (contains(set.numbers, number)) rd.fail(path, "mode " + std::to_string(number) + " is given twice");
    set.numbers.push_back(number);
    set.frequency_hz.push_back(rd.number(m["hz"], path + ".hz", true));
    set.damping.push_back(m.contains("zeta") ? rd.number(m["zeta"], path + ".zeta", false, true) : 0.0);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    set.frequency_std_hz.push_back(m.contains("hz_std") ? rd.number(m["hz_std"], path + ".hz_std", false, true) : nan);
    set.shape_std.push_back(m.contains("shape_std") ? rd.number(m["shape_std"], path + ".shape_std", false, true) : nan);
    any_std = any_std || m.contains("hz_std") || m.contains("shape_std");
    if (!m.contains("shape")) rd.fail(path, "needs \"shape\" ([[node, direction, re, im], ...])");
    const json& sh = m["shape"];
    if (!sh.is_array() || sh.empty())
      rd.fail(path + ".shape", "expected a non-empty array of [node, direction, re, im], got " + StudyReader::shown(sh));
    Eigen::VectorXcd phi(static_cast<Eigen::Index>(sh.size()));
    std::vector<Eigen::Index> rows;
    for (std::size_t k = 0; k < sh.size(); ++k) {
      const std::string at = path + ".shape[" + std::to_string(k) + "]";
      const json& e = sh[k];
      if (!e.is_array() || e.size() != 4) rd.fail(at, "expected [node, direction, re, im], got " + StudyReader::shown(e));
      const std::int64_t node = rd.integer(e[0], at + "[0]", 1);
      const int dir = rd.integer(e[1], at + "[1]", 1);
      if (dir > 6) rd.fail(at + "[1]", "expected a direction 1 … 6 (X, Y, Z, RX, RY, RZ), got " + std::to_string(dir));
      phi(static_cast<Eigen::Index>(k)) = {rd.number(e[2], at + "[2]"), rd.number(e[3], at + "[3]")};
      auto it = row_of.find({node, dir});
      if (i == 0) {
        if (it != row_of.end()) rd.fail(at, "node " + std::to_string(node) + " direction " + std::to_string(dir) + " is given twice");
        it = row_of.emplace(std::make_pair(node, dir), static_cast<Eigen::Index>(set.dofs.size())).first;
        set.dofs.push_back({node, dir});
        d.node_keys.emplace(node, at);
      } else if (it == row_of.end()) {
        rd.fail(at, "node " + std::to_string(node) + " direction " + std::to_string(dir) + " is not in modes[0].shape "
                    "(every mode must have the same measured DOFs)");
      } else if (std::find(rows.begin(), rows.end(), it->second) != rows.end()) {
        rd.fail(at, "node " + std::to_string(node) + " direction " + std::to_string(dir) + " is given twice");
      }
      rows.push_back(it->second);
    }
    if (rows.size() != set.dofs.size())
      rd.fail(path + ".shape", "has " + std::to_string(rows.size()) + " entries, modes[0].shape " +
                                   std::to_string(set.dofs.size()) + " (every mode must have the same measured DOFs)");
    if (phi.norm() == 0) rd.fail(path + ".shape", "is zero everywhere");
    // Complex to real as identify does for UFF 55.
    const Eigen::VectorXd real = identification::real_mode(phi);
    Eigen::VectorXd col(real.size());
    for (std::size_t k = 0; k < rows.size(); ++k) col(rows[k]) = real(static_cast<Eigen::Index>(k));
    shapes.push_back(col);
  }
  set.shapes.resize(static_cast<Eigen::Index>(set.dofs.size()), static_cast<Eigen::Index>(shapes.size()));
  for (std::size_t m = 0; m < shapes.size(); ++m) set.shapes.col(static_cast<Eigen::Index>(m)) = shapes[m];
  if (!any_std) {
    set.frequency_std_hz.clear();
    set.shape_std.clear();
  }
  return d;
}

MeasuredData read_measured(const std::string& path, bool frequencies_only) {
  auto ends_with = [&](const std::string& ext) {
    if (path.size() < ext.size()) return false;
    std::string tail = path.substr(path.size() - ext.size());
    for (auto& c : tail) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return tail == ext;
  };
  MeasuredData d;
  if (ends_with(".csv") || ends_with(".txt") || ends_with(".json")) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw formats::InputError(path + ": cannot open the measured file");
    std::stringstream ss;
    ss << in.rdbuf();
    if (ends_with(".json")) {
      json j;
      try {
        j = json::parse(ss.str());
      } catch (const json::parse_error& e) {
        throw formats::InputError(path + ": not valid JSON (byte " + std::to_string(e.byte) + "): " + e.what());
      }
      if (j.is_object() && j.contains("modes")) {  // ssid identify modes --json
        d = parse_identified_modes(j, path);
        if (frequencies_only) {
          d.modes.dofs.clear();
          d.modes.shapes.resize(0, static_cast<Eigen::Index>(d.modes.frequency_hz.size()));
          d.node_keys.clear();
        }
        return d;
      }
    }
    d.modes = parse_frequency_list(ss.str(), path, ends_with(".json"));
    return d;
  }
  const formats::uff::UffFile file = formats::uff::read_uff(path);
  translators::ModeSetReport rep;
  d.modes = translators::modes_from_uff(file, &rep);
  for (const auto& pr : rep.problems) d.notes.push_back(path + ": " + pr);
  if (rep.complex_modes)
    d.notes.push_back(path + ": " + std::to_string(rep.complex_modes) +
                      " complex mode(s) read and not used (the update uses real normal modes)");
  if (d.modes.frequency_hz.empty())
    throw formats::InputError(path + ": no real normal modes (dataset 55, analysis type 2) to estimate from");
  d.nodes = translators::test_nodes(file);
  d.trace_lines = translators::trace_segments(file);
  if (frequencies_only) {
    d.modes.dofs.clear();
    d.modes.shapes.resize(0, static_cast<Eigen::Index>(d.modes.frequency_hz.size()));
    d.nodes.clear();
  }
  return d;
}

std::vector<ConfigurationSource> load_configurations(const Study& study, const std::string& deck,
                                                     const std::string& measured) {
  std::vector<StudyConfiguration> configs = study.configurations;
  if (configs.empty()) configs.push_back({"", "", "", std::nullopt});
  std::vector<ConfigurationSource> out;
  for (auto& c : configs) {
    if (c.deck.empty()) c.deck = deck;
    if (c.measured.empty()) c.measured = measured;
    if (c.deck.empty())
      throw formats::InputError(study.source + ": configuration '" + c.name + "' names no deck and none was given");
    if (c.measured.empty())
      throw formats::InputError(study.source + ": configuration '" + c.name +
                                  "' names no measured universal file and none was given");
    // A missing deck is named before its measured file is read.
    if (!std::ifstream(c.deck)) throw formats::InputError(c.deck + ": cannot open the deck");
    ConfigurationSource src;
    src.name = c.name;
    src.deck = c.deck;
    src.measured = c.measured;
    src.data = read_measured(c.measured, study.frequencies_only);
    src.analysis_modes = c.analysis_modes;
    out.push_back(std::move(src));
  }
  return out;
}

EstimationProblem prepare_problem(const Study& study, const std::string& deck, const std::string& measured) {
  return prepare_problem(study, load_configurations(study, deck, measured));
}

EstimationProblem prepare_problem(const Study& study, const std::vector<ConfigurationSource>& configs) {
  EstimationProblem problem;
  set_options(study, problem);
  std::vector<std::string> labels;  // upper case
  for (const auto& fp : study.pairs)
    if (!fp.configuration.empty() &&
        std::none_of(configs.begin(), configs.end(), [&](const ConfigurationSource& c) { return c.name == fp.configuration; }))
      throw formats::InputError(study.source + ": pairs: no configuration named '" + fp.configuration + "'");
  for (std::size_t k = 0; k < configs.size(); ++k) {
    const auto& sc = configs[k];
    const std::string who = sc.name.empty() ? sc.deck : "configuration '" + sc.name + "' (" + sc.deck + ")";
    const LoadedDeck ld = sc.deck_text.empty() ? load_deck(sc.deck) : load_deck_text(sc.deck_text, sc.deck);
    const auto& params = ld.fe->parameters();
    if (params.empty())
      throw formats::InputError(sc.deck + ": the deck has no DESVAR: nothing to estimate (add DESVAR and "
                                  "DVPREL1/DVMREL1 cards for the parameters)");
    if (k == 0) labels = estimated_labels(study, params);
    const std::vector<std::size_t> index = parameter_indices(labels, params, sc.deck);
    if (k == 0) set_prior(study, labels, index, ld, problem);

    PreparedConfiguration pc;
    pc.name = sc.name;
    pc.deck = sc.deck;
    pc.measured = sc.measured;
    pc.notes = sc.data.notes;
    if (sc.data.modes.frequency_hz.empty())
      throw formats::InputError(sc.measured + ": no measured mode to estimate from");
    const ShapeRows shape_rows = map_sensors(study, sc, *ld.fe, pc);
    pc.shape_rows = shape_rows;
    select_measured_modes(study, sc, k, who, shape_rows, pc);
    attach_model(study, sc, who, ld, index, problem, pc);
    problem.configurations.push_back(std::move(pc));
  }
  problem.measurement_std = measurement_std_text(study, problem.configurations);
  return problem;
}

formats::ProblemFile to_problem_file(const EstimationProblem& problem) {
  formats::ProblemFile f;
  f.title = problem.title;
  const auto p = problem.prior.mean.size();
  for (Eigen::Index j = 0; j < p; ++j) {
    formats::ProblemParameter q;
    q.name = problem.prior.names[static_cast<std::size_t>(j)];
    q.desvar = j < static_cast<Eigen::Index>(problem.desvar_ids.size()) ? problem.desvar_ids[static_cast<std::size_t>(j)] : 0;
    q.initial = problem.prior.mean(j);
    q.prior_std = std::sqrt(problem.prior.cov(j, j));
    q.lower = std::isfinite(problem.prior.lower(j)) ? problem.prior.lower(j) : -1e20;
    q.upper = std::isfinite(problem.prior.upper(j)) ? problem.prior.upper(j) : 1e20;
    f.parameters.push_back(q);
  }
  const Eigen::VectorXd sd = problem.prior.cov.diagonal().array().sqrt();
  const Eigen::MatrixXd corr = sd.asDiagonal().inverse() * problem.prior.cov * sd.asDiagonal().inverse();
  if (!corr.isIdentity(0.0)) f.prior_correlation = corr;
  f.options.max_iterations = problem.options.max_iterations;
  f.options.tolerance = problem.options.tolerance;
  f.options.mac_min = problem.options.mac_min;
  f.options.freq_tol_pct = problem.options.freq_tol_pct;
  f.options.track_mac_min = problem.options.track_mac_min;
  f.options.shape_derivatives = problem.options.shape_derivatives;
  f.options.operators = "taylor";
  bool modal_sum = false;
  for (const auto& c : problem.configurations) {
    auto* om = dynamic_cast<OperatorModel*>(c.model.get());
    modal_sum = modal_sum || (om && om->shape_derivative() == ShapeDerivative::ModalSum);
    formats::ProblemConfiguration pc;
    pc.name = c.name;
    pc.deck = c.deck;
    pc.dofs = c.dofs;
    pc.sensor_labels = c.sensor_labels;
    pc.sensors = c.sensors;
    if (!c.assemble) throw std::invalid_argument("translate: configuration '" + c.name + "' has no operators");
    Operators op = c.assemble(problem.prior.mean);
    op.K.makeCompressed();
    op.M.makeCompressed();
    for (auto& d : op.dK) d.makeCompressed();
    for (auto& d : op.dM) d.makeCompressed();
    pc.K = std::move(op.K);
    pc.M = std::move(op.M);
    pc.dK = std::move(op.dK);
    pc.dM = std::move(op.dM);
    for (std::size_t m = 0; m < c.test.size(); ++m) {
      const auto& t = c.test[m];
      formats::ProblemMode pm;
      pm.id = t.id;
      pm.frequency_hz = t.frequency_hz;
      pm.frequency_std_hz = t.frequency_std_hz;
      pm.shape = t.shape;
      pm.shape_std = t.shape_std;
      pm.use_frequency = t.use_frequency;
      pm.use_shape = t.use_shape;
      pc.measured.push_back(pm);
    }
    pc.modes = c.analysis_modes;
    f.configurations.push_back(std::move(pc));
  }
  f.options.shape_derivative = modal_sum ? "modal-sum" : "nelson";
  return f;
}

EstimationProblem problem_from_file(const formats::ProblemFile& file) {
  EstimationProblem problem;
  problem.title = file.title;
  problem.operators = "taylor";
  const auto p = static_cast<Eigen::Index>(file.parameters.size());
  if (p == 0) throw formats::InputError("problem file: no parameters");
  problem.prior.mean.resize(p);
  problem.prior.lower.resize(p);
  problem.prior.upper.resize(p);
  Eigen::VectorXd sd(p);
  for (Eigen::Index j = 0; j < p; ++j) {
    const auto& q = file.parameters[static_cast<std::size_t>(j)];
    problem.prior.names.push_back(q.name);
    problem.desvar_ids.push_back(q.desvar);
    problem.prior.mean(j) = q.initial;
    problem.prior.lower(j) = q.lower <= -1e19 ? -INFINITY : q.lower;
    problem.prior.upper(j) = q.upper >= 1e19 ? INFINITY : q.upper;
    sd(j) = q.prior_std;
  }
  const Eigen::MatrixXd corr = file.prior_correlation.size() ? file.prior_correlation : Eigen::MatrixXd::Identity(p, p);
  problem.prior.cov = sd.asDiagonal() * corr * sd.asDiagonal();
  problem.options.max_iterations = file.options.max_iterations;
  problem.options.tolerance = file.options.tolerance;
  problem.options.mac_min = file.options.mac_min;
  problem.options.freq_tol_pct = file.options.freq_tol_pct;
  problem.options.track_mac_min = file.options.track_mac_min;
  problem.options.shape_derivatives = file.options.shape_derivatives;
  const ShapeDerivative sdk = file.options.shape_derivative == "modal-sum" ? ShapeDerivative::ModalSum : ShapeDerivative::Nelson;
  for (const auto& c : file.configurations) {
    PreparedConfiguration pc;
    pc.name = c.name;
    pc.deck = c.deck;
    pc.dofs = c.dofs;
    pc.sensor_labels = c.sensor_labels;
    pc.sensors = c.sensors;
    pc.analysis_modes = c.modes;
    for (const auto& m : c.measured) {
      MeasuredMode mm;
      mm.id = m.id;
      mm.frequency_hz = m.frequency_hz;
      mm.frequency_std_hz = m.frequency_std_hz;
      mm.shape = m.shape;
      mm.shape_std = m.shape_std;
      mm.use_frequency = m.use_frequency;
      mm.use_shape = m.use_shape;
      pc.test.push_back(mm);
      pc.test_numbers.push_back(m.id);
      pc.test_damping.push_back(0.0);
      pc.std_from.push_back("problem file");
    }
    const std::string who = "configuration '" + c.name + "'";
    if (file.options.operators == "exact") {
      // Re-assemble the deck the file names (path as stored), on the same DOFs.
      LoadedDeck ld = load_deck(c.deck);
      const auto& params = ld.fe->parameters();
      std::vector<std::size_t> index;
      for (const auto& q : file.parameters) {
        std::size_t found = params.size();
        for (std::size_t j = 0; j < params.size(); ++j)
          if (params[j].id == q.desvar) found = j;
        if (found == params.size())
          throw formats::InputError(c.deck + ": no DESVAR " + std::to_string(q.desvar) + " (" + q.name +
                                      ") that the problem file's " + who + " needs");
        index.push_back(found);
      }
      std::vector<std::pair<std::int64_t, int>> dofs;
      for (std::size_t a : ld.fe->reduction().a_to_g) {
        const auto& d = ld.fe->geometry().gset().at(a);
        dofs.emplace_back(d.point, d.component);
      }
      if (dofs != c.dofs)
        throw formats::InputError(c.deck + ": its analysis DOFs differ from those of the problem file's " + who +
                                    " (the deck changed since the file was written?)");
      Eigen::VectorXd x_fixed = ld.fe->initial_parameters();
      for (std::size_t j = 0; j < index.size(); ++j)
        x_fixed(static_cast<Eigen::Index>(index[j])) = problem.prior.mean(static_cast<Eigen::Index>(j));
      auto exact = exact_assembly(ld.fe, x_fixed, index);
      auto deck_keep = ld.deck;
      pc.assemble = [exact, deck_keep](const Eigen::VectorXd& r) { return exact(r); };
      problem.operators = "exact";
    } else {
      Operators nominal{c.K, c.M, c.dK, c.dM};
      pc.assemble = taylor_operators(nominal, problem.prior.mean);
    }
    pc.model = std::make_shared<OperatorModel>(pc.assemble, make_eigen_solve(who), pc.sensors, c.modes, sdk);
    pc.model->set_tracking_on_sensors(true);  // the study's default (deck_study.hpp)
    problem.configurations.push_back(std::move(pc));
  }
  return problem;
}

// ---------------------------------------------------------------------------

EstimationResult run_problem(EstimationProblem& problem, const Progress& progress) {
  if (problem.configurations.empty()) throw std::invalid_argument("estimate: no configuration");
  EstimationResult out;
  out.initial = problem.prior.mean;
  out.prior_std = problem.prior.cov.diagonal().array().sqrt();
  const std::size_t nc = problem.configurations.size();
  auto conf = [&](std::size_t k) {
    const auto& c = problem.configurations[k];
    return Configuration{c.name, c.model.get(), c.test};
  };
  if (!problem.recursive || nc == 1) {
    std::vector<Configuration> all;
    for (std::size_t k = 0; k < nc; ++k) all.push_back(conf(k));
    out.update = update(all, problem.prior, problem.options, progress);
    out.stages.push_back(out.update);
  } else {
    ParameterPrior prior = problem.prior;
    for (std::size_t k = 0; k < nc; ++k) {
      UpdateResult r;
      try {
        report(progress, "recursive stage", static_cast<long>(k), static_cast<long>(nc),
               "'" + problem.configurations[k].name + "'");
        r = update(std::vector<Configuration>{conf(k)}, prior, problem.options, progress);
      } catch (const Interrupted& ex) {
        if (out.stages.empty()) throw;
        out.interrupted = true;
        out.partial_reason = std::string(ex.what()) + " before recursive stage " + std::to_string(k + 1) + " of " +
                             std::to_string(nc) + " ('" + problem.configurations[k].name + "')";
        break;
      }
      for (auto& c : r.history)
        for (auto& q : c.pairs) q.config = static_cast<int>(k);
      for (auto& d : r.dropped) d.config = static_cast<int>(k);
      prior = posterior_as_prior(r, prior);
      const bool stopped = !r.stopped.empty();
      out.stages.push_back(std::move(r));
      if (stopped) break;  // later stages would start from a posterior that is not one
    }
    out.update = out.stages.back();
    out.update.final_solutions.clear();
  }
  // Why the result is partial, if it is.
  for (std::size_t s = 0; s < out.stages.size() && out.partial_reason.empty(); ++s) {
    const UpdateResult& st = out.stages[s];
    const std::string stage = out.stages.size() > 1 || nc > 1 ? "stage " + std::to_string(s + 1) + ": " : "";
    if (!st.stopped.empty()) {
      out.interrupted = st.interrupted;
      out.partial_reason = stage + st.stopped + (st.interrupted ? " after " : " (after ") +
                           std::to_string(st.history.size()) + (st.interrupted ? " cycle(s)" : " cycle(s))");
    } else if (!st.converged) {
      out.partial_reason = stage + "not converged after " + std::to_string(st.history.size()) + " cycle(s)";
    }
  }
  if (out.partial_reason.empty() && problem.recursive && out.stages.size() < nc)
    out.partial_reason = "recursive stages " + std::to_string(out.stages.size() + 1) + " to " + std::to_string(nc) +
                         " not run";
  const auto& u = out.update;
  // Correlation of every configuration at the answer.
  for (std::size_t k = 0; k < nc; ++k) {
    ModalSolution s;
    if (k < u.final_solutions.size() && (!problem.recursive || nc == 1)) s = u.final_solutions[k];
    else s = problem.configurations[k].model->solve(u.r);
    const auto& test = problem.configurations[k].test;
    Eigen::MatrixXd mac = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(test.size()), s.eigenvalues.size());
    for (std::size_t t = 0; t < test.size(); ++t)
      if (test[t].shape.size() == s.sensor_shapes.rows() && test[t].shape.size())
        mac.row(static_cast<Eigen::Index>(t)) = mac_matrix(test[t].shape, s.sensor_shapes).row(0);
    out.mac.push_back(mac);
    out.fe_hz.push_back(s.eigenvalues.unaryExpr(&eigenvalue_to_hz));
  }
  const auto& id = u.identifiability;
  for (Eigen::Index j = 0; j < id.std_ratio.size(); ++j)
    if (id.std_ratio(j) > problem.uninformed_ratio) out.uninformed.push_back(static_cast<int>(j));
  for (Eigen::Index a = 0; a < id.correlation.rows(); ++a)
    for (Eigen::Index b = a + 1; b < id.correlation.cols(); ++b)
      if (std::abs(id.correlation(a, b)) > problem.strong_correlation)
        out.correlated.push_back({static_cast<int>(a), static_cast<int>(b), id.correlation(a, b)});
  return out;
}

namespace {

/// Final pairs of each configuration (recursive: from its own stage).
std::vector<UpdatePair> final_pairs(const EstimationProblem& problem, const EstimationResult& r) {
  std::vector<UpdatePair> pairs;
  if (problem.recursive && problem.configurations.size() > 1) {
    for (const auto& s : r.stages) pairs.insert(pairs.end(), s.history.back().pairs.begin(), s.history.back().pairs.end());
  } else {
    pairs = r.update.history.back().pairs;
  }
  return pairs;
}

std::vector<int> unpaired_test(const EstimationProblem& problem, const std::vector<UpdatePair>& pairs, std::size_t k) {
  std::vector<int> out;
  const auto& c = problem.configurations[k];
  for (std::size_t t = 0; t < c.test.size(); ++t)
    if (std::none_of(pairs.begin(), pairs.end(),
                     [&](const UpdatePair& q) { return q.config == static_cast<int>(k) && q.test == static_cast<int>(t); }))
      out.push_back(c.test_numbers[t]);
  return out;
}

/// Analysis modes up to 1.1 × the highest measured frequency without a partner (1-based).
std::vector<int> unpaired_fe(const EstimationProblem& problem, const EstimationResult& r,
                             const std::vector<UpdatePair>& pairs, std::size_t k) {
  std::vector<int> out;
  double fmax = 0;
  for (const auto& t : problem.configurations[k].test) fmax = std::max(fmax, t.frequency_hz);
  const auto& hz = r.fe_hz[k];
  for (Eigen::Index i = 0; i < hz.size(); ++i) {
    if (hz(i) > 1.1 * fmax) break;
    if (std::none_of(pairs.begin(), pairs.end(),
                     [&](const UpdatePair& q) { return q.config == static_cast<int>(k) && q.fem == static_cast<int>(i); }))
      out.push_back(static_cast<int>(i) + 1);
  }
  return out;
}

json matrix_json(const Eigen::MatrixXd& m) {
  json j = json::array();
  for (Eigen::Index i = 0; i < m.rows(); ++i) {
    json row = json::array();
    for (Eigen::Index k = 0; k < m.cols(); ++k) row.push_back(m(i, k));
    j.push_back(row);
  }
  return j;
}

}  // namespace

json result_json(const EstimationProblem& problem, const EstimationResult& r) {
  const auto& u = r.update;
  const auto& names = problem.prior.names;
  json j;
  if (!problem.title.empty()) j["title"] = problem.title;
  j["converged"] = !r.partial();
  j["partial"] = r.partial();
  if (r.partial()) j["partial_reason"] = r.partial_reason;
  j["operators"] = problem.operators;
  j["recursive"] = problem.recursive && problem.configurations.size() > 1;
  j["iterations"] = json::array();
  for (std::size_t s = 0; s < r.stages.size(); ++s)
    for (const auto& c : r.stages[s].history) {
      json it;
      if (r.stages.size() > 1) it["stage"] = s + 1;
      it["cycle"] = c.cycle;
      json pv = json::object();
      for (std::size_t k = 0; k < names.size(); ++k) pv[names[k]] = c.r(static_cast<Eigen::Index>(k));
      it["parameters"] = pv;
      it["objective"] = c.objective;
      it["misfit"] = c.misfit;
      it["frequency_rms_pct"] = c.freq_rms_pct;
      it["mean_mac"] = c.mean_mac;
      it["pairs"] = c.pairs.size();
      it["bound_active"] = c.clipped;
      j["iterations"].push_back(it);
    }
  j["parameters"] = json::array();
  for (std::size_t k = 0; k < names.size(); ++k) {
    const auto e = static_cast<Eigen::Index>(k);
    json p = {{"name", names[k]},
              {"initial", r.initial(e)},
              {"estimate", u.r(e)},
              {"prior_std", r.prior_std(e)},
              {"posterior_std", u.posterior_std(e)}};
    if (k < problem.desvar_ids.size()) p["desvar"] = problem.desvar_ids[k];
    p["change_pct"] = r.initial(e) != 0 ? (u.r(e) - r.initial(e)) / std::abs(r.initial(e)) * 100.0 : 0.0;
    p["std_ratio"] = u.identifiability.std_ratio.size() ? u.identifiability.std_ratio(e) : 1.0;
    p["lower"] = std::isfinite(problem.prior.lower(e)) ? json(problem.prior.lower(e)) : json(nullptr);
    p["upper"] = std::isfinite(problem.prior.upper(e)) ? json(problem.prior.upper(e)) : json(nullptr);
    if (k < problem.units.size()) {
      p["unit"] = problem.units[k].unit;
      p["designs"] = problem.units[k].designs;
    }
    j["parameters"].push_back(p);
  }
  if (!problem.units_note.empty()) j["units"] = problem.units_note;
  {
    const UpdateCycle& last = u.history.back();
    j["frequency_rms_pct"] = last.freq_rms_pct;
    j["objective"] = {{"J", last.objective},
                      {"data_misfit", last.misfit},
                      {"prior_term", last.objective - last.misfit},
                      {"meaning", "J = sum of ((measured - predicted) / std)^2 over the measurements + the same for the "
                                  "parameters' distance from their prior means (docs/updating.md, Eq. (7))"}};
  }
  j["posterior_covariance"] = matrix_json(u.posterior_cov);
  {  // The measurement σ of each test mode, and where it came from.
    json mj = {{"std_from", problem.measurement_std}, {"modes", json::array()}};
    for (const auto& c : problem.configurations)
      for (std::size_t i = 0; i < c.test.size(); ++i) {
        json t = {{"test_mode", c.test_numbers[i]},
                  {"hz", c.test[i].frequency_hz},
                  {"frequency_std_hz", c.test[i].frequency_std_hz},
                  {"shape_std", c.test[i].shape_std},
                  {"from", i < c.std_from.size() ? c.std_from[i] : "study"}};
        if (problem.configurations.size() > 1) t["configuration"] = c.name;
        mj["modes"].push_back(t);
      }
    j["measurement"] = mj;
  }

  const auto pairs = final_pairs(problem, r);
  auto pair_json = [&](const UpdatePair& q) {
    const auto& c = problem.configurations[static_cast<std::size_t>(q.config)];
    json pj = {{"fe_mode", q.fem + 1},
               {"test_mode", c.test_numbers[static_cast<std::size_t>(q.test)]},
               {"fe_hz", q.fem_hz},
               {"test_hz", q.test_hz},
               {"error_pct", q.error_pct},
               {"mac", q.mac}};
    if (problem.configurations.size() > 1) pj["configuration"] = c.name;
    return pj;
  };
  j["pairs"] = json::array();
  for (const auto& q : pairs) j["pairs"].push_back(pair_json(q));
  // The pairs of the first cycle: the model before the update, to compare with.
  j["initial_pairs"] = json::array();
  for (const auto& q : r.stages.front().history.front().pairs) j["initial_pairs"].push_back(pair_json(q));
  j["correlation"] = matrix_json(r.mac.front());
  j["unpaired_test"] = unpaired_test(problem, pairs, 0);
  j["unpaired_fe"] = unpaired_fe(problem, r, pairs, 0);
  j["configurations"] = json::array();
  for (std::size_t k = 0; k < problem.configurations.size(); ++k) {
    const auto& c = problem.configurations[k];
    json cj = {{"name", c.name}, {"deck", c.deck}, {"measured", c.measured}, {"sensors", c.sensor_labels.size()},
               {"analysis_modes", c.analysis_modes}, {"test_modes", c.test_numbers}};
    cj["correlation"] = matrix_json(r.mac[k]);
    std::vector<double> hz(r.fe_hz[k].data(), r.fe_hz[k].data() + r.fe_hz[k].size());
    cj["fe_hz"] = hz;
    std::vector<double> test_hz;
    for (const auto& m : c.test) test_hz.push_back(m.frequency_hz);
    cj["test_hz"] = test_hz;  // of "test_modes", the rows of "correlation"
    cj["pairs"] = json::array();
    for (const auto& q : pairs)
      if (q.config == static_cast<int>(k)) cj["pairs"].push_back(pair_json(q));
    cj["unpaired_test"] = unpaired_test(problem, pairs, k);
    cj["unpaired_fe"] = unpaired_fe(problem, r, pairs, k);
    cj["notes"] = c.notes;
    j["configurations"].push_back(cj);
  }
  j["dropped"] = json::array();
  for (const auto& s : r.stages)
    for (const auto& d : s.dropped) {
      const auto& c = problem.configurations[static_cast<std::size_t>(d.config)];
      j["dropped"].push_back({{"configuration", c.name},
                              {"test_mode", c.test_numbers[static_cast<std::size_t>(d.test)]},
                              {"cycle", d.cycle},
                              {"why", d.why}});
    }
  const auto& id = u.identifiability;
  json ij;
  ij["parameters"] = names.size();
  ij["measurements"] = u.measurements;
  ij["rank"] = id.rank;
  ij["condition"] = std::isfinite(id.condition) ? json(id.condition) : json(nullptr);
  std::vector<double> sv(id.singular_values.data(), id.singular_values.data() + id.singular_values.size());
  ij["singular_values"] = sv;
  ij["uninformed"] = json::array();
  for (int k : r.uninformed) ij["uninformed"].push_back(names[static_cast<std::size_t>(k)]);
  ij["strongly_correlated"] = json::array();
  for (const auto& c : r.correlated)
    ij["strongly_correlated"].push_back({names[static_cast<std::size_t>(c.a)], names[static_cast<std::size_t>(c.b)], c.rho});
  ij["posterior_correlation"] = matrix_json(id.correlation);
  j["identifiability"] = ij;
  j["log_evidence"] = u.log_evidence;
  std::vector<std::string> notes = problem.notes;
  for (const auto& s : r.stages) notes.insert(notes.end(), s.notes.begin(), s.notes.end());
  j["notes"] = notes;
  return j;
}

std::string format_summary(const EstimationProblem& problem, const EstimationResult& r) {
  const auto& u = r.update;
  std::ostringstream o;
  std::size_t cycles = 0;
  for (const auto& s : r.stages) cycles += s.history.size();
  const std::string how = problem.recursive && problem.configurations.size() > 1
                              ? " (recursive, " + std::to_string(r.stages.size()) + " of " +
                                    std::to_string(problem.configurations.size()) + " stages)"
                              : "";
  if (!r.partial()) o << "converged after " << cycles << " cycle(s)" << how;
  else if (r.interrupted) o << "INTERRUPTED after " << cycles << " cycle(s)" << how;
  else if (r.partial_reason.find("not converged") != std::string::npos)
    o << "NOT converged after " << cycles << " cycle(s)" << how;
  else o << "STOPPED after " << cycles << " cycle(s)" << how;
  o << "; operators " << problem.operators << "\n";
  if (r.partial())
    o << "PARTIAL RESULT (" << r.partial_reason << "): the values below are those of the last accepted cycle, not an "
      << "estimate to trust\n";
  if (!problem.measurement_std.empty()) o << "measurement σ: " << problem.measurement_std << "\n";
  o << "\n";

  // Parameters, with what each designs and its unit.
  const bool with_units = problem.units.size() == problem.prior.names.size();
  o << "parameter            initial        estimate     prior std   posterior std  change %";
  if (with_units) o << "  unit            designs";
  o << "\n";
  for (std::size_t k = 0; k < problem.prior.names.size(); ++k) {
    const auto e = static_cast<Eigen::Index>(k);
    const double ch = r.initial(e) != 0 ? (u.r(e) - r.initial(e)) / std::abs(r.initial(e)) * 100.0 : 0.0;
    o << std::left << std::setw(16) << problem.prior.names[k] << std::right << std::setw(13) << significant(r.initial(e), 6)
      << std::setw(16) << significant(u.r(e), 8) << std::setw(14) << significant(r.prior_std(e), 4) << std::setw(16)
      << significant(u.posterior_std(e), 4) << std::setw(10) << fixed(ch, 2);
    if (with_units) {
      const auto& pu = problem.units[k];
      o << "  " << std::left << std::setw(15) << (pu.unit.empty() ? "?" : pu.unit) << " "
        << (pu.designs.empty() ? "(designs no field)" : pu.designs) << std::right;
    }
    o << "\n";
  }
  if (with_units)
    o << "  units: " << problem.units_note
      << "; a parameter has the unit of the fields it designs (DVPREL1/DVMREL1), or is a dimensionless scale "
         "factor of them when its XINIT is 1 and no coefficient is 1\n";
  else
    o << "  units: those of the deck the problem file was made from\n";

  // Pairs: frequencies to 7 significant digits, so that any error the error
  // column shows (0.001 % resolution) is visible in the frequencies too.
  const auto pairs = final_pairs(problem, r);
  for (std::size_t k = 0; k < problem.configurations.size(); ++k) {
    const auto& c = problem.configurations[k];
    o << "\npairs" << (c.name.empty() ? "" : " of '" + c.name + "'") << " at the estimate (" << c.sensor_labels.size()
      << " sensor DOFs):\n  FE mode    FE [Hz]  test mode  test [Hz]  error [%]     MAC\n";
    for (const auto& q : pairs) {
      if (q.config != static_cast<int>(k)) continue;
      o << "  " << std::setw(7) << q.fem + 1 << std::setw(11) << significant(q.fem_hz, 7) << std::setw(11)
        << c.test_numbers[static_cast<std::size_t>(q.test)] << std::setw(11) << significant(q.test_hz, 7) << std::setw(11)
        << fixed(q.error_pct, 3) << std::setw(8) << fixed(q.mac, 4) << "\n";
    }
    const auto ut = unpaired_test(problem, pairs, k), uf = unpaired_fe(problem, r, pairs, k);
    o << "  unpaired test modes:";
    if (ut.empty()) o << " none";
    for (int n : ut) o << " " << n;
    o << "; unpaired analysis modes (up to 1.1 x highest test frequency):";
    if (uf.empty()) o << " none";
    for (int n : uf) o << " " << n;
    o << "\n";
  }

  // The fit: frequency error and the objective J, at the start and at the estimate.
  const UpdateCycle& first = r.stages.front().history.front();
  const UpdateCycle& last = u.history.back();
  double largest = 0;
  for (const auto& q : pairs) largest = std::max(largest, std::abs(q.error_pct));
  o << "\nfrequency error, RMS over the pairs: " << fixed(last.freq_rms_pct, 3) << " % at the estimate ("
    << last.pairs.size() << " pairs, largest " << fixed(largest, 3) << " %), " << fixed(first.freq_rms_pct, 3)
    << " % at the start (" << first.pairs.size() << " pairs); mean MAC " << fixed(last.mean_mac, 3) << " (start "
    << fixed(first.mean_mac, 3) << ")\n";
  o << "objective J = " << significant(last.objective, 6) << " at the estimate (start " << significant(first.objective, 6)
    << "): J = data misfit " << significant(last.misfit, 6) << " + prior term " << significant(last.objective - last.misfit, 4)
    << ", where the data misfit is the sum of ((measured - predicted) / std)^2 over the " << u.measurements
    << " measurements (frequencies and shape components) and the prior term the same for the parameters' "
       "distance from their prior means (docs/updating.md, Eq. (7)); dimensionless, about the number of "
       "measurements when the model fits within the measurement noise\n";

  const auto& id = u.identifiability;
  o << "\nidentifiability: rank " << id.rank << " of " << problem.prior.names.size() << " parameters, condition "
    << significant(id.condition, 4) << ", " << u.measurements << " measurements\n";
  if (!r.uninformed.empty()) {
    o << "  not informed by the data (posterior std > " << problem.uninformed_ratio << " x prior std):";
    for (int k : r.uninformed) o << " " << problem.prior.names[static_cast<std::size_t>(k)];
    o << "\n";
  }
  for (const auto& c : r.correlated)
    o << "  strongly correlated: " << problem.prior.names[static_cast<std::size_t>(c.a)] << " and "
      << problem.prior.names[static_cast<std::size_t>(c.b)] << " (rho = " << significant(c.rho, 3) << ")\n";
  std::vector<std::string> notes = problem.notes;
  for (const auto& c : problem.configurations) notes.insert(notes.end(), c.notes.begin(), c.notes.end());
  for (const auto& s : r.stages) notes.insert(notes.end(), s.notes.begin(), s.notes.end());
  if (!notes.empty()) {
    o << "\nnotes:\n";
    for (const auto& n : notes) o << "  " << n << "\n";
  }
  return o.str();
}

}  // namespace ssid::estimator
