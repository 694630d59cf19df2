// ssid correlate DECK TEST.unv: the deck is solved and its modes sampled at the
// grids the test nodes map to; checked with synthetic tests of a clamped space
// frame (samples/frame.bdf, 16 grids, 72 a-set DOFs).
#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <unistd.h>

#include "cli_run.hpp"
#include "translators/operator_set.hpp"

namespace fs = std::filesystem;

namespace {
fs::path scratch() { return cli_scratch("corr_deck"); }
const std::string kDeck = std::string(SSID_SOURCE_DIR) + "/samples/frame.bdf";
}  // namespace

TEST_CASE("ssid correlate DECK: noise-free synthetic test pairs every mode with itself", "[cli][correlate][deck]") {
  const fs::path dir = scratch();
  const fs::path test = dir / "clean.unv";
  auto m = run_ssid("modes " + kDeck + " --nmodes 12 --uff " + test.string() + " --json -");
  INFO(m.err);
  REQUIRE(m.code == 0);
  const auto modes = nlohmann::json::parse(m.out)["modes"];
  auto r = run_ssid("correlate " + kDeck + " " + test.string() + " --nmodes 12 --json -");
  INFO(r.err);
  REQUIRE(r.code == 0);
  auto j = nlohmann::json::parse(r.out);
  CHECK(j["mapping"]["mapped"] == 16);
  CHECK(j["dofs"] == 48);
  REQUIRE(j["pairs"].size() == 12);
  for (const auto& p : j["pairs"]) {
    CHECK(p["fe_mode"] == p["test_mode"]);
    CHECK(p["accepted"] == true);
    CHECK(p["mac"].get<double>() > 1 - 1e-9);
    CHECK(std::abs(p["error_pct"].get<double>()) < 1e-9);
    const int k = p["fe_mode"].get<int>() - 1;
    CHECK(p["fe_hz"].get<double>() == Approx(modes[k]["cycles"].get<double>()).epsilon(1e-12));
  }
  CHECK(j["unpaired_fe"].empty());
  CHECK(j["unpaired_test"].empty());
}

TEST_CASE("ssid correlate DECK: noisy test at a sensor subset, mapped by position", "[cli][correlate][deck]") {
  const fs::path dir = scratch();
  const fs::path test = dir / "noisy.unv";
  auto m = run_ssid("modes " + kDeck + " --nmodes 8 --uff " + test.string() +
                    " --sensors 11:34 --noise-freq 0.5 --noise-shape 2 --seed 5 --uff-precision standard");
  INFO(m.err);
  REQUIRE(m.code == 0);
  auto r = run_ssid("correlate " + kDeck + " " + test.string() + " --nmodes 10 --map position --tol 1e-3 --json -");
  INFO(r.err);
  REQUIRE(r.code == 0);
  auto j = nlohmann::json::parse(r.out);
  CHECK(j["mapping"]["mapped"] == 12);
  CHECK(j["dofs"] == 36);
  std::size_t accepted = 0;
  for (const auto& p : j["pairs"]) {
    accepted += p["accepted"].get<bool>();
    if (p["accepted"].get<bool>()) {
      CHECK(p["mac"].get<double>() > 0.9);
      CHECK(std::abs(p["error_pct"].get<double>()) < 2.5);  // 5 sigma of 0.5 %
    }
  }
  CHECK(accepted >= 7);
  // A text table too, and the two-UFF form still works.
  auto t = run_ssid("correlate " + kDeck + " " + test.string() + " --nmodes 10");
  CHECK(t.code == 0);
  CHECK_THAT(t.out, Catch::Contains("accepted pairs"));
  auto u = run_ssid("correlate " + test.string() + " " + test.string() + " --json -");
  REQUIRE(u.code == 0);
  CHECK(nlohmann::json::parse(u.out)["pairs"].size() == 8);
  auto bad = run_ssid("correlate " + test.string() + " " + test.string() + " --nmodes 3");
  CHECK(bad.code == 2);
}

TEST_CASE("ssid correlate --tam guyan,irs: Guyan's cross-orthogonality is a dense static condensation's",
          "[cli][correlate][deck]") {
  // The rod model's own 12 modes measured at 12 of its 80 balls (36 DOFs), against the
  // deck. Reference: K and M from `ssid assemble`, condensed here by dense algebra,
  // M_G = Tᵀ M T with T = [I; −K_oo⁻¹ K_oa], and |X| = |φ_iᵀ M_G φ_k| normalised, with
  // the modes of a dense solve of (K, M). Modes are unique up to sign only where their
  // frequency is simple: entries of modes within 1e-6 of another are not compared.
  const std::string rod = (fs::path(SSID_SOURCE_DIR) / "samples" / "mpi_rod.bdf").string();
  const fs::path dir = scratch();
  const fs::path own = dir / "rod_own.unv", ops = dir / "rod_ops";
  const std::vector<long> balls{1, 3, 5, 7, 9, 11, 13, 15, 17, 19, 21, 23};
  std::string list;
  for (long b : balls) list += (list.empty() ? "" : ",") + std::to_string(b);
  REQUIRE(run_ssid("modes " + rod + " --nmodes 12 --uff " + own.string() + " --sensors " + list).code == 0);
  auto r = run_ssid("correlate " + rod + " " + own.string() + " --nmodes 12 --tam guyan,irs --json -");
  INFO(r.err);
  REQUIRE(r.code == 0);
  const auto j = nlohmann::json::parse(r.out);
  REQUIRE(j["dofs"] == 36);
  REQUIRE(run_ssid("assemble " + rod + " -o " + ops.string() + " --no-derivatives").code == 0);
  const auto set = ssid::translators::read_operator_set((ops / "manifest.json").string());
  const Eigen::MatrixXd K(set.K), M(set.M);
  std::vector<Eigen::Index> a, o;
  for (std::size_t i = 0; i < set.dofs.size(); ++i)
    (std::find(balls.begin(), balls.end(), set.dofs[i].point) != balls.end() && set.dofs[i].component <= 3 ? a : o)
        .push_back(static_cast<Eigen::Index>(i));
  REQUIRE(a.size() == 36);
  const auto n = K.rows();
  Eigen::MatrixXd T = Eigen::MatrixXd::Zero(n, 36);
  Eigen::MatrixXd Koo(o.size(), o.size()), Koa(o.size(), 36);
  for (std::size_t p = 0; p < o.size(); ++p) {
    for (std::size_t q = 0; q < o.size(); ++q) Koo(p, q) = K(o[p], o[q]);
    for (std::size_t q = 0; q < 36; ++q) Koa(p, q) = K(o[p], a[q]);
  }
  const Eigen::MatrixXd Toa = -Koo.ldlt().solve(Koa);
  for (std::size_t q = 0; q < 36; ++q) T(a[q], q) = 1;
  for (std::size_t p = 0; p < o.size(); ++p) T.row(o[p]) = Toa.row(p);
  const Eigen::MatrixXd Mg = T.transpose() * M * T;
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(K, M);
  Eigen::MatrixXd Pa(36, 12);
  for (std::size_t q = 0; q < 36; ++q) Pa.row(q) = es.eigenvectors().row(a[q]).head(12);
  const Eigen::MatrixXd G = Pa.transpose() * Mg * Pa;
  const Eigen::VectorXd lam = es.eigenvalues().head(12);
  auto simple = [&](int i) {
    for (int k = 0; k < 12; ++k)
      if (k != i && std::abs(lam(k) - lam(i)) < 1e-6 * lam(i)) return false;
    return true;
  };
  const auto& x = j["cross_orthogonality_tam"]["guyan"];
  REQUIRE(!x.contains("unavailable"));
  REQUIRE(x["fe_modes"].size() == 12);
  int compared = 0;
  for (int i = 0; i < 12; ++i)
    for (int k = 0; k < 12; ++k) {
      if (!simple(i) || !simple(k)) continue;
      const double want = std::abs(G(i, k)) / std::sqrt(G(i, i) * G(k, k));
      INFO("modes " << i + 1 << ", " << k + 1);
      CHECK(x["matrix"][static_cast<std::size_t>(i)][static_cast<std::size_t>(k)].get<double>() ==
            Approx(want).margin(2e-4));  // the test shapes went through UFF 55's E13.5
      ++compared;
    }
  CHECK(compared >= 100);
  // Guyan is not exact here: some off-diagonal terms are far from 0, unlike SEREP's.
  double off = 0;
  for (int i = 0; i < 12; ++i)
    for (int k = 0; k < 12; ++k)
      if (i != k) off = std::max(off, x["matrix"][static_cast<std::size_t>(i)][static_cast<std::size_t>(k)].get<double>());
  CHECK(off > 0.05);
  REQUIRE(!j["cross_orthogonality_tam"]["irs"].contains("unavailable"));

  // Every DOF measured: nothing is condensed, both TAMs are the full mass, X = I.
  const fs::path all = dir / "rod_all.unv";
  REQUIRE(run_ssid("modes " + rod + " --nmodes 12 --uff " + all.string()).code == 0);
  r = run_ssid("correlate " + rod + " " + all.string() + " --nmodes 12 --tam guyan,irs --json -");
  REQUIRE(r.code == 0);
  const auto full = nlohmann::json::parse(r.out);
  REQUIRE(full["dofs"] == 240);
  for (const char* tam : {"guyan", "irs"}) {
    const auto& xf = full["cross_orthogonality_tam"][tam];
    REQUIRE(!xf.contains("unavailable"));
    for (std::size_t i = 0; i < 12; ++i)
      for (std::size_t k = 0; k < 12; ++k)
        CHECK(xf["matrix"][i][k].get<double>() == Approx(i == k ? 1.0 : 0.0).margin(1e-4));
  }
  // The report draws each TAM's matrix beside SEREP's, with the JSON's values.
  const fs::path html = dir / "tam.html";
  r = run_ssid("correlate " + rod + " " + own.string() + " --nmodes 12 --tam guyan,irs --report " + html.string());
  REQUIRE(r.code == 0);
  const std::string page = cli_slurp(html);
  for (const char* id : {"fig-xor\"", "fig-xor-guyan\"", "fig-xor-irs\""})
    CHECK(page.find(std::string("<figure id=\"") + id) != std::string::npos);
  CHECK(page.find("M_r: Guyan (static condensation") != std::string::npos);
  // Refusals: an unknown TAM; a TAM without a deck.
  r = run_ssid("correlate " + rod + " " + own.string() + " --tam serep");
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Catch::Contains("--tam: expected guyan and/or irs (comma-separated), got \"serep\""));
  r = run_ssid("correlate " + own.string() + " " + own.string() + " --tam guyan");
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Catch::Contains("--tam needs the deck's stiffness and mass"));
}
