// FRF estimators (estimator/identification/frf.hpp): closed-form checks on noise-free
// steady-state data, and scipy.signal on the same random records.
#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <cmath>
#include <complex>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <unistd.h>

#include "estimator/identification/frf.hpp"
#include "formats/parse_error.hpp"
#include "translators/synthetic_modes.hpp"

using namespace ssid::estimator::identification;
using cd = std::complex<double>;
namespace fs = std::filesystem;

namespace {

/// Receptance of a chain system, (K − ω²M + iωC)⁻¹, at f Hz.
Eigen::MatrixXcd receptance(const Eigen::MatrixXd& M, const Eigen::MatrixXd& C, const Eigen::MatrixXd& K, double f) {
  const double w = 2 * M_PI * f;
  const Eigen::MatrixXcd D = K.cast<cd>() - w * w * M.cast<cd>() + cd(0, w) * C.cast<cd>();
  return D.inverse();
}

/// Records of `segments` blocks of N samples; block m holds one period of a multisine per
/// reference (unit amplitudes on lines 1 … N/2−1, phases from the deviates) and the exact
/// steady-state responses y = Re Σ_k H(f_k) X_k e^{iω_k t} of the system.
void multisine_records(const Eigen::MatrixXd& M, const Eigen::MatrixXd& C, const Eigen::MatrixXd& K,
                       const std::vector<Eigen::Index>& drive, Eigen::Index N, Eigen::Index segments, double dt,
                       Eigen::MatrixXd& x, Eigen::MatrixXd& y) {
  const auto ni = static_cast<Eigen::Index>(drive.size());
  const Eigen::Index no = M.rows();
  x = Eigen::MatrixXd::Zero(N * segments, ni);
  y = Eigen::MatrixXd::Zero(N * segments, no);
  ssid::translators::NormalDeviates z(7);
  for (Eigen::Index m = 0; m < segments; ++m)
    for (Eigen::Index k = 1; k < N / 2; ++k) {
      const double f = static_cast<double>(k) / (static_cast<double>(N) * dt);
      const Eigen::MatrixXcd H = receptance(M, C, K, f);
      Eigen::VectorXcd X(ni);
      for (Eigen::Index i = 0; i < ni; ++i) X(i) = std::polar(1.0, 2 * M_PI * z());
      Eigen::VectorXcd F = Eigen::VectorXcd::Zero(no);
      for (Eigen::Index i = 0; i < ni; ++i) F(drive[static_cast<std::size_t>(i)]) += X(i);
      const Eigen::VectorXcd Y = H * F;
      for (Eigen::Index n = 0; n < N; ++n) {
        const cd e = std::polar(1.0, 2 * M_PI * static_cast<double>(k * n) / static_cast<double>(N));
        for (Eigen::Index i = 0; i < ni; ++i) x(m * N + n, i) += (X(i) * e).real();
        for (Eigen::Index r = 0; r < no; ++r) y(m * N + n, r) += (Y(r) * e).real();
      }
    }
}

double max_rel(const Eigen::MatrixXcd& a, const Eigen::MatrixXcd& b) {
  return (a - b).cwiseAbs().maxCoeff() / b.cwiseAbs().maxCoeff();
}

}  // namespace

TEST_CASE("windows: Hann, flat-top, force and exponential samples", "[identification][frf]") {
  const Eigen::VectorXd hann = window_samples({WindowKind::Hann}, 8, 0.1);
  CHECK(hann(0) == Approx(0.0).margin(1e-15));
  CHECK(hann(4) == Approx(1.0));
  CHECK(hann(2) == Approx(0.5));
  const Eigen::VectorXd ft = window_samples({WindowKind::FlatTop}, 8, 0.1);
  CHECK(ft(4) == Approx(0.21557895 + 0.41663158 + 0.277263158 + 0.083578947 + 0.006947368));
  Window force{WindowKind::Force};
  force.force_fraction = 0.25;
  const Eigen::VectorXd fw = window_samples(force, 8, 0.1);
  CHECK(fw.sum() == 2.0);
  CHECK(fw(1) == 1.0);
  CHECK(fw(2) == 0.0);
  Window ex{WindowKind::Exponential};
  ex.exponential_tau = 0.5;
  const Eigen::VectorXd ew = window_samples(ex, 8, 0.1);
  CHECK(ew(5) == Approx(std::exp(-1.0)));
  Window bad{WindowKind::Force};
  bad.force_fraction = 0;
  CHECK_THROWS_WITH(window_samples(bad, 8, 0.1), "force window: fraction 0 (expected 0 < fraction ≤ 1)");
}

TEST_CASE("H1, H2, Hv of a noise-free SDOF equal its receptance at the bin centres", "[identification][frf]") {
  Eigen::MatrixXd M(1, 1), C(1, 1), K(1, 1);
  const double wn = 2 * M_PI * 5.0;
  M << 1.0;
  K << wn * wn;
  C << 2 * 0.02 * wn;
  const Eigen::Index N = 256;
  const double dt = 0.01;
  Eigen::MatrixXd x, y;
  multisine_records(M, C, K, {0}, N, 6, dt, x, y);
  WelchOptions o;
  o.segment_length = N;
  o.overlap = 0;
  o.reference_window = o.response_window = {WindowKind::Rectangular};
  for (const auto est : {FrfEstimator::H1, FrfEstimator::H2, FrfEstimator::Hv}) {
    const FrfEstimate e = estimate_frf(x, y, dt, o, est);
    REQUIRE(e.segments == 6);
    REQUIRE(e.frequency_hz.size() == N / 2 + 1);
    double worst = 0, worst_coh = 0;
    for (Eigen::Index k = 1; k < N / 2; ++k) {
      CHECK(e.frequency_hz(k) == Approx(static_cast<double>(k) / (N * dt)));
      const Eigen::MatrixXcd H = receptance(M, C, K, e.frequency_hz(k));
      worst = std::max(worst, max_rel(e.h[static_cast<std::size_t>(k)], H));
      worst_coh = std::max(worst_coh, std::abs(e.coherence(k, 0) - 1.0));
      worst_coh = std::max(worst_coh, std::abs(e.multiple_coherence(k, 0) - 1.0));
    }
    INFO("estimator " << static_cast<int>(est) << ": max relative error " << worst << ", coherence " << worst_coh);
    CHECK(worst < 1e-10);
    CHECK(worst_coh < 1e-10);
  }
}

TEST_CASE("H1 with two references (MIMO) equals the 2-DOF receptance; multiple coherence 1",
          "[identification][frf]") {
  Eigen::MatrixXd M(2, 2), C(2, 2), K(2, 2);
  M << 1.0, 0, 0, 0.5;
  K << 3e3, -1e3, -1e3, 1e3;
  C << 0.6, -0.2, -0.2, 0.3;
  const Eigen::Index N = 128;
  const double dt = 0.02;
  Eigen::MatrixXd x, y;
  multisine_records(M, C, K, {0, 1}, N, 5, dt, x, y);
  WelchOptions o;
  o.segment_length = N;
  o.overlap = 0;
  o.reference_window = o.response_window = {WindowKind::Rectangular};
  const FrfEstimate e = estimate_frf(x, y, dt, o, FrfEstimator::H1);
  const FrfEstimate v = estimate_frf(x, y, dt, o, FrfEstimator::Hv);
  double worst = 0, worst_v = 0, worst_mc = 0;
  for (Eigen::Index k = 1; k < N / 2; ++k) {
    const Eigen::MatrixXcd H = receptance(M, C, K, e.frequency_hz(k));
    worst = std::max(worst, max_rel(e.h[static_cast<std::size_t>(k)], H));
    worst_v = std::max(worst_v, max_rel(v.h[static_cast<std::size_t>(k)], H));
    worst_mc = std::max(worst_mc, (e.multiple_coherence.row(k).array() - 1.0).abs().maxCoeff());
  }
  INFO("H1 " << worst << ", Hv " << worst_v << ", multiple coherence " << worst_mc);
  CHECK(worst < 1e-9);
  CHECK(worst_v < 1e-9);
  CHECK(worst_mc < 1e-9);
  // Fully correlated references: G_xx singular at every line, NaN rather than a number made up.
  Eigen::MatrixXd same(x.rows(), 2);
  same << x.col(0), x.col(0);
  const FrfEstimate singular = estimate_frf(same, y, dt, o, FrfEstimator::H1);
  CHECK(std::isnan(singular.h[5](0, 0).real()));
  CHECK(std::isnan(singular.multiple_coherence(5, 1)));
  CHECK(singular.coherence(5, 0) >= 0.0);  // the ordinary coherences are still defined (NaN fails both)
  CHECK(singular.coherence(5, 0) <= 1.0);
  CHECK_THROWS_WITH(estimate_frf(x, y, dt, o, FrfEstimator::H2),
                    "FRF: H2 with 2 references (expected 1; use H1 or Hv with several)");
}

TEST_CASE("FRF input errors name the cause", "[identification][frf]") {
  const Eigen::MatrixXd x = Eigen::MatrixXd::Ones(100, 1);
  const Eigen::MatrixXd y = Eigen::MatrixXd::Ones(90, 2);
  WelchOptions o;
  o.segment_length = 64;
  CHECK_THROWS_WITH(welch_spectra(x, y, 0.01, o), "spectra: references have 100 samples, responses 90 (expected the same)");
  CHECK_THROWS_WITH(welch_spectra(x, x, 0.0, o), "spectra: sample interval 0 s (expected > 0)");
  o.segment_length = 128;
  CHECK_THROWS_WITH(welch_spectra(x, x, 0.01, o), "spectra: records of 100 samples are shorter than one segment (128)");
  o.segment_length = 64;
  o.overlap = 64;
  CHECK_THROWS_WITH(welch_spectra(x, x, 0.01, o),
                    "spectra: overlap 64 samples with segments of 64 (expected overlap < segment)");
  CHECK_THROWS_AS(welch_spectra(x, x, 0.01, o), ssid::formats::InputError);
}

namespace {

bool python_has_scipy() { return std::system("/usr/bin/python3 -c 'import scipy.signal' >/dev/null 2>&1") == 0; }

nlohmann::json run_reference(const Eigen::MatrixXd& x, const Eigen::MatrixXd& y, double dt, Eigen::Index n,
                             Eigen::Index overlap, const nlohmann::json& window, const std::string& tag) {
  const fs::path dir = fs::temp_directory_path() / ("ssid_frf_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path in = dir / (tag + "_in.json"), out = dir / (tag + "_out.json");
  nlohmann::json j;
  for (Eigen::Index r = 0; r < x.rows(); ++r) {
    j["x"].push_back(nlohmann::json::array());
    for (Eigen::Index c = 0; c < x.cols(); ++c) j["x"].back().push_back(x(r, c));
    j["y"].push_back(nlohmann::json::array());
    for (Eigen::Index c = 0; c < y.cols(); ++c) j["y"].back().push_back(y(r, c));
  }
  j["dt"] = dt;
  j["nperseg"] = n;
  j["noverlap"] = overlap;
  j["window"] = window;
  std::ofstream(in) << j.dump();
  const std::string script = std::string(SSID_SOURCE_DIR) + "/tests/estimator/identification/welch_reference.py";
  const std::string cmd = "/usr/bin/python3 '" + script + "' '" + in.string() + "' '" + out.string() + "'";
  REQUIRE(std::system(cmd.c_str()) == 0);
  nlohmann::json r;
  std::ifstream(out) >> r;
  fs::remove_all(dir);
  return r;
}

cd cplx(const nlohmann::json& v) { return {v[0].get<double>(), v[1].get<double>()}; }

/// Random references (white) and responses (FIR-filtered mixtures plus noise).
void random_records(Eigen::Index samples, Eigen::Index ni, Eigen::Index no, Eigen::MatrixXd& x, Eigen::MatrixXd& y) {
  ssid::translators::NormalDeviates z(2024);
  x.resize(samples, ni);
  for (Eigen::Index i = 0; i < x.size(); ++i) x(i) = z();
  const Eigen::Index taps = 8;
  std::vector<Eigen::MatrixXd> b(static_cast<std::size_t>(taps), Eigen::MatrixXd(no, ni));
  for (auto& m : b)
    for (Eigen::Index i = 0; i < m.size(); ++i) m(i) = z();
  y = Eigen::MatrixXd::Zero(samples, no);
  for (Eigen::Index n = 0; n < samples; ++n) {
    for (Eigen::Index l = 0; l < taps && l <= n; ++l) y.row(n) += (b[static_cast<std::size_t>(l)] * x.row(n - l).transpose()).transpose();
    for (Eigen::Index r = 0; r < no; ++r) y(n, r) += 0.3 * z();
  }
}

}  // namespace

TEST_CASE("Welch spectra, H1, H2 and coherences agree with scipy.signal", "[identification][frf][scipy][slow]") {
  if (!python_has_scipy()) {
    WARN("/usr/bin/python3 lacks scipy.signal: the comparison with scipy is skipped");
    SUCCEED();
    return;
  }
  struct Case {
    std::string tag;
    Eigen::Index ni, no, n, overlap;
    Window window;
    nlohmann::json py_window;
  };
  const double dt = 1.0 / 512;
  Window ex{WindowKind::Exponential};
  ex.exponential_tau = 40 * dt;
  const std::vector<Case> cases = {
      {"hann_mimo", 2, 3, 256, 128, {WindowKind::Hann}, "hann"},
      {"flattop_siso", 1, 2, 200, 50, {WindowKind::FlatTop}, "flattop"},
      {"exponential_siso", 1, 2, 128, 0, ex, nlohmann::json::array({"exponential", 40.0})},
  };
  for (const Case& c : cases) {
    Eigen::MatrixXd x, y;
    random_records(4096, c.ni, c.no, x, y);
    WelchOptions o;
    o.segment_length = c.n;
    o.overlap = c.overlap;
    o.reference_window = o.response_window = c.window;
    const Spectra s = welch_spectra(x, y, dt, o);
    const FrfEstimate e = estimate_frf(s, FrfEstimator::H1);
    const nlohmann::json r = run_reference(x, y, dt, c.n, c.overlap, c.py_window, c.tag);
    REQUIRE(r["f"].size() == static_cast<std::size_t>(s.frequency_hz.size()));
    double dev_g = 0, dev_h = 0, dev_coh = 0, dev_mc = 0, dev_h2 = 0, dev_f = 0;
    // Relative to each spectrum's largest value (lines near the window's zeros are tiny).
    double gmax = 0;
    for (const auto& v : s.gyy) gmax = std::max(gmax, v.maxCoeff());
    for (Eigen::Index k = 0; k < s.frequency_hz.size(); ++k) {
      const auto kk = static_cast<std::size_t>(k);
      dev_f = std::max(dev_f, std::abs(s.frequency_hz(k) - r["f"][kk].get<double>()));
      for (Eigen::Index a = 0; a < c.no; ++a) {
        const auto aa = static_cast<std::size_t>(a);
        dev_g = std::max(dev_g, std::abs(s.gyy[kk](a) - r["gyy"][kk][aa].get<double>()) / gmax);
        dev_mc = std::max(dev_mc, std::abs(e.multiple_coherence(k, a) - r["multiple_coherence"][kk][aa].get<double>()));
        for (Eigen::Index i = 0; i < c.ni; ++i) {
          const auto ii = static_cast<std::size_t>(i);
          dev_g = std::max(dev_g, std::abs(s.gyx[kk](a, i) - cplx(r["gyx"][kk][aa][ii])) / gmax);
          const cd h = cplx(r["h1"][kk][aa][ii]);
          dev_h = std::max(dev_h, std::abs(e.h[kk](a, i) - h) / std::abs(h));
          dev_coh = std::max(dev_coh, std::abs(e.coherence(k, a + c.no * i) - r["coherence"][kk][aa][ii].get<double>()));
        }
      }
      for (Eigen::Index i = 0; i < c.ni; ++i)
        for (Eigen::Index j = 0; j < c.ni; ++j)
          dev_g = std::max(dev_g, std::abs(s.gxx[kk](i, j) - cplx(r["gxx"][kk][static_cast<std::size_t>(i)]
                                                                    [static_cast<std::size_t>(j)])) / gmax);
    }
    if (c.ni == 1) {
      const FrfEstimate e2 = estimate_frf(s, FrfEstimator::H2);
      for (Eigen::Index k = 0; k < s.frequency_hz.size(); ++k)
        for (Eigen::Index a = 0; a < c.no; ++a) {
          const cd h = cplx(r["h2"][static_cast<std::size_t>(k)][static_cast<std::size_t>(a)]);
          dev_h2 = std::max(dev_h2, std::abs(e2.h[static_cast<std::size_t>(k)](a, 0) - h) / std::abs(h));
        }
    }
    INFO(c.tag << ": max deviation from scipy: spectra " << dev_g << " (of the largest), H1 " << dev_h << " (relative), H2 "
               << dev_h2 << ", coherence " << dev_coh << ", multiple coherence " << dev_mc << ", frequencies " << dev_f);
    CHECK(dev_f < 1e-12);
    CHECK(dev_g < 1e-12);
    CHECK(dev_h < 1e-12);
    CHECK(dev_h2 < 1e-12);
    CHECK(dev_coh < 1e-12);
    CHECK(dev_mc < 1e-12);
  }
}
