/// \file report_data.cpp
#include "cli/report/report_data.hpp"

#include <algorithm>
#include <fstream>
#include <cstdlib>
#include <ctime>
#include <deque>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <set>

#include <Eigen/SVD>
#include <fmt/format.h>

#include "cli/report/html_report.hpp"
#include "cli/report/sha256.hpp"
#include "cli/model_load.hpp"
#include "cli/version.hpp"
#include "estimator/correlation/measures.hpp"
#include "estimator/study/deck_study.hpp"
#include "formats/parse_error.hpp"
#include "translators/synthetic_modes.hpp"

namespace ssid::cli::report {

nlohmann::json run_json(const std::string& subcommand, const Args& args, const std::vector<std::string>& inputs) {
  std::string command = "ssid " + subcommand;
  for (const auto& a : args) command += " " + a;
  nlohmann::json in = nlohmann::json::array();
  for (const auto& p : inputs) {
    if (p.empty()) continue;
    in.push_back({{"path", p}, {"sha256", sha256_file(p)}, {"bytes", std::filesystem::file_size(p)}});
  }
  // SOURCE_DATE_EPOCH (reproducible-builds.org) fixes the date of a report made twice.
  std::time_t t = std::time(nullptr);
  if (const char* e = std::getenv("SOURCE_DATE_EPOCH")) t = static_cast<std::time_t>(std::strtoll(e, nullptr, 10));
  std::tm tm{};
  gmtime_r(&t, &tm);
  char date[32];
  std::strftime(date, sizeof date, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return {{"command", command}, {"inputs", in}, {"version", kSsidVersion}, {"date", date}};
}

namespace {

/// Element lines of the bulk data, each (g1, g2) once.
std::vector<std::pair<std::int64_t, std::int64_t>> element_lines(const formats::BulkModel& b) {
  std::set<std::pair<std::int64_t, std::int64_t>> set;
  auto add = [&](std::int64_t a, std::int64_t c) {
    if (a > 0 && c > 0 && a != c) set.insert({std::min(a, c), std::max(a, c)});
  };
  for (const auto& e : b.crods) add(e.g1, e.g2);
  for (const auto& e : b.conrods) add(e.g1, e.g2);
  for (const auto& e : b.cbars) add(e.ga, e.gb);
  for (const auto& e : b.cbeams) add(e.ga, e.gb);
  for (const auto& e : b.cbushes) add(e.ga, e.gb);
  for (const auto& e : b.celas1s) add(e.g1, e.g2);
  for (const auto& e : b.celas2s) add(e.g1, e.g2);
  for (const auto& e : b.rbars) add(e.ga, e.gb);
  for (const auto& e : b.rbe2s)
    for (auto g : e.gm) add(e.gn, g);
  return {set.begin(), set.end()};
}

}  // namespace

std::string sensor_component(const nlohmann::json& sensor) {
  const auto it = sensor.find("component");
  return it == sensor.end() || it->is_null() ? std::string() : std::to_string(it->get<int>());
}

std::string sensor_label(const nlohmann::json& sensor) {
  if (sensor.contains("label")) return sensor["label"].get<std::string>();
  return "T" + sensor_component(sensor);
}

Lines test_wire_frame(const Lines& lines, const Points& grids, const std::vector<std::int64_t>& test_grids) {
  std::map<std::int64_t, std::vector<std::int64_t>> adjacent;
  for (const auto& [a, b] : lines) {
    adjacent[a].push_back(b);
    adjacent[b].push_back(a);
  }
  // From each test grid, a breadth-first walk that stops at test grids finds
  // those the deck joins it to; the three nearest of them are kept (on a truss
  // measured at every other joint, all of them would be a web).
  const std::set<std::int64_t> tested(test_grids.begin(), test_grids.end());
  std::set<std::pair<std::int64_t, std::int64_t>> wire;
  for (std::int64_t s : tested) {
    if (!grids.count(s)) continue;
    std::set<std::int64_t> seen{s};
    std::deque<std::int64_t> queue{s};
    std::vector<std::pair<double, std::int64_t>> reached;
    while (!queue.empty()) {
      const std::int64_t n = queue.front();
      queue.pop_front();
      for (std::int64_t m : adjacent[n]) {
        if (!seen.insert(m).second) continue;
        if (tested.count(m)) {
          if (grids.count(m)) reached.push_back({(grids.at(m) - grids.at(s)).norm(), m});
        } else {
          queue.push_back(m);
        }
      }
    }
    std::sort(reached.begin(), reached.end());
    for (std::size_t k = 0; k < reached.size() && k < 3; ++k)
      wire.insert({std::min(s, reached[k].second), std::max(s, reached[k].second)});
  }
  return {wire.begin(), wire.end()};
}

nlohmann::json geometry_json(const translators::FeModel& model, const std::vector<translators::GridPosition>& grids,
                             const std::vector<std::int64_t>& test_grids) {
  nlohmann::json g = nlohmann::json::array();
  std::set<std::int64_t> known;
  for (const auto& p : grids) {
    g.push_back({p.id, p.position.x(), p.position.y(), p.position.z()});
    known.insert(p.id);
  }
  const auto lines = element_lines(model.bulk());
  nlohmann::json l = nlohmann::json::array();
  Lines positioned;
  for (const auto& [a, b] : lines)
    if (known.count(a) && known.count(b)) {  // scalar points have no position
      l.push_back({a, b});
      positioned.push_back({a, b});
    }
  Points at;
  for (const auto& p : grids) at[p.id] = p.position;
  const Lines wire = test_wire_frame(positioned, at, test_grids);
  nlohmann::json t = nlohmann::json::array();
  for (const auto& [a, b] : wire) t.push_back({a, b});
  return {{"grids", g}, {"lines", l}, {"test_lines", t}};
}

std::vector<nlohmann::json> grid_shapes_json(const translators::FeModel& model,
                                             const std::vector<translators::GridPosition>& grids,
                                             const Eigen::MatrixXd& a_modes) {
  translators::FeModeData fd;
  fd.shapes = a_modes;
  fd.frequency_hz.assign(static_cast<std::size_t>(a_modes.cols()), 0.0);
  // Every grid, translations only, no noise: the expansion and frame rotation of the synthetic test.
  const auto set = translators::synthetic_test(fd, model.reduction(), model.geometry().gset(), grids, {}).modes;
  std::vector<nlohmann::json> out;
  for (Eigen::Index m = 0; m < set.shapes.cols(); ++m)
    out.push_back(dof_shape_json(set.dofs, set.shapes.col(m), 1.0));
  return out;
}

nlohmann::json dof_shape_json(const std::vector<translators::MeasuredDof>& dofs, const Eigen::VectorXd& values,
                              double scale) {
  std::vector<std::int64_t> order;
  std::map<std::int64_t, std::array<double, 3>> d;
  for (std::size_t i = 0; i < dofs.size(); ++i) {
    const int dir = std::abs(dofs[i].direction);
    if (dir < 1 || dir > 3) continue;
    auto [it, fresh] = d.insert({dofs[i].node, {0.0, 0.0, 0.0}});
    if (fresh) order.push_back(dofs[i].node);
    it->second[static_cast<std::size_t>(dir - 1)] +=
        (dofs[i].direction < 0 ? -1.0 : 1.0) * scale * values(static_cast<Eigen::Index>(i));
  }
  nlohmann::json j = nlohmann::json::array();
  for (auto n : order) j.push_back({n, d[n][0], d[n][1], d[n][2]});
  return j;
}

double scale_onto(const Eigen::VectorXd& fe, const Eigen::VectorXd& test) {
  const double tt = test.squaredNorm();
  return tt > 0 ? fe.dot(test) / tt : 0.0;
}

namespace {

/// |X| = |normalised φ_aᵀ M_r φ_t| of the analysis shapes `fe` (columns, modes `rows`)
/// and the test shapes, with the pairs' acceptance: cross_orthogonality_json's object.
nlohmann::json xor_of_mass(const Eigen::MatrixXd& fe, const Eigen::MatrixXd& Mr, const std::vector<int>& rows,
                           const Eigen::MatrixXd& test, const std::vector<int>& test_numbers,
                           const std::vector<std::pair<int, int>>& pairs, const std::string& reduction,
                           const std::string& basis_text) {
  const Eigen::MatrixXd X = estimator::cross_orthogonality(fe, Mr, test, true).cwiseAbs();
  nlohmann::json matrix = nlohmann::json::array();
  for (Eigen::Index i = 0; i < X.rows(); ++i) {
    std::vector<double> r;
    for (Eigen::Index k = 0; k < X.cols(); ++k) r.push_back(X(i, k));
    matrix.push_back(r);
  }
  const double min_diagonal = 0.9, max_off = 0.1;
  nlohmann::json pj = nlohmann::json::array();
  for (const auto& [f, t] : pairs) {
    const auto i = std::find(rows.begin(), rows.end(), f) - rows.begin();
    const auto k = std::find(test_numbers.begin(), test_numbers.end(), t) - test_numbers.begin();
    if (i >= static_cast<long>(rows.size()) || k >= static_cast<long>(test_numbers.size())) continue;
    double off = 0;
    for (Eigen::Index c = 0; c < X.cols(); ++c)
      if (c != k) off = std::max(off, X(i, c));
    for (Eigen::Index r = 0; r < X.rows(); ++r)
      if (r != i) off = std::max(off, X(r, k));
    pj.push_back({{"fe_mode", f}, {"test_mode", t}, {"xor", X(i, k)}, {"largest_off_diagonal", off},
                  {"accepted", X(i, k) > min_diagonal && off < max_off}});
  }
  return {{"reduction", reduction},
          {"basis", basis_text},
          {"fe_modes", rows},
          {"test_modes", test_numbers},
          {"matrix", matrix},
          {"min_diagonal", min_diagonal},
          {"max_off_diagonal", max_off},
          {"pairs", pj}};
}

}  // namespace

nlohmann::json cross_orthogonality_json(const Eigen::MatrixXd& fe, const std::vector<double>& modal_mass,
                                        const std::vector<int>& fe_numbers, const Eigen::MatrixXd& test,
                                        const std::vector<int>& test_numbers,
                                        const std::vector<std::pair<int, int>>& pairs) {
  if (modal_mass.size() != static_cast<std::size_t>(fe.cols()) ||
      std::any_of(modal_mass.begin(), modal_mass.end(), [](double m) { return !(m > 0); }))
    return {{"unavailable", "the analysis modes carry no generalised mass"}};
  // SEREP's pseudo-inverse Φ_a⁺ of the basis, or nothing when the basis is not independent at the test DOFs.
  auto pinv_of = [](const Eigen::MatrixXd& Pa) -> std::optional<Eigen::MatrixXd> {
    if (Pa.cols() == 0 || Pa.rows() < Pa.cols()) return std::nullopt;
    Eigen::JacobiSVD<Eigen::MatrixXd> svd(Pa, Eigen::ComputeThinU | Eigen::ComputeThinV);
    const auto& sv = svd.singularValues();
    if (sv(sv.size() - 1) <= static_cast<double>(std::max(Pa.rows(), Pa.cols())) * 1e-12 * sv(0)) return std::nullopt;
    return Eigen::MatrixXd(svd.matrixV() * sv.cwiseInverse().asDiagonal() * svd.matrixU().transpose());
  };
  std::vector<Eigen::Index> basis;
  for (Eigen::Index i = 0; i < fe.cols(); ++i) basis.push_back(i);
  std::string basis_text = "every analysis mode";
  auto take = [&](const std::vector<Eigen::Index>& b) {
    Eigen::MatrixXd Pa(fe.rows(), static_cast<Eigen::Index>(b.size()));
    for (std::size_t k = 0; k < b.size(); ++k) Pa.col(static_cast<Eigen::Index>(k)) = fe.col(b[k]);
    return Pa;
  };
  auto pinv = pinv_of(take(basis));
  if (!pinv) {
    basis.clear();
    for (const auto& [f, t] : pairs) {
      const auto i = std::find(fe_numbers.begin(), fe_numbers.end(), f) - fe_numbers.begin();
      if (i < static_cast<long>(fe_numbers.size()) && std::find(basis.begin(), basis.end(), i) == basis.end()) basis.push_back(i);
    }
    std::sort(basis.begin(), basis.end());
    basis_text = "the analysis modes of the pairs (all of them are not independent at the test DOFs)";
    pinv = pinv_of(take(basis));
    if (!pinv)
      return {{"unavailable", fmt::format("the analysis modes are not independent at the {} test DOFs: SEREP needs at least "
                                          "as many independent sensors as modes", fe.rows())}};
  }
  Eigen::VectorXd m(static_cast<Eigen::Index>(basis.size()));
  for (std::size_t k = 0; k < basis.size(); ++k) m(static_cast<Eigen::Index>(k)) = modal_mass[static_cast<std::size_t>(basis[k])];
  const Eigen::MatrixXd Mr = pinv->transpose() * m.asDiagonal() * *pinv;
  std::vector<int> rows;
  for (auto i : basis) rows.push_back(fe_numbers[static_cast<std::size_t>(i)]);
  return xor_of_mass(take(basis), Mr, rows, test, test_numbers, pairs,
                     "SEREP from the analysis modes: M_r = pinv(Phi_a)^T diag(generalised mass) pinv(Phi_a)", basis_text);
}

nlohmann::json cross_orthogonality_json(const Eigen::MatrixXd& fe, const Eigen::MatrixXd& Mr,
                                        const std::vector<int>& fe_numbers, const Eigen::MatrixXd& test,
                                        const std::vector<int>& test_numbers,
                                        const std::vector<std::pair<int, int>>& pairs, const std::string& reduction) {
  return xor_of_mass(fe, Mr, fe_numbers, test, test_numbers, pairs, reduction, "every analysis mode");
}

void write_report(const std::string& path, const nlohmann::json& j) {
  std::ofstream o(path, std::ios::binary);
  if (!o) throw formats::InputError("cannot write " + path);
  o << html_report(j);
  if (!o) throw formats::InputError("cannot write " + path);
}

}  // namespace ssid::cli::report

namespace ssid::cli::report {

nlohmann::json mems_json(const std::vector<translators::MeasuredDof>& dofs, const Eigen::VectorXd& fe,
                         const Eigen::VectorXd& pair_test, const Eigen::MatrixXd& test_set,
                         const std::vector<int>& test_numbers) {
  const estimator::MemsResult m = estimator::mems(fe, test_set, estimator::ComparisonScaling::UnitNorm);
  const estimator::MemsResult one = estimator::mems(fe, pair_test, estimator::ComparisonScaling::UnitNorm);
  nlohmann::json alpha = nlohmann::json::array();
  for (Eigen::Index i = 0; i < m.alpha.size(); ++i) alpha.push_back({test_numbers[static_cast<std::size_t>(i)], m.alpha(i)});
  return {{"comparison", "every test mode, each scaled to unit norm"},
          {"alpha", alpha},
          {"error_squared", m.error_squared},
          {"mac_superposition", m.mac_superposition},
          {"error", dof_shape_json(dofs, m.error_mode, 1.0)},
          {"pair_error_squared", one.error_squared}};
}

void add_shapes(nlohmann::json& j, const translators::FeModel& model, const Eigen::MatrixXd& a_modes,
                const std::vector<translators::MeasuredDof>& dofs, const std::vector<ShapePair>& pairs,
                const Eigen::MatrixXd& test_set, const std::vector<int>& test_numbers, const Lines& test_lines) {
  const std::vector<translators::GridPosition> grids = grid_positions(model);
  std::vector<std::int64_t> test_grids;
  for (const auto& d : dofs)
    if (test_grids.empty() || test_grids.back() != d.node) test_grids.push_back(d.node);
  j["geometry"] = geometry_json(model, grids, test_grids);
  if (test_lines.empty()) {
    j["geometry"]["test_lines_from"] = "the deck's elements between the test grids";
  } else {
    nlohmann::json t = nlohmann::json::array();
    for (const auto& [a, b] : test_lines) t.push_back({a, b});
    j["geometry"]["test_lines"] = t;
    j["geometry"]["test_lines_from"] = "the test file's trace lines (dataset 82)";
  }
  Eigen::MatrixXd cols(a_modes.rows(), static_cast<Eigen::Index>(pairs.size()));
  for (std::size_t k = 0; k < pairs.size(); ++k) cols.col(static_cast<Eigen::Index>(k)) = a_modes.col(pairs[k].fe_column);
  const auto fe = grid_shapes_json(model, grids, cols);
  j["shapes"] = nlohmann::json::array();
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    const auto& p = pairs[k];
    const double s = scale_onto(p.fe_at_dofs, p.test_at_dofs);
    j["shapes"].push_back({{"fe_mode", p.fe_mode},
                           {"test_mode", p.test_mode},
                           {"fe_hz", p.fe_hz},
                           {"test_hz", p.test_hz},
                           {"mac", p.mac},
                           {"fe", fe[k]},
                           {"test", dof_shape_json(dofs, p.test_at_dofs, s)},
                           {"test_scale", s},
                           {"mems", mems_json(dofs, p.fe_at_dofs, p.test_at_dofs, test_set, test_numbers)}});
  }
}

std::vector<translators::MeasuredDof> dofs_of_labels(const std::vector<std::string>& labels) {
  std::vector<translators::MeasuredDof> d;
  for (const auto& l : labels) {
    const auto c = l.find(':');
    d.push_back({std::stoll(l.substr(0, c)), std::stoi(l.substr(c + 1))});
  }
  return d;
}

}  // namespace ssid::cli::report

namespace ssid::cli::report {

void write_diagnosis_report(const std::string& path, const Args& args, const boost::program_options::variables_map& vm,
                            nlohmann::json& j) {
  std::vector<std::string> inputs;
  for (const char* k : {"deck", "measured", "study", "frf"})
    if (vm.count(k)) inputs.push_back(vm[k].as<std::string>());
  j["run"] = run_json("diagnose", args, inputs);
  const LoadedModel lm = load_model(vm["deck"].as<std::string>());
  j["geometry"] = geometry_json(*lm.model, grid_positions(*lm.model), {});
  write_report(path, j);
}

}  // namespace ssid::cli::report

namespace ssid::cli::report {

/// Adds the run, the geometry and the pairs' shapes at the estimate (first
/// configuration; one more eigen-solve) to `j` and writes the report.
namespace {

/// The shapes of configuration `c`'s pairs (`pairs`: its JSON pairs) at parameters `r`,
/// added to `out` (add_shapes: "geometry", "shapes"), and, for the first configuration,
/// the cross-orthogonality. False when the configuration's deck is not there to draw
/// (a problem file's run, a deck moved away, or one whose a-set is no longer the estimate's).
bool configuration_shapes(const estimator::PreparedConfiguration& c, const nlohmann::json& pairs, const Eigen::VectorXd& r,
                          bool cross_orthogonality, nlohmann::json& out) {
  auto* om = dynamic_cast<estimator::OperatorModel*>(c.model.get());
  if (!om || c.deck.empty() || !std::ifstream(c.deck)) return false;
  const LoadedModel lm = load_model(c.deck);
  std::vector<std::pair<std::int64_t, int>> dofs;
  for (const auto& d : a_set_dofs(*lm.model)) dofs.emplace_back(d.point, d.component);
  if (dofs != c.dofs) return false;  // not the estimate's deck: its a-set must be the same, in the same order
  const estimator::ModalSolution sol = om->solve(r);
  std::vector<ShapePair> sp;
  for (const auto& p : pairs) {
    const int fe = p["fe_mode"], test = p["test_mode"];
    const auto t = std::find(c.test_numbers.begin(), c.test_numbers.end(), test) - c.test_numbers.begin();
    if (fe < 1 || fe > sol.sensor_shapes.cols() || t >= static_cast<long>(c.test.size())) continue;
    sp.push_back({fe, test, p["fe_hz"], p["test_hz"], p["mac"], fe - 1, sol.sensor_shapes.col(fe - 1),
                  c.test[static_cast<std::size_t>(t)].shape});
  }
  Eigen::MatrixXd test_set(sol.sensor_shapes.rows(), static_cast<Eigen::Index>(c.test.size()));
  for (std::size_t k = 0; k < c.test.size(); ++k) test_set.col(static_cast<Eigen::Index>(k)) = c.test[k].shape;
  add_shapes(out, *lm.model, om->modes(), dofs_of_labels(c.sensor_labels), sp, test_set, c.test_numbers, c.test_lines);
  if (cross_orthogonality) {
    // The eigen-solver's modes are mass-normalised: unit generalised masses.
    std::vector<int> fe_numbers;
    for (Eigen::Index i = 0; i < sol.sensor_shapes.cols(); ++i) fe_numbers.push_back(static_cast<int>(i) + 1);
    std::vector<std::pair<int, int>> paired;
    for (const auto& p : sp) paired.emplace_back(p.fe_mode, p.test_mode);
    out["cross_orthogonality"] = cross_orthogonality_json(
        sol.sensor_shapes, std::vector<double>(fe_numbers.size(), 1.0), fe_numbers, test_set, c.test_numbers, paired);
  }
  return true;
}

}  // namespace

translators::FeOperators operators_at(const estimator::PreparedConfiguration& c, const Eigen::VectorXd& r) {
  estimator::Operators ops = c.assemble(r);
  translators::FeOperators op;
  op.K = std::move(ops.K);
  op.M = std::move(ops.M);
  return op;
}

void write_estimate_report(const std::string& path, const Args& args, const boost::program_options::variables_map& vm,
                           const estimator::EstimationProblem& problem, const estimator::EstimationResult& result,
                           nlohmann::json& j) {
  std::vector<std::string> inputs;
  for (const char* k : {"deck", "measured", "study", "problem", "frf"})
    if (vm.count(k)) inputs.push_back(vm[k].as<std::string>());
  j["run"] = run_json("estimate", args, inputs);
  configuration_shapes(problem.configurations.front(), j["configurations"][0]["pairs"], result.update.r, true, j);
  // The second and later configurations' shapes (their own decks: bare, with a mass, ...).
  for (std::size_t k = 1; k < problem.configurations.size() && k < j["configurations"].size(); ++k) {
    nlohmann::json c{{"configuration", problem.configurations[k].name}};
    if (configuration_shapes(problem.configurations[k], j["configurations"][k]["pairs"], result.update.r, false, c))
      j["configuration_shapes"].push_back(c);
  }
  write_report(path, j);
}


}  // namespace ssid::cli::report
