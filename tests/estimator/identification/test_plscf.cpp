// pLSCF and LSFD (estimator/identification/plscf.hpp) on FRFs synthesised here from a modal
// model whose poles, shapes and participation factors the test chooses:
//   H(ω) = Σ_r ψ_r l_rᵀ/(iω − λ_r) + ψ_r* l_rᴴ/(iω − λ_r*)   (+ UR − LR/ω² where stated),
// two references, six responses, five modes of which two are 0.5 % apart (separable only
// through the two references' different participation).
#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <cmath>
#include <random>

#include "chain_model.hpp"
#include "estimator/identification/modal_indicators.hpp"
#include "estimator/identification/plscf.hpp"
#include "estimator/identification/stabilisation.hpp"
#include "formats/parse_error.hpp"

using namespace ssid::estimator::identification;
using cd = std::complex<double>;

namespace {

struct ModalModel {
  std::vector<cd> lambda;        ///< rad/s, Im > 0, by frequency
  Eigen::MatrixXcd psi;          ///< no × modes
  Eigen::MatrixXcd l;            ///< ni × modes
  Eigen::MatrixXd lr, ur;        ///< residual terms (no × ni), zero unless set
  double hz(std::size_t r) const { return std::abs(lambda[r]) / (2 * M_PI); }
  double zeta(std::size_t r) const { return -lambda[r].real() / std::abs(lambda[r]); }
};

/// Five modes (12, 27, 27.135, 45, 61 Hz; 1 … 2 % damping), six responses, two references;
/// shapes slightly complex, participation factors complex, from a fixed seed.
ModalModel model() {
  ModalModel m;
  const std::vector<double> hz{12.0, 27.0, 27.135, 45.0, 61.0}, zeta{0.010, 0.012, 0.011, 0.015, 0.020};
  for (std::size_t r = 0; r < hz.size(); ++r) {
    const double w = 2 * M_PI * hz[r];
    m.lambda.emplace_back(-zeta[r] * w, w * std::sqrt(1 - zeta[r] * zeta[r]));
  }
  std::mt19937_64 gen(7);
  std::normal_distribution<double> n01;
  const auto modes = static_cast<Eigen::Index>(hz.size());
  m.psi.resize(6, modes);
  m.l.resize(2, modes);
  for (Eigen::Index r = 0; r < modes; ++r) {
    for (Eigen::Index o = 0; o < 6; ++o) m.psi(o, r) = cd(n01(gen), 0.05 * n01(gen));
    for (Eigen::Index j = 0; j < 2; ++j) m.l(j, r) = cd(n01(gen), 0.1 * n01(gen));
  }
  // The close pair: each reference drives mostly one of the two.
  m.l.col(1) = Eigen::Vector2cd(cd(1.0, 0.05), cd(0.25, 0.0));
  m.l.col(2) = Eigen::Vector2cd(cd(0.3, 0.0), cd(-1.0, 0.02));
  m.lr = Eigen::MatrixXd::Zero(6, 2);
  m.ur = Eigen::MatrixXd::Zero(6, 2);
  return m;
}

/// The FRF lines f_k = k·df, k = 0 … count−1 (the 0 Hz line too; the estimators skip it).
std::vector<Eigen::MatrixXcd> synthesise(const ModalModel& m, double df, Eigen::Index count) {
  std::vector<Eigen::MatrixXcd> lines;
  for (Eigen::Index k = 0; k < count; ++k) {
    const double w = 2 * M_PI * df * static_cast<double>(k);
    const cd iw(0, w);
    Eigen::MatrixXcd h = m.ur.cast<cd>();
    if (k > 0) h -= m.lr.cast<cd>() / (w * w);
    for (std::size_t r = 0; r < m.lambda.size(); ++r) {
      const auto c = static_cast<Eigen::Index>(r);
      const Eigen::MatrixXcd res = m.psi.col(c) * m.l.col(c).transpose();
      h += res / (iw - m.lambda[r]) + res.conjugate() / (iw - std::conj(m.lambda[r]));
    }
    lines.push_back(h);
  }
  return lines;
}

Eigen::VectorXd frequencies(double df, Eigen::Index count) {
  return Eigen::VectorXd::LinSpaced(count, 0.0, df * static_cast<double>(count - 1));
}

/// Complex Gaussian noise of `level` × the RMS of each FRF (response, reference) over the lines.
std::vector<Eigen::MatrixXcd> with_noise(std::vector<Eigen::MatrixXcd> lines, double level, unsigned seed) {
  Eigen::MatrixXd rms = Eigen::MatrixXd::Zero(lines[0].rows(), lines[0].cols());
  for (const auto& h : lines) rms += h.cwiseAbs2();
  rms = (rms / static_cast<double>(lines.size())).cwiseSqrt();
  std::mt19937_64 gen(seed);
  std::normal_distribution<double> n01;
  for (auto& h : lines)
    for (Eigen::Index o = 0; o < h.rows(); ++o)
      for (Eigen::Index j = 0; j < h.cols(); ++j)
        h(o, j) += level * rms(o, j) * cd(n01(gen), n01(gen)) / std::sqrt(2.0);
  return lines;
}

std::vector<Eigen::Index> range(Eigen::Index from, Eigen::Index to) {
  std::vector<Eigen::Index> v;
  for (Eigen::Index p = from; p <= to; ++p) v.push_back(p);
  return v;
}

/// The identified pole nearest to λ (relative distance), or nullptr.
const IdentifiedPole* nearest(const std::vector<IdentifiedPole>& poles, cd lambda, double* distance = nullptr) {
  const IdentifiedPole* best = nullptr;
  double bd = 0;
  for (const auto& p : poles) {
    const double d = std::abs(p.lambda - lambda) / std::abs(lambda);
    if (!best || d < bd) {
      best = &p;
      bd = d;
    }
  }
  if (distance) *distance = bd;
  return best;
}

}  // namespace

TEST_CASE("pLSCF recovers the exact poles and participation factors (noise-free, 2 references, a pair 0.5 % apart)",
          "[identification][plscf]") {
  const ModalModel m = model();
  const double df = 0.05;
  const Eigen::Index count = 1601;  // 0 … 80 Hz
  const auto lines = synthesise(m, df, count);
  const auto result = plscf_orders(frequencies(df, count), lines, {}, {10, 20, 30});
  REQUIRE(result.size() == 3);
  CHECK(result[2].order == 30);
  // Order p has p·ni = 60 eigenvalues z: the complex ones once, the real ones each.
  CHECK(result[2].poles.size() >= 30);
  CHECK(result[2].poles.size() <= 60);
  double worst = 0, worst_l = 1, worst_shape = 1;
  for (std::size_t r = 0; r < m.lambda.size(); ++r) {
    double d = 0;
    const IdentifiedPole* p = nearest(result[2].poles, m.lambda[r], &d);
    REQUIRE(p);
    worst = std::max(worst, d);
    worst_l = std::min(worst_l, complex_mac(p->participation, m.l.col(static_cast<Eigen::Index>(r))));
    // The order's own shape, B(z)v from the numerator, is the exact one.
    worst_shape = std::min(worst_shape, complex_mac(p->shape, m.psi.col(static_cast<Eigen::Index>(r))));
    CHECK(std::abs(p->participation.norm() - 1) < 1e-12);
    CHECK(p->mpc == Approx(modal_phase_collinearity(m.psi.col(static_cast<Eigen::Index>(r)))).margin(1e-6));
  }
  INFO("order 30: worst relative pole error " << worst << ", lowest participation MAC " << worst_l
                                              << ", lowest shape MAC " << worst_shape);
  CHECK(worst < 1e-6);
  CHECK(worst_l > 0.999999);
  CHECK(worst_shape > 0.999999);
  // Convergence with the order: order 10 is not yet exact.
  double worst10 = 0;
  for (const cd lambda : m.lambda) {
    double d = 0;
    nearest(result[0].poles, lambda, &d);
    worst10 = std::max(worst10, d);
  }
  CHECK(worst10 > worst);
}

TEST_CASE("pLSCF with one reference (the scalar-denominator LSCF) recovers the exact poles", "[identification][plscf]") {
  ModalModel m = model();
  const Eigen::MatrixXcd first = m.l.topRows(1);
  m.l = first;
  m.lr = Eigen::MatrixXd::Zero(6, 1);
  m.ur = Eigen::MatrixXd::Zero(6, 1);
  const double df = 0.05;
  const Eigen::Index count = 1601;
  const auto lines = synthesise(m, df, count);
  const auto result = plscf_orders(frequencies(df, count), lines, {}, {40});
  double worst = 0;
  for (std::size_t r = 0; r < m.lambda.size(); ++r) {
    double d = 0;
    const IdentifiedPole* p = nearest(result[0].poles, m.lambda[r], &d);
    REQUIRE(p);
    worst = std::max(worst, d);
    CHECK(p->participation.size() == 1);
    CHECK(complex_mac(p->shape, m.psi.col(static_cast<Eigen::Index>(r))) > 0.999999);
  }
  INFO("order 40, one reference: worst relative pole error " << worst);
  CHECK(worst < 1e-6);
}

TEST_CASE("pLSCF over orders 1…40, stabilisation, LSFD: exact modes, residues and shapes (noise-free)",
          "[identification][plscf]") {
  const ModalModel m = model();
  const double df = 0.05;
  const Eigen::Index count = 1601;
  const auto lines = synthesise(m, df, count);
  const Eigen::VectorXd hz = frequencies(df, count);
  const auto orders = plscf_orders(hz, lines, {}, range(1, 40));
  const StabilisationResult st = stabilise(orders);
  REQUIRE(st.modes.size() == 5);
  const auto chosen = mode_poles(st, orders);
  REQUIRE(chosen.size() == 5);
  const LsfdResult fit = lsfd(hz, lines, chosen, {});
  REQUIRE(fit.modes.size() == 5);
  double worst_f = 0, worst_z = 0, worst_mac = 1, worst_res = 0;
  for (std::size_t r = 0; r < 5; ++r) {
    const auto c = static_cast<Eigen::Index>(r);
    const IdentifiedPole& p = fit.modes[r];
    worst_f = std::max(worst_f, std::abs(p.hz - m.hz(r)) / m.hz(r));
    worst_z = std::max(worst_z, std::abs(p.zeta - m.zeta(r)) / m.zeta(r));
    worst_mac = std::min(worst_mac, complex_mac(p.shape, m.psi.col(c)));
    // ψ lᵀ is the residue matrix whatever the participation's scaling.
    const Eigen::MatrixXcd res = p.shape * p.participation.transpose(), exact = m.psi.col(c) * m.l.col(c).transpose();
    worst_res = std::max(worst_res, (res - exact).norm() / exact.norm());
    CHECK(p.mpc == Approx(modal_phase_collinearity(m.psi.col(c))).margin(1e-4));
    // The cluster's spread over orders: the lower orders are biased by what they cannot yet
    // represent (measured up to 5e-5 relative), the chosen pole (the highest order) is not.
    CHECK(st.modes[r].hz_std > 0);
    CHECK(st.modes[r].hz_std < 1e-4 * m.hz(r));
    CHECK(p.lambda == chosen[r].lambda);
  }
  INFO("frequency " << worst_f << ", damping " << worst_z << ", MAC " << worst_mac << ", residue " << worst_res
                    << ", fit error " << fit.fit_error);
  CHECK(worst_f < 1e-6);
  CHECK(worst_z < 1e-4);
  CHECK(worst_mac > 0.9999);
  CHECK(worst_res < 1e-6);  // measured 3.6e-8
  CHECK(fit.fit_error < 1e-6);  // measured 5.1e-9
}

TEST_CASE("LSFD recovers shapes and exact lower and upper residuals with the exact poles", "[identification][plscf]") {
  ModalModel m = model();
  std::mt19937_64 gen(11);
  std::normal_distribution<double> n01;
  for (Eigen::Index o = 0; o < 6; ++o)
    for (Eigen::Index j = 0; j < 2; ++j) {
      m.ur(o, j) = 1e-3 * n01(gen);  // H's scale: |ψ l|/(ζω) ≈ 1e-2
      m.lr(o, j) = 50.0 * n01(gen);  // −LR/ω² ≈ 1e-2 at 5 Hz
    }
  const double df = 0.05;
  const Eigen::Index count = 1601;
  const auto lines = synthesise(m, df, count);
  std::vector<IdentifiedPole> exact(m.lambda.size());
  for (std::size_t r = 0; r < exact.size(); ++r) {
    exact[r].lambda = m.lambda[r];
    exact[r].participation = m.l.col(static_cast<Eigen::Index>(r));
  }
  PlscfOptions band;
  band.hz_min = 2;
  band.hz_max = 75;
  const LsfdResult fit = lsfd(frequencies(df, count), lines, exact, band);
  for (std::size_t r = 0; r < exact.size(); ++r)
    CHECK((fit.modes[r].shape - m.psi.col(static_cast<Eigen::Index>(r))).norm() <
          1e-9 * m.psi.col(static_cast<Eigen::Index>(r)).norm());
  CHECK((fit.upper_residual - m.ur).norm() < 1e-9 * m.ur.norm());
  CHECK((fit.lower_residual - m.lr).norm() < 1e-9 * m.lr.norm());
  CHECK(fit.fit_error < 1e-10);
  // Without the residual terms in the data, LSFD finds them zero.
  const auto plain = lsfd(frequencies(df, count), synthesise(model(), df, count), exact, band);
  CHECK(plain.upper_residual.norm() < 1e-12);
  CHECK(plain.lower_residual.norm() < 1e-7);
}

TEST_CASE("LSFD's synthesis with the exact poles is the chain's (K − ω²M + iωC)⁻¹ between the fitted lines",
          "[identification][plscf]") {
  // The non-proportionally damped chain, one force at DOF 0: its FRFs by dense solves at
  // lines every 0.25 Hz, LSFD with the exact poles (state-matrix eigenvalues; with one
  // reference any nonzero participation will do), then the model's FRFs at frequencies
  // between those lines, against dense solves there: an independent check of
  // lsfd_synthesis (the poles, residues and residual terms all enter it).
  const auto chain = ident_test::chain_model(false, {0});
  auto exact_frf = [&](double hz) {
    const double w = 2 * M_PI * hz;
    const Eigen::MatrixXcd Z = chain.K.cast<cd>() - w * w * chain.M.cast<cd>() + cd(0, w) * chain.C.cast<cd>();
    return Eigen::MatrixXcd(Z.inverse().col(0));
  };
  const double df = 0.25;
  const Eigen::Index count = 241;  // 0 … 60 Hz
  std::vector<Eigen::MatrixXcd> lines;
  for (Eigen::Index k = 0; k < count; ++k) lines.push_back(k == 0 ? Eigen::MatrixXcd::Zero(3, 1) : exact_frf(df * k));
  std::vector<cd> poles;
  std::vector<Eigen::VectorXcd> shapes;
  chain.exact(poles, shapes);
  std::vector<IdentifiedPole> exact(poles.size());
  for (std::size_t r = 0; r < poles.size(); ++r) {
    exact[r].lambda = poles[r];
    exact[r].participation = Eigen::VectorXcd::Constant(1, cd(0.3, -0.7));
  }
  const LsfdResult fit = lsfd(frequencies(df, count), lines, exact, {});
  CHECK(fit.fit_error < 1e-9);
  const Eigen::VectorXd between = Eigen::VectorXd::LinSpaced(57, 1.125, 57.125);
  const auto model = lsfd_synthesis(between, fit);
  REQUIRE(model.size() == 57);
  for (Eigen::Index k = 0; k < between.size(); ++k) {
    const Eigen::MatrixXcd h = exact_frf(between(k));
    INFO(between(k) << " Hz");
    CHECK((model[static_cast<std::size_t>(k)] - h).norm() < 1e-8 * h.norm());
  }
  CHECK_THROWS_WITH(lsfd_synthesis(Eigen::VectorXd::Zero(1), fit), "LSFD synthesis: line 0 at 0 Hz (expected > 0 Hz)");
}

TEST_CASE("pLSCF and LSFD with 2 % noise: frequencies within 0.5 %, damping within 10 %", "[identification][plscf]") {
  const ModalModel m = model();
  const double df = 0.05;
  const Eigen::Index count = 1601;
  const Eigen::VectorXd hz = frequencies(df, count);
  for (const unsigned seed : {1u, 2u, 3u}) {
    const auto lines = with_noise(synthesise(m, df, count), 0.02, seed);
    const auto orders = plscf_orders(hz, lines, {}, range(1, 40));
    const StabilisationResult st = stabilise(orders);
    const auto fit = lsfd(hz, lines, mode_poles(st, orders), {});
    double worst_f = 0, worst_z = 0, worst_mac = 1;
    for (std::size_t r = 0; r < m.lambda.size(); ++r) {
      const IdentifiedPole* p = nearest(fit.modes, m.lambda[r]);
      REQUIRE(p);
      worst_f = std::max(worst_f, std::abs(p->hz - m.hz(r)) / m.hz(r));
      worst_z = std::max(worst_z, std::abs(p->zeta - m.zeta(r)) / m.zeta(r));
      worst_mac = std::min(worst_mac, complex_mac(p->shape, m.psi.col(static_cast<Eigen::Index>(r))));
    }
    INFO("seed " << seed << ": " << fit.modes.size() << " modes; frequency " << worst_f << ", damping " << worst_z
                 << ", MAC " << worst_mac << ", fit error " << fit.fit_error);
    CHECK(fit.modes.size() == 5);
    CHECK(worst_f < 0.005);
    CHECK(worst_z < 0.10);
    CHECK(worst_mac > 0.99);
    // The modal model explains all but the noise: 2 % of each FRF's RMS.
    CHECK(fit.fit_error > 0.015);
    CHECK(fit.fit_error < 0.025);
  }
}

TEST_CASE("pLSCF and LSFD: bad input is refused with the cause", "[identification][plscf]") {
  const ModalModel m = model();
  const auto lines = synthesise(m, 0.05, 101);
  const Eigen::VectorXd hz = frequencies(0.05, 101);
  using ssid::formats::InputError;
  CHECK_THROWS_WITH(plscf_orders(hz, lines, {}, {4, 3}),
                    "pLSCF: order 3 listed after order 4 (expected increasing orders)");
  CHECK_THROWS_WITH(plscf_orders(hz, lines, {}, {0}), "pLSCF: model order 0 (expected ≥ 1)");
  CHECK_THROWS_WITH(plscf_orders(hz, lines, {}, {100}),
                    "pLSCF: 100 lines in the band 0 … inf Hz are too few for model order 100 (needs more than 101)");
  CHECK_THROWS_WITH(plscf_orders(hz.head(50), lines, {}, {4}),
                    "pLSCF: 50 frequencies for 101 FRF lines (expected one per line)");
  PlscfOptions empty;
  empty.hz_min = 90;
  CHECK_THROWS_WITH(plscf_orders(hz, lines, empty, {4}), "pLSCF: no line above 0 Hz in the band 90 … inf Hz");
  auto bad = lines;
  bad[20](1, 1) = cd(std::nan(""), 0);
  CHECK_THROWS_WITH(plscf_orders(hz, bad, {}, {4}),
                    "pLSCF: line 20 (1 Hz) is not finite (NaN or infinite values)");
  IdentifiedPole p;
  p.lambda = cd(-1, 0);
  p.participation = Eigen::Vector2cd(1, 0);
  CHECK_THROWS_WITH(lsfd(hz, lines, {p}, {}), "LSFD: pole 1 is λ = -1 +0i rad/s (expected Im λ > 0)");
  p.lambda = cd(-1, 60);
  p.participation = Eigen::Vector3cd(1, 0, 0);
  CHECK_THROWS_WITH(lsfd(hz, lines, {p}, {}),
                    "LSFD: pole 1 has 3 participation factors (expected 2, one per reference)");
  CHECK_THROWS_AS(lsfd(hz, lines, {}, {}), InputError);
  // Two lines (1 and 1.05 Hz) for five modes: 8 equations, 14 unknowns.
  std::vector<IdentifiedPole> five(5, p);
  for (auto& q : five) q.participation = Eigen::Vector2cd(1, 0);
  PlscfOptions narrow;
  narrow.hz_min = 0.99;
  narrow.hz_max = 1.07;
  CHECK_THROWS_WITH(lsfd(hz, lines, five, narrow),
                    "LSFD: 2 lines × 2 references give 8 equations for 14 unknowns per response");
  // A stabilisation result that does not belong to the orders given with it.
  StabilisationResult foreign;
  foreign.modes.emplace_back();
  CHECK_THROWS_WITH(mode_poles(foreign, {}), "pLSCF: mode 1 has no pole in the diagram");
  DiagramPole d;
  d.order = 5;
  d.index = 0;
  d.mode = 0;
  foreign.diagram.push_back(d);
  CHECK_THROWS_WITH(mode_poles(foreign, {}), "pLSCF: mode 1 refers to order 5, pole 1, which the orders do not have");
}
