// `ssid identify check`: every check passes on clean data and fails when its defect is
// built in — a nonreciprocal driving-point pair, a band of low coherence, a frequency
// resolution coarser than the half-power bandwidth (exact receptances of the 3-DOF chain),
// and a cubic-stiffness (Duffing) oscillator whose FRF moves at the higher force level
// (time histories simulated here, H1 by ssid).
#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <cmath>
#include <complex>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>

#include "cli/cli_run.hpp"
#include "estimator/identification/chain_model.hpp"
#include "formats/uff.hpp"
#include "translators/synthetic_modes.hpp"

namespace fs = std::filesystem;
namespace uff = ssid::formats::uff;
using cd = std::complex<double>;

namespace {

fs::path scratch(const std::string& name) { return cli_scratch("check") / name; }

uff::Function58 spectrum(int type, std::int64_t node, std::int64_t ref, double df, const std::vector<cd>& y) {
  uff::Function58 fn;
  fn.function_type = type;
  fn.response_node = node;
  fn.response_direction = 1;
  fn.reference_node = ref;
  fn.reference_direction = 1;
  fn.ordinate_type = type == 4 ? 6 : 4;
  fn.even = true;
  fn.abscissa_min = 0;
  fn.abscissa_increment = df;
  fn.axes[0].specific_data_type = 18;
  for (std::size_t k = 0; k < y.size(); ++k) fn.x.push_back(df * static_cast<double>(k));
  fn.y = y;
  return fn;
}

struct Defects {
  double df = 0.02;                 ///< Hz
  double nonreciprocal = 1.0;       ///< factor on H(node 1 / node 3)
  bool low_coherence = false;       ///< coherence 0.5 over 15…35 Hz on H(node 2 / node 1)
};

/// Receptances of the Rayleigh-damped chain (7.08, 18.03, 31.57 Hz; ζ 1.0, 1.35, 2.1 %)
/// from references at nodes 1 and 3 to nodes 1, 2, 3, 0…50 Hz, with coherences.
fs::path chain_file(const std::string& name, const Defects& d) {
  const auto model = ident_test::chain_model(true, {0, 2});
  const auto lines = static_cast<int>(std::lround(50.0 / d.df)) + 1;
  uff::UffFile f;
  for (int ref : {0, 2})
    for (int o = 0; o < 3; ++o) {
      std::vector<cd> h, c;
      for (int k = 0; k < lines; ++k) {
        const double fk = d.df * k, w = 2 * M_PI * fk;
        const Eigen::MatrixXcd H =
            (model.K.cast<cd>() - w * w * model.M.cast<cd>() + cd(0, w) * model.C.cast<cd>()).inverse();
        h.push_back(H(o, ref) * (ref == 2 && o == 0 ? d.nonreciprocal : 1.0));
        c.emplace_back(d.low_coherence && ref == 0 && o == 1 && fk >= 15 && fk <= 35 ? 0.5 : 0.99);
      }
      f.datasets.emplace_back(spectrum(4, o + 1, ref + 1, d.df, h));
      f.datasets.emplace_back(spectrum(6, o + 1, ref + 1, d.df, c));
    }
  const fs::path p = scratch(name);
  uff::write_uff(f, p.string(), uff::Precision::Extended);
  return p;
}

nlohmann::json run_check(const std::string& args, CliResult& r) {
  const fs::path json = scratch("check.json");
  r = run_ssid("identify check " + args + " --json " + json.string());
  nlohmann::json j;
  std::ifstream(json) >> j;
  return j;
}

std::string verdict_of(const nlohmann::json& j, const std::string& check) {
  for (const auto& c : j["checks"])
    if (c["check"] == check) return c["verdict"].get<std::string>();
  return "missing";
}

/// A Duffing oscillator m x'' + c x' + k x + k3 x³ = F(t): 1 kg, 5 Hz, ζ 2 %, driven by a
/// white Gaussian force of standard deviation `sigma` (N) held over each sample (dt =
/// 0.02 s, 16384 samples), integrated by RK4 with 8 steps per sample; the force and the
/// displacement as UFF 58 time histories (types 13 and 8 at node 1 +X).
fs::path duffing_file(const std::string& name, double sigma, double k3, std::uint64_t seed, double* rms = nullptr) {
  const double m = 1, k = std::pow(2 * M_PI * 5, 2), c = 2 * 0.02 * std::sqrt(k * m), dt = 0.02;
  const int n = 16384, sub = 8;
  ssid::translators::NormalDeviates z(seed);
  Eigen::VectorXd F(n), X(n);
  double x = 0, v = 0, sum2 = 0;
  const auto acc = [&](double xx, double vv, double f) { return (f - c * vv - k * xx - k3 * xx * xx * xx) / m; };
  for (int i = 0; i < n; ++i) {
    F(i) = sigma * z();
    X(i) = x;
    sum2 += x * x;
    const double h = dt / sub;
    for (int s = 0; s < sub; ++s) {
      const double k1x = v, k1v = acc(x, v, F(i));
      const double k2x = v + 0.5 * h * k1v, k2v = acc(x + 0.5 * h * k1x, v + 0.5 * h * k1v, F(i));
      const double k3x = v + 0.5 * h * k2v, k3v = acc(x + 0.5 * h * k2x, v + 0.5 * h * k2v, F(i));
      const double k4x = v + h * k3v, k4v = acc(x + h * k3x, v + h * k3v, F(i));
      x += h / 6 * (k1x + 2 * k2x + 2 * k3x + k4x);
      v += h / 6 * (k1v + 2 * k2v + 2 * k3v + k4v);
    }
  }
  if (rms) *rms = std::sqrt(sum2 / n);
  uff::UffFile f;
  for (int rec = 0; rec < 2; ++rec) {
    uff::Function58 fn;
    fn.function_type = 1;
    fn.function_id = rec + 1;
    fn.response_node = 1;
    fn.response_direction = 1;
    fn.reference_node = 1;
    fn.reference_direction = 1;
    fn.ordinate_type = 4;
    fn.even = true;
    fn.abscissa_increment = dt;
    fn.axes[0].specific_data_type = 17;
    fn.axes[1].specific_data_type = rec == 0 ? 13 : 8;
    const Eigen::VectorXd& s = rec == 0 ? F : X;
    for (int i = 0; i < n; ++i) {
      fn.x.push_back(i * dt);
      fn.y.emplace_back(s(i));
    }
    f.datasets.emplace_back(fn);
  }
  const fs::path p = scratch(name);
  uff::write_uff(f, p.string(), uff::Precision::Extended);
  return p;
}

}  // namespace

TEST_CASE("ssid identify check passes clean FRFs and fails each built-in defect", "[cli][identify][check]") {
  CliResult r;
  const fs::path clean = chain_file("clean.unv", {});
  nlohmann::json j = run_check(clean.string(), r);
  INFO(r.out << r.err);
  REQUIRE(r.code == 0);
  CHECK(r.out.find("6 FRF(s) and 6 coherence(s) from " + clean.string() + ": 3 response(s) × 2 reference(s), 2500 lines "
                   "0.02…50 Hz every 0.02 Hz") != std::string::npos);
  CHECK(verdict_of(j, "reciprocity") == "pass");
  CHECK(verdict_of(j, "linearity") == "n/a");
  CHECK(verdict_of(j, "coherence") == "pass");
  CHECK(verdict_of(j, "resolution") == "pass");
  CHECK(j["overall"] == "pass");
  CHECK(j["checks"][0]["items"][0]["error"].get<double>() < 1e-12);
  // The three peaks, their damping from the half-power band within 3 % of the chain's
  // (ζ = α/2ω + βω/2 with α = 0.5 s⁻¹, β = 2e-4 s; frequencies from the exact poles).
  const auto& peaks = j["checks"][3]["items"];
  REQUIRE(peaks.size() == 3);
  const double zeta_exact[3] = {0.5 / (2 * 2 * M_PI * 7.0824) + 2e-4 * 2 * M_PI * 7.0824 / 2,
                                0.5 / (2 * 2 * M_PI * 18.0287) + 2e-4 * 2 * M_PI * 18.0287 / 2,
                                0.5 / (2 * 2 * M_PI * 31.5731) + 2e-4 * 2 * M_PI * 31.5731 / 2};
  for (int p = 0; p < 3; ++p) CHECK(peaks[p]["zeta"].get<double>() == Approx(zeta_exact[p]).epsilon(0.03));
  CHECK(r.out.find("reciprocity  pass  H(3:1 / 1:1) against H(1:1 / 3:1): difference 0.00 %") != std::string::npos);

  // The same file at the "other level": linear, passes.
  j = run_check(clean.string() + " --second " + clean.string(), r);
  CHECK(verdict_of(j, "linearity") == "pass");

  Defects nonrec;
  nonrec.nonreciprocal = 1.3;
  j = run_check(chain_file("nonrec.unv", nonrec).string(), r);
  CHECK(verdict_of(j, "reciprocity") == "fail");
  CHECK(j["checks"][0]["items"][0]["error"].get<double>() == Approx(0.3 / std::sqrt(1.3)).epsilon(1e-6));
  CHECK(j["overall"] == "fail");
  CHECK(verdict_of(j, "resolution") == "pass");

  Defects coh;
  coh.low_coherence = true;
  j = run_check(chain_file("coh.unv", coh).string(), r);
  CHECK(verdict_of(j, "coherence") == "fail");
  CHECK(verdict_of(j, "reciprocity") == "pass");
  CHECK(r.out.find("coherence    fail  2:1 / 1:1: 40.04 % of the lines below 0.9 in 1 band(s), lowest 0.500 in 15…35 Hz") !=
        std::string::npos);

  Defects coarse;
  coarse.df = 0.25;  // against a first half-power band of 0.14 Hz
  j = run_check(chain_file("coarse.unv", coarse).string(), r);
  CHECK(verdict_of(j, "resolution") == "fail");
  CHECK(verdict_of(j, "reciprocity") == "pass");
  CHECK(r.out.find("resolution   fail  Δf = 0.25 Hz; peak at 7 Hz") != std::string::npos);
}

TEST_CASE("ssid identify check: linearity fails for a cubic stiffness at the higher force level",
          "[cli][identify][check]") {
  // The cubic term: 5 % of k at the high level's RMS displacement (equivalent linear
  // stiffness k + 3k3σ² ≈ 1.15 k there, 1.0015 k at the low level).
  double rms = 0;
  const double k = std::pow(2 * M_PI * 5, 2);
  duffing_file("probe.unv", 10.0, 0.0, 3, &rms);
  const double k3 = 0.05 * k / (rms * rms);
  CliResult r;
  const fs::path lin_lo = duffing_file("lin_lo.unv", 1.0, 0.0, 1), lin_hi = duffing_file("lin_hi.unv", 10.0, 0.0, 2);
  nlohmann::json j = run_check(lin_lo.string() + " --second " + lin_hi.string(), r);
  INFO(r.out << r.err);
  REQUIRE(r.code == 0);
  CHECK(verdict_of(j, "linearity") == "pass");
  const double e_lin = j["checks"][1]["items"][0]["error"];
  CHECK(e_lin < 0.1);

  const fs::path nl_lo = duffing_file("nl_lo.unv", 1.0, k3, 1), nl_hi = duffing_file("nl_hi.unv", 10.0, k3, 2);
  j = run_check(nl_lo.string() + " --second " + nl_hi.string(), r);
  REQUIRE(r.code == 0);
  CHECK(verdict_of(j, "linearity") == "fail");
  const auto& item = j["checks"][1]["items"][0];
  CHECK(item["error"].get<double>() > 0.2);
  // The resonance moves up with the level (hardening spring).
  CHECK(item["peak_hz"][1].get<double>() > 1.03 * item["peak_hz"][0].get<double>());
  CHECK(verdict_of(j, "reciprocity") == "n/a");
}

namespace {

/// A free decay of the oscillator of duffing_file at 0.5 % damping from x(0) = 0.01 m
/// (dt = 0.005 s, 4000 samples, RK4 with 4 steps per sample), with 0.5 % noise of the
/// initial amplitude; `k3` its cubic stiffness. Reference fields 0: no record is a force.
fs::path decay_file(const std::string& name, double k3) {
  const double m = 1, k = std::pow(2 * M_PI * 5, 2), c = 2 * 0.005 * std::sqrt(k * m), dt = 0.005;
  const int n = 4000, sub = 4;
  ssid::translators::NormalDeviates z(11);
  const auto acc = [&](double xx, double vv) { return (-c * vv - k * xx - k3 * xx * xx * xx) / m; };
  double x = 0.01, v = 0;
  uff::Function58 fn;
  fn.function_type = 1;
  fn.response_node = 1;
  fn.response_direction = 1;
  fn.ordinate_type = 4;
  fn.abscissa_increment = dt;
  fn.axes[1].specific_data_type = 8;
  for (int i = 0; i < n; ++i) {
    fn.x.push_back(i * dt);
    fn.y.emplace_back(x + 0.005 * 0.01 * z());
    const double h = dt / sub;
    for (int s = 0; s < sub; ++s) {
      const double k1x = v, k1v = acc(x, v);
      const double k2x = v + 0.5 * h * k1v, k2v = acc(x + 0.5 * h * k1x, v + 0.5 * h * k1v);
      const double k3x = v + 0.5 * h * k2v, k3v = acc(x + 0.5 * h * k2x, v + 0.5 * h * k2v);
      const double k4x = v + h * k3v, k4v = acc(x + h * k3x, v + h * k3v);
      x += h / 6 * (k1x + 2 * k2x + 2 * k3x + k4x);
      v += h / 6 * (k1v + 2 * k2v + 2 * k3v + k4v);
    }
  }
  uff::UffFile f;
  f.datasets.emplace_back(fn);
  const fs::path p = scratch(name);
  uff::write_uff(f, p.string(), uff::Precision::Extended);
  return p;
}

}  // namespace

TEST_CASE("ssid identify check: linearity of free decays from ERA on overlapping segments", "[cli][identify][check]") {
  CliResult r;
  // Linear: the dominant frequency stays at the oscillator's damped 5 Hz.
  nlohmann::json j = run_check(decay_file("decay_lin.unv", 0.0).string(), r);
  INFO(r.out << r.err);
  REQUIRE(r.code == 0);
  CHECK(r.out.find("1 free decay(s) (no force record)") != std::string::npos);
  CHECK(verdict_of(j, "linearity") == "pass");
  CHECK(verdict_of(j, "reciprocity") == "n/a");
  const auto& segs = j["checks"][0]["items"];
  REQUIRE(segs.size() == 7);  // quarter-record segments every half segment
  for (const auto& sgm : segs) CHECK(sgm["hz"].get<double>() == Approx(5.0).epsilon(2e-4));
  // Hardening cubic spring, k3 x0² = 0.3 k: about 11 % stiffer-in-frequency at the start,
  // falling towards 5 Hz as the decay dies out.
  const double k3 = 0.3 * std::pow(2 * M_PI * 5, 2) / (0.01 * 0.01);
  j = run_check(decay_file("decay_nl.unv", k3).string(), r);
  REQUIRE(r.code == 0);
  CHECK(verdict_of(j, "linearity") == "fail");
  const auto& nl = j["checks"][0]["items"];
  CHECK(nl[0]["hz"].get<double>() > 1.03 * nl[6]["hz"].get<double>());
  CHECK(nl[0]["rms"].get<double>() > nl[6]["rms"].get<double>());
  const CliResult second = run_ssid("identify check " + scratch("decay_nl.unv").string() + " --second " +
                                    scratch("decay_lin.unv").string());
  CHECK(second.code == 2);
  CHECK(second.err == "ssid: error: " + scratch("decay_nl.unv").string() +
                          ": free decays (no force record): --second compares FRFs at two force levels, which free "
                          "decays do not have\n");
}

TEST_CASE("ssid identify check: bad input exits 2 with the reason", "[cli][identify][check]") {
  const fs::path clean = chain_file("clean2.unv", {});
  CHECK(run_ssid("identify check --help").code == 0);
  const CliResult js = run_ssid("identify check " + clean.string() + " --json -");  // the JSON alone on stdout
  CHECK(js.code == 0);
  CHECK(nlohmann::json::parse(js.out)["overall"] == "pass");
  CliResult r = run_ssid("identify check " + clean.string() + " --coherence-min 1.5");
  CHECK(r.code == 2);
  CHECK(r.err == "ssid: error: --coherence-min: expected 0 < C < 1, got 1.5\n");
  Defects coarse;
  coarse.df = 0.25;
  const fs::path other = chain_file("other.unv", coarse);
  r = run_ssid("identify check " + clean.string() + " --second " + other.string());
  CHECK(r.code == 2);
  CHECK(r.err == "ssid: error: " + other.string() +
                     ": 201 lines every 0.25 Hz (expected 2501 every 0.02 Hz as the first set)\n");
  r = run_ssid("identify check " + clean.string() + " --band 60:70");
  CHECK(r.code == 2);
  CHECK(r.err == "ssid: error: " + clean.string() + ": 0 line(s) in the band checked (expected at least 3)\n");
}
