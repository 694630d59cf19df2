/// \file cmd_pretest.cpp
/// `ssid pretest DECK`: pretest planning (issue 23): target modes, sensor
/// placement (EI, KE, AKE, EVP), test-analysis models on the sensor set
/// (Guyan, SEREP, IRS) with the cross-orthogonality check, and exciter placement
/// (MIF drop-offs and the genetic algorithm), and with --evaluate the simulated
/// impulse test of the placement (ERA, issue 23 item 5); the picture (--svg),
/// the sensors and the test wire frame as UFF 15 + 82 (--uff) and the report
/// (--report, issue 24).
#include <Eigen/Geometry>
#include <Eigen/SparseCore>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <iterator>
#include <algorithm>
#include <map>
#include <optional>
#include <set>
#include <sstream>

#include "cli/cli_util.hpp"
#include "cli/exit_codes.hpp"
#include "cli/model_load.hpp"
#include "cli/report/pretest_picture.hpp"
#include "cli/report/report_data.hpp"
#include "estimator/correlation/measures.hpp"
#include "estimator/pretest/evaluation.hpp"
#include "estimator/pretest/exciter_placement.hpp"
#include "estimator/pretest/measurement_coordinates.hpp"
#include "estimator/pretest/model_error.hpp"
#include "estimator/pretest/sensor_placement.hpp"
#include "estimator/pretest/tam.hpp"
#include "estimator/pretest/targets.hpp"
#include "formats/parse_error.hpp"
#include "formats/uff.hpp"
#include "translators/synthetic_modes.hpp"

namespace ssid::cli {

namespace pt = estimator::pretest;

namespace {

pt::PlacementMethod parse_method(const std::string& s) {
  if (s == "ei") return pt::PlacementMethod::EffectiveIndependence;
  if (s == "ke") return pt::PlacementMethod::KineticEnergy;
  if (s == "ake") return pt::PlacementMethod::AverageKineticEnergy;
  if (s == "evp") return pt::PlacementMethod::EigenvectorProduct;
  if (s == "evp-sum") return pt::PlacementMethod::EigenvectorSum;
  throw formats::InputError("--method: expected ei, ke, ake, evp or evp-sum, got \"" + s + "\"");
}

/// "GRID:X,Y,Z" → the grid and the vector (not normalised, not zero), for `option`.
std::pair<std::int64_t, Eigen::Vector3d> parse_grid_direction(const std::string& text, const std::string& option) {
  const auto colon = text.find(':');
  const std::string what = option + " \"" + text + "\": ";
  if (colon == std::string::npos) throw formats::InputError(what + "expected GRID:X,Y,Z");
  std::int64_t grid = 0;
  Eigen::Vector3d d;
  try {
    std::size_t used = 0;
    grid = std::stoll(text.substr(0, colon), &used);
    if (used != colon) throw std::invalid_argument("grid");
    std::stringstream ss(text.substr(colon + 1));
    std::string item;
    int k = 0;
    while (std::getline(ss, item, ',')) {
      if (k == 3) throw std::invalid_argument("count");
      std::size_t u = 0;
      d(k++) = std::stod(item, &u);
      if (u != item.size()) throw std::invalid_argument("number");
    }
    if (k != 3) throw std::invalid_argument("count");
  } catch (const std::logic_error&) {
    throw formats::InputError(what + "expected GRID:X,Y,Z (a grid id and three direction cosines)");
  }
  if (d.norm() == 0) throw formats::InputError(what + "the direction is the zero vector");
  return {grid, d};
}

/// "GRID:X,Y,Z" → an exciter on that grid (direction normalised).
pt::Exciter parse_exciter(const std::string& text, const std::map<std::int64_t, int>& group_of) {
  const auto [grid, d] = parse_grid_direction(text, "--exciter-at");
  const auto it = group_of.find(grid);
  if (it == group_of.end())
    throw formats::InputError("--exciter-at \"" + text + "\": grid " + std::to_string(grid) + " is not a candidate grid");
  return {it->second, d.normalized()};
}

std::string fmt(double v, int prec = 4) {
  std::ostringstream o;
  o << std::setprecision(prec) << v;
  return o.str();
}

nlohmann::json matrix_rows(const Eigen::MatrixXd& X) {
  nlohmann::json j = nlohmann::json::array();
  for (Eigen::Index i = 0; i < X.rows(); ++i) {
    std::vector<double> r(static_cast<std::size_t>(X.cols()));
    for (Eigen::Index k = 0; k < X.cols(); ++k) r[static_cast<std::size_t>(k)] = X(i, k);
    j.push_back(r);
  }
  return j;
}

/// The "evaluation" object of the JSON (issue 23 item 7 names the first three keys).
nlohmann::json evaluation_json(const estimator::pretest::PlacementEvaluation& ev,
                               const std::vector<Eigen::Index>& target_cols, const Eigen::VectorXd& hz,
                               const estimator::pretest::SimulatedTestOptions& so) {
  auto num = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); };
  nlohmann::json e;
  e["identified"] = ev.identified_count;
  e["max_frequency_error_pct"] = num(ev.max_frequency_error_pct);
  e["max_offdiagonal_xor"] = num(ev.max_offdiagonal_xor);
  e["min_diagonal_xor"] = num(ev.min_diagonal_xor);
  e["targets"] = nlohmann::json::array();
  for (std::size_t t = 0; t < ev.targets.size(); ++t) {
    const auto& tm = ev.targets[t];
    nlohmann::json x{{"mode", target_cols[t] + 1}, {"fe_hz", hz(static_cast<Eigen::Index>(t))}, {"identified", tm.identified}};
    if (tm.identified) {
      x["hz"] = tm.hz;
      x["damping_ratio"] = tm.zeta;
      x["frequency_error_pct"] = tm.frequency_error_pct;
      x["mac"] = tm.mac;
    }
    e["targets"].push_back(x);
  }
  e["stable_modes"] = ev.identified.size();
  if (ev.xor_status == estimator::ReductionStatus::Ok) {
    e["xor"] = matrix_rows(ev.xor_matrix);
    std::vector<Eigen::Index> rows;
    for (int r : ev.xor_rows) rows.push_back(target_cols[static_cast<std::size_t>(r)] + 1);
    e["xor_rows"] = rows;
  } else {
    e["xor_message"] = ev.xor_message;
  }
  e["test"] = {{"dt", ev.dt}, {"samples", ev.samples}, {"bandwidth_hz", ev.bandwidth_hz},
               {"response_modes", ev.response_modes}, {"era_orders", {ev.orders.front(), ev.orders.back()}},
               {"noise_pct", so.noise_pct}, {"noise_seed", so.seed}, {"adc_bits", so.adc_bits},
               {"damping_ratio", so.damping}, {"match_frequency_tolerance", so.match_freq_tol},
               {"match_mac_min", so.match_mac_min}};
  return e;
}

/// The evaluation as text.
void print_evaluation(std::ostream& o, const char* title, const estimator::pretest::PlacementEvaluation& ev,
                      const std::vector<Eigen::Index>& target_cols, const Eigen::VectorXd& hz,
                      const estimator::pretest::SimulatedTestOptions& so) {
  o << "\n" << title << ": impulse responses of " << ev.response_modes << " mode(s) up to " << fmt(ev.bandwidth_hz)
    << " Hz, " << ev.samples << " samples every " << fmt(ev.dt * 1e3) << " ms, noise " << fmt(so.noise_pct)
    << " %, damping " << fmt(100 * so.damping) << " %; ERA orders " << ev.orders.front() << "…" << ev.orders.back()
    << ": " << ev.identified.size() << " stable mode(s)\n";
  o << "  mode   FE (Hz)  identified (Hz)  error (%)    MAC\n";
  for (std::size_t t = 0; t < ev.targets.size(); ++t) {
    const auto& tm = ev.targets[t];
    o << "  " << std::setw(4) << target_cols[t] + 1 << "  " << std::setw(8) << std::fixed << std::setprecision(3)
      << hz(static_cast<Eigen::Index>(t));
    if (tm.identified)
      o << "  " << std::setw(15) << tm.hz << "  " << std::setw(9) << std::setprecision(4) << tm.frequency_error_pct
        << "  " << std::setw(5) << std::setprecision(3) << tm.mac;
    else
      o << "  not identified";
    o << std::defaultfloat << "\n";
  }
  o << "  identified " << ev.identified_count << " of " << ev.targets.size() << " target(s)";
  if (ev.identified_count > 0) o << ", max frequency error " << fmt(ev.max_frequency_error_pct, 3) << " %";
  if (ev.xor_status != estimator::ReductionStatus::Ok)
    o << "; cross-orthogonality: SEREP failed: " << ev.xor_message;
  else if (ev.identified_count > 0)
    o << "; cross-orthogonality (SEREP mass): min diagonal " << fmt(ev.min_diagonal_xor, 3) << ", max off-diagonal "
      << fmt(ev.max_offdiagonal_xor, 3);
  o << "\n";
}

/// The displacement systems of the sensor grids for the UFF: per grid of the selected
/// sensors (`selected`, positions in `cand`) whose measured axes are not the basic ones,
/// a 2420 system (id = grid id) whose rows are those axes in basic — the grid's
/// displacement frame, or its selected given directions when they are mutually
/// orthogonal (completed to a right-handed frame). Sets each sensor record's
/// "uff_direction" (±1..3 in its node's displacement system; `sensors` in selection
/// order; `frame_of`: each grid's displacement frame, columns its axes in basic). Returns the
/// systems and the grids whose given directions no frame holds.
std::pair<std::vector<formats::uff::Cs2420>, std::vector<std::int64_t>> sensor_systems(
    const std::vector<pt::CandidateDof>& cand, const std::vector<Eigen::Index>& selected,
    const std::map<std::int64_t, Eigen::Matrix3d>& frame_of, nlohmann::json& sensors) {
  std::map<std::int64_t, std::vector<std::size_t>> at;  // grid → positions in `selected`
  std::vector<std::int64_t> order;
  for (std::size_t i = 0; i < selected.size(); ++i) {
    const auto g = cand[static_cast<std::size_t>(selected[i])].dof.point;
    if (!at.count(g)) order.push_back(g);
    at[g].push_back(i);
  }
  std::vector<formats::uff::Cs2420> systems;
  std::vector<std::int64_t> unoriented;
  for (auto g : order) {
    const Eigen::Matrix3d& F = frame_of.at(g);
    Eigen::Matrix3d axes = F.transpose();  // rows: the displacement frame's axes in basic
    std::vector<int> code;
    std::vector<Eigen::Vector3d> given;
    for (auto i : at[g]) {
      const auto& c = cand[static_cast<std::size_t>(selected[i])];
      if (c.directed) given.push_back(F * c.direction);
      code.push_back(c.directed ? static_cast<int>(given.size()) : c.dof.component);
    }
    if (!given.empty()) {
      bool orthogonal = given.size() == at[g].size();  // a grid's sensors are all given or all not
      for (std::size_t a = 0; a < given.size() && orthogonal; ++a)
        for (std::size_t b = a + 1; b < given.size(); ++b) orthogonal = orthogonal && std::abs(given[a].dot(given[b])) < 1e-9;
      if (!orthogonal) {
        unoriented.push_back(g);
        for (auto i : at[g]) sensors[i]["uff_direction"] = nullptr;
        continue;
      }
      axes.row(0) = given[0].transpose();
      axes.row(1) = (given.size() > 1 ? given[1] : given[0].unitOrthogonal()).transpose();
      const Eigen::Vector3d x = axes.row(0).transpose(), y = axes.row(1).transpose();
      const Eigen::Vector3d z = x.cross(y);
      axes.row(2) = z.transpose();
      if (given.size() == 3 && z.dot(given[2]) < 0) code[2] = -3;  // a left-handed triple: the third along −Z
    }
    for (std::size_t k = 0; k < at[g].size(); ++k) sensors[at[g][k]]["uff_direction"] = code[k];
    if ((axes - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() < 1e-12) continue;  // the basic axes: system 0
    formats::uff::Cs2420 cs;
    cs.id = g;
    cs.name = "grid " + std::to_string(g) + " sensors";
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) cs.rows[static_cast<std::size_t>(r)][static_cast<std::size_t>(c)] = axes(r, c);
    systems.push_back(cs);
  }
  return {systems, unoriented};
}

}  // namespace

int cmd_pretest(const Args& args) {
  po::options_description desc("ssid pretest options");
  desc.add_options()("deck", po::value<std::string>()->required(), "NASTRAN input file (SOL 103 bulk data)")(
      "target-modes", po::value<int>()->required(), "N: the N lowest modes above --min-hz are the targets")(
      "min-hz", po::value<double>()->default_value(0.1, "0.1"),
      "F: targets lie strictly above F Hz (the default skips rigid-body modes)")(
      "sensors", po::value<int>()->required(), "S: the number of sensors (DOFs); a multiple of 3 with --triax")(
      "method", po::value<std::string>()->default_value("ei"),
      "ei (effective independence), ke (kinetic energy), ake (average kinetic energy), evp (eigenvector product) "
      "or evp-sum (absolute eigenvector sum)")(
      "triax", po::bool_switch(), "place S/3 triaxes (the three translations of a grid) instead of single DOFs")(
      "grids", po::value<std::string>(),
      "candidate grids, e.g. \"1:80\" (default: every grid with a translational DOF)")(
      "sensor-direction", po::value<std::vector<std::string>>()->composing(),
      "GRID:X,Y,Z: at GRID the candidate sensors measure along the given direction (in the grid's displacement "
      "frame) instead of along T1, T2, T3; repeat for up to three independent directions at a grid (with --triax: "
      "exactly three, a skewed triax); the grid joins the candidates")(
      "ke-mass", po::value<std::string>()->default_value("fe"),
      "ke/ake: the mass of the kinetic energy, fe (the FE mass) or guyan (reduced to the candidate DOFs)")(
      "exciters", po::value<int>()->default_value(0), "E: place E exciters with the GA over MIF drop-offs (0: none)")(
      "exciter-at", po::value<std::vector<std::string>>()->composing(),
      "evaluate a given exciter, GRID:X,Y,Z (repeat for several; compared with the GA's)")(
      "population", po::value<int>()->default_value(20), "GA population (the paper: 20)")(
      "generations", po::value<int>()->default_value(40), "GA generations (the paper: 40)")(
      "seed", po::value<std::uint64_t>()->default_value(1), "GA seed (same seed, same exciters)")(
      "damping", po::value<double>()->default_value(0.01, "0.01"),
      "modal damping ratio of every mode (the MIF's FRFs and --evaluate's simulated test)")(
      "frf-modes", po::value<int>(),
      "modes solved for (targets, rigid-body and the MIF's modal model; default max(3N, N + 12), at most the "
      "DOF count less one)")(
      "evaluate", po::bool_switch(),
      "judge the placement by a simulated impulse test at the exciters (full model, noise, ERA; docs/pretest.md)")(
      "noise", po::value<double>()->default_value(2.0, "2"),
      "--evaluate: noise standard deviation, % of each channel's RMS")(
      "noise-seed", po::value<std::uint64_t>()->default_value(1), "--evaluate: seed of the noise")(
      "perturb-areas", po::value<std::uint64_t>(),
      "SEED: rerun the placement on the model with a third of the struts' areas -20 % and a third +20 % (chosen by "
      "SEED) and report the sensors that change")(
      "json", po::value<std::string>(), "write every figure as JSON to this file ('-' for stdout)")(
      "uff", po::value<std::string>(),
      "write the sensor grids (and exciter grids) as UFF dataset 15 and the test wire frame joining the sensor grids "
      "as dataset 82 to this file")(
      "svg", po::value<std::string>(), "draw the structure with the sensors and exciters as SVG to this file")(
      "view", po::value<std::string>()->default_value("iso"), "--svg: view direction, iso, x, y or z (looking along it)")(
      "compare-methods", po::bool_switch(),
      "also place the sensors by every method (ei, ke, ake, evp, evp-sum) and report each one's Fisher figures")(
      "report", po::value<std::string>(),
      "write an HTML report (sensors and exciters, Fisher figures per method, cross-orthogonality, MIF/GA, the "
      "simulated test) to this file; the JSON then also holds the run, geometry and every method's placement "
      "(docs/report.md)");
  po::positional_options_description pos;
  pos.add("deck", 1);
  po::variables_map vm;
  int rc = 0;
  if (!parse_options(args,
                     "ssid pretest DECK --target-modes N [--min-hz F] --sensors S --method ei|ke|ake|evp|evp-sum "
                     "[--triax] [--grids LIST] [--sensor-direction GRID:X,Y,Z ...] [--exciters E] [--evaluate] [--perturb-areas SEED] [--json OUT] [--uff OUT.unv] [--svg OUT.svg] "
                     "[--view iso|x|y|z] [--report OUT.html]",
                     desc, pos, vm, rc))
    return rc;
  const int n_targets = vm["target-modes"].as<int>();
  const int n_sensors = vm["sensors"].as<int>();
  const bool triax = vm["triax"].as<bool>();
  const auto method = parse_method(vm["method"].as<std::string>());
  const int n_exciters = vm["exciters"].as<int>();
  const std::string ke_mass = vm["ke-mass"].as<std::string>();
  if (n_targets < 1) throw formats::InputError("--target-modes: expected at least 1, got " + std::to_string(n_targets));
  if (n_sensors < 1) throw formats::InputError("--sensors: expected at least 1, got " + std::to_string(n_sensors));
  if (triax && n_sensors % 3 != 0)
    throw formats::InputError("--sensors " + std::to_string(n_sensors) + " with --triax: expected a multiple of 3");
  if (ke_mass != "fe" && ke_mass != "guyan")
    throw formats::InputError("--ke-mass: expected fe or guyan, got \"" + ke_mass + "\"");
  if (n_exciters < 0) throw formats::InputError("--exciters: expected 0 or more, got " + std::to_string(n_exciters));
  const double zeta = vm["damping"].as<double>();
  if (!(zeta > 0 && zeta < 1)) throw formats::InputError("--damping: expected a ratio in (0, 1), got " + fmt(zeta));
  const bool evaluate = vm["evaluate"].as<bool>();
  const double noise_pct = vm["noise"].as<double>();
  if (!(noise_pct >= 0)) throw formats::InputError("--noise: expected a percentage ≥ 0, got " + fmt(noise_pct));
  if (evaluate && n_exciters == 0 && !vm.count("exciter-at"))
    throw formats::InputError("--evaluate: needs exciters (--exciters E for the GA's, or --exciter-at GRID:X,Y,Z)");
  const report::View view = report::view_named(vm["view"].as<std::string>(), "--view");
  const bool compare = vm["compare-methods"].as<bool>() || vm.count("report") > 0;  // the report shows every method

  // --- the model and its modes
  LoadedModel lm = load_model(vm["deck"].as<std::string>());
  print_model_notes(lm);
  const translators::FeModel& model = *lm.model;
  const translators::FeOperators op = model.operators(model.initial_parameters(), false);
  const long n = op.K.rows();
  int n_solve = vm.count("frf-modes") ? vm["frf-modes"].as<int>() : std::max(3 * n_targets, n_targets + 12);
  n_solve = static_cast<int>(std::min<long>(n_solve, n - 1));
  std::string source;
  estimator::EigenOptions eo = eigen_options(model, n_solve, n, source);
  const auto dofs = a_set_dofs(model);
  const estimator::EigenResult er = solve_model(op, eo, dofs);
  for (const auto& w : er.warnings) std::cerr << "warning: " << w << "\n";
  const double min_hz = vm["min-hz"].as<double>();
  const auto target_cols = pt::select_target_modes(er.eigenvalues, n_targets, min_hz);
  Eigen::MatrixXd Phi(n, n_targets);
  Eigen::VectorXd hz(n_targets);
  for (int j = 0; j < n_targets; ++j) {
    Phi.col(j) = er.modes.col(target_cols[static_cast<std::size_t>(j)]);
    hz(j) = er.cycles(static_cast<int>(target_cols[static_cast<std::size_t>(j)]));
  }

  // --- candidates
  const auto grids = grid_positions(model);
  std::vector<std::int64_t> grid_list;
  if (vm.count("grids")) grid_list = translators::parse_sensor_list(vm["grids"].as<std::string>(), grids, "--grids");
  std::vector<pt::SensorDirection> sensor_dirs;
  if (vm.count("sensor-direction"))
    for (const auto& text : vm["sensor-direction"].as<std::vector<std::string>>()) {
      const auto [grid, d] = parse_grid_direction(text, "--sensor-direction");
      sensor_dirs.push_back({grid, d});
      if (!grid_list.empty() && std::find(grid_list.begin(), grid_list.end(), grid) == grid_list.end())
        grid_list.push_back(grid);
    }
  // `cand`/`groups`: every translation of the candidate grids, where exciters act.
  // `scand`/`sgroups`: the sensor candidates, rows of the measurement
  // coordinates q (measurement_coordinates.hpp; q = u without --sensor-direction),
  // in which the placement, the TAMs and the simulated test work.
  const auto cand = pt::translational_candidates(dofs, grid_list);
  const auto groups = pt::group_by_grid(cand);
  const pt::MeasurementCoordinates mc = pt::measurement_coordinates(dofs, cand, sensor_dirs);
  const auto& scand = mc.candidates;
  const auto sgroups = pt::group_by_grid(scand);
  if (triax)
    for (const auto& g : sgroups)
      if (g.size() != 3)
        throw formats::InputError("--triax: grid " + std::to_string(scand[static_cast<std::size_t>(g[0])].dof.point) +
                                  " has " + std::to_string(g.size()) +
                                  " sensor direction(s); a triax needs three (give three --sensor-direction at it)");
  std::vector<Eigen::Index> cand_rows;
  for (const auto& c : scand) cand_rows.push_back(c.row);
  const bool directed = !sensor_dirs.empty();
  const Eigen::SparseMatrix<double> Kq = directed ? mc.congruent(op.K) : op.K;
  const Eigen::SparseMatrix<double> Mq = directed ? mc.congruent(op.M) : op.M;
  const Eigen::MatrixXd Phi_q = directed ? mc.displacements(Phi) : Phi;

  // --- sensor placement
  const int keep = triax ? n_sensors / 3 : n_sensors;
  const std::vector<std::vector<Eigen::Index>> no_groups;
  const auto& place_groups = triax ? sgroups : no_groups;
  // One placement of the targets `Phi_t` of a model (K, M): the run's, and the perturbed model's.
  auto place = [&](const Eigen::SparseMatrix<double>& K_, const Eigen::SparseMatrix<double>& M_,
                   const Eigen::MatrixXd& Phi_t, pt::PlacementMethod method) {
    const Eigen::MatrixXd Phi_c = pt::take_rows(Phi_t, cand_rows);
    pt::Placement placement;
    if (method == pt::PlacementMethod::EffectiveIndependence) {
      placement = pt::effective_independence(Phi_c, keep, place_groups);
    } else {
      Eigen::MatrixXd ke;
      if (method == pt::PlacementMethod::KineticEnergy || method == pt::PlacementMethod::AverageKineticEnergy) {
        if (ke_mass == "fe") {
          ke = pt::kinetic_energy_fractions(Phi_t, M_, cand_rows);
        } else {
          const estimator::ReducedModel g = estimator::guyan_reduce(K_, M_, cand_rows);
          if (g.status != estimator::ReductionStatus::Ok)
            throw formats::NumericalError("--ke-mass guyan: " + g.message);
          std::vector<Eigen::Index> all(cand_rows.size());
          for (std::size_t i = 0; i < all.size(); ++i) all[i] = static_cast<Eigen::Index>(i);
          ke = pt::kinetic_energy_fractions(Phi_c, g.M.sparseView(), all);
        }
      }
      placement = pt::rank_placement(method, Phi_c, pt::placement_metric(method, Phi_c, ke), keep, place_groups);
    }
    return placement;
  };
  const pt::Placement placement = place(Kq, Mq, Phi_q, method);
  std::vector<Eigen::Index> sensor_rows;
  for (auto s : placement.selected) sensor_rows.push_back(scand[static_cast<std::size_t>(s)].row);

  // --- model error: the same placement on the perturbed model
  struct ModelError {
    pt::AreaPerturbation perturbation;
    Eigen::VectorXd hz;
    pt::Placement placement;
  };
  std::optional<ModelError> model_error;
  if (vm.count("perturb-areas")) {
    formats::Deck pdeck = formats::read_deck(lm.path);
    ModelError me;
    me.perturbation = pt::perturb_strut_areas(pdeck, vm["perturb-areas"].as<std::uint64_t>());
    const auto pmodel = translators::assemble_deck(pdeck, lm.path);
    const translators::FeOperators pop = pmodel->operators(pmodel->initial_parameters(), false);
    const estimator::EigenResult per = solve_model(pop, eo, dofs);
    const auto ptargets = pt::select_target_modes(per.eigenvalues, n_targets, min_hz);
    Eigen::MatrixXd Phi_p(n, n_targets);
    me.hz.resize(n_targets);
    for (int t = 0; t < n_targets; ++t) {
      Phi_p.col(t) = per.modes.col(ptargets[static_cast<std::size_t>(t)]);
      me.hz(t) = per.cycles(static_cast<int>(ptargets[static_cast<std::size_t>(t)]));
    }
    me.placement = directed ? place(mc.congruent(pop.K), mc.congruent(pop.M), mc.displacements(Phi_p), method)
                            : place(pop.K, pop.M, Phi_p, method);
    model_error = std::move(me);
  }

  // --- TAMs on the sensor set
  std::vector<pt::TamCheck> tams;
  for (auto k : {pt::TamKind::Guyan, pt::TamKind::Irs, pt::TamKind::Serep})
    tams.push_back(pt::tam_check(k, Kq, Mq, Phi_q, hz, sensor_rows));

  // --- exciters
  std::map<std::int64_t, int> group_of;
  for (std::size_t g = 0; g < groups.size(); ++g) group_of[cand[static_cast<std::size_t>(groups[g][0])].dof.point] = static_cast<int>(g);
  std::vector<pt::Exciter> given;
  if (vm.count("exciter-at"))
    for (const auto& s : vm["exciter-at"].as<std::vector<std::string>>()) given.push_back(parse_exciter(s, group_of));
  std::optional<pt::ExciterPlacement> xp;
  std::optional<Eigen::MatrixXd> given_drop;
  if (n_exciters > 0 || !given.empty()) {
    const Eigen::MatrixXd Phi_o = pt::take_rows(directed ? mc.displacements(er.modes) : er.modes, sensor_rows);
    const pt::DropoffModel dm(er.modes, er.eigenvalues, Phi_o, cand, groups, target_cols, zeta);
    if (!given.empty()) given_drop = dm.dropoffs(given);
    if (n_exciters > 0) {
      pt::GeneticOptions go;
      go.population = vm["population"].as<int>();
      go.generations = vm["generations"].as<int>();
      go.seed = vm["seed"].as<std::uint64_t>();
      if (go.population < 3) throw formats::InputError("--population: expected 3 or more, got " + std::to_string(go.population));
      if (go.generations < 0) throw formats::InputError("--generations: expected 0 or more, got " + std::to_string(go.generations));
      xp = pt::place_exciters(dm, n_exciters, go);
    }
  }
  auto grid_of_group = [&](int g) { return cand[static_cast<std::size_t>(groups[static_cast<std::size_t>(g)][0])].dof.point; };

  // --- the simulated test (on modes of the full model reaching above the test's band)
  std::optional<pt::PlacementEvaluation> evaluation, given_evaluation;
  pt::SimulatedTestOptions so;
  so.damping = zeta;
  so.noise_pct = noise_pct;
  so.seed = vm["noise-seed"].as<std::uint64_t>();
  if (evaluate) {
    estimator::EigenResult full = er;
    const double band = pt::evaluation_bandwidth(er.eigenvalues, target_cols, so);
    int n_full = n_solve;
    while (full.size() < n && full.cycles(static_cast<int>(full.size()) - 1) <= band && n_full < n - 1) {
      n_full = static_cast<int>(std::min<long>(2L * n_full, n - 1));
      std::string src;
      full = solve_model(op, eigen_options(model, n_full, n, src), dofs);
    }
    const auto full_targets = pt::select_target_modes(full.eigenvalues, n_targets, min_hz);
    const Eigen::MatrixXd full_q = directed ? mc.displacements(full.modes) : full.modes;
    auto run = [&](const std::vector<pt::Exciter>& ex) {
      const Eigen::MatrixXd B = pt::exciter_inputs(n, cand, groups, ex);
      return pt::evaluate_placement(Kq, Mq, full_q, full.eigenvalues, full_targets, sensor_rows,
                                    directed ? mc.loads(B) : B, so);
    };
    if (xp) evaluation = run(xp->exciters);
    if (!given.empty()) (xp ? given_evaluation : evaluation) = run(given);
  }

  // --- JSON
  nlohmann::json j;
  j["deck"] = lm.path;
  j["dof"] = n;
  j["method"] = pt::method_name(method);
  j["triax"] = triax;
  j["candidates"] = scand.size();
  if (directed) {
    j["sensor_directions"] = nlohmann::json::array();
    for (const auto& sd : sensor_dirs) {
      const Eigen::Vector3d u = sd.direction.normalized();
      j["sensor_directions"].push_back({{"grid", sd.grid}, {"direction", {u(0), u(1), u(2)}}});
    }
  }
  j["target_modes"] = nlohmann::json::array();
  for (int t = 0; t < n_targets; ++t)
    j["target_modes"].push_back({{"mode", target_cols[static_cast<std::size_t>(t)] + 1}, {"hz", hz(t)}});
  // Directions in basic for the picture: a sensor measures along its grid's
  // displacement-frame axis; an exciter's cosines are in that frame too.
  std::map<std::int64_t, Eigen::Matrix3d> frame_of;
  for (const auto& g : grids) frame_of[g.id] = g.frame;
  auto basic = [&](std::int64_t grid, const Eigen::Vector3d& d) {
    const Eigen::Vector3d b = frame_of.at(grid) * d;
    return nlohmann::json{b.x(), b.y(), b.z()};
  };
  // A sensor's record: "component" is null for one along a given direction.
  auto sensor_json = [&](const pt::CandidateDof& c) {
    return nlohmann::json{{"grid", c.dof.point},
                          {"component", c.directed ? nlohmann::json(nullptr) : nlohmann::json(c.dof.component)},
                          {"label", pt::sensor_label(c)},
                          {"direction", {c.direction(0), c.direction(1), c.direction(2)}},
                          {"direction_basic", basic(c.dof.point, c.direction)}};
  };
  j["sensors"] = nlohmann::json::array();
  for (std::size_t i = 0; i < placement.selected.size(); ++i) {
    nlohmann::json x = sensor_json(scand[static_cast<std::size_t>(placement.selected[i])]);
    x["score"] = placement.score(static_cast<Eigen::Index>(i));
    j["sensors"].push_back(x);
  }
  // The sensor grids' frames for the UFF (sensor_systems), and each sensor's direction code there.
  const auto [systems, unoriented] = sensor_systems(scand, placement.selected, frame_of, j["sensors"]);
  auto finite_or_null = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); };
  j["fisher_determinant"] = placement.fisher.determinant;
  j["log10_fisher_determinant"] = finite_or_null(placement.fisher.log10_determinant);
  j["condition_number"] = finite_or_null(placement.fisher.condition_number);
  j["fisher_rank"] = placement.fisher.rank;
  if (triax) j["protected_grids"] = placement.protected_groups;
  j["tam"] = nlohmann::json::object();
  for (const auto& t : tams) {
    nlohmann::json x{{"status", t.status == estimator::ReductionStatus::Ok ? "ok" : "failed"}};
    if (t.status != estimator::ReductionStatus::Ok) x["message"] = t.message;
    else {
      x["min_diagonal_xor"] = t.min_diagonal;
      x["max_offdiagonal_xor"] = t.max_offdiagonal;
      x["max_frequency_error_pct"] = t.max_frequency_error_pct;
      x["accepted"] = t.accepted;
      x["accepted_primary"] = t.accepted_primary;
      x["xor"] = matrix_rows(t.xor_matrix);
    }
    j["tam"][pt::tam_name(t.kind)] = x;
  }
  j["acceptance"] = {{"min_diagonal", 0.9}, {"max_offdiagonal", 0.1}, {"max_offdiagonal_primary", 0.02}};
  j["exciters"] = nlohmann::json::array();
  if (xp) {
    for (const auto& e : xp->exciters)
      j["exciters"].push_back({{"grid", grid_of_group(e.group)},
                               {"direction", {e.direction(0), e.direction(1), e.direction(2)}},
                               {"direction_basic", basic(grid_of_group(e.group), e.direction)}});
    j["exciter_objective"] = xp->objective;
    j["mif_dropoff"] = matrix_rows(xp->dropoffs);
    j["ga"] = {{"population", vm["population"].as<int>()}, {"generations", vm["generations"].as<int>()},
               {"seed", vm["seed"].as<std::uint64_t>()}, {"evaluations", xp->ga.evaluations},
               {"best_per_generation", xp->ga.best_per_generation}};
  }
  if (given_drop) {
    nlohmann::json g;
    g["exciters"] = nlohmann::json::array();
    for (const auto& e : given)
      g["exciters"].push_back({{"grid", grid_of_group(e.group)},
                               {"direction", {e.direction(0), e.direction(1), e.direction(2)}},
                               {"direction_basic", basic(grid_of_group(e.group), e.direction)}});
    g["objective"] = pt::exciter_objective(*given_drop);
    g["mif_dropoff"] = matrix_rows(*given_drop);
    j["given_exciters"] = g;
  }
  j["damping_ratio"] = zeta;
  if (evaluation) j["evaluation"] = evaluation_json(*evaluation, target_cols, hz, so);
  // Model error: the sensors (triaxes: grids) of the nominal set missing from the perturbed one, and those added.
  using Key = std::pair<std::int64_t, Eigen::Index>;  // grid, position in scand (-1 for a triax)
  auto keys = [&](const pt::Placement& pl) {
    std::set<Key> k;
    for (auto s : pl.selected) k.insert({scand[static_cast<std::size_t>(s)].dof.point, triax ? Eigen::Index{-1} : s});
    return k;
  };
  std::vector<Key> removed, added;
  if (model_error) {
    const auto a = keys(placement), b = keys(model_error->placement);
    std::set_difference(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(removed));
    std::set_difference(b.begin(), b.end(), a.begin(), a.end(), std::back_inserter(added));
    auto list = [&](const std::vector<Key>& v) {
      nlohmann::json l = nlohmann::json::array();
      for (const auto& [g, c] : v) l.push_back(triax ? nlohmann::json{{"grid", g}} : sensor_json(scand[static_cast<std::size_t>(c)]));
      return l;
    };
    nlohmann::json m;
    m["seed"] = vm["perturb-areas"].as<std::uint64_t>();
    m["struts"] = model_error->perturbation.struts;
    m["areas_decreased"] = model_error->perturbation.decreased;
    m["areas_increased"] = model_error->perturbation.increased;
    m["area_change"] = 0.2;
    std::vector<double> change;
    for (int t = 0; t < n_targets; ++t) change.push_back(100 * (model_error->hz(t) - hz(t)) / hz(t));
    m["target_hz"] = std::vector<double>(model_error->hz.data(), model_error->hz.data() + n_targets);
    m["frequency_change_pct"] = change;
    m["sensors"] = nlohmann::json::array();
    for (auto s : model_error->placement.selected) m["sensors"].push_back(sensor_json(scand[static_cast<std::size_t>(s)]));
    m["changed"] = removed.size();
    m["of"] = a.size();
    m["unit"] = triax ? "triaxes" : "sensors";
    m["removed"] = list(removed);
    m["added"] = list(added);
    j["model_error"] = m;
  }
  if (given_evaluation) j["given_exciters"]["evaluation"] = evaluation_json(*given_evaluation, target_cols, hz, so);
  if (compare) {
    // Every method on the same targets and candidates (the run's own placement reused).
    j["methods"] = nlohmann::json::array();
    for (auto m : {pt::PlacementMethod::EffectiveIndependence, pt::PlacementMethod::KineticEnergy,
                   pt::PlacementMethod::AverageKineticEnergy, pt::PlacementMethod::EigenvectorProduct,
                   pt::PlacementMethod::EigenvectorSum}) {
      pt::Placement pm;
      try {
        pm = m == method ? placement : place(Kq, Mq, Phi_q, m);
      } catch (const formats::InputError& e) {  // e.g. EI with fewer sensors than targets: that method has no set
        j["methods"].push_back({{"method", pt::method_name(m)}, {"error", e.what()}});
        continue;
      }
      nlohmann::json x{{"method", pt::method_name(m)},
                       {"fisher_determinant", pm.fisher.determinant},
                       {"log10_fisher_determinant", finite_or_null(pm.fisher.log10_determinant)},
                       {"condition_number", finite_or_null(pm.fisher.condition_number)},
                       {"fisher_rank", pm.fisher.rank},
                       {"sensors", nlohmann::json::array()}};
      for (auto sel : pm.selected) x["sensors"].push_back(sensor_json(scand[static_cast<std::size_t>(sel)]));
      j["methods"].push_back(x);
    }
  }
  // The sensor grids and the test wire frame joining them (report_data.hpp test_wire_frame).
  std::vector<std::int64_t> sensor_grids;
  for (auto sel : placement.selected) {
    const auto g = scand[static_cast<std::size_t>(sel)].dof.point;
    if (std::find(sensor_grids.begin(), sensor_grids.end(), g) == sensor_grids.end()) sensor_grids.push_back(g);
  }
  if (vm.count("svg") || vm.count("report")) j["geometry"] = report::geometry_json(model, grids, sensor_grids);
  if (vm.count("report")) j["run"] = report::run_json("pretest", args, {lm.path});

  // --- report
  const std::string json_path = vm.count("json") ? vm["json"].as<std::string>() : "";
  if (json_path != "-") {
    std::ostream& o = std::cout;
    o << lm.path << ": " << n << " analysis-set DOF(s), " << er.size() << " mode(s) solved, " << scand.size()
      << " candidate sensor DOF(s) on " << sgroups.size() << " grid(s)";
    if (directed) o << ", " << sensor_dirs.size() << " of them along given directions";
    o << "\n\n";
    o << "target modes (" << n_targets << " lowest above " << min_hz << " Hz):";
    for (int t = 0; t < n_targets; ++t) o << (t % 6 == 0 ? "\n  " : "  ") << "#" << target_cols[static_cast<std::size_t>(t)] + 1 << " " << std::fixed << std::setprecision(3) << hz(t) << " Hz";
    o << std::defaultfloat << "\n\n";
    o << "sensors: " << pt::method_name(method) << (triax ? ", triaxial (" + std::to_string(keep) + " grids)" : "")
      << ", " << placement.selected.size() << " DOF(s)\n";
    std::size_t width = 8;
    for (auto sel : placement.selected) width = std::max(width, pt::sensor_label(scand[static_cast<std::size_t>(sel)]).size());
    o << "  grid  " << std::left << std::setw(static_cast<int>(width)) << "measures" << std::right << "  score\n";
    for (std::size_t i = 0; i < placement.selected.size(); ++i) {
      const auto& c = scand[static_cast<std::size_t>(placement.selected[i])];
      o << "  " << std::setw(4) << c.dof.point << "  " << std::left << std::setw(static_cast<int>(width))
        << pt::sensor_label(c) << std::right << "  " << fmt(placement.score(static_cast<Eigen::Index>(i))) << "\n";
    }
    o << "Fisher information (unit noise, mass-normalised modes): det " << fmt(placement.fisher.determinant)
      << " (log10 " << fmt(placement.fisher.log10_determinant) << "), condition number "
      << fmt(placement.fisher.condition_number) << ", rank " << placement.fisher.rank << " of " << n_targets << "\n";
    if (triax && placement.protected_groups)
      o << "  " << placement.protected_groups << " grid(s) kept because one of their DOFs has EI = 1\n";
    o << "\ntest-analysis models on the sensors (cross-orthogonality of the target modes; accept: diagonal > 0.9, "
         "off-diagonal < 0.1, primary < 0.02):\n";
    for (const auto& t : tams) {
      o << "  " << std::left << std::setw(6) << pt::tam_name(t.kind) << std::right;
      if (t.status != estimator::ReductionStatus::Ok) {
        o << " failed: " << t.message << "\n";
        continue;
      }
      o << " min diagonal " << fmt(t.min_diagonal) << ", max off-diagonal " << fmt(t.max_offdiagonal)
        << ", max frequency error " << fmt(t.max_frequency_error_pct, 3) << " %: "
        << (t.accepted_primary ? "accepted (primary)" : t.accepted ? "accepted (secondary)" : "NOT accepted") << "\n";
    }
    auto print_exciters = [&](const char* title, const std::vector<pt::Exciter>& ex, const Eigen::MatrixXd& D) {
      o << "\n" << title << " (MIF drop-off at each target; objective " << fmt(pt::exciter_objective(D), 6) << ")\n";
      for (std::size_t e = 0; e < ex.size(); ++e)
        o << "  exciter " << e + 1 << ": grid " << grid_of_group(ex[e].group) << ", direction (" << fmt(ex[e].direction(0), 3)
          << ", " << fmt(ex[e].direction(1), 3) << ", " << fmt(ex[e].direction(2), 3) << ")\n";
      o << "  mode  " ;
      for (std::size_t e = 0; e < ex.size(); ++e) o << "  exciter " << e + 1;
      o << "\n";
      for (int t = 0; t < n_targets; ++t) {
        o << "  " << std::setw(4) << target_cols[static_cast<std::size_t>(t)] + 1 << "  ";
        for (Eigen::Index e = 0; e < D.cols(); ++e) o << "  " << std::setw(9) << std::fixed << std::setprecision(4) << D(t, e);
        o << std::defaultfloat << "\n";
      }
    };
    if (xp) print_exciters("exciters placed by the GA", xp->exciters, xp->dropoffs);
    if (given_drop) print_exciters("exciters given (--exciter-at)", given, *given_drop);
    if (evaluation)
      print_evaluation(o, xp ? "simulated test with the GA's exciters" : "simulated test with the given exciters",
                       *evaluation, target_cols, hz, so);
    if (given_evaluation) print_evaluation(o, "simulated test with the given exciters", *given_evaluation, target_cols, hz, so);
    if (model_error) {
      const auto& pe = model_error->perturbation;
      o << "\nmodel error (--perturb-areas " << vm["perturb-areas"].as<std::uint64_t>() << "): of " << pe.struts
        << " strut(s), " << pe.decreased << " area(s) -20 %, " << pe.increased << " +20 %; target frequency change (%):";
      for (int t = 0; t < n_targets; ++t)
        o << (t % 6 == 0 ? "\n  " : "  ") << std::fixed << std::setprecision(2) << 100 * (model_error->hz(t) - hz(t)) / hz(t);
      o << std::defaultfloat << "\n  " << removed.size() << " of " << keys(placement).size()
        << (triax ? " triax(es)" : " sensor(s)") << " changed";
      auto name = [&](const Key& k) {
        return std::to_string(k.first) + (triax ? "" : " " + pt::sensor_label(scand[static_cast<std::size_t>(k.second)]));
      };
      if (!removed.empty()) {
        o << "; dropped:";
        for (const auto& k : removed) o << " " << name(k);
        o << "; added:";
        for (const auto& k : added) o << " " << name(k);
      }
      o << "\n";
    }
  }
  if (!json_path.empty()) write_json(json_path, j);

  if (vm.count("uff")) {
    std::set<std::int64_t> ids;
    for (auto s : placement.selected) ids.insert(scand[static_cast<std::size_t>(s)].dof.point);
    if (xp)
      for (const auto& e : xp->exciters) ids.insert(grid_of_group(e.group));
    // Each sensor grid measures along its displacement frame's axes, or along its given
    // directions: where those are not the basic axes, a coordinate system (2420, id = the
    // grid's) whose axes they are becomes the node's displacement system, so lab software
    // knows how to mount the sensors; every sensor record gets its direction code there.
    formats::uff::NodeSet ns;
    ns.dataset = 15;
    for (const auto& g : grids)
      if (ids.count(g.id)) {
        formats::uff::Node nd;
        nd.id = g.id;
        nd.xyz = {g.position(0), g.position(1), g.position(2)};
        for (const auto& cs : systems)
          if (cs.id == g.id) nd.displacement_cs = static_cast<int>(cs.id);
        ns.nodes.push_back(nd);
      }
    formats::uff::UffFile f;
    if (!systems.empty()) {
      formats::uff::CoordinateSystems2420 cs;
      cs.part_name = "ssid pretest sensor frames";
      cs.systems = systems;
      f.datasets.push_back(cs);
    }
    f.datasets.push_back(ns);
    for (auto g : unoriented)
      std::cerr << "warning: grid " << g << ": its given sensor directions are not mutually orthogonal; no coordinate "
                << "system carries them to the UFF (they are in the JSON's direction_basic)\n";
    // The test wire frame as one trace line, its segments separated by pen lifts (0).
    const report::Lines wire = j.contains("geometry") ? report::read_lines(j["geometry"]["test_lines"])
                                                      : report::read_lines(report::geometry_json(model, grids, sensor_grids)["test_lines"]);
    if (!wire.empty()) {
      formats::uff::TraceLine82 t;
      t.id = 1;
      t.color = 8;
      t.label = "ssid pretest: sensor wire frame";
      for (const auto& [a, b] : wire) {
        if (!t.nodes.empty()) t.nodes.push_back(0);
        t.nodes.push_back(a);
        t.nodes.push_back(b);
      }
      f.datasets.push_back(t);
    }
    const std::string out = vm["uff"].as<std::string>();
    formats::uff::write_uff(f, out, formats::uff::Precision::Standard);
    std::cerr << "wrote " << out << ": " << ns.nodes.size() << " node(s) (dataset 15, positions in the basic system), "
              << wire.size() << " trace segment(s) between sensor grids (dataset 82)"
              << (systems.empty() ? std::string()
                                  : ", " + std::to_string(systems.size()) +
                                        " coordinate system(s) orienting sensor grids (dataset 2420)")
              << "\n";
  }
  if (vm.count("svg")) {
    const std::string out = vm["svg"].as<std::string>();
    std::ofstream o(out, std::ios::binary);
    o << report::pretest_picture_file(j, view);
    if (!o) throw formats::InputError("cannot write " + out);
    std::cerr << "wrote " << out << ": the structure with " << j["sensors"].size() << " sensor DOF(s) and "
              << j["exciters"].size() + (j.contains("given_exciters") ? j["given_exciters"]["exciters"].size() : 0)
              << " exciter(s), " << view.label << " view\n";
  }
  if (vm.count("report")) {
    report::write_report(vm["report"].as<std::string>(), j);
    std::cerr << "wrote " << vm["report"].as<std::string>() << "\n";
  }
  return kExitSuccess;
}

}  // namespace ssid::cli
