#include <catch2/catch.hpp>

#include <Eigen/Geometry>
#include <random>

#include "translators/coord_system.hpp"

using namespace ssid::translators;
using Eigen::Matrix3d;
using Eigen::Vector3d;

namespace {
CoordDefinition def(long cid, long rid, CoordType t, Vector3d a, Vector3d b, Vector3d c) {
  return {cid, rid, t, a, b, c, ""};
}
double err(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) { return (a - b).cwiseAbs().maxCoeff(); }
}  // namespace

TEST_CASE("CORD2R: axes from A, B, C and a hand-computed point", "[coord]") {
  // Local Z along basic X, local X along basic Y, so local Y = Z x X = basic Z.
  CoordSystems cs({def(1, 0, CoordType::Rectangular, {1, 2, 3}, {5, 2, 3}, {1, 7, 3})});
  const CoordSystem& s = cs.get(1);
  Matrix3d expect;
  expect << 0, 0, 1, 1, 0, 0, 0, 1, 0;
  CHECK(err(s.axes, expect) < 1e-15);
  // local (1,2,3) = 1*Yb + 2*Zb + 3*Xb, shifted by the origin.
  CHECK(err(cs.position_to_basic(1, {1, 2, 3}), Vector3d(4, 3, 5)) < 1e-14);
  CHECK(err(cs.displacement_frame(1, {9, 9, 9}), expect) < 1e-15);
  // C need not be on the X axis, only in the X-Z plane.
  CoordSystems cs2({def(1, 0, CoordType::Rectangular, {1, 2, 3}, {5, 2, 3}, {8, 7, 3})});
  CHECK(err(cs2.get(1).axes, expect) < 1e-15);
}

TEST_CASE("CORD2C: position (R, theta, Z) and the local (r, theta, z) frame", "[coord]") {
  CoordSystems cs({def(5, 0, CoordType::Cylindrical, {0, 0, 1}, {0, 0, 2}, {1, 0, 1})});
  CHECK(err(cs.position_to_basic(5, {2, 90, 5}), Vector3d(0, 2, 6)) < 1e-14);
  CHECK(err(cs.position_to_basic(5, {2, 210, -1}), Vector3d(-std::sqrt(3.0), -1, 0)) < 1e-14);
  Matrix3d f = cs.displacement_frame(5, {0, 2, 6});
  CHECK(err(f.col(0), Vector3d(0, 1, 0)) < 1e-15);   // radial
  CHECK(err(f.col(1), Vector3d(-1, 0, 0)) < 1e-15);  // tangential
  CHECK(err(f.col(2), Vector3d(0, 0, 1)) < 1e-15);
  // On the axis the frame is the theta = 0 limit: the system's own axes.
  CHECK(err(cs.displacement_frame(5, {0, 0, 3}), Matrix3d::Identity()) < 1e-15);
}

TEST_CASE("CORD2S: position (R, theta, phi) and the local (r, theta, phi) frame", "[coord]") {
  CoordSystems cs({def(7, 0, CoordType::Spherical, {0, 0, 0}, {0, 0, 1}, {1, 0, 0})});
  CHECK(err(cs.position_to_basic(7, {2, 90, 90}), Vector3d(0, 2, 0)) < 1e-14);
  CHECK(err(cs.position_to_basic(7, {2, 0, 33}), Vector3d(0, 0, 2)) < 1e-14);
  CHECK(err(cs.position_to_basic(7, {1, 45, 0}), Vector3d(std::sqrt(0.5), 0, std::sqrt(0.5))) < 1e-14);
  Matrix3d f = cs.displacement_frame(7, {0, 2, 0});
  CHECK(err(f.col(0), Vector3d(0, 1, 0)) < 1e-15);   // u_r outward
  CHECK(err(f.col(1), Vector3d(0, 0, -1)) < 1e-15);  // u_theta: away from +Z
  CHECK(err(f.col(2), Vector3d(-1, 0, 0)) < 1e-15);  // u_phi
}

TEST_CASE("nested systems: A, B, C given in a cylindrical reference", "[coord]") {
  // System 1: cylindrical about basic Z, origin (10,0,0).
  // System 2: rectangular, defined in system 1 coordinates:
  //   A = (R=1, θ=90, Z=0)  -> basic (10, 1, 0)
  //   B = (R=1, θ=90, Z=2)  -> basic (10, 1, 2)   so local Z = basic Z
  //   C = (R=2, θ=90, Z=0)  -> basic (10, 2, 0)   so local X = basic Y
  // System 3: rectangular with RID 2, a pure shift of (1,0,0) in system 2
  //   = basic +Y.
  std::vector<CoordDefinition> defs = {
      def(3, 2, CoordType::Rectangular, {1, 0, 0}, {1, 0, 1}, {2, 0, 0}),
      def(2, 1, CoordType::Rectangular, {1, 90, 0}, {1, 90, 2}, {2, 90, 0}),
      def(1, 0, CoordType::Cylindrical, {10, 0, 0}, {10, 0, 1}, {11, 0, 0})};
  CoordSystems cs(defs);
  Matrix3d ax2;
  ax2 << 0, -1, 0, 1, 0, 0, 0, 0, 1;
  CHECK(err(cs.get(2).axes, ax2) < 1e-14);
  CHECK(err(cs.get(2).origin, Vector3d(10, 1, 0)) < 1e-14);
  CHECK(err(cs.get(3).origin, Vector3d(10, 2, 0)) < 1e-14);
  CHECK(err(cs.get(3).axes, ax2) < 1e-14);
  // A point at (1, 1, 1) in system 3: origin + 1*Yb + 1*(-Xb) + 1*Zb.
  CHECK(err(cs.position_to_basic(3, {1, 1, 1}), Vector3d(9, 3, 1)) < 1e-14);
}

TEST_CASE("round trip of positions and frames in random nested systems", "[coord]") {
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> u(-3, 3);
  auto rv = [&] { return Vector3d(u(rng), u(rng), u(rng)); };
  const CoordType types[] = {CoordType::Rectangular, CoordType::Cylindrical, CoordType::Spherical};
  std::vector<CoordDefinition> defs;
  for (int i = 1; i <= 9; ++i) {
    // Points given in the reference's coordinates; any three generic triples
    // give a valid (non-collinear) system with probability one.
    Vector3d a = rv(), b = rv(), c = rv();
    a(0) = std::abs(a(0)) + 0.5, b(0) = std::abs(b(0)) + 0.5, c(0) = std::abs(c(0)) + 0.5;
    for (Vector3d* p : {&a, &b, &c}) (*p)(1) *= 40, (*p)(2) *= 40;
    defs.push_back(def(i, i == 1 ? 0 : i - 1, types[i % 3], a, b, c));
  }
  CoordSystems cs(defs);
  for (int i = 1; i <= 9; ++i) {
    const CoordSystem& s = cs.get(i);
    CHECK(err(s.axes.transpose() * s.axes, Matrix3d::Identity()) < 1e-13);
    CHECK(s.axes.determinant() == Approx(1.0));
    INFO("system " << i << " origin " << s.origin.transpose());
    for (int k = 0; k < 20; ++k) {
      Vector3d x = rv();
      CHECK(err(s.to_basic(s.from_basic(x)), x) < 1e-13 * (1 + (x - s.origin).norm()));
      Matrix3d f = s.displacement_frame(x);
      CHECK(err(f.transpose() * f, Matrix3d::Identity()) < 1e-13);
      CHECK(f.determinant() == Approx(1.0));
      // Each displacement direction is the direction in which the point moves
      // when its own coordinate increases (central differences).
      if (s.type != CoordType::Rectangular) {
        Vector3d q = s.from_basic(x);
        for (int j = 0; j < 3; ++j) {
          const double h = 1e-6;
          Vector3d qp = q, qm = q;
          qp(j) += h, qm(j) -= h;
          Vector3d d = (s.to_basic(qp) - s.to_basic(qm)).normalized();
          CHECK(err(d, f.col(j)) < 1e-7);
        }
      }
    }
  }
}

TEST_CASE("coordinate-system input errors name the definition", "[coord]") {
  using Catch::Matchers::Contains;
  CHECK_THROWS_WITH(CoordSystems({def(1, 0, CoordType::Rectangular, {0, 0, 0}, {0, 0, 1}, {0, 0, 2})}),
                    Contains("CORD2R 1") && Contains("collinear"));
  CHECK_THROWS_WITH(CoordSystems({def(2, 9, CoordType::Cylindrical, {0, 0, 0}, {0, 0, 1}, {1, 0, 0})}),
                    Contains("CORD2C 2") && Contains("RID 9"));
  CHECK_THROWS_WITH(CoordSystems({def(2, 3, CoordType::Rectangular, {0, 0, 0}, {0, 0, 1}, {1, 0, 0}),
                                  def(3, 2, CoordType::Rectangular, {0, 0, 0}, {0, 0, 1}, {1, 0, 0})}),
                    Contains("cycle"));
  CHECK_THROWS_AS(CoordSystems().get(4), std::out_of_range);
  CHECK(err(dof_transform(Matrix3d::Identity() * 2).diagonal(), Eigen::Matrix<double, 6, 1>::Constant(2)) == 0);
}
