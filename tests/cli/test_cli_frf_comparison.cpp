// The analysis FRFs laid over measured ones in `ssid correlate --frf` and `ssid estimate
// --frf` (issue 24: the seed's Figures 6–9): the measured FRFs and the test modes are
// built here from the dense solve (K − ω²M + iωC)⁻¹ of a spring–mass system written out
// by hand (spring_deck.hpp), so the analysis curves are checked against an independent
// solve, at the deck's parameters and at the estimate's.
#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <cmath>
#include <complex>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <vector>

#include "cli/cli_run.hpp"
#include "cli/spring_deck.hpp"
#include "formats/uff.hpp"

namespace fs = std::filesystem;
namespace uff = ssid::formats::uff;
using json = nlohmann::json;
using cd = std::complex<double>;

namespace {

fs::path scratch(const std::string& name) { return cli_scratch("frf_comparison") / name; }

json read_json(const fs::path& p) {
  std::ifstream in(p);
  json j;
  in >> j;
  return j;
}

/// The spring system's modes as UFF 55 (shapes at nodes 1–3 in X, scaled by 7: a test
/// shape's scale is arbitrary), each with its damping ratio `zeta` (0: none given).
void write_test_modes(const Spring3& s, const Eigen::Vector3d& zeta, const fs::path& path) {
  uff::UffFile f;
  for (int r = 0; r < 3; ++r) {
    Eigen::MatrixXd v = Eigen::MatrixXd::Zero(3, 3);
    v.col(0) = 7.0 * s.phi.col(r);
    f.datasets.emplace_back(
        uff::NodalData55::normal_mode(r + 1, std::sqrt(s.lambda(r)) / (2 * M_PI), {1, 2, 3}, v, 0.0, zeta(r)));
  }
  uff::write_uff(f, path.string(), uff::Precision::Extended);
}

/// One measured accelerance record: response (node, signed direction) to the reference,
/// 0 … 60 Hz every 0.25 Hz, from the dense solve; a −X direction negates the values.
uff::Function58 accelerance(const Spring3& s, const Eigen::Vector3d& zeta, int id, int resp, int resp_dir, int ref,
                            int ref_dir) {
  uff::Function58 fn;
  fn.function_type = 4;
  fn.function_id = id;
  fn.response_node = resp;
  fn.response_direction = resp_dir;
  fn.reference_node = ref;
  fn.reference_direction = ref_dir;
  fn.ordinate_type = 6;
  fn.even = true;
  fn.abscissa_min = 0;
  fn.abscissa_increment = 0.25;
  fn.axes[1].specific_data_type = 12;  // acceleration
  fn.axes[2].specific_data_type = 13;
  for (int k = 0; k <= 240; ++k) {
    const double f = 0.25 * k, w = 2 * M_PI * f;
    fn.x.push_back(f);
    const double sign = (resp_dir < 0 ? -1.0 : 1.0) * (ref_dir < 0 ? -1.0 : 1.0);
    fn.y.push_back(sign * (-w * w) * s.direct(f, zeta)(resp - 1, ref - 1));
  }
  return fn;
}

/// The dense accelerance (response, reference in +X) at f (Hz).
cd dense_accelerance(const Spring3& s, const Eigen::Vector3d& zeta, double f, int resp, int ref) {
  const double w = 2 * M_PI * f;
  return -w * w * s.direct(f, zeta)(resp - 1, ref - 1);
}

/// The analysis's damping ratios in the JSON (one per mode, three modes).
Eigen::Vector3d zeta_of(const json& analysis) {
  REQUIRE(analysis["modes"].size() == 3);
  return {analysis["modes"][0]["zeta"].get<double>(), analysis["modes"][1]["zeta"].get<double>(),
          analysis["modes"][2]["zeta"].get<double>()};
}

/// Checks every analysis curve of `frf` against the dense accelerance of `s` at the
/// damping the JSON gives that analysis, every 20th line, to 1e-9 of the peak.
void check_against_dense(const json& frf, const json& analysis_json, std::size_t a, const Spring3& s) {
  const Eigen::Vector3d zeta = zeta_of(analysis_json);
  const int resp = frf["response"][0], ref = frf["reference"][0];
  const double sign = (frf["response"][1].get<int>() < 0 ? -1.0 : 1.0) * (frf["reference"][1].get<int>() < 0 ? -1.0 : 1.0);
  const auto& hz = frf["hz"];
  double peak = 0;
  for (std::size_t k = 0; k < hz.size(); ++k) peak = std::max(peak, std::abs(dense_accelerance(s, zeta, hz[k], resp, ref)));
  for (std::size_t k = 0; k < hz.size(); k += 20) {
    const cd want = sign * dense_accelerance(s, zeta, hz[k], resp, ref);
    const cd got(frf["analyses"][a]["re"][k].get<double>(), frf["analyses"][a]["im"][k].get<double>());
    INFO("line " << hz[k].get<double>() << " Hz, analysis " << a);
    CHECK(std::abs(got - want) <= 1e-9 * peak);
  }
}

}  // namespace

TEST_CASE("ssid correlate --frf: the deck's FRFs over measured ones, damped as the test modes", "[cli][frf][report]") {
  const Spring3 s;
  const Eigen::Vector3d zeta(0.01, 0.02, 0.03);
  const fs::path deck = scratch("springs.bdf"), test = scratch("test.unv"), meas = scratch("frf.unv"),
                 out = scratch("c.json"), rep = scratch("c.html");
  std::ofstream(deck) << spring_deck_text();
  write_test_modes(s, zeta, test);
  {
    uff::UffFile m;
    m.datasets.emplace_back(accelerance(s, zeta, 1, 3, -1, 1, 1));  // response 3 measured along −X
    m.datasets.emplace_back(accelerance(s, zeta, 2, 1, 1, 1, 1));   // drive point 1
    m.datasets.emplace_back(accelerance(s, zeta, 3, 1, 1, 2, -1));  // force along −X at node 2
    m.datasets.emplace_back(accelerance(s, zeta, 4, 2, 1, 2, 1));   // drive point 2
    uff::write_uff(m, meas.string(), uff::Precision::Extended);
  }
  const CliResult r = run_ssid("correlate " + deck.string() + " " + test.string() + " --frf " + meas.string() +
                               " --frf-max 3 --json " + out.string() + " --report " + rep.string());
  INFO(r.err);
  REQUIRE(r.code == 0);
  CHECK(r.out.find("FRFs: 3 measured FRF(s) of " + meas.string()) != std::string::npos);
  const json j = read_json(out);
  REQUIRE(j.contains("frf_comparison"));
  const json& c = j["frf_comparison"];
  REQUIRE(c["frfs"].size() == 3);
  // Drive points first, then the file's order; the fourth is beyond --frf-max.
  CHECK(c["frfs"][0]["response"] == json({1, 1}));
  CHECK(c["frfs"][1]["response"] == json({2, 1}));
  CHECK(c["frfs"][2]["response"] == json({3, -1}));
  REQUIRE(c["left_out"].size() == 1);
  CHECK(c["left_out"][0].get<std::string>().find("beyond the 3 FRF(s) drawn (--frf-max)") != std::string::npos);
  // Each mode damped as its test mode (all three carry one).
  REQUIRE(c["analyses"].size() == 1);
  const Eigen::Vector3d used = zeta_of(c["analyses"][0]);
  for (int r2 = 0; r2 < 3; ++r2) CHECK(used(r2) == Approx(zeta(r2)).epsilon(1e-6));  // UFF 55 holds E13.5
  CHECK(c["analyses"][0]["modes"][1]["zeta_from"].get<std::string>().rfind("test mode 2 at", 0) == 0);
  for (const auto& f : c["frfs"]) {
    CHECK(f["hz"][0].get<double>() == 0.25);  // the 0 Hz line left out
    CHECK(f["quantity"] == "acceleration");
    CHECK(f["analyses"][0]["frac"].get<double>() == Approx(1.0).epsilon(1e-9));
    check_against_dense(f, c["analyses"][0], 0, s);
  }
  // The report draws each FRF with the JSON's FRAC.
  const std::string html = cli_slurp(rep);
  for (int k = 0; k < 3; ++k) {
    const std::string tag = "<figure id=\"fig-frfc-" + std::to_string(k) + "\"";
    const auto at = html.find(tag);
    REQUIRE(at != std::string::npos);
    const auto v = html.find("data-frac=\"", at) + 11;
    REQUIRE(v < html.find('>', at));
    CHECK(std::stod(html.substr(v, html.find('"', v) - v)) ==
          Approx(c["frfs"][static_cast<std::size_t>(k)]["analyses"][0]["frac"].get<double>()).epsilon(1e-14));
    CHECK(html.find("id=\"frfc-" + std::to_string(k) + "-mag\"") != std::string::npos);
  }
  CHECK(html.find("<section id=\"frf-comparison\">") != std::string::npos);
  CHECK(html.find("Modal damping of the analysis FRFs") != std::string::npos);

  // A wrong spring to ground: the analysis misses the measurement (FRAC well below 1).
  std::ofstream(deck) << spring_deck_text(6e4);
  const CliResult w = run_ssid("correlate " + deck.string() + " " + test.string() + " --frf " + meas.string() +
                               " --json " + out.string());
  REQUIRE(w.code == 0);
  const json jw = read_json(out);
  CHECK(jw["frf_comparison"]["frfs"].size() == 4);
  CHECK(jw["frf_comparison"]["frfs"][0]["analyses"][0]["frac"].get<double>() < 0.9);
  check_against_dense(jw["frf_comparison"]["frfs"][0], jw["frf_comparison"]["analyses"][0], 0, Spring3(6e4));
}

TEST_CASE("ssid correlate --frf: test modes without damping need --frf-damping; a test file's own FRFs",
          "[cli][frf][report]") {
  const Spring3 s;
  const Eigen::Vector3d zeta = Eigen::Vector3d::Constant(0.02);
  const fs::path deck = scratch("springs2.bdf"), test = scratch("undamped.unv"), out = scratch("d.json"),
                 rep = scratch("d.html");
  std::ofstream(deck) << spring_deck_text();
  // Test modes without damping and, in the same file, the measured FRFs.
  {
    uff::UffFile f;
    for (int r = 0; r < 3; ++r) {
      Eigen::MatrixXd v = Eigen::MatrixXd::Zero(3, 3);
      v.col(0) = s.phi.col(r);
      f.datasets.emplace_back(uff::NodalData55::normal_mode(r + 1, std::sqrt(s.lambda(r)) / (2 * M_PI), {1, 2, 3}, v));
    }
    f.datasets.emplace_back(accelerance(s, zeta, 1, 2, 1, 1, 1));
    uff::write_uff(f, test.string(), uff::Precision::Extended);
  }
  const CliResult no = run_ssid("correlate " + deck.string() + " " + test.string() + " --report " + rep.string());
  CHECK(no.code == 2);
  CHECK(no.err.find("the test modes carry no damping") != std::string::npos);
  CHECK(no.err.find("--frf-damping Z") != std::string::npos);
  const CliResult ok = run_ssid("correlate " + deck.string() + " " + test.string() + " --report " + rep.string() +
                                " --frf-damping 0.02 --json " + out.string());
  INFO(ok.err);
  REQUIRE(ok.code == 0);
  const json c = read_json(out)["frf_comparison"];
  REQUIRE(c["frfs"].size() == 1);
  CHECK(c["file"] == test.string());
  CHECK(c["analyses"][0]["modes"][0]["zeta_from"] == "--frf-damping (no damped test mode near)");
  CHECK(c["frfs"][0]["analyses"][0]["frac"].get<double>() == Approx(1.0).epsilon(1e-9));
  check_against_dense(c["frfs"][0], c["analyses"][0], 0, s);
  // Without --report the test file's FRFs are not looked at; a universal file of FE modes cannot synthesize.
  const CliResult plain = run_ssid("correlate " + deck.string() + " " + test.string() + " --json " + out.string());
  REQUIRE(plain.code == 0);
  CHECK_FALSE(read_json(out).contains("frf_comparison"));
  const CliResult uffe = run_ssid("correlate " + test.string() + " " + test.string() + " --frf " + test.string());
  CHECK(uffe.code == 2);
  CHECK(uffe.err.find("--frf needs the deck's modes") != std::string::npos);
  CHECK(run_ssid("correlate " + deck.string() + " " + test.string() + " --frf " + test.string() + " --frf-max 0").code == 2);
}

TEST_CASE("ssid estimate --frf: FRFs at the prior mean and at the estimate against the dense solves",
          "[cli][frf][estimate][report]") {
  // The spring to ground a PELAS designed by DESVAR K1 (deck 3e4 N/m, truth 4e4 N/m).
  const double k_deck = 3e4, k_true = 4e4;
  std::string deck_text = spring_deck_text(k_deck);
  const std::string celas = "CELAS2,11,30000.0,1,1\n";
  REQUIRE(deck_text.find(celas) != std::string::npos);
  deck_text.replace(deck_text.find(celas), celas.size(),
                    "CELAS1,11,11,1,1\nPELAS,11,30000.0\nDESVAR,1,K1,30000.0,1000.0,1.0E6\n"
                    "DVPREL1,1,PELAS,11,K,,,0.0,,+DV1\n+DV1,1,1.0\n");
  const Spring3 truth(k_true);
  const Eigen::Vector3d zeta(0.01, 0.02, 0.03);
  const fs::path deck = scratch("pelas.bdf"), test = scratch("truth.unv"), meas = scratch("truth_frf.unv"),
                 out = scratch("e.json"), rep = scratch("e.html");
  std::ofstream(deck) << deck_text;
  write_test_modes(truth, zeta, test);
  {
    uff::UffFile m;
    m.datasets.emplace_back(accelerance(truth, zeta, 1, 1, 1, 1, 1));
    m.datasets.emplace_back(accelerance(truth, zeta, 2, 3, 1, 1, 1));
    uff::write_uff(m, meas.string(), uff::Precision::Extended);
  }
  const CliResult r = run_ssid("estimate " + deck.string() + " " + test.string() + " --frf " + meas.string() +
                               " --json " + out.string() + " --report " + rep.string() + " -q");
  INFO(r.out << r.err);
  REQUIRE(r.code == 0);
  const json j = read_json(out);
  const double k_hat = j["parameters"][0]["estimate"];
  // The prior (3e4 ± 1.45e4) pulls the estimate a little: within its posterior σ of the truth.
  CHECK(std::abs(k_hat - k_true) < j["parameters"][0]["posterior_std"].get<double>());
  const json& c = j["frf_comparison"];
  REQUIRE(c["analyses"].size() == 2);
  CHECK(c["analyses"][0]["label"] == "prior mean");
  CHECK(c["analyses"][1]["label"] == "estimate");
  REQUIRE(c["frfs"].size() == 2);
  for (const auto& f : c["frfs"]) {
    // Each curve is the dense solve at its own parameters and damping.
    check_against_dense(f, c["analyses"][0], 0, Spring3(k_deck));
    check_against_dense(f, c["analyses"][1], 1, Spring3(k_hat));
    const double before = f["analyses"][0]["frac"], after = f["analyses"][1]["frac"];
    CHECK(before < 0.9);
    CHECK(after > 0.99);
  }
  CHECK(r.out.find("FRAC estimate") != std::string::npos);
  // A problem file carries no deck to place the FRFs on: refused before the cycles run.
  const fs::path prob = scratch("pelas.ssidprob");
  REQUIRE(run_ssid("translate " + deck.string() + " " + test.string() + " -o " + prob.string()).code == 0);
  const CliResult p = run_ssid("estimate --problem " + prob.string() + " --frf " + meas.string());
  CHECK(p.code == 2);
  CHECK(p.err.find("--frf needs the deck") != std::string::npos);
  CHECK(p.out.empty());
  const std::string html = cli_slurp(rep);
  CHECK(html.find("FRFs before and after the update") != std::string::npos);
  CHECK(html.find("data-frac-before=\"") != std::string::npos);
}

namespace {

/// Eight 1 kg masses in X (grids 1–8 at x = 1…8 m) on a fixed-free chain of springs, all
/// one PELAS 11 (k = 1e4 N/m) designed by DESVAR KS; `hidden` kg more at grid 6 in the truth.
struct Chain8 {
  Eigen::MatrixXd M, K, phi;
  Eigen::VectorXd lambda;
  explicit Chain8(double hidden = 0) {
    const int n = 8;
    const double k = 1e4;
    M = Eigen::MatrixXd::Identity(n, n);
    M(5, 5) += hidden;
    K = Eigen::MatrixXd::Zero(n, n);
    for (int i = 0; i < n; ++i) {  // spring i joins mass i to mass i−1 (to ground for i = 0)
      K(i, i) += k;
      if (i > 0) K(i - 1, i - 1) += k, K(i, i - 1) -= k, K(i - 1, i) -= k;
    }
    Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(K, M);
    lambda = es.eigenvalues();
    phi = es.eigenvectors();
  }
  /// Accelerance from `ref` to `resp` (grids 1–8) at f Hz, modal damping ζ_r for every mode.
  cd accelerance(double f, const Eigen::VectorXd& zeta, int resp, int ref) const {
    const double w = 2 * M_PI * f;
    Eigen::VectorXd c(lambda.size());
    for (Eigen::Index r = 0; r < lambda.size(); ++r) c(r) = 2 * zeta(r) * std::sqrt(lambda(r));
    const Eigen::MatrixXd C = M * phi * c.asDiagonal() * phi.transpose() * M;
    const Eigen::MatrixXcd D = K.cast<cd>() - w * w * M.cast<cd>() + cd(0, w) * C.cast<cd>();
    return -w * w * D.partialPivLu().solve(Eigen::MatrixXcd::Identity(8, 8))(resp - 1, ref - 1);
  }
  static std::string deck() {
    std::string d = "SOL 103\nCEND\nBEGIN BULK\n";
    for (int g = 1; g <= 8; ++g) d += "GRID," + std::to_string(g) + ",," + std::to_string(g) + ".,0.,0.,,23456\n";
    d += "CELAS1,101,11,1,1\n";
    for (int g = 2; g <= 8; ++g)
      d += "CELAS1," + std::to_string(100 + g) + ",11," + std::to_string(g) + ",1," + std::to_string(g - 1) + ",1\n";
    for (int g = 1; g <= 8; ++g) d += "CONM2," + std::to_string(200 + g) + "," + std::to_string(g) + ",,1.0\n";
    d += "PELAS,11,10000.0\nDESVAR,1,KS,10000.0,1000.0,1.0E5\nDVPREL1,1,PELAS,11,K,,,0.0,,+DV1\n+DV1,1,1.0\nENDDATA\n";
    return d;
  }
};

}  // namespace

TEST_CASE("ssid diagnose --frf: the deck's, the ordinary update's and the named cause's FRFs over measured ones",
          "[cli][frf][diagnose][report]") {
  const Chain8 nominal, truth(0.3);
  const Eigen::VectorXd zeta = Eigen::VectorXd::Constant(8, 0.02);
  const fs::path deck = scratch("chain8.bdf"), test = scratch("chain8_test.unv"), meas = scratch("chain8_frf.unv"),
                 out = scratch("g.json"), rep = scratch("g.html");
  std::ofstream(deck) << Chain8::deck();
  {
    uff::UffFile f;
    std::vector<std::int64_t> nodes{1, 2, 3, 4, 5, 6, 7, 8};
    for (int r = 0; r < 6; ++r) {
      Eigen::MatrixXd v = Eigen::MatrixXd::Zero(8, 3);
      v.col(0) = truth.phi.col(r);
      f.datasets.emplace_back(uff::NodalData55::normal_mode(r + 1, std::sqrt(truth.lambda(r)) / (2 * M_PI), nodes, v,
                                                            0.0, zeta(r)));
    }
    uff::write_uff(f, test.string(), uff::Precision::Extended);
    uff::UffFile m;
    for (const auto& [resp, ref] : {std::pair<int, int>{8, 8}, {6, 8}}) {
      uff::Function58 fn;
      fn.function_type = 4;
      fn.function_id = resp;
      fn.response_node = resp;
      fn.response_direction = 1;
      fn.reference_node = ref;
      fn.reference_direction = 1;
      fn.even = true;
      fn.abscissa_min = 0;
      fn.abscissa_increment = 0.05;
      fn.axes[1].specific_data_type = 12;
      for (int k = 0; k <= 600; ++k) {
        fn.x.push_back(0.05 * k);
        fn.y.push_back(truth.accelerance(0.05 * k, zeta, resp, ref));
      }
      m.datasets.emplace_back(fn);
    }
    uff::write_uff(m, meas.string(), uff::Precision::Extended);
  }
  const CliResult r = run_ssid("diagnose -q " + deck.string() + " " + test.string() + " --kinds missing_mass --frf " +
                               meas.string() + " --json " + out.string() + " --report " + rep.string());
  INFO(r.out << r.err);
  REQUIRE((r.code == 0 || r.code == 3));
  const json j = read_json(out);
  REQUIRE(j["cause"]["kind"] == "missing_mass");
  CHECK(j["cause"]["location"]["grids"][0] == 6);
  const json& c = j["frf_comparison"];
  REQUIRE(c["analyses"].size() == 3);
  CHECK(c["analyses"][0]["label"] == "deck");
  CHECK(c["analyses"][1]["label"] == "parameters updated");
  CHECK(c["analyses"][2]["label"] == "cause: missing_mass");
  REQUIRE(c["frfs"].size() == 2);
  for (const auto& f : c["frfs"]) {
    // The deck's curve is the dense solve of the nominal chain, with every mode (8 DOFs:
    // all modes solved), the damping of the test mode each stands for (or the mean).
    const Eigen::VectorXd z = [&] {
      Eigen::VectorXd v(8);
      for (int m = 0; m < 8; ++m) v(m) = c["analyses"][0]["modes"][m]["zeta"];
      return v;
    }();
    const auto& hz = f["hz"];
    double peak = 0;
    for (const auto& x : hz) peak = std::max(peak, std::abs(nominal.accelerance(x, z, f["response"][0], f["reference"][0])));
    for (std::size_t k = 0; k < hz.size(); k += 25) {
      const cd want = nominal.accelerance(hz[k], z, f["response"][0], f["reference"][0]);
      const cd got(f["analyses"][0]["re"][k].get<double>(), f["analyses"][0]["im"][k].get<double>());
      CHECK(std::abs(got - want) <= 1e-9 * peak);
    }
    // The named cause brings the FRFs closest to the measured ones.
    const double deck_frac = f["analyses"][0]["frac"], param = f["analyses"][1]["frac"], cause = f["analyses"][2]["frac"];
    CHECK(cause > 0.99);
    CHECK(cause > param);
    CHECK(cause > deck_frac);
  }
  const std::string html = cli_slurp(rep);
  CHECK(html.find("FRFs of the deck, of the ordinary update and of the named cause") != std::string::npos);
  CHECK(html.find("id=\"fig-frfc-1\"") != std::string::npos);
}
