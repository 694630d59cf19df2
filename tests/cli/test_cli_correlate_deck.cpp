// ssid correlate DECK TEST.unv: the deck is solved and its modes sampled at the
// grids the test nodes map to; checked with synthetic tests of a clamped space
// frame (samples/frame.bdf, 16 grids, 72 a-set DOFs).
#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>
#include <unistd.h>

#include "cli_run.hpp"

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
