#include <catch2/catch.hpp>

#include "element_test_util.hpp"
#include "translators/elements/elements.hpp"  // the umbrella header must compile on its own
#include "translators/elements/point.hpp"
#include "translators/elements/rigid_body.hpp"

using namespace ssid::translators::elements;
using namespace element_test;
using Eigen::MatrixXd;
using Eigen::Vector3d;

TEST_CASE("CONM2: kinetic energy of a rigid motion with offset, CID inertia frame and CD frame", "[conm2]") {
  std::mt19937 rng(21);
  for (int trial = 0; trial < 20; ++trial) {
    Conm2 c;
    c.mass = 2.5;
    c.offset = random_vector(rng, 0.5);
    c.i11 = 0.3, c.i22 = 0.4, c.i33 = 0.5, c.i21 = 0.05, c.i31 = -0.04, c.i32 = 0.02;
    c.inertia_frame = random_rotation(rng);
    c.t = random_rotation(rng);
    const Matrix6d M = conm2_matrix(c);
    CHECK((M - M.transpose()).norm() < 1e-14);
    // Grid velocity (v0, ω) in basic; the element sees it in the CD frame.
    const Vector3d v0 = random_vector(rng), w = random_vector(rng);
    Eigen::Matrix<double, 6, 1> q;
    q << c.t.transpose() * v0, c.t.transpose() * w;
    Eigen::Matrix3d I;
    I << c.i11, -c.i21, -c.i31, -c.i21, c.i22, -c.i32, -c.i31, -c.i32, c.i33;
    const Eigen::Matrix3d Ib = c.inertia_frame * I * c.inertia_frame.transpose();
    const double twice_ke = c.mass * (v0 + w.cross(c.offset)).squaredNorm() + w.dot(Ib * w);
    CHECK(q.dot(M * q) == Approx(twice_ke).epsilon(1e-13));
  }
}

TEST_CASE("CONM2: I21 is +∫x1 x2 dm (QRG sign) — equals two offset point masses", "[conm2]") {
  // Masses m/2 at ±(a, a, 0): about their CG, I11 = I22 = m a², I33 = 2 m a²,
  // ∫ x y dm = m a².
  const double m = 3.0, a = 0.4;
  Matrix6d sum = Matrix6d::Zero();
  for (double sgn : {1.0, -1.0}) {
    Conm2 p;
    p.mass = m / 2;
    p.offset = Vector3d(sgn * a, sgn * a, 0);
    sum += conm2_matrix(p);
  }
  Conm2 c;
  c.mass = m;
  c.i11 = m * a * a, c.i22 = m * a * a, c.i33 = 2 * m * a * a, c.i21 = m * a * a;
  CHECK((conm2_matrix(c) - sum).norm() < 1e-14);
  // Derivatives: linear, and they rebuild M.
  Matrix6d rebuilt = c.mass * conm2_derivative(c, Conm2Param::Mass) + c.i11 * conm2_derivative(c, Conm2Param::I11) +
                     c.i21 * conm2_derivative(c, Conm2Param::I21) + c.i22 * conm2_derivative(c, Conm2Param::I22) +
                     c.i33 * conm2_derivative(c, Conm2Param::I33);
  CHECK((rebuilt - conm2_matrix(c)).norm() < 1e-14);
  Conm2 cp = c;
  cp.i32 += 1e-3;
  CHECK(((conm2_matrix(cp) - conm2_matrix(c)) / 1e-3 - conm2_derivative(c, Conm2Param::I32)).norm() < 1e-10);
}

TEST_CASE("CONM2 on a grounded CBUSH: six closed-form frequencies with offset coupling", "[conm2][cbush]") {
  const double m = 2.0, r = 0.3;
  Conm2 c;
  c.mass = m;
  c.offset = Vector3d(r, 0, 0);
  c.i11 = 0.05, c.i22 = 0.07, c.i33 = 0.09;
  BushGeometry b;
  b.grounded = true;
  Eigen::Matrix<double, 6, 1> k;
  k << 100, 200, 300, 10, 20, 30;
  const MatrixXd K = bush_stiffness(b, k);
  Eigen::GeneralizedSelfAdjointEigenSolver<MatrixXd> es(K, MatrixXd(conm2_matrix(c)));
  // u: k1/m; θx: k4/I11; (v, θz) and (w, θy) pairs, M = [m ±m r; ±m r I + m r²]:
  //   λ² m I − λ (k_t (I + m r²) + k_r m) + k_t k_r = 0.
  auto pair = [&](double kt, double kr, double I) {
    const double A = m * I, B = -(kt * (I + m * r * r) + kr * m), C = kt * kr;
    const double disc = std::sqrt(B * B - 4 * A * C);
    return std::vector<double>{(-B - disc) / (2 * A), (-B + disc) / (2 * A)};
  };
  std::vector<double> expect = {k(0) / m, k(3) / c.i11};
  for (double x : pair(k(1), k(5), c.i33)) expect.push_back(x);
  for (double x : pair(k(2), k(4), c.i22)) expect.push_back(x);
  std::sort(expect.begin(), expect.end());
  for (int i = 0; i < 6; ++i) CHECK(es.eigenvalues()(i) == Approx(expect[i]).epsilon(1e-12));
}

TEST_CASE("CELAS/CMASS: two-DOF chain against the closed form", "[scalar]") {
  const double k1 = 3.0, k2 = 5.0, m1 = 2.0, m2 = 0.5;
  MatrixXd K = MatrixXd::Zero(2, 2), M = MatrixXd::Zero(2, 2);
  K(0, 0) += scalar_element_matrix(k1, true)(0, 0);  // CELAS grounded on DOF 1
  K += scalar_element_matrix(k2, false);              // CELAS between DOF 1 and 2
  M(0, 0) += scalar_element_matrix(m1, true)(0, 0);
  M(1, 1) += scalar_element_matrix(m2, true)(0, 0);
  Eigen::GeneralizedSelfAdjointEigenSolver<MatrixXd> es(K, M);
  const double A = m1 * m2, B = -(m1 * k2 + m2 * (k1 + k2)), C = k1 * k2;
  const double disc = std::sqrt(B * B - 4 * A * C);
  CHECK(es.eigenvalues()(0) == Approx((-B - disc) / (2 * A)).epsilon(1e-13));
  CHECK(es.eigenvalues()(1) == Approx((-B + disc) / (2 * A)).epsilon(1e-13));
  CHECK((scalar_element_matrix(1.0, false) - scalar_element_matrix(k2, false) / k2).norm() < 1e-15);
}

TEST_CASE("CBUSH: rigid-body free for any grid distance and S, derivatives, element-axis springs", "[cbush]") {
  std::mt19937 rng(31);
  for (int trial = 0; trial < 20; ++trial) {
    BushGeometry b;
    b.grids.xa = random_vector(rng);
    b.grids.xb = b.grids.xa + random_vector(rng);
    b.grids.ta = random_rotation(rng);
    b.grids.tb = random_rotation(rng);
    b.s = trial % 2 ? 0.5 : 0.2;
    b.axes = trial % 3 ? bush_axes_from_vector(b.grids.xa, b.grids.xb, random_vector(rng)) : random_rotation(rng);
    Eigen::Matrix<double, 6, 1> k;
    k << 1, 2, 3, 4, 5, 6;
    const MatrixXd K = bush_stiffness(b, k);
    CHECK((K - K.transpose()).norm() < 1e-13);
    CHECK(rigid_body_residual(K, rigid_body_modes({b.grids.xa, b.grids.xb}, {b.grids.ta, b.grids.tb})) < 1e-14);
    MatrixXd rebuilt = MatrixXd::Zero(12, 12);
    for (int i = 1; i <= 6; ++i) rebuilt += k(i - 1) * bush_derivative(b, i);
    CHECK((rebuilt - K).norm() < 1e-12);
  }
  // Element axes from v: x along GA->GB, v in the x-y plane.
  const Eigen::Matrix3d R = bush_axes_from_vector(Vector3d(0, 0, 0), Vector3d(0, 0, 2), Vector3d(1, 1, 0));
  CHECK((R.row(0).transpose() - Vector3d(0, 0, 1)).norm() < 1e-15);
  CHECK((R.row(1).transpose() - Vector3d(1, 1, 0).normalized()).norm() < 1e-15);
  // Translational springs along the element axes: a mass at GB (rotations
  // held) vibrates at sqrt(Ki/m) along each element axis.
  BushGeometry b;
  b.grids.xb = Vector3d(0, 0, 2);
  b.axes = R;
  Eigen::Matrix<double, 6, 1> k;
  k << 4, 9, 16, 1, 1, 1;
  const MatrixXd K = bush_stiffness(b, k);
  const Eigen::Matrix3d kt = K.block<3, 3>(6, 6);
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(kt / 2.0);  // m = 2
  CHECK(es.eigenvalues()(0) == Approx(2.0));
  CHECK(es.eigenvalues()(2) == Approx(8.0));
  CHECK(std::abs(es.eigenvectors().col(2).dot(R.row(2))) == Approx(1.0));  // stiffest along element z
  CHECK_THROWS_WITH(bush_axes_from_vector(Vector3d::Zero(), Vector3d::Zero(), Vector3d::UnitX()),
                    Catch::Matchers::Contains("CID"));
}
