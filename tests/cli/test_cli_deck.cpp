#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>
#include <unistd.h>

#include "cli_run.hpp"

namespace fs = std::filesystem;

namespace {
fs::path scratch() { return cli_scratch("deck"); }
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
  CHECK_THAT(r.out, Catch::Contains("254 bulk data cards in 30 file(s)"));
  auto j = nlohmann::json::parse(cli_slurp(json));
  CHECK(j["files"].size() == 30);
  CHECK(j["cards"]["GRID"] == 108);
  CHECK(j["unsupported"]["FORCE"] == 53);
  CHECK(j["typed"]["GRID"] == 108);
  CHECK(j["typed"]["PBAR"] == 44);
  CHECK(j["typed"].count("FORCE") == 0);
  CHECK(j["problems"].empty());
}

TEST_CASE("ssid deck summary: typed counts of every card family, warnings do not fail", "[cli]") {
  const fs::path dir = scratch();
  for (const char* family : {"elements", "scalar", "coord", "constraints"}) {
    INFO(family);
    const fs::path json = dir / (std::string(family) + ".json");
    auto r = run_ssid("deck summary " + std::string(SSID_SOURCE_DIR) + "/tests/data/cards/" + family + ".bdf --json " +
                      json.string());
    CHECK(r.code == 0);
    CHECK_THAT(r.out, Catch::Contains("(typed)"));
    CHECK_THAT(r.out, Catch::Contains("kept verbatim (no typed parser): 0 card(s)"));
    auto j = nlohmann::json::parse(cli_slurp(json));
    CHECK(j["unsupported"].empty());
    CHECK(j["typed"] == j["cards"]);
  }
  auto j = nlohmann::json::parse(cli_slurp(dir / "elements.json"));
  CHECK(j["typed"]["MAT1"] == 3);
  CHECK(j["typed"]["CBAR"] == 4);
  CHECK(j["typed"]["PBEAML"] == 1);
  CHECK(j["problems"].empty());  // PBARL 23 CHAN is sectioned (the full PBARL list)
  // A warning (a section type outside the list) does not fail the summary.
  std::ofstream(dir / "warn.bdf") << "MAT1    1       2.+11           .3\n"
                                     "PBARL   2       1               HAT9\n        1.      1.      .1      .2\n";
  auto w = run_ssid("deck summary " + (dir / "warn.bdf").string());
  CHECK(w.code == 0);
  CHECK_THAT(w.out + w.err, Catch::Contains("warning: PBARL 2: TYPE HAT9 is not a section type"));
  auto c = nlohmann::json::parse(cli_slurp(dir / "constraints.json"));
  CHECK(c["typed"]["RBE3"] == 1);
  CHECK(c["typed"]["DVPREL1"] == 2);
  CHECK(c["typed"]["SPC1"] == 2);
}

TEST_CASE("ssid deck summary: resolve problems, all at once, on stderr and in JSON; exit 2", "[cli][errors]") {
  const fs::path dir = scratch();
  std::ofstream(dir / "refs.bdf") << "GRID    1               0.      0.      0.\n"
                                     "PBAR    3       1       1.\n"
                                     "CROD    10      3       1       12\n"
                                     "CROD    10      3       1       12\n";
  const fs::path json = dir / "refs.json";
  auto r = run_ssid("deck summary " + (dir / "refs.bdf").string() + " --json " + json.string());
  CHECK(r.code == 2);
  CHECK_THAT(r.out, Catch::Contains("problems: 6 (6 error(s), 0 warning(s)"));
  CHECK_THAT(r.err, Catch::Contains("refs.bdf:4: duplicate element 10 (CROD; first defined by CROD at"));
  CHECK_THAT(r.err, Catch::Contains("refs.bdf:3: GRID 12 required by CROD 10 does not exist"));
  CHECK_THAT(r.err, Catch::Contains("refs.bdf:3: CROD 10 refers to PID 3, which is a PBAR, expected PROD"));
  CHECK_THAT(r.err, Catch::Contains("refs.bdf:2: MAT1 1 required by PBAR 3 does not exist"));
  auto j = nlohmann::json::parse(cli_slurp(json));
  CHECK(j["problems"].size() == 6);
}

TEST_CASE("ssid deck: bad input exits 2 with file:line on stderr and no result on stdout", "[cli][errors]") {
  const fs::path dir = scratch();
  std::ofstream(dir / "bad.bdf") << "GRID    1\nINCLUDE 'missing.bdf'\n";
  auto r = run_ssid("deck summary " + (dir / "bad.bdf").string());
  CHECK(r.code == 2);
  CHECK(r.out.empty());
  CHECK_THAT(r.err, Catch::Contains("bad.bdf:2") && Catch::Contains("missing.bdf"));

  std::ofstream(dir / "field.bdf") << "$ comment\nCROD    10      1       1.5     2\n";
  auto f = run_ssid("deck summary " + (dir / "field.bdf").string());
  CHECK(f.code == 2);
  CHECK_THAT(f.err, Catch::Contains("field.bdf:2: CROD 10 field 4 (G1): expected integer, got \"1.5\""));

  auto w = run_ssid("deck write " + (dir / "nope.bdf").string() + " -o " + (dir / "o.bdf").string());
  CHECK(w.code == 2);
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
