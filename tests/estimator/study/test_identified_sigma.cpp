// The identification's σ as the estimator's measurement covariance (issue 22
// item 5): identified modes (the JSON of `ssid identify modes`) read with their
// per-mode σ, which replace the study's percentages — checked on a spring chain
// whose posterior variance has a closed form.
#include <catch2/catch.hpp>
#include <cmath>
#include <complex>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <unistd.h>

#include "estimator/study/deck_study.hpp"
#include "formats/parse_error.hpp"

using namespace ssid;
using json = nlohmann::json;
namespace fs = std::filesystem;

namespace {

/// Three unit masses on springs of stiffness k (ground–2–3–4, along X), one
/// parameter KSPR designing all three: K = k K₀, so ω² = k λ₀ and the
/// frequencies' sensitivities are ∂f/∂k = f/(2k) exactly; the shapes do not
/// depend on k. (Three masses for two test modes: the estimator computes at most
/// n_a − 1 analysis modes.)
const char* const kChainDeck =
    "SOL 103\nCEND\nSPC = 1\nBEGIN BULK\n"
    "GRID,1,,0.,0.,0.\nGRID,2,,1.,0.,0.\nGRID,3,,2.,0.,0.\nGRID,4,,3.,0.,0.\n"
    "CELAS1,10,1,1,1,2,1\nCELAS1,11,1,2,1,3,1\nCELAS1,12,1,3,1,4,1\nPELAS,1,1000.\n"
    "CONM2,20,2,,1.0\nCONM2,21,3,,1.0\nCONM2,22,4,,1.0\n"
    "SPC1,1,123456,1\nSPC1,1,23456,2,3,4\n"
    "DESVAR,1,KSPR,1000.,100.,1.0E4\nDVPREL1,30,PELAS,1,K1,,,,\n,1,1.0\n"
    "ENDDATA\n";
constexpr double kStiffness = 1000.0, kMass = 1.0;

fs::path scratch() {
  const fs::path p = fs::temp_directory_path() / ("ssid_idsigma_" + std::to_string(::getpid()));
  fs::create_directories(p);
  return p;
}

/// Closed form of the fixed–free chain of n = 3 equal masses and springs:
/// λ_j = (k/m) 4 sin²((2j − 1)π / (2(2n + 1))), shape x_r = sin(r (2j − 1)π/(2n + 1));
/// the two lowest modes.
struct ChainMode {
  double hz;
  double x[3];
};
std::vector<ChainMode> chain_modes() {
  std::vector<ChainMode> out;
  for (int j = 1; j <= 2; ++j) {
    const double a = (2 * j - 1) * M_PI / 7.0;
    const double lambda = kStiffness / kMass * 4 * std::pow(std::sin(a / 2), 2);
    out.push_back({std::sqrt(lambda) / (2 * M_PI), {std::sin(a), std::sin(2 * a), std::sin(3 * a)}});
  }
  return out;
}

/// The modes as identify writes them: complex shapes (the real shape turned by
/// an arbitrary phase), with the given σ (negative: key left out).
json identified(const std::vector<double>& hz_std, const std::vector<double>& shape_std) {
  json modes = json::array();
  const auto exact = chain_modes();
  for (std::size_t i = 0; i < exact.size(); ++i) {
    const std::complex<double> turn = std::polar(0.3, 0.7 + static_cast<double>(i));
    json shape = json::array();
    for (int r = 0; r < 3; ++r) {
      const std::complex<double> v = turn * exact[i].x[r];
      shape.push_back({r + 2, 1, v.real(), v.imag()});
    }
    json m = {{"hz", exact[i].hz}, {"zeta", 0.01}, {"zeta_std", 1e-4}, {"shape", shape}, {"mpc", 1.0}};
    if (hz_std[i] >= 0) m["hz_std"] = hz_std[i];
    if (shape_std[i] >= 0) m["shape_std"] = shape_std[i];
    modes.push_back(m);
  }
  return {{"modes", modes}, {"method", "era"}};
}

struct Run {
  estimator::EstimationProblem problem;
  estimator::EstimationResult result;
};

Run estimate(const json& data, const json& study_json) {
  const fs::path dir = scratch();
  std::ofstream(dir / "chain.bdf") << kChainDeck;
  std::ofstream(dir / "chain_id.json") << data.dump(1);
  const estimator::Study study = estimator::parse_study(study_json, "s.json");
  Run r{estimator::prepare_problem(study, (dir / "chain.bdf").string(), (dir / "chain_id.json").string()), {}};
  r.result = estimator::run_problem(r.problem);
  return r;
}

/// 1 / (Σ s_i²/σ_i² + 1/σ_p²), s_i = ∂f_i/∂k = f_i/(2k): the linear posterior variance.
double closed_form_variance(const std::vector<double>& sigma_hz, double prior_std) {
  const auto exact = chain_modes();
  double info = 1.0 / (prior_std * prior_std);
  for (std::size_t i = 0; i < exact.size(); ++i) {
    const double s = exact[i].hz / (2 * kStiffness);
    info += s * s / (sigma_hz[i] * sigma_hz[i]);
  }
  return 1.0 / info;
}

}  // namespace

TEST_CASE("identified modes: complex shapes become the real modes, node/direction the test DOFs",
          "[estimator][deck_study][identified]") {
  const estimator::MeasuredData d = estimator::parse_identified_modes(identified({0.01, 0.2}, {0.003, -1}), "id.json");
  const auto exact = chain_modes();
  REQUIRE(d.modes.dofs.size() == 3);
  CHECK(d.modes.dofs[0].node == 2);
  CHECK(d.modes.dofs[2].node == 4);
  CHECK(d.modes.dofs[0].direction == 1);
  REQUIRE(d.modes.shapes.cols() == 2);
  for (int m = 0; m < 2; ++m) {
    // Parallel to the exact real shape, whatever its scale and sign.
    const auto& x = exact[static_cast<std::size_t>(m)].x;
    const Eigen::Vector3d e(x[0], x[1], x[2]);
    const Eigen::Vector3d s = d.modes.shapes.col(m);
    CHECK(std::abs(e.normalized().dot(s.normalized())) == Approx(1.0).epsilon(1e-12));
  }
  CHECK(d.modes.numbers == std::vector<int>{1, 2});
  CHECK(d.modes.frequency_std_hz == std::vector<double>{0.01, 0.2});
  CHECK(d.modes.shape_std[0] == 0.003);
  CHECK(std::isnan(d.modes.shape_std[1]));
  CHECK(d.node_keys.at(3) == "modes[0].shape[1]");
  CHECK(d.node_keys.at(4) == "modes[0].shape[2]");
}

TEST_CASE("per-mode σ of the identification give the closed-form posterior variance of the spring chain",
          "[estimator][deck_study][identified]") {
  const double prior_std = 100.0;
  const json priors = {{"KSPR", {{"std", prior_std}}}};
  const auto exact = chain_modes();

  // σ_f from the identification: 0.01 Hz on mode 1 (0.45 %), 0.2 Hz on mode 2 (3.2 %).
  const Run id = estimate(identified({0.01, 0.2}, {-1, -1}), {{"priors", priors}});
  REQUIRE(id.result.update.converged);
  CHECK(id.result.update.r(0) == Approx(kStiffness).epsilon(1e-9));  // the data are the deck's: no move
  REQUIRE(id.problem.configurations.front().test.size() == 2);
  CHECK(id.problem.configurations.front().test[0].frequency_std_hz == 0.01);
  CHECK(id.problem.configurations.front().test[1].frequency_std_hz == 0.2);
  CHECK(id.problem.configurations.front().std_from == std::vector<std::string>{"identification", "identification"});
  const double var_id = closed_form_variance({0.01, 0.2}, prior_std);
  CHECK(id.result.update.posterior_cov(0, 0) == Approx(var_id).epsilon(1e-6));

  // The study's uniform 1 %: another variance, also closed form.
  const Run pct = estimate(identified({0.01, 0.2}, {-1, -1}),
                           {{"priors", priors}, {"measurement", {{"std_from", "study"}, {"frequency_std_pct", 1.0}}}});
  CHECK(pct.problem.configurations.front().std_from == std::vector<std::string>{"study", "study"});
  const double var_pct = closed_form_variance({0.01 * exact[0].hz, 0.01 * exact[1].hz}, prior_std);
  CHECK(pct.result.update.posterior_cov(0, 0) == Approx(var_pct).epsilon(1e-6));
  CHECK(var_id < 0.5 * var_pct);  // distinct: mode 1's 0.45 % weighs more than 1 %

  // A σ of 0 (a cluster whose poles agree exactly) is floored at 0.05 % of the frequency.
  const Run zero = estimate(identified({0.0, 0.2}, {-1, -1}), {{"priors", priors}});
  CHECK(zero.problem.configurations.front().test[0].frequency_std_hz == Approx(5e-4 * exact[0].hz).epsilon(1e-14));
  CHECK(zero.result.update.posterior_cov(0, 0) ==
        Approx(closed_form_variance({5e-4 * exact[0].hz, 0.2}, prior_std)).epsilon(1e-6));
  CHECK_THAT(zero.problem.measurement_std,
             Catch::Equals("from the identification (per mode: its hz_std, and its shape_std where given, else 5 % of "
                           "the RMS shape component), floored at 0.05 % of the frequency and 0.5 % of the RMS shape "
                           "component"));
}

TEST_CASE("shape σ of the identification, floors, scales and the study's choice", "[estimator][deck_study][identified]") {
  const fs::path dir = scratch();
  std::ofstream(dir / "chain.bdf") << kChainDeck;
  std::ofstream(dir / "id.json") << identified({0.01, -1}, {0.02, 1e-6}).dump();
  const auto exact = chain_modes();
  auto prepared = [&](const json& s) {
    return estimator::prepare_problem(estimator::parse_study(s, "s.json"), (dir / "chain.bdf").string(),
                                      (dir / "id.json").string());
  };
  {
    const auto p = prepared(json::object());
    const auto& t = p.configurations.front().test;
    CHECK(t[0].frequency_std_hz == 0.01);
    CHECK(t[0].shape_std == 0.02);
    // Mode 2 carries no hz_std: the study's 1 %; its shape σ 1e-6 is floored at 0.5 %/√3.
    CHECK(t[1].frequency_std_hz == Approx(0.01 * exact[1].hz).epsilon(1e-14));
    CHECK(t[1].shape_std == Approx(0.005 / std::sqrt(3.0)).epsilon(1e-14));
    CHECK(p.configurations.front().std_from == std::vector<std::string>{"identification", "study"});
    CHECK_THAT(p.measurement_std, Catch::EndsWith("for test modes 1; the study's 1 % of each frequency, 5 % of the RMS "
                                                  "shape component for test modes 2"));
  }
  {  // What the diagnosis sets from its noise estimate: factors on the identification's σ.
    estimator::Study s = estimator::parse_study(json::object(), "s.json");
    s.identified_frequency_std_scale = 3.0;
    s.identified_shape_std_scale = 0.5;
    const auto p = estimator::prepare_problem(s, (dir / "chain.bdf").string(), (dir / "id.json").string());
    CHECK(p.configurations.front().test[0].frequency_std_hz == Approx(0.03).epsilon(1e-14));
    CHECK(p.configurations.front().test[0].shape_std == Approx(0.01).epsilon(1e-14));
  }
  {
    const auto p = prepared({{"measurement", {{"std_from", "study"}, {"shape_std_pct", 4.0}}}});
    CHECK(p.configurations.front().test[0].frequency_std_hz == Approx(0.01 * exact[0].hz).epsilon(1e-14));
    CHECK(p.configurations.front().test[0].shape_std == Approx(0.04 / std::sqrt(3.0)).epsilon(1e-14));
  }
  {
    const auto p = prepared({{"measurement", {{"frequency_std_floor_pct", 1.0}}}});  // above 0.01 Hz = 0.45 %
    CHECK(p.configurations.front().test[0].frequency_std_hz == Approx(0.01 * exact[0].hz).epsilon(1e-14));
  }
  CHECK_THROWS_WITH(estimator::parse_study(json::parse(R"({"measurement": {"std_from": "guess"}})"), "s.json"),
                    "s.json: measurement.std_from: expected one of identification, study, got \"guess\"");
  // std_from "identification" on data without σ.
  std::ofstream(dir / "f.json") << R"([3.1, 8.1])";
  CHECK_THROWS_WITH(estimator::prepare_problem(estimator::parse_study(json::parse(R"({"measurement": {"std_from": "identification"}})"), "s.json"),
                                               (dir / "chain.bdf").string(), (dir / "f.json").string()),
                    "s.json: measurement.std_from: \"identification\", but " + (dir / "f.json").string() +
                        " carries no σ of its own (the JSON of ssid identify modes does; UFF 55 and frequency lists do "
                        "not)");
}
