// ERA and ERA/DC (estimator/identification/era.hpp) against the exact poles and shapes of
// a 3-DOF chain (dense eigen-solve of its first-order state matrix), and the modal
// indicators and complex-to-real conversion (modal_indicators.hpp).
#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <cmath>

#include "chain_model.hpp"
#include "estimator/identification/era.hpp"
#include "estimator/identification/frf.hpp"
#include "estimator/identification/modal_indicators.hpp"
#include "formats/parse_error.hpp"

using namespace ssid::estimator::identification;
using ident_test::cd;

namespace {

struct Errors {
  double freq = 0, zeta = 0, mac = 1, mpc = 0, emac = 1;
};

/// Compare the identified poles with the exact ones (one-to-one by frequency).
Errors compare(const EraResult& r, const ident_test::ChainModel& model) {
  std::vector<cd> poles;
  std::vector<Eigen::VectorXcd> shapes;
  model.exact(poles, shapes);
  REQUIRE(r.poles.size() == poles.size());
  Errors e;
  for (std::size_t i = 0; i < poles.size(); ++i) {
    const double f = std::abs(poles[i]) / (2 * M_PI);
    const double z = -poles[i].real() / std::abs(poles[i]);
    e.freq = std::max(e.freq, std::abs(r.poles[i].hz - f) / f);
    e.zeta = std::max(e.zeta, std::abs(r.poles[i].zeta - z) / z);
    e.mac = std::min(e.mac, complex_mac(r.poles[i].shape, shapes[i]));
    e.mpc = std::max(e.mpc, std::abs(r.poles[i].mpc - modal_phase_collinearity(shapes[i])));
    e.emac = std::min(e.emac, r.poles[i].emac);
  }
  return e;
}

}  // namespace

TEST_CASE("modal indicators: MPC, MPD, complex MAC and real modes of known shapes", "[identification][indicators]") {
  const Eigen::Vector3cd real_shape(cd(1, 0), cd(-2, 0), cd(3, 0));
  const Eigen::Vector3cd rotated = real_shape * std::polar(1.0, 0.3);
  CHECK(modal_phase_collinearity(rotated) == Approx(1.0));
  CHECK(mean_phase_deviation(rotated) == Approx(0.0).margin(1e-12));
  CHECK((real_mode(rotated) - real_shape.real()).norm() < 1e-14);
  CHECK((real_mode(-rotated) - real_shape.real()).norm() < 1e-14);  // largest component made positive
  const Eigen::Vector2cd circular(cd(1, 0), cd(0, 1));
  CHECK(modal_phase_collinearity(circular) == Approx(0.0).margin(1e-15));
  // Two unit components 10° apart: the best line bisects them, each 5° off it.
  const Eigen::Vector2cd ten(cd(1, 0), std::polar(1.0, 10 * M_PI / 180));
  CHECK(mean_phase_deviation(ten) == Approx(5.0));
  CHECK(modal_phase_collinearity(ten) == Approx(std::pow(std::cos(10 * M_PI / 180), 2)));
  CHECK(complex_mac(rotated, real_shape) == Approx(1.0));
  CHECK(complex_mac(circular, Eigen::Vector2cd(cd(1, 0), cd(0, -1))) == Approx(0.0).margin(1e-15));
}

TEST_CASE("ERA recovers the exact poles and shapes of a 3-DOF chain (noise-free, 2 inputs)",
          "[identification][era]") {
  const auto model = ident_test::chain_model(false, {0, 2});
  const double dt = 0.004;
  const auto Y = model.markov(dt, 400);
  EraOptions o;
  o.order = 6;
  o.dt = dt;
  const EraResult r = era(Y, o);
  const Errors e = compare(r, model);
  INFO("ERA: max relative frequency error " << e.freq << ", damping " << e.zeta << ", min MAC " << e.mac
                                            << ", MPC deviation " << e.mpc << ", min EMAC " << e.emac);
  CHECK(e.freq < 1e-10);
  CHECK(e.zeta < 1e-9);
  CHECK(e.mac > 0.999999);
  CHECK(e.mpc < 1e-6);
  CHECK(e.emac > 0.999);
  for (const auto& p : r.poles) {
    CHECK(p.mpd >= 0);
    CHECK(p.msv > 0);
    CHECK(p.cmi == Approx(p.emac * p.mpc));
  }
  // The singular values drop by many orders after the true order (6).
  CHECK(r.singular_values(6) < 1e-8 * r.singular_values(5));
}

TEST_CASE("ERA/DC recovers the exact poles and shapes of a 3-DOF chain", "[identification][era]") {
  const auto model = ident_test::chain_model(false, {1});
  const double dt = 0.004;
  const auto Y = model.markov(dt, 400);
  EraOptions o;
  o.order = 6;
  o.dt = dt;
  o.block_rows = 20;
  o.block_cols = 200;
  o.dc_blocks = 3;
  const EraResult r = era(Y, o);
  const Errors e = compare(r, model);
  INFO("ERA/DC: max relative frequency error " << e.freq << ", damping " << e.zeta << ", min MAC " << e.mac
                                               << ", min EMAC " << e.emac);
  CHECK(e.freq < 1e-10);
  CHECK(e.zeta < 1e-9);
  CHECK(e.mac > 0.999999);
  CHECK(e.emac > 0.999);
}

TEST_CASE("ERA with 2 % noise stays close to the exact poles", "[identification][era]") {
  const auto model = ident_test::chain_model(false, {0, 2});
  const double dt = 0.004;
  const auto Y = ident_test::with_noise(model.markov(dt, 1000), 0.02, 11);
  EraOptions o;
  o.order = 6;
  o.dt = dt;
  const Errors e = compare(era(Y, o), model);
  INFO("ERA, 2 % noise: frequency " << e.freq << ", damping " << e.zeta << ", MAC " << e.mac);
  CHECK(e.freq < 1e-3);
  CHECK(e.zeta < 0.05);
  CHECK(e.mac > 0.999);
}

TEST_CASE("driving-point residues scale ERA shapes to unit modal mass", "[identification][era][scaling]") {
  // Proportional damping: the scaled shapes are the real mass-normalised modes of (K, M).
  const auto model = ident_test::chain_model(true, {0});
  const double dt = 0.004;
  EraOptions o;
  o.order = 6;
  o.dt = dt;
  const EraResult r = era(model.markov(dt, 400), o);
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> ges(model.K, model.M);
  REQUIRE(r.poles.size() == 3);
  double worst = 0, worst_imag = 0, worst_complexity = 0;
  for (std::size_t m = 0; m < 3; ++m) {
    const IdentifiedPole& p = r.poles[m];
    const Eigen::VectorXcd residue = p.shape * p.participation(0);  // R(:, 0) = c_r l_r0
    const Eigen::VectorXcd phi = unit_modal_mass_shape(residue, p.lambda, 0);
    Eigen::VectorXd exact = ges.eigenvectors().col(static_cast<Eigen::Index>(m));
    Eigen::Index big = 0;
    exact.cwiseAbs().maxCoeff(&big);
    if (exact(big) < 0) exact = -exact;
    worst = std::max(worst, (phi.real() - exact).norm() / exact.norm());
    worst_imag = std::max(worst_imag, phi.imag().norm() / exact.norm());
    worst_complexity = std::max(worst_complexity, 1 - modal_phase_collinearity(p.shape));
    CHECK((real_mode(p.shape).normalized() - exact.normalized()).norm() < 1e-7);
  }
  INFO("unit-modal-mass shapes: max relative error " << worst << ", imaginary part " << worst_imag
                                                     << ", complexity 1−MPC " << worst_complexity);
  CHECK(worst < 1e-7);
  CHECK(worst_imag < 1e-7);
  CHECK(worst_complexity < 1e-10);
  CHECK_THROWS_WITH(unit_modal_mass_shape(Eigen::VectorXcd::Ones(3), cd(-1, 10), 3),
                    "modal scaling: driving point 3 out of range (0 … 2)");
}

TEST_CASE("ERA on Markov parameters from exact FRF lines (inverse FFT) finds the chain's poles",
          "[identification][era]") {
  const auto model = ident_test::chain_model(false, {0});
  std::vector<cd> poles;
  std::vector<Eigen::VectorXcd> shapes;
  model.exact(poles, shapes);
  // Receptance lines 0 … 1000 Hz every 0.25 Hz: fs = 2000 Hz, period 4 s.
  const double df = 0.25;
  std::vector<Eigen::MatrixXcd> frf;
  for (int k = 0; k <= 4000; ++k) {
    const double w = 2 * M_PI * df * k;
    frf.push_back((model.K.cast<cd>() - w * w * model.M.cast<cd>() + cd(0, w) * model.C.cast<cd>())
                      .inverse()
                      .col(0));
  }
  const auto Y = markov_from_frf(frf, df);
  REQUIRE(Y.size() == 8000);
  // The sampled impulse response wrapped over the period T = N dt,
  // Σ_m h(t + mT) = Cc e^{Ac t} (I − e^{Ac T})⁻¹ Bc; the lines cut at the Nyquist frequency
  // leave the difference (largest near t = 0, where the spectrum's cut rings most).
  const double dt = 1.0 / 2000;
  const Eigen::MatrixXd Ad = (model.Ac * dt).exp();
  const Eigen::MatrixXd I = Eigen::MatrixXd::Identity(Ad.rows(), Ad.cols());
  Eigen::MatrixXd X = (I - (model.Ac * (8000 * dt)).exp()).inverse() * model.Bc;
  double worst_h = 0, scale = 0;
  std::vector<Eigen::MatrixXd> wrapped;
  for (int k = 0; k < 400; ++k, X = Ad * X) wrapped.push_back(model.Cc * X);
  for (const auto& w : wrapped) scale = std::max(scale, w.cwiseAbs().maxCoeff());
  for (std::size_t k = 20; k < wrapped.size(); ++k)
    worst_h = std::max(worst_h, (Y[k] - wrapped[k]).cwiseAbs().maxCoeff() / scale);
  EraOptions o;
  o.order = 6;
  o.dt = 1.0 / 2000;
  o.block_rows = 40;
  o.block_cols = 2000;
  const std::vector<Eigen::MatrixXd> head(Y.begin() + 1, Y.begin() + 2100);
  const Errors e = compare(era(head, o), model);
  INFO("impulse response from FRF lines vs exact: " << worst_h << " of its peak; ERA: frequency " << e.freq
                                                    << ", damping " << e.zeta << ", MAC " << e.mac);
  CHECK(worst_h < 1e-4);
  CHECK(e.freq < 1e-5);
  CHECK(e.zeta < 1e-3);
  CHECK(e.mac > 0.9999);
}

TEST_CASE("impact test: force and exponential windows, H1, inverse FFT and ERA give the poles shifted by 1/τ",
          "[identification][era][frf]") {
  // One hammer blow of area a·dt on DOF 0 at t = 0, the exact displacement response, and
  // noise on the force channel after the blow (what the force window is for).
  const auto model = ident_test::chain_model(false, {0});
  const double dt = 1.0 / 500, a = 250.0, tau = 1.0;
  const Eigen::Index N = 4096;
  const auto h = model.markov(dt, N);
  Eigen::MatrixXd x = Eigen::MatrixXd::Zero(N, 1), y(N, 3);
  ssid::translators::NormalDeviates z(3);
  x(0, 0) = a;
  for (Eigen::Index n = N / 10; n < N; ++n) x(n, 0) = 0.05 * a * z();
  for (Eigen::Index n = 0; n < N; ++n) y.row(n) = a * dt * h[static_cast<std::size_t>(n)].transpose();
  WelchOptions w;
  w.segment_length = N;
  w.overlap = 0;
  w.reference_window = {WindowKind::Force, 0.05};
  w.response_window = {WindowKind::Exponential, 0.1, tau};
  const FrfEstimate frf = estimate_frf(x, y, dt, w, FrfEstimator::H1);
  const auto Y = markov_from_frf(frf.h, frf.frequency_hz(1));
  // The windowed response divided by the blow's area, exactly: e^{−t/τ} h(t).
  double worst_h = 0, scale = 0;
  for (Eigen::Index n = 0; n < N; ++n) {
    const Eigen::MatrixXd expect = std::exp(-static_cast<double>(n) * dt / tau) * h[static_cast<std::size_t>(n)];
    scale = std::max(scale, expect.cwiseAbs().maxCoeff());
    worst_h = std::max(worst_h, (Y[static_cast<std::size_t>(n)] - expect).cwiseAbs().maxCoeff());
  }
  worst_h /= scale;
  EraOptions o;
  o.order = 6;
  o.dt = dt;
  const EraResult r = era(std::vector<Eigen::MatrixXd>(Y.begin(), Y.begin() + 1500), o);
  std::vector<cd> poles;
  std::vector<Eigen::VectorXcd> shapes;
  model.exact(poles, shapes);
  REQUIRE(r.poles.size() == 3);
  double worst_shift = 0, worst_wd = 0;
  for (std::size_t m = 0; m < 3; ++m) {
    // Subtracting 1/τ from the decay rate gives back the structure's pole.
    worst_shift = std::max(worst_shift, std::abs(r.poles[m].lambda.real() + 1 / tau - poles[m].real()) /
                                            std::abs(poles[m].real()));
    worst_wd = std::max(worst_wd, std::abs(r.poles[m].lambda.imag() - poles[m].imag()) / poles[m].imag());
  }
  INFO("windowed impulse response " << worst_h << " of its peak; decay rate after −1/τ " << worst_shift
                                    << " relative; damped frequency " << worst_wd);
  CHECK(worst_h < 1e-10);
  CHECK(worst_shift < 1e-8);
  CHECK(worst_wd < 1e-10);
}

TEST_CASE("ERA input errors name the cause", "[identification][era]") {
  const auto model = ident_test::chain_model(false, {0});
  const auto Y = model.markov(0.004, 40);
  EraOptions o;
  o.order = 6;
  o.dt = 0.004;
  o.block_rows = 30;
  o.block_cols = 20;
  CHECK_THROWS_WITH(era(Y, o),
                    "ERA: 40 Markov parameters are too few for 30 block rows, 20 block columns and 0 correlation "
                    "blocks (needs rows + columns + 2·blocks ≤ 40)");
  o.block_rows = 1;
  o.block_cols = 30;
  CHECK_THROWS_WITH(era(Y, o), "ERA: order 6 exceeds the Hankel matrix's size 3×30 (more block rows needed)");
  o.dt = 0;
  CHECK_THROWS_AS(era(Y, o), ssid::formats::InputError);
}
