// The hand-over of issue 22 item 5: `ssid identify modes --json` to `ssid estimate`
// and `ssid diagnose`, the identification's σ per mode as the measurement σ.
// FRFs of a three-spring chain written as UFF 58, identified by ERA, estimated
// against the chain's deck; and identified modes with errors, refused naming the
// file and the key path.
#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli/chain_frf.hpp"
#include "cli/cli_run.hpp"

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

fs::path scratch(const std::string& name) { return cli_scratch("idsigma_cli") / name; }

/// Three unit masses on three springs of 1e5 N/m (ground–2–3–4 along X), one
/// parameter KSPR designing all: 22.4, 62.7 and 90.7 Hz.
const char* const kChainDeck =
    "SOL 103\nCEND\nSPC = 1\nBEGIN BULK\n"
    "GRID,1,,0.,0.,0.\nGRID,2,,1.,0.,0.\nGRID,3,,2.,0.,0.\nGRID,4,,3.,0.,0.\n"
    "CELAS1,10,1,1,1,2,1\nCELAS1,11,1,2,1,3,1\nCELAS1,12,1,3,1,4,1\nPELAS,1,1.0E5\n"
    "CONM2,20,2,,1.0\nCONM2,21,3,,1.0\nCONM2,22,4,,1.0\n"
    "SPC1,1,123456,1\nSPC1,1,23456,2,3,4\n"
    "DESVAR,1,KSPR,1.0E5,1.0E4,1.0E6\nDVPREL1,30,PELAS,1,K1,,,,\n,1,1.0\n"
    "ENDDATA\n";

/// Receptance FRFs of the chain (C = M + 2e-5 K: 0.4 … 0.9 % damping) from node 2
/// to nodes 2, 3 and 4, 0 … 500 Hz every 0.25 Hz, as dataset 58.
fs::path chain_frf_file() {
  const Eigen::MatrixXd K = ident_test::chain({1e5, 1e5, 1e5}), M = Eigen::MatrixXd::Identity(3, 3);
  const fs::path p = scratch("chain_frf.unv");
  write_chain_frf(ident_test::ChainModel(M, M + 2e-5 * K, K, {0}), p.string(), 2);
  return p;
}

/// A number as the CLI prints it (3 significant digits).
std::string estimator_text(double x) {
  std::ostringstream s;
  s.precision(3);
  s << x;
  return s.str();
}

json read_json(const fs::path& p) {
  json j;
  std::ifstream(p) >> j;
  return j;
}

}  // namespace

TEST_CASE("ssid identify modes --json into ssid estimate: the identification's σ per mode",
          "[cli][estimate][identify][identified]") {
  const fs::path deck = scratch("chain.bdf"), id = scratch("chain_id.json"), out = scratch("estimate.json");
  std::ofstream(deck) << kChainDeck;
  const auto r = run_ssid("identify modes " + chain_frf_file().string() + " --method era --max-hz 75 --json " + id.string());
  INFO(r.out << r.err);
  REQUIRE(r.code == 0);
  const json ident = read_json(id);
  REQUIRE(ident["modes"].size() == 2);
  for (const auto& m : ident["modes"]) {
    CHECK(m.contains("shape_std"));  // ERA's clusters give a shape spread
    CHECK(m["shape_std"].get<double>() >= 0);
  }

  const auto e = run_ssid("estimate " + deck.string() + " " + id.string() + " --json " + out.string() + " -q");
  INFO(e.out << e.err);
  REQUIRE(e.code == 0);
  CHECK_THAT(e.out, Catch::Contains("\nmeasurement σ: from the identification (per mode: its hz_std, and its shape_std "
                                    "where given, else 5 % of the RMS shape component), floored at 0.05 % of the "
                                    "frequency and 0.5 % of the RMS shape component\n"));
  const json j = read_json(out);
  REQUIRE(j["measurement"]["modes"].size() == 2);
  for (std::size_t m = 0; m < 2; ++m) {
    const auto& used = j["measurement"]["modes"][m];
    const auto& given = ident["modes"][m];
    const double hz = given["hz"].get<double>();
    INFO("identified " << given.dump() << "; used " << used.dump());
    CHECK(used["from"] == "identification");
    CHECK(used["test_mode"] == m + 1);
    CHECK(used["hz"].get<double>() == hz);
    // σ_f = max(hz_std, 0.05 % f), σ_s = max(shape_std, 0.5 %/√n_s) with n_s = 3 sensors.
    CHECK(used["frequency_std_hz"].get<double>() == std::max(given["hz_std"].get<double>(), 5e-4 * hz));
    CHECK(used["shape_std"].get<double>() == std::max(given["shape_std"].get<double>(), 0.005 / std::sqrt(3.0)));
  }
  // The estimate recovers the deck's own stiffness from its own identified modes.
  CHECK(std::abs(j["parameters"][0]["estimate"].get<double>() / 1e5 - 1) < 1e-3);

  // The study's percentages instead, on request.
  const fs::path study = scratch("study.json");
  std::ofstream(study) << R"({"measurement": {"std_from": "study", "frequency_std_pct": 2}})";
  const auto s = run_ssid("estimate " + deck.string() + " " + id.string() + " --study " + study.string() + " --json " +
                          out.string() + " -q");
  INFO(s.err);
  REQUIRE(s.code == 0);
  CHECK_THAT(s.out, Catch::Contains("\nmeasurement σ: the study's 2 % of each frequency, 5 % of the RMS shape "
                                    "component\n"));
  const json js = read_json(out);
  for (std::size_t m = 0; m < 2; ++m) {
    CHECK(js["measurement"]["modes"][m]["from"] == "study");
    CHECK(js["measurement"]["modes"][m]["frequency_std_hz"].get<double>() ==
          Approx(0.02 * ident["modes"][m]["hz"].get<double>()).epsilon(1e-14));
  }
}

TEST_CASE("identified modes with errors: exit 2 naming the file and the key path", "[cli][estimate][identified]") {
  const fs::path deck = scratch("chain.bdf");
  std::ofstream(deck) << kChainDeck;
  auto with = [&](const std::string& name, const std::string& text) {
    const fs::path p = scratch(name);
    std::ofstream(p) << text;
    return std::make_pair(p.string(), run_ssid("estimate " + deck.string() + " " + p.string() + " -q"));
  };
  const std::string good1 = R"({"hz": 31.1, "hz_std": 0.01, "shape": [[2, 1, 0.53, 0], [3, 1, 0.85, 0]]})";
  {
    const auto [p, r] = with("no_hz.json", R"({"modes": [)" + good1 + R"(, {"hz_std": 0.1, "shape": [[2, 1, 0.85, 0], [3, 1, -0.53, 0]]}]})");
    CHECK(r.code == 2);
    CHECK(r.err == "ssid: error: " + p + ": modes[1]: needs \"hz\" (the mode's frequency [Hz])\n");
  }
  {
    const auto [p, r] = with("negative.json", R"({"modes": [{"hz": 31.1, "hz_std": -0.1, "shape": [[2, 1, 0.53, 0], [3, 1, 0.85, 0]]}]})");
    CHECK(r.code == 2);
    CHECK(r.err == "ssid: error: " + p + ": modes[0].hz_std: expected a number >= 0, got -0.1\n");
  }
  {
    const auto [p, r] = with("node.json", R"({"modes": [{"hz": 31.1, "hz_std": 0.1, "shape": [[2, 1, 0.53, 0], [7, 1, 0.85, 0]]}]})");
    CHECK(r.code == 2);
    CHECK(r.err == "ssid: error: " + p + ": modes[0].shape[1]: test node 7: no grid with this id in the deck " +
                       deck.string() + "\n");
  }
  {
    const auto [p, r] = with("direction.json", R"({"modes": [{"hz": 31.1, "shape": [[2, 9, 0.53, 0]]}]})");
    CHECK(r.code == 2);
    CHECK(r.err == "ssid: error: " + p + ": modes[0].shape[0][1]: expected a direction 1 … 6 (X, Y, Z, RX, RY, RZ), got 9\n");
  }
  {
    const auto [p, r] = with("dofs.json", R"({"modes": [)" + good1 + R"(, {"hz": 81.4, "shape": [[2, 1, 0.85, 0]]}]})");
    CHECK(r.code == 2);
    CHECK(r.err == "ssid: error: " + p + ": modes[1].shape: has 1 entries, modes[0].shape 2 (every mode must have the "
                                         "same measured DOFs)\n");
  }
  // The same reader for diagnose.
  {
    const fs::path p = scratch("negative.json");
    const auto r = run_ssid("diagnose " + deck.string() + " " + p.string() + " -q");
    CHECK(r.code == 2);
    CHECK(r.err == "ssid: error: " + p.string() + ": modes[0].hz_std: expected a number >= 0, got -0.1\n");
  }
}

TEST_CASE("ssid diagnose: the estimated noise scales the identification's σ, not a uniform percentage",
          "[cli][diagnose][identified]") {
  // The chain's two lowest modes with exact shapes and frequencies off by +0.4 % and −0.3 %
  // (one stiffness cannot fit both: a residual to estimate the noise from), σ of 0.05 Hz
  // and 0.3 Hz (0.22 % and 0.48 %, above the floors).
  const fs::path deck = scratch("chain.bdf"), id = scratch("diagnose_id.json"), out = scratch("diagnose.json");
  std::ofstream(deck) << kChainDeck;
  const double k0 = 1e5, sigma[2] = {0.05, 0.3}, off[2] = {1.004, 0.997};
  double c[2];  // f_i(k) = c_i √k
  json modes = json::array();
  for (int j = 0; j < 2; ++j) {
    const double a = (2 * j + 1) * M_PI / 7.0;
    c[j] = 2 * std::sin(a / 2) / (2 * M_PI);
    json shape = json::array();
    for (int r = 0; r < 3; ++r) shape.push_back({r + 2, 1, std::sin((r + 1) * a), 0.0});
    modes.push_back({{"hz", off[j] * c[j] * std::sqrt(k0)}, {"hz_std", sigma[j]}, {"shape", shape}});
  }
  std::ofstream(id) << json{{"modes", modes}}.dump();
  const double prior_std = 4.5e4;  // half the distance from XINIT 1e5 to the bound 1e4
  // 1/(Σ s_i²/(ŝ σ_i)² + 1/σ_p²), s_i = ∂f_i/∂k = c_i/(2√k) at the estimate (the shapes do not move).
  auto variance = [&](double k, double scale, const double* s) {
    double info = 1 / (prior_std * prior_std);
    for (int j = 0; j < 2; ++j) info += std::pow(c[j] / (2 * std::sqrt(k)) / (scale * s[j]), 2);
    return 1 / info;
  };
  auto parameter_hypothesis = [](const json& j) {
    for (const auto& h : j["ranking"])
      if (h["kind"] == "parameter") return h;
    FAIL("no parameter hypothesis");
    return json();
  };
  for (const std::string noise : {"estimated", "given"}) {
    const auto r = run_ssid("diagnose " + deck.string() + " " + id.string() + " --noise " + noise + " --json " +
                            out.string() + " -q");
    INFO(noise << ": " << r.out << r.err);
    REQUIRE(r.code == 0);
    const json j = read_json(out);
    CHECK(j["noise"]["identified"] == true);
    const double scale = j["noise"]["frequency"]["scale"].get<double>();
    if (noise == "given") CHECK(scale == 1.0);
    else CHECK(std::abs(scale - 1) > 0.1);  // the test means something: the scale is not 1
    const json h = parameter_hypothesis(j);
    const double k = h["all_parameters"][0]["estimate"].get<double>();
    const double var = h["posterior_covariance"][0][0].get<double>();
    const double uniform[2] = {0.01 * off[0] * c[0] * std::sqrt(k0), 0.01 * off[1] * c[1] * std::sqrt(k0)};
    INFO("k = " << k << ", scale " << scale << ", posterior variance " << var << "; with the identification's σ "
                << variance(k, scale, sigma) << ", with 1 % " << variance(k, scale, uniform));
    CHECK(var == Approx(variance(k, scale, sigma)).epsilon(1e-3));
    CHECK(std::abs(var / variance(k, scale, uniform) - 1) > 0.1);
    const std::string times = estimator_text(scale);
    CHECK_THAT(r.out, Catch::Contains("\n   - noise " + std::string(noise == "given" ? "(given)" : "the data imply") +
                                      ": the assumed sigma times " + times + " (frequencies) and " + times + " (shapes)" +
                                      (noise == "given" ? "" : " (1 and 6 degrees of freedom, one scale for both)") +
                                      "\n   - assumed sigma: from the identification (per mode: its hz_std, and its "
                                      "shape_std where given, else 5 % of the RMS shape component), floored at 0.05 % "
                                      "of the frequency and 0.5 % of the RMS shape component\n"));
  }
}
