// FRF synthesis by modal superposition (estimator/identification/frf_synthesis.hpp)
// against the closed-form receptance of a 2-DOF spring–mass system with proportional
// damping, (K − ω²M + iωC)⁻¹ written out as adj(D)/det(D).
#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <cmath>
#include <complex>
#include <optional>
#include <string>
#include <vector>

#include "estimator/identification/frf_synthesis.hpp"
#include "formats/parse_error.hpp"

using namespace ssid::estimator::identification;
using cd = std::complex<double>;

namespace {

/// m1 = 2 kg, m2 = 1 kg; k1 = 4e4 N/m to ground, k2 = 1.5e4 N/m between them;
/// Rayleigh damping C = αM + βK (modal ζ_r = α/(2ω_r) + βω_r/2).
struct TwoDof {
  double m1 = 2.0, m2 = 1.0, k1 = 4e4, k2 = 1.5e4, alpha = 0.8, beta = 2e-5;
  Eigen::Matrix2d M() const { return (Eigen::Matrix2d() << m1, 0, 0, m2).finished(); }
  Eigen::Matrix2d K() const { return (Eigen::Matrix2d() << k1 + k2, -k2, -k2, k2).finished(); }
  Eigen::Matrix2d C() const { return alpha * M() + beta * K(); }
  /// Closed form: D = K − ω²M + iωC, D⁻¹ = [d22 −d12; −d21 d11] / (d11 d22 − d12 d21).
  Eigen::Matrix2cd receptance(double f) const {
    const double w = 2 * M_PI * f;
    const Eigen::Matrix2d Kd = K(), Md = M(), Cd = C();
    const cd d11 = Kd(0, 0) - w * w * Md(0, 0) + cd(0, w) * Cd(0, 0);
    const cd d12 = Kd(0, 1) - w * w * Md(0, 1) + cd(0, w) * Cd(0, 1);
    const cd d22 = Kd(1, 1) - w * w * Md(1, 1) + cd(0, w) * Cd(1, 1);
    const cd det = d11 * d22 - d12 * d12;
    Eigen::Matrix2cd h;
    h << d22 / det, -d12 / det, -d12 / det, d11 / det;
    return h;
  }
  /// Mass-normalised modes by the closed-form roots of det(K − λM) = 0.
  ModalFrfModel modes(Eigen::Index drive) const {
    const Eigen::Matrix2d Kd = K(), Md = M();
    const double a = m1 * m2, b = -(Kd(0, 0) * m2 + Kd(1, 1) * m1), c = Kd.determinant();
    const double disc = std::sqrt(b * b - 4 * a * c);
    ModalFrfModel m;
    m.eigenvalue = Eigen::Vector2d((-b - disc) / (2 * a), (-b + disc) / (2 * a));
    m.zeta.resize(2);
    m.response.resize(2, 2);
    for (int r = 0; r < 2; ++r) {
      const double lam = m.eigenvalue(r), wr = std::sqrt(lam);
      Eigen::Vector2d phi(1.0, (Kd(0, 0) - lam * m1) / k2);  // first row of (K − λM)φ = 0
      phi /= std::sqrt(phi.dot(Md * phi));
      m.response.col(r) = phi;
      m.zeta(r) = alpha / (2 * wr) + beta * wr / 2;
    }
    m.drive = m.response.row(drive).transpose();
    return m;
  }
};

}  // namespace

TEST_CASE("FRF synthesis (Eq. 2) equals the closed-form 2-DOF receptance", "[identification][frf_synthesis]") {
  const TwoDof s;
  Eigen::VectorXd f = Eigen::VectorXd::LinSpaced(801, 0.0, 80.0);  // both modes (≈ 12.6, 30.5 Hz) inside
  for (Eigen::Index drive = 0; drive < 2; ++drive) {
    const ModalFrfModel m = s.modes(drive);
    const Eigen::MatrixXcd h = synthesize_frf(f, m);
    const Eigen::MatrixXcd v = synthesize_frf(f, m, FrfQuantity::Velocity);
    const Eigen::MatrixXcd a = synthesize_frf(f, m, FrfQuantity::Acceleration);
    REQUIRE(h.rows() == f.size());
    REQUIRE(h.cols() == 2);
    double worst = 0;
    for (Eigen::Index k = 0; k < f.size(); ++k) {
      const Eigen::Matrix2cd exact = s.receptance(f(k));
      const cd iw(0, 2 * M_PI * f(k));
      for (int o = 0; o < 2; ++o) {
        const double scale = std::abs(exact(o, drive));
        worst = std::max(worst, std::abs(h(k, o) - exact(o, drive)) / scale);
        CHECK(std::abs(v(k, o) - iw * exact(o, drive)) <= 1e-10 * scale * std::max(1.0, std::abs(iw)));
        CHECK(std::abs(a(k, o) - iw * iw * exact(o, drive)) <= 1e-10 * scale * std::max(1.0, std::norm(iw)));
      }
    }
    CHECK(worst < 1e-10);
  }
  // Reciprocity of the synthesis: H_12 = H_21.
  const Eigen::MatrixXcd h0 = synthesize_frf(f, s.modes(0)), h1 = synthesize_frf(f, s.modes(1));
  CHECK((h0.col(1) - h1.col(0)).norm() <= 1e-12 * h0.col(1).norm());
  // A lightly damped driving point: negative imaginary part at its first resonance.
  const double f1 = std::sqrt(s.modes(0).eigenvalue(0)) / (2 * M_PI);
  CHECK(synthesize_frf(Eigen::VectorXd::Constant(1, f1), s.modes(0))(0, 0).imag() < 0);
}

TEST_CASE("FRAC: 1 for proportional FRFs, lower for shifted ones", "[identification][frf_synthesis]") {
  const TwoDof s;
  const Eigen::VectorXd f = Eigen::VectorXd::LinSpaced(401, 1.0, 60.0);
  const Eigen::VectorXcd h = synthesize_frf(f, s.modes(0)).col(0);
  CHECK(frf_assurance(h, cd(0.3, -2.0) * h) == Approx(1.0).epsilon(1e-12));
  TwoDof stiffer = s;
  stiffer.k1 *= 1.1;
  const double frac = frf_assurance(h, synthesize_frf(f, stiffer.modes(0)).col(0));
  CHECK(frac < 0.9);
  CHECK(frac > 0.0);
  CHECK(std::isnan(frf_assurance(h, Eigen::VectorXcd::Zero(h.size()))));
  CHECK_THROWS_WITH(frf_assurance(h, h.head(3)), "FRAC: FRFs of 401 and 3 lines (expected the same lines)");
}

TEST_CASE("FRF synthesis refuses what has no answer", "[identification][frf_synthesis]") {
  ModalFrfModel m;
  m.eigenvalue = Eigen::Vector2d(0.0, 100.0);  // a rigid-body mode and one at 10 rad/s
  m.zeta = Eigen::Vector2d(0.0, 0.01);
  m.response = Eigen::Matrix2d::Identity();
  m.drive = Eigen::Vector2d(1.0, 1.0);
  CHECK_THROWS_WITH(synthesize_frf(Eigen::VectorXd::Zero(1), m),
                    "FRF synthesis: the line at 0 Hz meets mode 1 (0 Hz) with zero damping or as a rigid-body mode at "
                    "0 Hz: the FRF is infinite there (start the band above it or give damping)");
  // Above 0 Hz the rigid-body mode is a mass line, −φφ/ω².
  const double f = 5.0, w = 2 * M_PI * f;
  const Eigen::MatrixXcd h = synthesize_frf(Eigen::VectorXd::Constant(1, f), m);
  CHECK(std::abs(h(0, 0) - cd(-1.0 / (w * w), 0)) < 1e-15);
  m.zeta(1) = -0.1;
  CHECK_THROWS_WITH(synthesize_frf(Eigen::VectorXd::Constant(1, f), m),
                    "FRF synthesis: mode 2 has damping ratio -0.1 (expected ≥ 0)");
  m.zeta.resize(1);
  CHECK_THROWS_AS(synthesize_frf(Eigen::VectorXd::Constant(1, f), m), ssid::formats::InputError);
}

TEST_CASE("damping partners: nearest pairs first, each mode once, within the tolerance", "[identification][frf_synthesis]") {
  // Relative distances: (10, 10.5) 0.048, (20, 19) 0.053, (30.5, 31) 0.016 — and (20, 19)
  // would lose to nothing; 45 Hz has no measured mode within 10 %.
  const auto p = damping_partners(Eigen::Vector4d(10, 20, 30.5, 45), {10.5, 31, 19}, 0.1);
  REQUIRE(p.size() == 4);
  CHECK(p[0] == std::optional<std::size_t>(0));
  CHECK(p[1] == std::optional<std::size_t>(2));
  CHECK(p[2] == std::optional<std::size_t>(1));
  CHECK_FALSE(p[3]);
  // Two analysis modes equally near one measured mode: the lower takes it, the other none.
  const auto q = damping_partners(Eigen::Vector2d(9.9, 10.1), {10.0}, 0.05);
  CHECK(q[0] == std::optional<std::size_t>(0));
  CHECK_FALSE(q[1]);
  // A nearer analysis mode wins over the file order.
  const auto r = damping_partners(Eigen::Vector2d(9.0, 10.05), {10.0}, 0.2);
  CHECK_FALSE(r[0]);
  CHECK(r[1] == std::optional<std::size_t>(0));
  CHECK(damping_partners(Eigen::Vector2d(1, 2), {}, 0.1) == std::vector<std::optional<std::size_t>>(2));
}

TEST_CASE("FRF quantities and dataset 58's data types", "[identification][frf_synthesis]") {
  for (const FrfQuantity q : {FrfQuantity::Displacement, FrfQuantity::Velocity, FrfQuantity::Acceleration})
    CHECK(quantity_of_data_type(quantity_data_type(q)) == q);
  CHECK(quantity_data_type(FrfQuantity::Acceleration) == 12);  // UFF 58 record 9: 8 displacement, 11 velocity, 12 acceleration
  CHECK_FALSE(quantity_of_data_type(13));                       // excitation force
  CHECK(std::string(quantity_unit(FrfQuantity::Velocity)) == "length/s/force");
}
