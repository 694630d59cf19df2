// The simulated test of a placement (issue 23 item 5): the impulse responses against an
// independent time integration, the noise's level and reproducibility, and the whole
// evaluation on a chain whose modes are known in closed form, with a sensor set that sees
// every target and one that sits on a target's node.
#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <cmath>

#include "estimator/pretest/evaluation.hpp"

using namespace ssid::estimator;
using namespace ssid::estimator::pretest;
using Sparse = Eigen::SparseMatrix<double>;

namespace {

constexpr double kPi = 3.14159265358979323846;

/// A fixed-fixed chain of n unit masses and n + 1 springs k: ω_j² = 2k(1 − cos(jπ/(n+1))),
/// φ_j(i) ∝ sin(jπi/(n+1)) (i = 1 … n).
void uniform_chain(int n, double k, Sparse& K, Sparse& M) {
  Eigen::MatrixXd kk = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i) {
    kk(i, i) = 2 * k;
    if (i + 1 < n) kk(i, i + 1) = kk(i + 1, i) = -k;
  }
  K = kk.sparseView();
  M = Eigen::MatrixXd::Identity(n, n).sparseView();
}

struct Modes {
  Eigen::VectorXd lam;
  Eigen::MatrixXd Phi;  ///< mass-normalised
};

Modes solve(const Sparse& K, const Sparse& M) {
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es{Eigen::MatrixXd(K), Eigen::MatrixXd(M)};
  return {es.eigenvalues(), es.eigenvectors()};
}

double closed_form_hz(int j, int n, double k) { return std::sqrt(2 * k * (1 - std::cos(j * kPi / (n + 1)))) / (2 * kPi); }

}  // namespace

TEST_CASE("pretest evaluation: acceleration impulse responses match a time integration with modal damping",
          "[pretest][evaluation]") {
  // Two unequal masses, three springs; C = M Φ diag(2ζω) Φᵀ M (modal damping). The
  // response to a unit impulse at DOF 0 is x(0+) = 0, v(0+) = M⁻¹ e₀; RK4 with 200 steps
  // per sample integrates it; acceleration a = −M⁻¹(K x + C v).
  Eigen::MatrixXd k(2, 2), m(2, 2);
  k << 3000, -1000, -1000, 1500;
  m << 1.0, 0, 0, 2.5;
  const Sparse K = k.sparseView(), M = m.sparseView();
  const Modes md = solve(K, M);
  const double zeta = 0.03;
  const Eigen::VectorXd w = md.lam.cwiseSqrt();
  const Eigen::MatrixXd C = m * md.Phi * (2 * zeta * w).asDiagonal() * md.Phi.transpose() * m;
  const Eigen::MatrixXd Minv = m.inverse();
  const double dt = 0.01;
  const int samples = 60;
  Eigen::MatrixXd B = Eigen::MatrixXd::Zero(2, 1);
  B(0, 0) = 1;
  const auto Y = impulse_accelerations(md.Phi, md.lam, zeta, {0, 1}, B, dt, samples, 1e9);
  REQUIRE(Y.size() == static_cast<std::size_t>(samples));

  Eigen::VectorXd x = Eigen::VectorXd::Zero(2), v = Minv * B.col(0);
  auto acc = [&](const Eigen::VectorXd& xx, const Eigen::VectorXd& vv) { return Eigen::VectorXd(-Minv * (k * xx + C * vv)); };
  const int sub = 200;
  const double h = dt / sub;
  double worst = 0, peak = 0;
  for (int s = 0; s < samples; ++s) {
    const Eigen::VectorXd a = acc(x, v);
    worst = std::max(worst, (a - Y[static_cast<std::size_t>(s)].col(0)).cwiseAbs().maxCoeff());
    peak = std::max(peak, a.cwiseAbs().maxCoeff());
    for (int i = 0; i < sub; ++i) {
      const Eigen::VectorXd k1x = v, k1v = acc(x, v);
      const Eigen::VectorXd k2x = v + h / 2 * k1v, k2v = acc(x + h / 2 * k1x, v + h / 2 * k1v);
      const Eigen::VectorXd k3x = v + h / 2 * k2v, k3v = acc(x + h / 2 * k2x, v + h / 2 * k2v);
      const Eigen::VectorXd k4x = v + h * k3v, k4v = acc(x + h * k3x, v + h * k3v);
      x += h / 6 * (k1x + 2 * k2x + 2 * k3x + k4x);
      v += h / 6 * (k1v + 2 * k2v + 2 * k3v + k4v);
    }
  }
  CHECK(peak > 10);
  CHECK(worst < 1e-8 * peak);

  // The cutoff leaves out the modes above it.
  const double f2 = std::sqrt(md.lam(1)) / (2 * kPi);
  const auto Y1 = impulse_accelerations(md.Phi, md.lam, zeta, {0, 1}, B, dt, samples, 0.99 * f2);
  const auto Y_only1 = impulse_accelerations(md.Phi.leftCols(1), md.lam.head(1), zeta, {0, 1}, B, dt, samples, 1e9);
  for (int s = 0; s < samples; ++s) CHECK((Y1[static_cast<std::size_t>(s)] - Y_only1[static_cast<std::size_t>(s)]).norm() == 0);
}

TEST_CASE("pretest evaluation: measurement noise is σ = p % of each channel's RMS, seeded", "[pretest][evaluation]") {
  // Two channels 1000 times apart in level: the noise follows each one's RMS.
  std::vector<Eigen::MatrixXd> Y(20000, Eigen::MatrixXd::Zero(2, 1));
  for (std::size_t k = 0; k < Y.size(); ++k) {
    const double s = std::sin(0.01 * static_cast<double>(k));
    Y[k] << s, 1000 * s;
  }
  auto noisy = Y, again = Y, other = Y;
  add_measurement_noise(noisy, 5.0, 0, 7);
  add_measurement_noise(again, 5.0, 0, 7);
  add_measurement_noise(other, 5.0, 0, 8);
  Eigen::Vector2d rms = Eigen::Vector2d::Zero(), noise = Eigen::Vector2d::Zero();
  bool same = true, differs = false;
  for (std::size_t k = 0; k < Y.size(); ++k) {
    rms += Y[k].col(0).cwiseAbs2();
    noise += (noisy[k] - Y[k]).col(0).cwiseAbs2();
    same = same && noisy[k] == again[k];
    differs = differs || noisy[k] != other[k];
  }
  // 20 000 samples: the sample σ is within ~1 % (3 standard errors) of the true one.
  const Eigen::Vector2d ratio = noise.cwiseSqrt().cwiseQuotient(rms.cwiseSqrt());
  CHECK(ratio(0) == Approx(0.05).epsilon(0.015));
  CHECK(ratio(1) == Approx(0.05).epsilon(0.015));
  CHECK(same);
  CHECK(differs);

  // Rounding to b bits of the peak: every value is a multiple of 2·peak/2^b, off by at most half of it.
  auto rounded = Y;
  add_measurement_noise(rounded, 0.0, 8, 1);
  double peak = 0, worst = 0;
  for (const auto& y : Y) peak = std::max(peak, std::abs(y(1, 0)));
  const double step = 2 * peak / 256;
  double off_grid = 0;
  for (std::size_t k = 0; k < Y.size(); ++k) {
    worst = std::max(worst, std::abs(rounded[k](1, 0) - Y[k](1, 0)) / step);
    off_grid = std::max(off_grid, std::abs(rounded[k](1, 0) / step - std::round(rounded[k](1, 0) / step)));
  }
  CHECK(off_grid < 1e-9);
  CHECK(worst <= 0.5 + 1e-12);
  CHECK(worst > 0.45);
}

TEST_CASE("pretest evaluation: a chain's targets are identified when the sensors see them", "[pretest][evaluation]") {
  const int n = 5;
  const double k = 1000;
  Sparse K, M;
  uniform_chain(n, k, K, M);
  const Modes md = solve(K, M);
  const std::vector<Eigen::Index> targets{0, 1, 2};
  const std::vector<Eigen::Index> all{0, 1, 2, 3, 4};
  Eigen::MatrixXd B = Eigen::MatrixXd::Zero(n, 1);
  B(0, 0) = 1;  // at mass 1: no mode has a node there

  SECTION("no noise: exact frequencies (against the closed form) and an identity cross-orthogonality") {
    SimulatedTestOptions o;
    o.noise_pct = 0;
    const PlacementEvaluation ev = evaluate_placement(K, M, md.Phi, md.lam, targets, all, B, o);
    // The band 1.25 f_3 holds modes 1-4 (f_4/f_3 = 1.22, f_5/f_3 = 1.37).
    CHECK(ev.response_modes == 4);
    CHECK(ev.bandwidth_hz == Approx(1.25 * closed_form_hz(3, n, k)).epsilon(1e-12));
    CHECK(ev.dt == Approx(1 / (2.56 * ev.bandwidth_hz)).epsilon(1e-12));
    REQUIRE(ev.identified_count == 3);
    for (int j = 0; j < 3; ++j) {
      INFO("target " << j + 1);
      const auto& tm = ev.targets[static_cast<std::size_t>(j)];
      REQUIRE(tm.identified);
      CHECK(std::abs(tm.hz - closed_form_hz(j + 1, n, k)) / closed_form_hz(j + 1, n, k) < 1e-5);  // < 1e-3 %
      CHECK(tm.zeta == Approx(0.01).epsilon(1e-4));
      CHECK(tm.mac > 1 - 1e-9);
    }
    CHECK(ev.max_frequency_error_pct < 1e-3);
    REQUIRE(ev.xor_status == ReductionStatus::Ok);
    CHECK(ev.min_diagonal_xor > 1 - 1e-8);
    CHECK(ev.max_offdiagonal_xor < 1e-6);
  }

  SECTION("2 % noise: still every target, within 0.1 % in frequency") {
    const PlacementEvaluation ev = evaluate_placement(K, M, md.Phi, md.lam, targets, all, B);
    CHECK(ev.identified_count == 3);
    CHECK(ev.max_frequency_error_pct < 0.1);
    CHECK(ev.max_offdiagonal_xor < 0.1);
  }

  SECTION("a sensor on the middle mass, the node of mode 2: mode 2 is not identified, 1 and 3 are") {
    SimulatedTestOptions o;
    o.noise_pct = 0;
    const PlacementEvaluation ev = evaluate_placement(K, M, md.Phi, md.lam, targets, {2}, B, o);
    CHECK(ev.identified_count == 2);
    CHECK(ev.targets[0].identified);
    CHECK_FALSE(ev.targets[1].identified);
    CHECK(ev.targets[2].identified);
    CHECK(std::abs(ev.targets[0].frequency_error_pct) < 1e-3);
    CHECK(std::abs(ev.targets[2].frequency_error_pct) < 1e-3);
    // One sensor cannot carry a SEREP of three targets: no cross-orthogonality, said so.
    CHECK(ev.xor_status != ReductionStatus::Ok);
    CHECK(std::isnan(ev.max_offdiagonal_xor));
  }

  SECTION("solved modes that stop below the band are refused") {
    CHECK_THROWS_WITH(evaluate_placement(K, M, md.Phi.leftCols(3), md.lam.head(3), targets, all, B),
                      Catch::Contains("solve for more modes"));
  }
}
