// `ssid identify modes`: FRFs of a 3-DOF chain written as UFF 58, modes back as JSON and
// UFF 55, compared with the chain's exact modes (dense eigen-solve); and the time histories
// of the ARMAX paper's 2-DOF system, compared with its exact modes (Eigen's eigenvalues).
#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "cli/chain_frf.hpp"
#include "cli/cli_run.hpp"
#include "estimator/identification/armax_paper.hpp"
#include "estimator/identification/chain_model.hpp"
#include "formats/uff.hpp"

namespace fs = std::filesystem;
namespace uff = ssid::formats::uff;
using cd = std::complex<double>;

namespace {

fs::path scratch(const std::string& name) { return cli_scratch("identify") / name; }

/// The chain's FRFs (chain_frf.hpp) in the scratch folder.
fs::path chain_frf_file(const ident_test::ChainModel& model, const std::string& name = "chain_frf.unv") {
  const fs::path p = scratch(name);
  write_chain_frf(model, p.string());
  return p;
}

/// `ssid identify modes ARGS --json JSON`, required to succeed: its stdout, stderr and JSON.
struct IdentifyRun {
  std::string out, err;
  nlohmann::json j;
};
IdentifyRun identify_json(const std::string& args, const fs::path& json) {
  const auto r = run_ssid("identify modes " + args + " --json " + json.string());
  INFO(r.out << r.err);
  REQUIRE(r.code == 0);
  IdentifyRun run{r.out, r.err, {}};
  std::ifstream(json) >> run.j;
  return run;
}

/// One time history as dataset 58 (function type 1, real double, evenly sampled from 0 s):
/// `ordinate` is its ordinate's specific data type (8 displacement, 13 excitation force).
uff::Function58 time_record(std::int64_t id, std::int64_t node, int direction, int ordinate,
                            const Eigen::VectorXd& samples, double dt) {
  uff::Function58 fn;
  fn.function_type = 1;
  fn.function_id = id;
  fn.response_node = node;
  fn.response_direction = direction;
  fn.reference_node = 1;  // the force's DOF, as test software marks every channel of a run
  fn.reference_direction = 1;
  fn.ordinate_type = 4;
  fn.even = true;
  fn.abscissa_min = 0;
  fn.abscissa_increment = dt;
  fn.axes[0].specific_data_type = 17;  // time
  fn.axes[1].specific_data_type = ordinate;
  for (Eigen::Index k = 0; k < samples.size(); ++k) {
    fn.x.push_back(static_cast<double>(k) * dt);
    fn.y.emplace_back(samples(k));
  }
  return fn;
}

/// The ARMAX paper's 2-DOF records (seed 1) as UFF 58 time histories: the force on mass 1
/// (node 1, +X, ordinate type 13) and the noisy displacements of masses 1 and 2 (nodes 1
/// and 2, +X, type 8).
fs::path two_dof_time_file(const armax_test::Lumped& system, double dt) {
  const armax_test::Records rec = armax_test::simulate(system, dt, {0, 1}, 1);
  uff::UffFile f;
  f.datasets.emplace_back(time_record(1, 1, 1, 13, rec.force.col(0), dt));
  f.datasets.emplace_back(time_record(2, 1, 1, 8, rec.response.col(0), dt));
  f.datasets.emplace_back(time_record(3, 2, 1, 8, rec.response.col(1), dt));
  const fs::path p = scratch("two_dof_time.unv");
  uff::write_uff(f, p.string(), uff::Precision::Extended);
  return p;
}

}  // namespace

TEST_CASE("ssid identify modes --method armax: the paper's 2-DOF modes from its time histories",
          "[cli][identify][armax]") {
  // The paper's 2-DOF case: k = k_c, Δt = 1.476649e-4 s, exact 977.47 and 1693.02 Hz. (Record 7
  // holds Δt as E13.5, 1.47665e-4 s: the frequencies read back shift by 7e-6, well inside 0.05 %.)
  const armax_test::Lumped system = armax_test::lumped_system(2, armax_test::kGround, false, false);
  const double dt = 1.476649e-4;
  const auto exact = armax_test::exact_modes(system, 0, 1);
  REQUIRE(exact.size() == 2);
  const fs::path in = two_dof_time_file(system, dt);
  const fs::path json = scratch("armax_modes.json"), out55 = scratch("armax_modes.unv");
  const IdentifyRun r = identify_json(in.string() + " --method armax --uff " + out55.string(), json);
  CHECK_THAT(r.out, Catch::StartsWith("3 time histories: 2 response(s), 1 force(s), 2048 samples every 0.000147665 s; "
                                      "ARMAX orders s = 6, m = 45 on all responses, then 12, 90 on each\n"));
  const nlohmann::json& j = r.j;
  CHECK(j["method"] == "armax");
  REQUIRE(j["modes"].size() == 2);
  for (std::size_t m = 0; m < 2; ++m) {
    const auto& mode = j["modes"][m];
    INFO("exact " << exact[m].hz << " Hz, zeta " << exact[m].zeta << "; identified " << mode.dump());
    CHECK(std::abs(mode["hz"].get<double>() - exact[m].hz) <= 5e-4 * exact[m].hz);  // the paper's 0.05 %
    CHECK(std::abs(mode["zeta"].get<double>() - exact[m].zeta) <= 0.05 * exact[m].zeta);
    // Three runs (both responses, each alone): the spread is a real standard deviation.
    CHECK(mode["runs"] == 3);
    CHECK(mode["hz_std"].get<double>() > 0);
    CHECK(mode["hz_std"].get<double>() < 5e-4 * exact[m].hz);
    CHECK(mode["zeta_std"].get<double>() > 0);
    REQUIRE(mode["shape"].size() == 2);
    const auto& a = mode["shape"][0];
    const auto& b = mode["shape"][1];
    CHECK(a[0] == 1);
    CHECK(a[1] == 1);
    CHECK(b[0] == 2);
    CHECK(b[1] == 1);
    // In phase, then out of phase (exact ratios 1 and −1; 0.03 as the estimator's test).
    const cd ratio = cd(a[2].get<double>(), a[3].get<double>()) / cd(b[2].get<double>(), b[3].get<double>());
    CHECK(std::abs(ratio - exact[m].ratio) <= 0.03);
  }
  const uff::UffFile back = uff::read_uff(out55.string());
  const auto modes55 = back.nodal_data();
  REQUIRE(modes55.size() == 2);
  for (std::size_t m = 0; m < 2; ++m)
    CHECK(modes55[m]->frequency_hz() == Approx(j["modes"][m]["hz"].get<double>()).epsilon(1e-5));
}

TEST_CASE("ssid identify modes --method armax --subsets: the order rule over pairs of responses",
          "[cli][identify][armax]") {
  // Three masses of the paper's lumped chain (k = k_c between them, k_g to ground, ends
  // k_c too; Δt as its 6-DOF cases), force on mass 1, all three displacements with 5 %
  // noise. Runs: all three at (4, 30), then the pairs {1, 2} and {2, 3} at ⌈4·3/2⌉ = 6,
  // ⌈30·3/2⌉ = 45. Exact: the state matrix's eigenvalues.
  const armax_test::Lumped system = armax_test::lumped_system(3, armax_test::kCoupling, true, false);
  const double dt = 1.51224e-4;
  const armax_test::Records rec = armax_test::simulate(system, dt, {0, 1, 2}, 3);
  uff::UffFile f;
  f.datasets.emplace_back(time_record(1, 1, 1, 13, rec.force.col(0), dt));
  for (int o = 0; o < 3; ++o) f.datasets.emplace_back(time_record(o + 2, o + 1, 1, 8, rec.response.col(o), dt));
  const fs::path in = scratch("three_dof_time.unv"), json = scratch("armax_pairs.json");
  uff::write_uff(f, in.string(), uff::Precision::Extended);
  const IdentifyRun r = identify_json(in.string() + " --method armax --subsets \"1:1,2:1;2:1,3:1\"", json);
  CHECK_THAT(r.out, Catch::Contains("ARMAX orders s = 4, m = 30 on all responses, then on 2 subset(s): {1:1,2:1} at 6, 45; "
                                    "{2:1,3:1} at 6, 45;\n"));
  const auto& runs = r.j["armax_runs"];
  REQUIRE(runs.size() == 3);
  CHECK(runs[0]["responses"] == nlohmann::json::parse("[[1, 1], [2, 1], [3, 1]]"));
  CHECK(runs[1]["responses"] == nlohmann::json::parse("[[1, 1], [2, 1]]"));
  CHECK(runs[2]["responses"] == nlohmann::json::parse("[[2, 1], [3, 1]]"));
  CHECK(runs[2]["ar_order"] == 6);
  CHECK(runs[2]["arx_order"] == 45);
  const Eigen::VectorXcd lambda = Eigen::EigenSolver<Eigen::MatrixXd>(armax_test::state_matrix(system)).eigenvalues();
  std::vector<double> exact;
  for (Eigen::Index i = 0; i < lambda.size(); ++i)
    if (lambda(i).imag() > 0) exact.push_back(std::abs(lambda(i)) / (2 * M_PI));
  std::sort(exact.begin(), exact.end());
  REQUIRE(r.j["modes"].size() == 3);
  for (std::size_t m = 0; m < 3; ++m) {
    INFO("exact " << exact[m] << " Hz, identified " << r.j["modes"][m]["hz"]);
    CHECK(std::abs(r.j["modes"][m]["hz"].get<double>() - exact[m]) <= 5e-4 * exact[m]);  // the paper's 0.05 %
    CHECK(r.j["modes"][m]["runs"] == 3);
    // The pairs share responses with the all-responses run: the shape's spread over the
    // runs is a real σ on the unit shape (measured 7e-5 … 5e-4 at 5 % noise).
    REQUIRE(r.j["modes"][m].contains("shape_std"));
    CHECK(r.j["modes"][m]["shape_std"].get<double>() > 0);
    CHECK(r.j["modes"][m]["shape_std"].get<double>() < 0.01);
  }
  // Each response alone (the default runs): mass 2 sits on the node of the middle mode,
  // so the run on response 2 cannot see it and the rule drops it.
  const IdentifyRun single = identify_json(in.string() + " --method armax", json);
  REQUIRE(single.j["modes"].size() == 2);
  CHECK(!single.j["modes"][0].contains("shape_std"));  // single responses carry no shape spread
  CHECK(std::abs(single.j["modes"][0]["hz"].get<double>() - exact[0]) <= 5e-4 * exact[0]);
  CHECK(std::abs(single.j["modes"][1]["hz"].get<double>() - exact[2]) <= 5e-4 * exact[2]);
  // Refusals: a DOF that is not a response; a subset with a DOF twice; subsets for ERA.
  auto bad = run_ssid("identify modes " + in.string() + " --method armax --subsets \"1:1,9:1\"");
  CHECK(bad.code == 2);
  CHECK_THAT(bad.err, Catch::EndsWith("--subsets: 9:1 is not a response record of the file\n"));
  bad = run_ssid("identify modes " + in.string() + " --method armax --subsets \"2:1,2:1\"");
  CHECK(bad.code == 2);
  CHECK_THAT(bad.err, Catch::EndsWith("--subsets: 2:1 twice in one subset\n"));
  bad = run_ssid("identify modes " + in.string() + " --method era --subsets \"1:1\"");
  CHECK(bad.code == 2);
  CHECK(bad.err == "ssid: error: --subsets: the order rule's runs are ARMAX's (--method armax)\n");
}

TEST_CASE("ssid identify modes --method era on time histories: H1 by Welch, then ERA", "[cli][identify]") {
  // The same 2-DOF records: 2048 samples give H1 only three Welch averages of 1024 (Hann),
  // so this checks the path (forces as references, H1's orientation, the line spacing),
  // not ERA's accuracy: the two modes within 0.1 % (measured 0.039 % and 0.041 %; a third,
  // spurious cluster near 1706 Hz survives too and is not checked).
  const armax_test::Lumped system = armax_test::lumped_system(2, armax_test::kGround, false, false);
  const double dt = 1.476649e-4;
  const auto exact = armax_test::exact_modes(system, 0, 1);
  const fs::path in = two_dof_time_file(system, dt);
  const fs::path json = scratch("era_time_modes.json");
  const auto r = run_ssid("identify modes " + in.string() + " --method era --max-order 20 --json " + json.string());
  INFO(r.out << r.err);
  REQUIRE(r.code == 0);
  CHECK_THAT(r.out, Catch::StartsWith("3 time histories: 2 response(s), 1 force(s), 2048 samples every 0.000147665 s; "
                                      "H1 by Welch (1024 samples, Hann, half overlap): 513 lines every "));
  nlohmann::json j;
  std::ifstream(json) >> j;
  for (const auto& e : exact) {
    double closest = 0;
    for (const auto& mode : j["modes"])
      if (std::abs(mode["hz"].get<double>() - e.hz) < std::abs(closest - e.hz)) closest = mode["hz"].get<double>();
    INFO("exact " << e.hz << " Hz, closest identified " << closest);
    CHECK(std::abs(closest - e.hz) <= 1e-3 * e.hz);
  }
}

namespace {

/// The largest relative errors of the identified frequencies and damping ratios, and
/// the smallest MAC of the shapes, against the chain's exact modes (poles of the state
/// matrix; real shapes, Rayleigh damping: the modes of (K, M)); `j` is `identify modes
/// --json`'s, three modes at nodes 1, 2, 3 in +X.
struct ExactErrors {
  double frequency = 0, damping = 0, mac = 1;
};
ExactErrors errors_vs_exact(const ident_test::ChainModel& model, const nlohmann::json& j) {
  std::vector<cd> poles;
  std::vector<Eigen::VectorXcd> shapes;
  model.exact(poles, shapes);
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> ges(model.K, model.M);
  ExactErrors e;
  for (std::size_t m = 0; m < 3; ++m) {
    const auto& mode = j["modes"][m];
    const double f = std::abs(poles[m]) / (2 * M_PI), z = -poles[m].real() / std::abs(poles[m]);
    e.frequency = std::max(e.frequency, std::abs(mode["hz"].get<double>() - f) / f);
    e.damping = std::max(e.damping, std::abs(mode["zeta"].get<double>() - z) / z);
    CHECK(mode["hz_std"].get<double>() >= 0);
    CHECK(mode["zeta_std"].get<double>() >= 0);
    REQUIRE(mode["shape"].size() == 3);
    Eigen::Vector3d phi;
    for (int o = 0; o < 3; ++o) {
      const auto& row = mode["shape"][static_cast<std::size_t>(o)];
      CHECK(row[0].get<int>() == o + 1);
      CHECK(row[1].get<int>() == 1);
      phi(o) = row[2].get<double>();
    }
    const Eigen::Vector3d exact = ges.eigenvectors().col(static_cast<Eigen::Index>(m));
    e.mac = std::min(e.mac, std::pow(phi.dot(exact), 2) / (phi.squaredNorm() * exact.squaredNorm()));
  }
  return e;
}

}  // namespace

TEST_CASE("ssid identify modes --method era: the chain's three modes from its FRFs", "[cli][identify]") {
  const auto model = ident_test::chain_model(true, {0});
  const fs::path in = chain_frf_file(model);
  const fs::path json = scratch("modes.json"), out55 = scratch("modes.unv");
  const auto r = run_ssid("identify modes " + in.string() + " --method era --json " + json.string() + " --uff " +
                          out55.string());
  INFO(r.err);
  REQUIRE(r.code == 0);
  CHECK_THAT(r.out, Catch::StartsWith("3 FRF(s): 3 response(s) × 1 reference(s), 2001 lines every 0.25 Hz; ERA orders 2…40\n"));
  nlohmann::json j;
  std::ifstream(json) >> j;
  REQUIRE(j["modes"].size() == 3);
  const ExactErrors e = errors_vs_exact(model, j);
  INFO("vs exact: frequency " << e.frequency << ", damping " << e.damping << ", MAC " << e.mac);
  CHECK(e.frequency < 1e-6);  // measured 5e-8
  CHECK(e.damping < 1e-4);  // measured 9e-7
  CHECK(e.mac > 0.9999);
  // UFF 55 back: three real normal modes at the same frequencies.
  const uff::UffFile back = uff::read_uff(out55.string());
  const auto modes55 = back.nodal_data();
  REQUIRE(modes55.size() == 3);
  for (std::size_t m = 0; m < 3; ++m) {
    CHECK(modes55[m]->is_normal_mode());
    CHECK(modes55[m]->frequency_hz() == Approx(j["modes"][m]["hz"].get<double>()).epsilon(1e-5));
  }
}

TEST_CASE("ssid identify modes --method era on free decays: the chain's three modes", "[cli][identify]") {
  // The chain released with a velocity at DOF 0 (its impulse response, sampled exactly by the
  // matrix exponential: chain_model.hpp), displacements of the three masses for 4 s every
  // 2 ms, no force record (reference fields 0): free decays. Exact: the state matrix's poles.
  const auto model = ident_test::chain_model(true, {0});
  const double dt = 0.002;
  auto decay_file = [&](const std::string& name, double noise) {
    auto Y = model.markov(dt, 2048);
    if (noise > 0) Y = ident_test::with_noise(Y, noise, 5);
    uff::UffFile f;
    for (int o = 0; o < 3; ++o) {
      Eigen::VectorXd y(2048);
      for (Eigen::Index k = 0; k < 2048; ++k) y(k) = Y[static_cast<std::size_t>(k)](o, 0);
      uff::Function58 fn = time_record(o + 1, o + 1, 1, 8, y, dt);
      fn.reference_node = 0;
      fn.reference_direction = 0;
      f.datasets.emplace_back(fn);
    }
    const fs::path p = scratch(name);
    uff::write_uff(f, p.string(), uff::Precision::Extended);
    return p;
  };
  const fs::path json = scratch("decay_modes.json"), svg = scratch("decay.svg");
  // Noise-free records have a Hankel matrix of numerical rank 6: no order above the
  // model's own, so no mode recurs across orders; the run says why.
  auto r = run_ssid("identify modes " + decay_file("decay_exact.unv", 0).string() + " --method era");
  REQUIRE(r.code == 0);
  CHECK_THAT(r.out, Catch::Contains("(no mode stable across the orders)"));
  CHECK_THAT(r.err, Catch::Contains("note: the records' Hankel matrix has numerical rank 6"));
  // 0.5 % noise on every channel (of its RMS): the three modes, close to exact.
  IdentifyRun decay = identify_json(decay_file("decay.unv", 0.005).string() + " --method era --svg " + svg.string(), json);
  CHECK_THAT(decay.out, Catch::StartsWith("3 time histories: 3 response(s), no force: free decays, 2048 samples every "
                                          "0.002 s; ERA orders 2…40\n"));
  nlohmann::json j = decay.j;
  REQUIRE(j["modes"].size() == 3);
  ExactErrors e = errors_vs_exact(model, j);
  INFO("0.5 % noise vs exact: frequency " << e.frequency << ", damping " << e.damping << ", MAC " << e.mac);
  CHECK(e.frequency < 1e-3);
  CHECK(e.damping < 0.05);
  CHECK(e.mac > 0.9999);
  // No FRF: no FRF fit; the diagram's curve is the decays' spectra, peaking at the modes.
  CHECK(!j.contains("frf_fit"));
  const auto& bg = j["stabilisation"]["frf_sum"];
  CHECK(bg["of"] == "free-decay spectra");
  CHECK(bg["hz"].size() == 1025);
  {
    const auto hz = bg["hz"].get<std::vector<double>>();
    const auto mag = bg["magnitude"].get<std::vector<double>>();
    const auto peak = std::max_element(mag.begin(), mag.end()) - mag.begin();
    CHECK(std::abs(hz[static_cast<std::size_t>(peak)] - j["modes"][0]["hz"].get<double>()) <= hz[1]);
  }
  CHECK(cli_slurp(svg).find("<polyline class=\"frf-sum\"") != std::string::npos);

  // 2 % noise on every channel: still the three modes, close to exact.
  j = identify_json(decay_file("decay_noisy.unv", 0.02).string() + " --method era", json).j;
  REQUIRE(j["modes"].size() == 3);
  e = errors_vs_exact(model, j);
  INFO("2 % noise vs exact: frequency " << e.frequency << ", damping " << e.damping << ", MAC " << e.mac);
  CHECK(e.frequency < 1e-3);
  CHECK(e.damping < 0.1);
  CHECK(e.mac > 0.999);
  // pLSCF needs FRFs: free decays are refused with the way out.
  r = run_ssid("identify modes " + scratch("decay.unv").string() + " --method plscf");
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Catch::EndsWith("free decays, which --method plscf cannot use without the forces; --method era "
                                    "identifies free decays\n"));
}

TEST_CASE("ssid identify modes --method plscf: the chain's three modes from FRFs of two references",
          "[cli][identify][plscf]") {
  // Forces at DOFs 0 and 2: 3 responses × 2 references; the band 0.25 … 60 Hz holds the three
  // modes (7.1, 18.0, 31.6 Hz). Exact: the dense eigen-solve of the state matrix; real shapes
  // (Rayleigh damping): the mass-normalised modes of (K, M).
  const auto model = ident_test::chain_model(true, {0, 2});
  const fs::path in = chain_frf_file(model, "chain_frf_2ref.unv");
  const auto table = run_ssid("identify modes " + in.string() + " --method plscf --max-hz 60");
  INFO(table.out << table.err);
  REQUIRE(table.code == 0);
  CHECK_THAT(table.out, Catch::StartsWith("6 FRF(s): 3 response(s) × 2 reference(s), 2001 lines every 0.25 Hz; "
                                          "pLSCF orders 1…40\nmode   frequency (Hz)      ± (Hz)   damping (%)     ± (%)"
                                          "     MPC     MPD  orders\n"));
  CHECK_THAT(table.out, Catch::Contains("\nFRFs of the identified modes (LSFD with residuals, 0.25…60 Hz): FRAC mean "));
  const fs::path out55 = scratch("plscf_modes.unv");
  const auto r = run_ssid("identify modes " + in.string() + " --method plscf --max-hz 60 --json - --uff " +
                          out55.string());
  INFO(r.err);
  REQUIRE(r.code == 0);
  const nlohmann::json j = nlohmann::json::parse(r.out);  // stdout holds the JSON alone
  CHECK(j["method"] == "plscf");
  // Every FRF (3 responses × 2 references) against the identified modes' FRF; without
  // --report the JSON holds each one's FRAC, not the curves.
  REQUIRE(j["frf_fit"]["records"].size() == 6);
  CHECK(!j["frf_fit"].contains("hz"));
  CHECK(j["frf_fit"]["fit_error"].get<double>() == j["lsfd_fit_error"].get<double>());
  for (const auto& rec : j["frf_fit"]["records"]) {
    CHECK(rec["frac"].get<double>() > 0.99999);
    CHECK(!rec.contains("measured"));
  }
  CHECK(j["lsfd_fit_error"].get<double>() < 1e-6);
  REQUIRE(j["modes"].size() == 3);
  for (const auto& mode : j["modes"]) {
    CHECK(mode["mpc"].get<double>() > 0.9999);
    CHECK(mode["mpd"].get<double>() < 1.0);
    CHECK(mode["orders"].get<int>() >= 20);
  }
  const ExactErrors e = errors_vs_exact(model, j);
  INFO("vs exact: frequency " << e.frequency << ", damping " << e.damping << ", MAC " << e.mac);
  CHECK(e.frequency < 1e-8);  // measured 3.1e-10
  CHECK(e.damping < 1e-6);  // measured 9.5e-9
  CHECK(e.mac > 0.9999);
  const uff::UffFile back = uff::read_uff(out55.string());
  const auto modes55 = back.nodal_data();
  REQUIRE(modes55.size() == 3);
  for (std::size_t m = 0; m < 3; ++m)
    CHECK(modes55[m]->frequency_hz() == Approx(j["modes"][m]["hz"].get<double>()).epsilon(1e-5));
}

TEST_CASE("ssid identify modes --method plscf on time histories: H1 by Welch, then pLSCF", "[cli][identify][plscf]") {
  // The ARMAX paper's 2-DOF records as for ERA above: this checks the path (H1 lines into
  // pLSCF), the two modes within 0.1 %.
  const armax_test::Lumped system = armax_test::lumped_system(2, armax_test::kGround, false, false);
  const double dt = 1.476649e-4;
  const auto exact = armax_test::exact_modes(system, 0, 1);
  const fs::path in = two_dof_time_file(system, dt);
  const auto r = run_ssid("identify modes " + in.string() + " --method plscf --max-order 20 --json -");
  INFO(r.out << r.err);
  REQUIRE(r.code == 0);
  const nlohmann::json j = nlohmann::json::parse(r.out);
  for (const auto& e : exact) {
    double closest = 0;
    for (const auto& mode : j["modes"])
      if (std::abs(mode["hz"].get<double>() - e.hz) < std::abs(closest - e.hz)) closest = mode["hz"].get<double>();
    INFO("exact " << e.hz << " Hz, closest identified " << closest);
    CHECK(std::abs(closest - e.hz) <= 1e-3 * e.hz);
  }
}

TEST_CASE("ssid identify: bad input exits 2 with the cause", "[cli][identify]") {
  const auto model = ident_test::chain_model(true, {0});
  const fs::path in = chain_frf_file(model);
  const auto m = run_ssid("identify modes " + in.string() + " --method frobnicate");
  CHECK(m.code == 2);
  CHECK(m.err == "ssid: error: --method: expected armax, era or plscf, got \"frobnicate\"\n");
  const auto p = run_ssid("identify modes " + in.string() + " --method plscf --max-order 0");
  CHECK(p.code == 2);
  CHECK(p.err == "ssid: error: --max-order: expected an order ≥ 1, got 0\n");
  // The band holds fewer lines (0.25 … 10 Hz: 40) than the order needs.
  const auto b = run_ssid("identify modes " + in.string() + " --method plscf --max-hz 10 --max-order 40");
  CHECK(b.code == 2);
  CHECK(b.err == "ssid: error: pLSCF: 40 lines in the band 0 … 10 Hz are too few for model order 40 (needs more "
                 "than 41)\n");
  const auto a = run_ssid("identify modes " + in.string() + " --method armax");
  CHECK(a.code == 2);
  CHECK(a.err == "ssid: error: " + in.string() +
                     ": --method armax needs time histories (dataset 58, function type 1); the file has FRFs only\n");
  const auto o = run_ssid("identify modes " + in.string() + " --max-order 7");
  CHECK(o.code == 2);
  CHECK(o.err == "ssid: error: --max-order: expected an even number ≥ 2, got 7\n");
  // A file without FRFs: only a mode (dataset 55).
  uff::UffFile f;
  f.datasets.emplace_back(uff::NodalData55::normal_mode(1, 10.0, {1}, Eigen::MatrixXd::Ones(1, 3)));
  const fs::path none = scratch("no_frf.unv");
  uff::write_uff(f, none.string());
  const auto n = run_ssid("identify modes " + none.string());
  CHECK(n.code == 2);
  CHECK(n.err == "ssid: error: " + none.string() +
                     ": no frequency response functions or time histories (dataset 58, function type 4 or 1)\n");
  const auto u = run_ssid("identify frobnicate");
  CHECK(u.code == 2);
  CHECK_THAT(u.err, Catch::StartsWith("ssid identify: unknown subcommand 'frobnicate'\n"));
  const auto h = run_ssid("identify --help");
  CHECK(h.code == 0);
  CHECK_THAT(h.out, Catch::StartsWith("usage: ssid identify <modes|frf|check> ...\n"));
}

TEST_CASE("ssid identify: time histories it cannot use exit 2 with the cause", "[cli][identify]") {
  const Eigen::VectorXd samples = Eigen::VectorXd::LinSpaced(64, 0.0, 1.0);
  const auto write = [](const std::string& name, const std::vector<uff::Function58>& records) {
    uff::UffFile f;
    for (const auto& r : records) f.datasets.emplace_back(r);
    const fs::path p = scratch(name);
    uff::write_uff(f, p.string(), uff::Precision::Extended);
    return p;
  };
  // No record typed as a force, and none its own reference: no input to identify from.
  const fs::path no_force =
      write("no_force.unv", {time_record(1, 2, 1, 8, samples, 1e-3), time_record(2, 3, 1, 8, samples, 1e-3)});
  const auto f = run_ssid("identify modes " + no_force.string() + " --method armax");
  CHECK(f.code == 2);
  CHECK(f.err == "ssid: error: " + no_force.string() +
                     ": no force record among the time histories (expected dataset 58 of ordinate type 13, excitation "
                     "force, or one whose response DOF is its reference DOF): free decays, which --method armax cannot "
                     "use without the forces; --method era identifies free decays\n");
  // Records sampled differently: located at the second record.
  const fs::path mixed = write("mixed_dt.unv", {time_record(1, 1, 1, 13, samples, 1e-3),
                                                time_record(2, 2, 1, 8, samples, 2e-3)});
  const auto d = run_ssid("identify modes " + mixed.string() + " --method armax");
  CHECK(d.code == 2);
  CHECK(d.err == "ssid: error: " + mixed.string() +
                     ":32: dataset 58: 64 samples every 0.002 s (expected 64 every 0.001 s as at " + mixed.string() +
                     ":2)\n");
  // One response: the order rule has nothing to compare.
  const fs::path one = write("one_response.unv", {time_record(1, 1, 1, 13, samples, 1e-3),
                                                  time_record(2, 2, 1, 8, samples, 1e-3)});
  const auto o = run_ssid("identify modes " + one.string() + " --method armax");
  CHECK(o.code == 2);
  CHECK(o.err == "ssid: error: " + one.string() +
                     ": --method armax needs at least two response records (the order rule compares the "
                     "identification from all of them with each one's)\n");
  // Two responses but 64 samples: too few for the prior ARX model; the file is named.
  const fs::path short_records =
      write("short.unv", {time_record(1, 1, 1, 13, samples, 1e-3), time_record(2, 2, 1, 8, samples, 1e-3),
                          time_record(3, 3, 1, 8, samples, 1e-3)});
  const auto s = run_ssid("identify modes " + short_records.string() + " --method armax");
  CHECK(s.code == 2);
  CHECK(s.err == "ssid: error: " + short_records.string() +
                     ": ARMAX: 64 samples are too few for a prior ARX model of order 45 (136 unknowns per output; at "
                     "least twice as many equations are required)\n");
  // ERA on time data shorter than a Welch segment.
  const auto e = run_ssid("identify modes " + one.string() + " --method era");
  CHECK(e.code == 2);
  CHECK(e.err == "ssid: error: " + one.string() +
                     ": 64 samples per record, fewer than one Welch segment of 1024 (--segment)\n");
}
