// ssid pretest: the sensor set's Fisher determinant against the modes that
// `ssid modes` writes, the JSON layout scripts rely on, the UFF 15 of the
// sensors, reproducible exciters, and refusals.
#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <fstream>
#include <map>
#include <set>
#include <nlohmann/json.hpp>
#include <unistd.h>

#include "cli_run.hpp"
#include "formats/uff.hpp"

namespace fs = std::filesystem;

namespace {

fs::path scratch() {
  fs::path p = fs::temp_directory_path() / ("ssid_cli_pretest_" + std::to_string(::getpid()));
  fs::create_directories(p);
  return p;
}

nlohmann::json read_json(const fs::path& p) {
  std::ifstream in(p);
  return nlohmann::json::parse(in);
}

std::string rod() { return (fs::path(SSID_SOURCE_DIR) / "samples" / "mpi_rod.bdf").string(); }

}  // namespace

TEST_CASE("ssid pretest: EI on the MPI rod model; its Fisher determinant from ssid modes' shapes", "[cli][pretest]") {
  const fs::path dir = scratch();
  const fs::path pj = dir / "ei.json", mj = dir / "modes.json", unv = dir / "sensors.unv";
  auto r = run_ssid("pretest " + rod() + " --target-modes 12 --min-hz 1 --sensors 18 --method ei --json " + pj.string() +
                    " --uff " + unv.string());
  INFO(r.err);
  REQUIRE(r.code == 0);
  CHECK_THAT(r.out, Catch::Contains("sensors: ei, 18 DOF(s)"));
  const auto j = read_json(pj);
  REQUIRE(j["sensors"].size() == 18);
  REQUIRE(j["target_modes"].size() == 12);
  CHECK(j["exciters"].empty());
  CHECK(j["tam"]["serep"]["max_offdiagonal_xor"].get<double>() < 1e-8);

  // The same 12 modes from `ssid modes --shapes` (g-set), partitioned to the sensors.
  auto m = run_ssid("modes " + rod() + " --nmodes 24 --shapes --json " + mj.string());
  REQUIRE(m.code == 0);
  const auto mo = read_json(mj);
  std::map<std::pair<long, int>, std::size_t> where;
  for (std::size_t i = 0; i < mo["shape_dofs"].size(); ++i)
    where[{mo["shape_dofs"][i][0].get<long>(), mo["shape_dofs"][i][1].get<int>()}] = i;
  Eigen::MatrixXd S(18, 12);
  for (int t = 0; t < 12; ++t) {
    const int mode = j["target_modes"][static_cast<std::size_t>(t)]["mode"].get<int>();
    const auto& shape = mo["modes"][static_cast<std::size_t>(mode - 1)]["shape"];
    CHECK(mo["modes"][static_cast<std::size_t>(mode - 1)]["cycles"].get<double>() ==
          Approx(j["target_modes"][static_cast<std::size_t>(t)]["hz"].get<double>()).epsilon(1e-8));
    for (int s = 0; s < 18; ++s) {
      const auto& sj = j["sensors"][static_cast<std::size_t>(s)];
      S(s, t) = shape[where.at({sj["grid"].get<long>(), sj["component"].get<int>()})].get<double>();
    }
  }
  const double det = (S.transpose() * S).determinant();
  CHECK(j["fisher_determinant"].get<double>() == Approx(det).epsilon(1e-6));

  // UFF 15: the sensor grids with their positions.
  const auto f = ssid::formats::uff::read_uff(unv.string());
  std::set<long> grids;
  for (const auto& s : j["sensors"]) grids.insert(s["grid"].get<long>());
  CHECK(f.nodes().size() == grids.size());
  for (const auto& nd : f.nodes()) CHECK(grids.count(nd.id) == 1);
}

TEST_CASE("ssid pretest: triaxes, KE and the GA's exciters are reproducible", "[cli][pretest]") {
  const fs::path dir = scratch();
  const std::string base = "pretest " + rod() + " --target-modes 12 --min-hz 1 --sensors 18 --method ke --triax --exciters 2 "
                           "--population 10 --generations 4 --exciter-at 41:0,1,0 --exciter-at 79:0,0,1 --json ";
  auto a = run_ssid(base + (dir / "a.json").string());
  INFO(a.err);
  REQUIRE(a.code == 0);
  auto b = run_ssid(base + (dir / "b.json").string());
  REQUIRE(b.code == 0);
  const auto ja = read_json(dir / "a.json"), jb = read_json(dir / "b.json");
  REQUIRE(ja["sensors"].size() == 18);
  std::map<long, int> per_grid;
  for (const auto& s : ja["sensors"]) ++per_grid[s["grid"].get<long>()];
  CHECK(per_grid.size() == 6);
  for (const auto& [g, c] : per_grid) CHECK(c == 3);
  REQUIRE(ja["exciters"].size() == 2);
  CHECK(ja["exciters"] == jb["exciters"]);
  CHECK(ja["exciter_objective"] == jb["exciter_objective"]);
  CHECK(ja["given_exciters"]["exciters"][0]["grid"] == 41);
  CHECK(ja["given_exciters"]["mif_dropoff"].size() == 12);
  // Elitism: the GA's final objective is the best it saw.
  CHECK(ja["exciter_objective"].get<double>() == Approx(ja["ga"]["best_per_generation"].back().get<double>()));
}

TEST_CASE("ssid pretest: refusals are bad input", "[cli][pretest]") {
  auto r = run_ssid("pretest " + rod() + " --target-modes 12 --sensors 18 --method foo");
  CHECK(r.code == 2);
  CHECK(r.err == "ssid: error: --method: expected ei, ke, ake, evp or evp-sum, got \"foo\"\n");
  r = run_ssid("pretest " + rod() + " --target-modes 12 --sensors 10 --method ei");
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Catch::Contains("effective independence: 10 sensors cannot resolve 12 target modes"));
  r = run_ssid("pretest " + rod() + " --target-modes 12 --sensors 17 --triax");
  CHECK(r.code == 2);
  CHECK(r.err == "ssid: error: --sensors 17 with --triax: expected a multiple of 3\n");
  r = run_ssid("pretest " + rod() + " --target-modes 12 --sensors 18 --exciter-at 41:0,1");
  CHECK(r.code == 2);
  // The model's notes come first (the deck is read before the exciters are checked).
  CHECK_THAT(r.err, Catch::EndsWith("\nssid: error: --exciter-at \"41:0,1\": expected GRID:X,Y,Z (a grid id and three "
                                    "direction cosines)\n"));
}

TEST_CASE("ssid pretest --evaluate: without noise the EI set identifies all 12 rod targets exactly", "[cli][pretest]") {
  const fs::path dir = scratch();
  const fs::path pj = dir / "eval.json";
  auto r = run_ssid("pretest " + rod() + " --target-modes 12 --min-hz 1 --sensors 18 --method ei "
                    "--exciter-at 24:0,1,1 --exciter-at 65:1,0,-1 --evaluate --noise 0 --json " + pj.string());
  INFO(r.err);
  REQUIRE(r.code == 0);
  const auto j = read_json(pj);
  const auto& ev = j["evaluation"];
  CHECK(ev["identified"] == 12);
  CHECK(ev["max_frequency_error_pct"].get<double>() < 1e-3);
  CHECK(ev["max_offdiagonal_xor"].get<double>() < 1e-3);
  CHECK(ev["min_diagonal_xor"].get<double>() > 0.999);
  REQUIRE(ev["targets"].size() == 12);
  for (std::size_t t = 0; t < 12; ++t) {
    CHECK(ev["targets"][t]["fe_hz"] == j["target_modes"][t]["hz"]);
    CHECK(ev["targets"][t]["damping_ratio"].get<double>() == Approx(0.01).epsilon(1e-3));
  }
  CHECK(ev["test"]["noise_pct"] == 0.0);
  CHECK_THAT(r.out, Catch::Contains("identified 12 of 12 target(s)"));
}

TEST_CASE("ssid pretest --evaluate: refused without exciters", "[cli][pretest]") {
  auto r = run_ssid("pretest " + rod() + " --target-modes 12 --min-hz 1 --sensors 18 --evaluate");
  CHECK(r.code == 2);
  CHECK(r.err == "ssid: error: --evaluate: needs exciters (--exciters E for the GA's, or --exciter-at GRID:X,Y,Z)\n");
  r = run_ssid("pretest " + rod() + " --target-modes 12 --min-hz 1 --sensors 18 --exciters 1 --evaluate --noise -1");
  CHECK(r.code == 2);
  CHECK(r.err == "ssid: error: --noise: expected a percentage ≥ 0, got -1\n");
}

TEST_CASE("ssid pretest --perturb-areas: the model-error study is seeded and counts the changed sensors", "[cli][pretest]") {
  const fs::path dir = scratch();
  const std::string base = "pretest " + rod() + " --target-modes 12 --min-hz 1 --sensors 18 --method ei --perturb-areas 3 --json ";
  auto a = run_ssid(base + (dir / "pa.json").string());
  INFO(a.err);
  REQUIRE(a.code == 0);
  auto b = run_ssid(base + (dir / "pb.json").string());
  REQUIRE(b.code == 0);
  const auto ja = read_json(dir / "pa.json"), jb = read_json(dir / "pb.json");
  const auto& m = ja["model_error"];
  CHECK(m == jb["model_error"]);
  const long struts = m["struts"].get<long>();
  CHECK(struts > 100);
  CHECK(m["areas_decreased"].get<long>() == struts / 3);
  CHECK(m["areas_increased"].get<long>() == struts / 3);
  // The sets differ by exactly the listed sensors.
  std::set<std::pair<long, int>> nominal, perturbed;
  for (const auto& s : ja["sensors"]) nominal.insert({s["grid"].get<long>(), s["component"].get<int>()});
  for (const auto& s : m["sensors"]) perturbed.insert({s["grid"].get<long>(), s["component"].get<int>()});
  REQUIRE(perturbed.size() == 18);
  std::size_t missing = 0;
  for (const auto& k : nominal) missing += perturbed.count(k) == 0;
  CHECK(m["changed"].get<std::size_t>() == missing);
  CHECK(m["removed"].size() == missing);
  CHECK(m["added"].size() == missing);
  // A stiffness change moves every target.
  for (const auto& c : m["frequency_change_pct"]) CHECK(std::abs(c.get<double>()) > 1e-3);
}
