#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>
#include <unistd.h>

#include "cli_run.hpp"

namespace fs = std::filesystem;

namespace {
fs::path scratch() {
  fs::path p = fs::temp_directory_path() / ("ssid_cli_deck_" + std::to_string(::getpid()));
  fs::create_directories(p);
  return p;
}
}  // namespace

TEST_CASE("ssid --help lists the commands; each command has --help", "[cli]") {
  auto r = run_ssid("--help");
  CHECK(r.code == 0);
  CHECK_THAT(r.out, Catch::Contains("deck"));
  auto d = run_ssid("deck summary --help");
  CHECK(d.code == 0);
  CHECK_THAT(d.out, Catch::Contains("--json"));
  auto bad = run_ssid("nosuchcommand");
  CHECK(bad.code == 2);
}

TEST_CASE("ssid deck summary: counts, verbatim cards, JSON", "[cli]") {
  const fs::path dir = scratch();
  const fs::path json = dir / "s.json";
  auto r = run_ssid("deck summary " + std::string(SSID_SOURCE_DIR) + "/tests/data/deck/nested/main.bdf --json " + json.string());
  CHECK(r.code == 0);
  CHECK_THAT(r.out, Catch::Contains("252 bulk data cards in 30 file(s)"));
  auto j = nlohmann::json::parse(cli_slurp(json));
  CHECK(j["files"].size() == 30);
  CHECK(j["cards"]["GRID"] == 108);
  CHECK(j["unsupported"]["FORCE"] == 53);
  CHECK(j["problems"].empty());
}

TEST_CASE("ssid deck: bad input exits 1 with file:line on stderr and no result on stdout", "[cli][errors]") {
  const fs::path dir = scratch();
  std::ofstream(dir / "bad.bdf") << "GRID    1\nINCLUDE 'missing.bdf'\n";
  auto r = run_ssid("deck summary " + (dir / "bad.bdf").string());
  CHECK(r.code == 1);
  CHECK(r.out.empty());
  CHECK_THAT(r.err, Catch::Contains("bad.bdf:2") && Catch::Contains("missing.bdf"));

  std::ofstream(dir / "field.bdf") << "$ comment\nCROD    10      1       1.5     2\n";
  auto f = run_ssid("deck summary " + (dir / "field.bdf").string());
  CHECK(f.code == 1);
  CHECK_THAT(f.err, Catch::Contains("field.bdf:2: CROD 10 field 4 (G1): expected integer, got \"1.5\""));

  auto w = run_ssid("deck write " + (dir / "nope.bdf").string() + " -o " + (dir / "o.bdf").string());
  CHECK(w.code == 1);
  CHECK(w.out.empty());
  CHECK_THAT(w.err, Catch::Contains("nope.bdf") && Catch::Contains("not found"));
}

TEST_CASE("ssid deck write round-trips the nested deck", "[cli]") {
  const fs::path dir = scratch() / "rt";
  fs::remove_all(dir);
  auto r = run_ssid("deck write " + std::string(SSID_SOURCE_DIR) + "/tests/data/deck/nested/main.bdf -o " + (dir / "main.bdf").string());
  CHECK(r.code == 0);
  CHECK(cli_slurp(dir / "main.bdf") == cli_slurp(fs::path(SSID_SOURCE_DIR) / "tests/data/deck/nested/main.bdf"));
  CHECK(cli_slurp(dir / "mesh/sub/part03.bdf") == cli_slurp(fs::path(SSID_SOURCE_DIR) / "tests/data/deck/nested/mesh/sub/part03.bdf"));
}
