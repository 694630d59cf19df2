#include "cli/report/tam_xor.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <map>
#include <optional>
#include <sstream>

#include "cli/cli_util.hpp"
#include "cli/model_load.hpp"
#include "cli/report/report_data.hpp"
#include "estimator/correlation/measures.hpp"
#include "estimator/pretest/measurement_coordinates.hpp"
#include "formats/parse_error.hpp"

namespace ssid::cli::report {

bool parse_tams(const std::string& value, std::vector<std::string>& tams) {
  std::stringstream ss(value);
  for (std::string t; std::getline(ss, t, ',');) {
    if (t != "guyan" && t != "irs") {
      print_error("--tam: expected guyan and/or irs (comma-separated), got \"" + t + "\"");
      return false;
    }
    if (std::find(tams.begin(), tams.end(), t) == tams.end()) tams.push_back(t);
  }
  return true;
}

TestCoordinates test_coordinates(const translators::FeModel& model, const translators::FeOperators& op,
                                 const std::vector<translators::MeasuredDof>& dofs) {
  namespace pt = estimator::pretest;
  std::map<std::int64_t, Eigen::Matrix3d> frame;
  for (const auto& g : grid_positions(model)) frame[g.id] = g.frame;
  std::vector<pt::SensorDirection> dirs;
  std::vector<std::int64_t> test_grids;
  for (const auto& d : dofs) {
    const int axis = std::abs(d.direction);
    if (axis < 1 || axis > 3)
      throw formats::InputError(fmt::format("test DOF {}:{} is a rotation (the TAMs reduce onto translations)", d.node,
                                            d.direction));
    const auto f = frame.find(d.node);
    if (f == frame.end()) throw formats::InputError(fmt::format("test DOF {}:{}: no grid {}", d.node, d.direction, d.node));
    // The basic direction in the grid's displacement frame (the frame's columns are its axes in basic).
    const Eigen::Vector3d e = (d.direction < 0 ? -1.0 : 1.0) * Eigen::Vector3d::Unit(axis - 1);
    dirs.push_back({d.node, f->second.transpose() * e});
    if (std::find(test_grids.begin(), test_grids.end(), d.node) == test_grids.end()) test_grids.push_back(d.node);
  }
  const auto a_set = a_set_dofs(model);
  const pt::MeasurementCoordinates mc =
      pt::measurement_coordinates(a_set, pt::translational_candidates(a_set, test_grids), dirs);
  // The i-th direction given at a grid is its i-th directed candidate.
  std::map<std::int64_t, std::vector<Eigen::Index>> rows_of;
  for (const auto& c : mc.candidates)
    if (c.directed) rows_of[c.dof.point].push_back(c.row);
  std::map<std::int64_t, std::size_t> used;
  TestCoordinates tc{mc.congruent(op.K), mc.congruent(op.M), {}};
  for (const auto& d : dofs) tc.rows.push_back(rows_of.at(d.node).at(used[d.node]++));
  return tc;
}

/// The reduced mass of a test-analysis model ("guyan" or "irs") on the test DOFs of `tc`.
/// Throws InputError when the reduction fails.
Eigen::MatrixXd tam_mass(const std::string& kind, const TestCoordinates& tc) {
  const estimator::ReducedModel r =
      kind == "guyan" ? estimator::guyan_reduce(tc.K, tc.M, tc.rows) : estimator::irs_reduce(tc.K, tc.M, tc.rows);
  if (r.status != estimator::ReductionStatus::Ok) throw formats::InputError(r.message);
  return r.M;
}


nlohmann::json tam_cross_orthogonality_json(const std::vector<std::string>& tams, const translators::FeModel& model,
                                            const translators::FeOperators& op,
                                            const std::vector<translators::MeasuredDof>& dofs, const Eigen::MatrixXd& fe,
                                            const std::vector<int>& fe_numbers, const Eigen::MatrixXd& test,
                                            const std::vector<int>& test_numbers,
                                            const std::vector<std::pair<int, int>>& pairs,
                                            std::vector<std::string>& problems) {
  nlohmann::json out = nlohmann::json::object();
  std::optional<TestCoordinates> tc;  // made once for every TAM asked
  for (const auto& t : tams) {
    nlohmann::json x;
    try {
      if (!tc) tc = test_coordinates(model, op, dofs);
      x = cross_orthogonality_json(fe, tam_mass(t, *tc), fe_numbers, test, test_numbers, pairs,
                                   t == "guyan" ? "Guyan (static condensation of the deck's K, M onto the test DOFs)"
                                                : "IRS (Guyan corrected for the omitted DOFs' inertia, O'Callahan)");
    } catch (const formats::InputError& e) {
      x = {{"unavailable", e.what()}};
      problems.push_back("--tam " + t + ": " + e.what());
    }
    out[t] = x;
  }
  return out;
}

nlohmann::json estimate_tam_json(const estimator::PreparedConfiguration& c, const Eigen::VectorXd& r,
                                 const nlohmann::json& pairs, const std::vector<std::string>& tams,
                                 std::vector<std::string>& problems) {
  auto* om = dynamic_cast<estimator::OperatorModel*>(c.model.get());
  if (!c.fe || !c.assemble || !om)
    throw formats::InputError("--tam needs the deck's K and M: a problem file's estimate has only its operators' Taylor model");
  const estimator::ModalSolution sol = om->solve(r);  // mass-normalised: unit generalised masses
  const translators::FeOperators op = operators_at(c, r);
  std::vector<int> fe_numbers;
  for (Eigen::Index i = 0; i < sol.sensor_shapes.cols(); ++i) fe_numbers.push_back(static_cast<int>(i) + 1);
  Eigen::MatrixXd test(sol.sensor_shapes.rows(), static_cast<Eigen::Index>(c.test.size()));
  for (std::size_t k = 0; k < c.test.size(); ++k) test.col(static_cast<Eigen::Index>(k)) = c.test[k].shape;
  std::vector<std::pair<int, int>> paired;
  for (const auto& p : pairs) paired.emplace_back(p["fe_mode"].get<int>(), p["test_mode"].get<int>());
  return tam_cross_orthogonality_json(tams, *c.fe, op, dofs_of_labels(c.sensor_labels), sol.sensor_shapes, fe_numbers,
                                      test, c.test_numbers, paired, problems);
}

}  // namespace ssid::cli::report
