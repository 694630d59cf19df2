#include <catch2/catch.hpp>

#include <Eigen/Geometry>
#include <random>

#include "formats/parse_error.hpp"
#include "translators/measurement/sensor_mapping.hpp"
#include "translators/measurement/mode_set.hpp"

using namespace ssid::translators;

namespace {
std::vector<GridPosition> grids3() {
  return {GridPosition{1, {0, 0, 0}, Eigen::Matrix3d::Identity()}, GridPosition{2, {1, 0, 0}, Eigen::Matrix3d::Identity()},
          GridPosition{7, {2, 0, 0}, Eigen::Matrix3d::Identity()}};
}
}  // namespace

TEST_CASE("Test nodes map to grids by id; unknown ids are reported", "[mapping]") {
  std::vector<TestNode> nodes{{1, {0, 0, 0}, 0}, {2, {1, 0, 0}, 0}, {99, {5, 5, 5}, 0}};
  auto m = map_test_nodes(nodes, grids3(), {});
  CHECK(m.matches.size() == 2);
  CHECK(m.grid_of(2) == 2);
  CHECK_FALSE(m.grid_of(99));
  CHECK(m.unmapped == std::vector<std::int64_t>{99});
  REQUIRE(m.problems.size() == 1);
  CHECK(m.problems[0] == "test node 99: no grid with this id");
}

TEST_CASE("Measured DOFs on test nodes that map to no grid are refused, each node named", "[mapping][integrity]") {
  auto message = [](const std::vector<MeasuredDof>& measured, const NodeMapping& m) {
    try {
      require_mapped(measured, m, "test.unv", "the deck rod.bdf");
    } catch (const ssid::formats::InputError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  std::vector<TestNode> nodes{{1, {0, 0, 0}, 0}, {5, {1, 0, 0}, 0}, {6, {2, 0, 0}, 0}, {99, {3, 0, 0}, 0}};
  const auto m = map_test_nodes(nodes, grids3(), {});
  CHECK(m.why_unmapped.at(5) == "no grid with this id");
  // Node 99 carries no measured DOF (geometry only): not checked.
  CHECK(message({{1, 1}, {1, 2}}, m) == "accepted");
  CHECK(message({{1, 1}, {5, 1}, {5, 2}}, m) == "test.unv: test node 5: no grid with this id in the deck rod.bdf");
  CHECK(message({{6, 3}, {1, 1}, {5, 1}}, m) ==
        "test.unv: 2 measured test nodes map to no grid of the deck rod.bdf:\n"
        "  test node 6: no grid with this id\n"
        "  test node 5: no grid with this id");
  // A measured node the test geometry does not list at all.
  CHECK(message({{1, 1}, {42, 1}}, m) ==
        "test.unv: test node 42: not a node of the test geometry (dataset 15 or 2411), so no grid of the deck rod.bdf");
  // Position matching: the reason is the distance.
  NodeMapOptions o;
  o.by = MapBy::Position;
  o.tolerance = 0.01;
  const auto p = map_test_nodes({{103, {4, 0, 0}, 0}}, grids3(), o);
  CHECK(message({{103, 1}}, p) ==
        "test.unv: test node 103: nearest grid 7 at 2 is beyond the tolerance 0.01 in the deck rod.bdf");
  // At most ten listed.
  std::vector<MeasuredDof> many;
  for (int k = 0; k < 12; ++k) many.push_back({1000 + k, 1});
  const std::string all = message(many, m);
  CHECK_THAT(all, Catch::StartsWith("test.unv: 12 measured test nodes map to no grid of the deck rod.bdf:\n"));
  CHECK_THAT(all, Catch::EndsWith("  test node 1009: not a node of the test geometry (dataset 15 or 2411)\n  ... and 2 more"));
}

TEST_CASE("Test nodes map to the nearest grid within a tolerance", "[mapping]") {
  std::vector<TestNode> nodes{{101, {1.001, 0, 0}, 0}, {102, {2, 0.004, -0.003}, 0}, {103, {4, 0, 0}, 0}};
  NodeMapOptions o;
  o.by = MapBy::Position;
  o.tolerance = 0.01;
  auto m = map_test_nodes(nodes, grids3(), o);
  CHECK(m.grid_of(101) == 2);
  CHECK(m.grid_of(102) == 7);
  CHECK(m.matches[1].distance == Approx(0.005));
  CHECK(m.matches[1].by_position);
  CHECK(m.unmapped == std::vector<std::int64_t>{103});
  CHECK_THAT(m.problems.at(0), Catch::Contains("test node 103: nearest grid 7 at 2 is beyond the tolerance 0.01"));
  // Id first, position for the rest.
  o.by = MapBy::IdThenPosition;
  std::vector<TestNode> mixed{{1, {9, 9, 9}, 0}, {500, {0.999, 0, 0}, 0}};
  auto k = map_test_nodes(mixed, grids3(), o);
  CHECK(k.grid_of(1) == 1);
  CHECK_FALSE(k.matches[0].by_position);
  CHECK(k.grid_of(500) == 2);
  // Two test nodes on one grid, and a local displacement system, are reported.
  std::vector<TestNode> twice{{11, {1.0, 0, 0}, 0}, {12, {1.002, 0, 0}, 3}};
  o.by = MapBy::Position;
  auto t = map_test_nodes(twice, grids3(), o);
  CHECK(t.matches.size() == 2);
  CHECK(t.problems.size() == 2);
  CHECK_THAT(t.problems[0], Catch::Contains("displacement system 3"));
  CHECK(t.problems[1] == "grid 2 receives test nodes 11 12");
  o.tolerance = 0;
  CHECK_THROWS_AS(map_test_nodes(twice, grids3(), o), ssid::formats::InputError);
}

TEST_CASE("Measured directions become FE DOF combinations through the grid's displacement frame", "[mapping]") {
  // Identity frame: -Y on test node 5 -> grid 2 component 2 with -1.
  NodeMapping m;
  m.matches.push_back({5, 2, 0.0, false});
  auto g = grids3();
  auto obs = observe({{5, -2}, {5, 6}, {77, 1}}, m, g);
  REQUIRE(obs.rows.size() == 2);
  REQUIRE(obs.rows[0].terms.size() == 1);
  CHECK(obs.rows[0].terms[0].first == Dof{2, 2});
  CHECK(obs.rows[0].terms[0].second == -1.0);
  CHECK(obs.rows[1].terms[0].first == Dof{2, 6});
  CHECK(obs.unmapped == std::vector<MeasuredDof>{{77, 1}});
  CHECK_THROWS_AS(observe({{5, 7}}, m, g), ssid::formats::InputError);

  // A rotated frame: the observation of u_cd = Rᵀ u_basic returns the basic component.
  Eigen::Matrix3d R = (Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized())).toRotationMatrix();
  g[1].frame = R;
  std::mt19937 rng(3);
  std::normal_distribution<double> n;
  Eigen::Vector3d u(n(rng), n(rng), n(rng)), w(n(rng), n(rng), n(rng));
  Eigen::Vector3d u_cd = R.transpose() * u, w_cd = R.transpose() * w;
  auto o2 = observe({{5, 1}, {5, -2}, {5, 3}, {5, 4}, {5, -6}}, m, g);
  REQUIRE(o2.rows.size() == 5);
  const double expected[] = {u(0), -u(1), u(2), w(0), -w(2)};
  for (int r = 0; r < 5; ++r) {
    double z = 0;
    for (const auto& [dof, c] : o2.rows[r].terms) z += c * (dof.component <= 3 ? u_cd(dof.component - 1) : w_cd(dof.component - 4));
    CHECK(z == Approx(expected[r]).epsilon(1e-14));
  }
  // As a sparse matrix over a DOF map; DOFs the map lacks (constrained) drop out.
  DofMap dm;
  for (int c = 1; c <= 6; ++c) dm.add({1, c});
  for (int c = 1; c <= 5; ++c) dm.add({2, c});  // (2, 6) constrained
  auto C = observation_matrix(o2, dm);
  CHECK(C.rows() == 5);
  CHECK(C.cols() == 11);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(11);
  x.segment(6, 3) = u_cd;
  x(9) = w_cd(0);
  x(10) = w_cd(1);
  Eigen::VectorXd z = C * x;
  CHECK(z(0) == Approx(u(0)).epsilon(1e-14));
  CHECK(z(1) == Approx(-u(1)).epsilon(1e-14));
  CHECK(z(3) == Approx(w(0) - R(0, 2) * w_cd(2)).epsilon(1e-12));
}

TEST_CASE("Mode sets from UFF 55: common DOFs, complex modes counted, restriction and relabelling", "[mapping][modes]") {
  auto f = ssid::formats::uff::read_uff(std::string(SSID_TEST_DATA) + "/uff/testlab_mixed.unv");
  ModeSetReport rep;
  ModeSet s = modes_from_uff(f, &rep);
  CHECK(rep.complex_modes == 1);
  // Mode 2 has rotations at nodes 1-3 that mode 1 lacks: 9 DOFs are dropped.
  REQUIRE(rep.problems.size() == 1);
  CHECK_THAT(rep.problems[0], Catch::StartsWith("9 DOF(s)"));
  REQUIRE(s.dofs.size() == 9);
  REQUIRE(s.shapes.cols() == 2);
  CHECK(s.numbers == std::vector<int>{1, 2});
  CHECK(s.frequency_hz == std::vector<double>{7.75, 11.65});
  CHECK(s.damping[1] == 0.015);
  CHECK(s.dofs[4] == MeasuredDof{2, 2});
  CHECK(s.shapes(4, 0) == -0.0625);
  CHECK(s.shapes(4, 1) == -2.0);
  auto r = restrict_to(s, {{3, 1}, {1, 2}, {42, 1}});
  REQUIRE(r.dofs.size() == 2);
  CHECK(r.shapes(0, 0) == 1e-3);
  CHECK(r.shapes(1, 0) == -0.5);
  CHECK(common_dofs(s, r) == std::vector<MeasuredDof>{{1, 2}, {3, 1}});
  NodeMapping m;
  m.matches.push_back({3, 300, 0, false});
  auto l = relabel(s, m);
  REQUIRE(l.dofs.size() == 3);
  CHECK(l.dofs[0] == MeasuredDof{300, 1});
  CHECK(l.shapes(2, 0) == -2.0);
  // Sensors of an FRF test from the 58 records.
  CHECK(measured_dofs(f) == std::vector<MeasuredDof>{{1, 1}, {3, -2}});
}

TEST_CASE("Mode sets written as UFF 55 read back to the same set", "[mapping][modes]") {
  ModeSet s;
  for (std::int64_t n : {4, 9, 2})
    for (int c = 1; c <= 3; ++c) s.dofs.push_back({n, c});
  s.shapes = Eigen::MatrixXd::Random(9, 3);
  s.frequency_hz = {1.5, 2.25, 7.125};
  s.numbers = {1, 2, 5};
  s.damping = {0.01, 0.02, 0.03};
  s.modal_mass = {1, 1, 1};
  auto f = mode_set_to_uff(s, {{4, 0, 0, 1, {0, 0, 0}}, {9, 0, 0, 1, {1, 0, 0}}, {2, 0, 0, 1, {2, 0, 0}}});
  auto back = modes_from_uff(ssid::formats::uff::parse_uff(
      ssid::formats::uff::format_uff(f, ssid::formats::uff::Precision::Extended), "set.unv"));
  CHECK(back.dofs == s.dofs);
  CHECK(back.shapes == s.shapes);
  CHECK(back.frequency_hz == s.frequency_hz);
  CHECK(back.numbers == s.numbers);
  CHECK(back.damping == s.damping);
  // Signed and partial sensor sets: -Y becomes the negated value on +Y, the rest 0.
  ModeSet p;
  p.dofs = {{7, -2}, {7, 5}};
  p.shapes = Eigen::Matrix<double, 2, 1>(0.5, 0.25);
  p.frequency_hz = {3.0};
  auto g = mode_set_to_uff(p);
  const auto& m = *g.nodal_data()[0];
  CHECK(m.values_per_node == 6);
  CHECK(m.values(0, 1) == -0.5);
  CHECK(m.values(0, 4) == 0.25);
  CHECK(m.values(0, 0) == 0.0);
  CHECK(m.mode_number() == 1);
}
