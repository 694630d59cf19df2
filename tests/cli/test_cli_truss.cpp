#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>
#include <unistd.h>

#include "cli_run.hpp"

namespace fs = std::filesystem;

namespace {
fs::path scratch() { return cli_scratch("truss"); }
}  // namespace

TEST_CASE("ssid truss list-configs names the report's configurations", "[cli][truss]") {
  auto r = run_ssid("truss list-configs");
  CHECK(r.code == 0);
  for (const char* name : {"bare", "metrology_tip_mass", "optics_tip_mass", "tower_diagonal_1", "tower_diagonal_2",
                           "strut_mass", "long_bnut", "massless_springs", "surge_springs", "component1", "component7"})
    CHECK_THAT(r.out, Catch::Contains(name));
  auto j = run_ssid("truss list-configs --json -");
  CHECK(j.code == 0);
  CHECK(nlohmann::json::parse(j.out).size() == 17);
}

TEST_CASE("ssid truss mpi writes a deck that ssid deck reads with no problems; JSON has counts and parameters", "[cli][truss]") {
  const fs::path dir = scratch();
  for (const std::string model : {"rod", "beam"}) {
    const fs::path deck = dir / (model + ".bdf"), json = dir / (model + ".json"), copy = dir / (model + "_copy.bdf");
    auto r = run_ssid("truss mpi --model " + model + " --config surge_springs --config optics_tip_mass -o " + deck.string() +
                      " --json " + json.string());
    INFO(r.err);
    REQUIRE(r.code == 0);
    CHECK_THAT(r.out, Catch::Contains("80 balls, 252 struts"));
    auto j = nlohmann::json::parse(cli_slurp(json));
    CHECK(j["balls"] == 80);
    CHECK(j["struts"] == 252);
    CHECK(j["configs"].size() == 2);
    CHECK(j["mass_kg"].get<double>() == Approx(226.4).epsilon(0.01));
    // Rod: 3 DOF per ball plus the vertical DOF of 11 interior grids in each of the 3 surge springs.
    if (model == "rod") CHECK(j["dof"] == 240 + 3 * 11);
    CHECK(j["parameters"].size() >= 3);
    auto s = run_ssid("deck summary " + deck.string() + " --json -");
    INFO(s.err);
    CHECK(s.code == 0);
    auto sj = nlohmann::json::parse(s.out);
    CHECK(sj["problems"].empty());
    CHECK(sj["cards"]["GRID"] == j["grids"]);
    // Writing again over an existing output is allowed (it is not an input).
    CHECK(run_ssid("truss mpi --model " + model + " --config surge_springs --config optics_tip_mass -o " + deck.string()).code == 0);
    // The deck round-trips through the reader and writer byte for byte.
    auto w = run_ssid("deck write " + deck.string() + " -o " + copy.string());
    CHECK(w.code == 0);
    CHECK(cli_slurp(copy) == cli_slurp(deck));
  }
}

TEST_CASE("ssid truss mpi --modes and --svg", "[cli][truss]") {
  const fs::path dir = scratch();
  auto r = run_ssid("truss mpi --model rod --modes 10 --json - --svg " + (dir / "t.svg").string());
  INFO(r.err);
  REQUIRE(r.code == 0);
  auto j = nlohmann::json::parse(r.out);  // stdout holds only the JSON
  REQUIRE(j["modes_hz"].size() == 10);
  CHECK(j["modes_hz"][5].get<double>() < 1.0);
  CHECK(j["modes_hz"][6].get<double>() == Approx(7.75).epsilon(0.03));
  const std::string svg = cli_slurp(dir / "t.svg");
  CHECK_THAT(svg, Catch::Contains("<svg") && Catch::Contains("optics boom") && Catch::Contains("metrology boom") &&
                      Catch::Contains("tower"));
}

TEST_CASE("ssid truss: bad input gives a clear error and a non-zero exit", "[cli][truss][errors]") {
  auto a = run_ssid("truss mpi --model shell -o x.bdf");
  CHECK(a.code == 2);
  CHECK_THAT(a.err, Catch::Contains("rod or beam"));
  auto b = run_ssid("truss mpi --config nonsense -o " + (scratch() / "n.bdf").string());
  CHECK(b.code == 2);
  CHECK_THAT(b.err, Catch::Contains("unknown configuration 'nonsense'"));
  CHECK(b.out.empty());
  auto c = run_ssid("truss mpi");
  CHECK(c.code == 2);
  auto d = run_ssid("truss frobnicate");
  CHECK(d.code == 2);
}

TEST_CASE("samples/mpi_rod.bdf and samples/mpi_beam.bdf are what the generator writes today", "[cli][truss][golden]") {
  const fs::path dir = scratch();
  for (const std::string model : {"rod", "beam"}) {
    const fs::path out = dir / ("golden_" + model + ".bdf");
    auto r = run_ssid("truss mpi --model " + model + " -o " + out.string());
    REQUIRE(r.code == 0);
    INFO("regenerate with: ssid truss mpi --model " << model << " -o samples/mpi_" << model << ".bdf");
    CHECK(cli_slurp(out) == cli_slurp(fs::path(SSID_SOURCE_DIR) / "samples" / ("mpi_" + model + ".bdf")));
  }
}
