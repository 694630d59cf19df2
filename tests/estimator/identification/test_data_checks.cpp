// Test-data checks (estimator/identification/data_checks.hpp): the half-power bandwidth
// of an SDOF receptance against its exact half-power points, coherence bands, FRF
// differences.
#include <catch2/catch.hpp>

#include <cmath>
#include <complex>

#include "estimator/identification/data_checks.hpp"
#include "formats/parse_error.hpp"

using namespace ssid::estimator::identification;
using cd = std::complex<double>;

namespace {

/// SDOF receptance 1/(k − mω² + icω), m = 1 kg, f_n = 10 Hz, damping ratio ζ.
Eigen::VectorXcd sdof(const Eigen::VectorXd& f, double zeta) {
  const double wn = 2 * M_PI * 10;
  Eigen::VectorXcd h(f.size());
  for (Eigen::Index k = 0; k < f.size(); ++k) {
    const double w = 2 * M_PI * f(k);
    h(k) = 1.0 / cd(wn * wn - w * w, 2 * zeta * wn * w);
  }
  return h;
}

}  // namespace

TEST_CASE("half-power bandwidth of a finely sampled SDOF peak gives its damping", "[identification][data_checks]") {
  const double zeta = 0.01;
  const Eigen::VectorXd f = Eigen::VectorXd::LinSpaced(4001, 0.0, 20.0);  // 0.005 Hz
  const auto peaks = peak_resolution(f, sdof(f, zeta).cwiseAbs());
  REQUIRE(peaks.size() == 1);
  // Exact half-power points of |H|: ω² = ω_n²(1 − 2ζ² ± 2ζ√(1 − ζ²)).
  const double lo = 10 * std::sqrt(1 - 2 * zeta * zeta - 2 * zeta * std::sqrt(1 - zeta * zeta));
  const double hi = 10 * std::sqrt(1 - 2 * zeta * zeta + 2 * zeta * std::sqrt(1 - zeta * zeta));
  CHECK(peaks[0].half_power_hz == Approx(hi - lo).epsilon(2e-3));
  CHECK(peaks[0].zeta == Approx(zeta).epsilon(5e-3));
  CHECK(peaks[0].lines == Approx((hi - lo) / 0.005).epsilon(2e-3));
  CHECK(peaks[0].hz == Approx(10.0).margin(0.005));
  CHECK_FALSE(peaks[0].from_identified);
  // An identified damping replaces the FRF's bandwidth.
  const auto with = peak_resolution(f, sdof(f, zeta).cwiseAbs(), {{10.02, 0.02}, {30.0, 0.5}});
  REQUIRE(with.size() == 1);
  CHECK(with[0].from_identified);
  CHECK(with[0].half_power_hz == Approx(2 * 0.02 * 10.02));
}

TEST_CASE("a coarse resolution leaves less than one line in the half-power band", "[identification][data_checks]") {
  const Eigen::VectorXd f = Eigen::VectorXd::LinSpaced(41, 0.0, 20.0);  // 0.5 Hz against 0.2 Hz half-power band
  const auto peaks = peak_resolution(f, sdof(f, 0.01).cwiseAbs());
  REQUIRE(peaks.size() == 1);
  CHECK(peaks[0].lines < 1.0);
  CHECK_THROWS_AS(peak_resolution(f.head(2), f.head(2)), ssid::formats::InputError);
}

TEST_CASE("low-coherence bands and FRF differences", "[identification][data_checks]") {
  const Eigen::VectorXd f = Eigen::VectorXd::LinSpaced(11, 0.0, 10.0);
  Eigen::VectorXd c = Eigen::VectorXd::Constant(11, 0.99);
  c(3) = 0.5;
  c(4) = 0.7;
  c(8) = std::nan("");
  const auto bands = low_coherence_bands(f, c, 0.9);
  REQUIRE(bands.size() == 2);
  CHECK(bands[0].lo_hz == 3.0);
  CHECK(bands[0].hi_hz == 4.0);
  CHECK(bands[0].min == 0.5);
  CHECK(bands[0].lines == 2);
  CHECK(bands[1].lo_hz == 8.0);
  CHECK(bands[1].min == 0.0);

  const Eigen::VectorXd g = Eigen::VectorXd::LinSpaced(2001, 0.0, 20.0);
  const Eigen::VectorXcd a = sdof(g, 0.02);
  const FrfDifference same = compare_frfs(g, a, a);
  CHECK(same.error == 0.0);
  CHECK(same.frac == Approx(1.0));
  const FrfDifference scaled = compare_frfs(g, a, 1.3 * a);
  CHECK(scaled.error == Approx(0.3 / std::sqrt(1.3)).epsilon(1e-12));
  CHECK(scaled.frac == Approx(1.0));
  CHECK(scaled.peak_hz_a == scaled.peak_hz_b);
  CHECK_THROWS_WITH(compare_frfs(g, a, a.head(5)),
                    "FRF comparison: 2001 lines, FRFs of 2001 and 5 values (expected one per line)");
}

TEST_CASE("decay segments: ERA finds the dominant mode of each segment of a two-mode decay",
          "[identification][data_checks]") {
  // x(t) = e^{−ζ₁ω₁t} cos(ω_d1 t) + 0.1 e^{−ζ₂ω₂t} cos(ω_d2 t): 8 Hz at 1 %, 23 Hz at 2 %.
  const double dt = 0.004;
  const Eigen::Index n = 2000;
  Eigen::MatrixXd x(n, 2);
  for (Eigen::Index k = 0; k < n; ++k) {
    const double t = static_cast<double>(k) * dt;
    const auto mode = [t](double hz, double zeta) {
      const double w = 2 * M_PI * hz;
      return std::exp(-zeta * w * t) * std::cos(w * std::sqrt(1 - zeta * zeta) * t);
    };
    x(k, 0) = mode(8, 0.01) + 0.1 * mode(23, 0.02);
    x(k, 1) = -0.5 * mode(8, 0.01) + 0.3 * mode(23, 0.02);
  }
  const auto segs = decay_segments(x, dt, 500, 250);
  REQUIRE(segs.size() == 7);
  for (const auto& s : segs) {
    CHECK(s.hz == Approx(8.0).epsilon(1e-8));
    CHECK(s.zeta == Approx(0.01).epsilon(1e-6));
  }
  CHECK(segs[1].start_s == Approx(1.0));
  CHECK(segs[0].rms > segs[6].rms);
  CHECK_THROWS_AS(decay_segments(x, dt, 3000, 250), ssid::formats::InputError);
  CHECK_THROWS_AS(decay_segments(x, 0.0, 500, 250), ssid::formats::InputError);
}
