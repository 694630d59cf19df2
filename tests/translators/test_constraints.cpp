#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <random>

#include "translators/constraints.hpp"

using namespace ssid::translators;

TEST_CASE("reduction substitutes chained dependents and drops SPC DOFs", "[constraints]") {
  // g = {u0, u1, u2, u3, u4}: u2 = 0.5 u0 (dependent), u3 = 2 u0 + u2 (chained), u4 fixed.
  std::vector<MpcEquation> mpc = {{2, {{0, 0.5}}, "MPC 1"}, {3, {{0, 2.0}, {2, 1.0}}, "MPC 2"}};
  Reduction r = build_reduction(5, mpc, {4});
  REQUIRE(r.a_to_g == std::vector<std::size_t>{0, 1});
  Eigen::MatrixXd T = Eigen::MatrixXd(r.T);
  Eigen::MatrixXd expect(5, 2);
  expect << 1, 0, 0, 1, 0.5, 0, 2.5, 0, 0, 0;
  CHECK((T - expect).norm() == Approx(0.0).margin(1e-15));
  // T^T A T of a symmetric matrix is symmetric and matches the dense product.
  Eigen::MatrixXd A = Eigen::MatrixXd::Random(5, 5);
  A = (A + A.transpose()).eval();
  SparseMatrix As = A.sparseView();
  Eigen::MatrixXd red = Eigen::MatrixXd(reduce(As, r));
  CHECK((red - expect.transpose() * A * expect).norm() == Approx(0.0).margin(1e-12));
}

TEST_CASE("reduction errors name the constraint", "[constraints]") {
  std::vector<MpcEquation> twice = {{1, {{0, 1.0}}, "RBE2 7"}, {1, {{2, 1.0}}, "MPC 3"}};
  CHECK_THROWS_WITH(build_reduction(3, twice, {}), Catch::Contains("RBE2 7") && Catch::Contains("MPC 3"));
  std::vector<MpcEquation> cyc = {{1, {{2, 1.0}}, "MPC 1"}, {2, {{1, 1.0}}, "MPC 2"}};
  CHECK_THROWS_WITH(build_reduction(3, cyc, {}), Catch::Contains("cycle"));
  std::vector<MpcEquation> one = {{1, {{0, 1.0}}, "RBAR 4"}};
  CHECK_THROWS_WITH(build_reduction(3, one, {1}), Catch::Contains("RBAR 4"));
}

namespace {
std::array<std::size_t, 6> block(std::size_t first) { return {first, first + 1, first + 2, first + 3, first + 4, first + 5}; }

/// Displacements of grid p under the rigid motion q = (u0, θ0) about x0, computed
/// independently of rigid_body_rows: u = u0 + θ0 × (x − x0).
Eigen::Matrix<double, 6, 1> rigid_motion(const Eigen::Matrix<double, 6, 1>& q, const Eigen::Vector3d& x,
                                         const Eigen::Vector3d& x0) {
  Eigen::Matrix<double, 6, 1> u;
  u.head<3>() = q.head<3>() + Eigen::Vector3d(q.tail<3>()).cross(x - x0);
  u.tail<3>() = q.tail<3>();
  return u;
}

double check_equations(const std::vector<MpcEquation>& eqs, const Eigen::VectorXd& ug) {
  double worst = 0;
  for (const auto& e : eqs) {
    double rhs = 0;
    for (const auto& [j, c] : e.terms) rhs += c * ug(static_cast<int>(j));
    worst = std::max(worst, std::abs(ug(static_cast<int>(e.dependent)) - rhs));
  }
  return worst;
}
}  // namespace

TEST_CASE("rigid elements: every rigid-body motion satisfies RBE2 and general RBAR equations", "[constraints][rigid]") {
  const Eigen::Vector3d xa(0.3, -1.2, 2.0), xb(1.7, 0.4, -0.5), xc(-0.8, 2.2, 1.1);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  SECTION("RBE2: GN 123456, two dependent grids") {
    std::vector<RigidGrid> g = {{xa, block(0), "123456", ""}, {xb, block(6), "", "123456"}, {xc, block(12), "", "123"}};
    auto eqs = rigid_equations(g, "RBE2 1");
    CHECK(eqs.size() == 9);
    for (int trial = 0; trial < 5; ++trial) {
      Eigen::Matrix<double, 6, 1> q;
      for (int i = 0; i < 6; ++i) q(i) = u(rng);
      Eigen::VectorXd ug(18);
      ug.segment<6>(0) = rigid_motion(q, xa, xa);
      ug.segment<6>(6) = rigid_motion(q, xb, xa);
      ug.segment<6>(12) = rigid_motion(q, xc, xa);
      CHECK(check_equations(eqs, ug) < 1e-13);
    }
  }
  SECTION("RBAR with independent components split between the ends") {
    std::vector<RigidGrid> g = {{xa, block(0), "12345", "6"}, {xb, block(6), "1", "23456"}};
    auto eqs = rigid_equations(g, "RBAR 2");
    CHECK(eqs.size() == 6);
    Eigen::Matrix<double, 6, 1> q;
    for (int i = 0; i < 6; ++i) q(i) = u(rng);
    Eigen::VectorXd ug(12);
    ug.segment<6>(0) = rigid_motion(q, xa, xb);
    ug.segment<6>(6) = rigid_motion(q, xb, xb);
    CHECK(check_equations(eqs, ug) < 1e-13);
  }
  SECTION("too few independent components is an error naming the element") {
    std::vector<RigidGrid> g = {{xa, block(0), "123", ""}, {xb, block(6), "", "123456"}};
    CHECK_THROWS_WITH(rigid_equations(g, "RBAR 9"), Catch::Contains("RBAR 9"));
  }
}

TEST_CASE("RBE3 reproduces rigid-body motions of its independent grids", "[constraints][rbe3]") {
  const Eigen::Vector3d xref(0.1, 0.2, 0.3);
  Rbe3Group grp;
  grp.weight = 1.0;
  grp.components = "123";
  std::vector<Eigen::Vector3d> xs = {{1, 0, 0}, {0, 1, 0}, {-1, 0, 0.2}, {0, -1, 0.5}};
  for (std::size_t i = 0; i < xs.size(); ++i) grp.grids.push_back({xs[i], block(6 * (i + 1))});
  Rbe3Group heavy = grp;
  heavy.weight = 3.0;
  heavy.grids.resize(1);
  heavy.grids[0] = {Eigen::Vector3d(0.5, 0.5, -0.4), block(30)};
  auto eqs = rbe3_equations(xref, block(0), "123456", {grp, heavy}, "RBE3 5");
  REQUIRE(eqs.size() == 6);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int trial = 0; trial < 5; ++trial) {
    Eigen::Matrix<double, 6, 1> q;
    for (int i = 0; i < 6; ++i) q(i) = u(rng);
    Eigen::VectorXd ug = Eigen::VectorXd::Zero(36);
    ug.segment<6>(0) = rigid_motion(q, xref, xref);
    for (std::size_t i = 0; i < xs.size(); ++i) ug.segment<6>(6 * static_cast<int>(i + 1)) = rigid_motion(q, xs[i], xref);
    ug.segment<6>(30) = rigid_motion(q, Eigen::Vector3d(0.5, 0.5, -0.4), xref);
    CHECK(check_equations(eqs, ug) < 1e-12);
  }
  // Translations only: the reference translation is the weighted mean when grids are symmetric.
  Rbe3Group sym;
  sym.components = "123";
  for (std::size_t i = 0; i < 4; ++i) sym.grids.push_back({xs[i].cwiseProduct(Eigen::Vector3d(1, 1, 0)), block(6 * (i + 1))});
  auto e2 = rbe3_equations(Eigen::Vector3d::Zero(), block(0), "1", {sym}, "RBE3 6");
  REQUIRE(e2.size() == 1);
  double sum = 0;
  for (const auto& [j, c] : e2[0].terms) {
    CHECK(c == Approx(0.25));
    sum += c;
  }
  CHECK(sum == Approx(1.0));
  // Collinear grids cannot determine the rotation about their line.
  Rbe3Group line;
  line.components = "123";
  line.grids = {{Eigen::Vector3d(1, 0, 0), block(6)}, {Eigen::Vector3d(-1, 0, 0), block(12)}};
  CHECK_THROWS_WITH(rbe3_equations(Eigen::Vector3d::Zero(), block(0), "4", {line}, "RBE3 7"), Catch::Contains("RBE3 7"));
}

TEST_CASE("AUTOSPC finds the rotations and the out-of-plane translation of a planar rod truss", "[constraints][autospc]") {
  // Three grids in the x-y plane joined by three rods; 18 DOFs.
  DofMap dofs;
  for (int gid = 1; gid <= 3; ++gid)
    for (int c = 1; c <= 6; ++c) dofs.add({gid, c});
  std::vector<Eigen::Vector3d> x = {{0, 0, 0}, {2, 0, 0}, {0.5, 1.5, 0}};
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(18, 18);
  auto rod = [&](int a, int b) {
    Eigen::Vector3d n = (x[b] - x[a]);
    double L = n.norm();
    n /= L;
    Eigen::Matrix3d k = 1e6 / L * n * n.transpose();
    K.block<3, 3>(6 * a, 6 * a) += k;
    K.block<3, 3>(6 * b, 6 * b) += k;
    K.block<3, 3>(6 * a, 6 * b) -= k;
    K.block<3, 3>(6 * b, 6 * a) -= k;
  };
  rod(0, 1);
  rod(1, 2);
  rod(0, 2);
  Reduction none = build_reduction(18, {}, {});
  auto s = find_singular_dofs(SparseMatrix(K.sparseView()), none, dofs);
  // Per grid: z translation (3) and all rotations (4, 5, 6).
  std::vector<std::size_t> expect;
  for (std::size_t g = 0; g < 3; ++g)
    for (std::size_t c : {2, 3, 4, 5}) expect.push_back(6 * g + c);
  CHECK(s == expect);
}

TEST_CASE("rigid elements in rotated displacement frames (GRID CD)", "[constraints][rigid]") {
  // The same rigid-body motion, written in each grid's own displacement frame,
  // must satisfy RBE2 and RBE3 equations built with those frames.
  const Eigen::Vector3d xa(0.3, -1.2, 2.0), xb(1.7, 0.4, -0.5), xc(-0.8, 2.2, 1.1);
  const Eigen::Matrix3d ta = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const Eigen::Matrix3d tb = Eigen::AngleAxisd(-1.1, Eigen::Vector3d(0, 1, 1).normalized()).toRotationMatrix();
  const Eigen::Matrix3d tc = Eigen::AngleAxisd(2.0, Eigen::Vector3d(1, 0, 0)).toRotationMatrix();
  auto local = [](const Eigen::Matrix<double, 6, 1>& u, const Eigen::Matrix3d& t) {
    Eigen::Matrix<double, 6, 1> out;
    out.head<3>() = t.transpose() * u.head<3>();
    out.tail<3>() = t.transpose() * u.tail<3>();
    return out;
  };
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  Eigen::Matrix<double, 6, 1> q;
  for (int i = 0; i < 6; ++i) q(i) = u(rng);
  Eigen::VectorXd ug(18);
  ug.segment<6>(0) = local(rigid_motion(q, xa, xa), ta);
  ug.segment<6>(6) = local(rigid_motion(q, xb, xa), tb);
  ug.segment<6>(12) = local(rigid_motion(q, xc, xa), tc);
  SECTION("RBE2") {
    RigidGrid a{xa, block(0), "123456", "", ta}, b{xb, block(6), "", "123456", tb}, c{xc, block(12), "", "1236", tc};
    const auto eqs = rigid_equations({a, b, c}, "RBE2 7");
    CHECK(eqs.size() == 10);
    CHECK(check_equations(eqs, ug) < 1e-12);
    // Without the frames the same equations are violated: the test can fail.
    RigidGrid a0{xa, block(0), "123456", ""}, b0{xb, block(6), "", "123456"}, c0{xc, block(12), "", "1236"};
    CHECK(check_equations(rigid_equations({a0, b0, c0}, "RBE2 7"), ug) > 1e-3);
  }
  SECTION("RBE3 reference in a rotated frame") {
    Rbe3Group grp;
    grp.components = "123";
    grp.grids = {{xb, block(6)}, {xc, block(12)}, {Eigen::Vector3d(2.0, -1.0, 0.5), block(18)}};
    const Eigen::Matrix3d td = Eigen::AngleAxisd(0.4, Eigen::Vector3d(0, 0, 1)).toRotationMatrix();
    grp.frames = {tb, tc, td};
    Eigen::VectorXd ug4(24);
    ug4.head<18>() = ug;
    ug4.segment<6>(18) = local(rigid_motion(q, Eigen::Vector3d(2.0, -1.0, 0.5), xa), td);
    const auto eqs = rbe3_equations(xa, block(0), "123456", {grp}, "RBE3 8", ta);
    CHECK(eqs.size() == 6);
    CHECK(check_equations(eqs, ug4) < 1e-12);  // a rigid motion is interpolated exactly
  }
}
