// ssid pretest: the sensor set's Fisher determinant against the modes that
// `ssid modes` writes, the JSON layout scripts rely on, the UFF 15 of the
// sensors, reproducible exciters, and refusals.
#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <algorithm>
#include <fstream>
#include <iterator>
#include <map>
#include <set>
#include <sstream>
#include <variant>
#include <nlohmann/json.hpp>
#include <unistd.h>

#include "cli_run.hpp"
#include "formats/uff.hpp"

namespace fs = std::filesystem;

namespace {

fs::path scratch() { return cli_scratch("pretest"); }

nlohmann::json read_json(const fs::path& p) {
  std::ifstream in(p);
  return nlohmann::json::parse(in);
}

std::string rod() { return (fs::path(SSID_SOURCE_DIR) / "samples" / "mpi_rod.bdf").string(); }

/// `ssid pretest` on the rod model with `options`, its JSON written to `json`;
/// requires success and returns the JSON (and stdout in `out`).
nlohmann::json pretest_rod(const std::string& options, const fs::path& json, std::string& out) {
  auto r = run_ssid("pretest " + rod() + " " + options + " --json " + json.string());
  INFO(r.err);
  REQUIRE(r.code == 0);
  out = r.out;
  return read_json(json);
}

/// The rod model's g-set mode shapes as `ssid modes --shapes` writes them: an
/// independent route to the rows the pretest works on.
struct RodShapes {
  nlohmann::json modes;
  std::map<std::pair<long, int>, std::size_t> where;  ///< (grid, component) → position in a shape
  /// Mode `mode` (1-based) at (grid, component).
  double at(int mode, long grid, int component) const {
    return modes["modes"][static_cast<std::size_t>(mode - 1)]["shape"][where.at({grid, component})].get<double>();
  }
};

RodShapes rod_shapes(const fs::path& json) {
  auto m = run_ssid("modes " + rod() + " --nmodes 24 --shapes --json " + json.string());
  REQUIRE(m.code == 0);
  RodShapes s{read_json(json), {}};
  for (std::size_t i = 0; i < s.modes["shape_dofs"].size(); ++i)
    s.where[{s.modes["shape_dofs"][i][0].get<long>(), s.modes["shape_dofs"][i][1].get<int>()}] = i;
  return s;
}

}  // namespace

TEST_CASE("ssid pretest: EI on the MPI rod model; its Fisher determinant from ssid modes' shapes", "[cli][pretest]") {
  const fs::path dir = scratch();
  const fs::path pj = dir / "ei.json", mj = dir / "modes.json", unv = dir / "sensors.unv";
  std::string out;
  const auto j = pretest_rod("--target-modes 12 --min-hz 1 --sensors 18 --method ei --uff " + unv.string(), pj, out);
  CHECK_THAT(out, Catch::Contains("sensors: ei, 18 DOF(s)"));
  REQUIRE(j["sensors"].size() == 18);
  REQUIRE(j["target_modes"].size() == 12);
  CHECK(j["exciters"].empty());
  CHECK(j["tam"]["serep"]["max_offdiagonal_xor"].get<double>() < 1e-8);

  // The same 12 modes from `ssid modes --shapes` (g-set), partitioned to the sensors.
  const RodShapes mo = rod_shapes(mj);
  Eigen::MatrixXd S(18, 12);
  for (int t = 0; t < 12; ++t) {
    const int mode = j["target_modes"][static_cast<std::size_t>(t)]["mode"].get<int>();
    CHECK(mo.modes["modes"][static_cast<std::size_t>(mode - 1)]["cycles"].get<double>() ==
          Approx(j["target_modes"][static_cast<std::size_t>(t)]["hz"].get<double>()).epsilon(1e-8));
    for (int s = 0; s < 18; ++s) {
      const auto& sj = j["sensors"][static_cast<std::size_t>(s)];
      S(s, t) = mo.at(mode, sj["grid"].get<long>(), sj["component"].get<int>());
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

TEST_CASE("ssid pretest --sensor-direction: skewed sensors' Fisher determinant from ssid modes' shapes",
          "[cli][pretest][directions]") {
  // Skewed sensors at the boom tips (where EI puts its sensors), two of them at
  // grid 79; each one's mode row is its direction's dot product with the grid's
  // translations in `ssid modes`' shapes: an independent route to det F.
  const fs::path dir = scratch();
  const fs::path pj = dir / "skew.json", mj = dir / "modes.json";
  const std::string dirs = " --sensor-direction 2:0,1,1 --sensor-direction 4:1,2,-1 --sensor-direction 29:0,-1,1"
                           " --sensor-direction 31:3,0,1 --sensor-direction 77:0,1,0.5 --sensor-direction 79:1,0,1"
                           " --sensor-direction 79:1,0,-0.2";
  std::string out;
  const auto j = pretest_rod("--target-modes 12 --min-hz 1 --sensors 18 --method ei" + dirs, pj, out);
  CHECK_THAT(out, Catch::Contains("7 of them along given directions"));
  REQUIRE(j["sensors"].size() == 18);
  REQUIRE(j["sensor_directions"].size() == 7);
  CHECK(j["candidates"].get<int>() == 3 * 80 - 6 * 3 + 7);
  const RodShapes mo = rod_shapes(mj);
  int skewed = 0;
  Eigen::MatrixXd S(18, 12);
  for (int s = 0; s < 18; ++s) {
    const auto& sj = j["sensors"][static_cast<std::size_t>(s)];
    const long grid = sj["grid"].get<long>();
    Eigen::Vector3d d;
    for (int k = 0; k < 3; ++k) d(k) = sj["direction"][static_cast<std::size_t>(k)].get<double>();
    CHECK(d.norm() == Approx(1.0));
    if (sj["component"].is_null()) {
      ++skewed;
      CHECK(std::set<long>{2, 4, 29, 31, 77, 79}.count(grid) == 1);
      CHECK(sj["label"].get<std::string>().front() == '(');
    } else {
      CHECK(d == Eigen::Vector3d::Unit(sj["component"].get<int>() - 1));
    }
    for (int t = 0; t < 12; ++t) {
      const int mode = j["target_modes"][static_cast<std::size_t>(t)]["mode"].get<int>();
      S(s, t) = 0;
      for (int k = 0; k < 3; ++k) S(s, t) += d(k) * mo.at(mode, grid, k + 1);
    }
  }
  CHECK(skewed >= 3);
  const double det = (S.transpose() * S).determinant();
  CHECK(j["fisher_determinant"].get<double>() == Approx(det).epsilon(1e-6));
  CHECK(j["tam"]["serep"]["max_offdiagonal_xor"].get<double>() < 1e-8);

  // The UFF carries the orientation: each sensor grid whose measured axes are not basic
  // gets a coordinate system (2420) as its node's displacement system, and each sensor's
  // uff_direction there is, through the reader's own system algebra, its direction_basic.
  // Grid 2's two given directions are not orthogonal: no system, a warning, null.
  {
    const fs::path unv = dir / "skew.unv", sj = dir / "skew_uff.json";
    const auto u = run_ssid("pretest " + rod() + " --target-modes 3 --min-hz 1 --sensors 6 --method ei --grids "
                            "2,40,77,79 --sensor-direction 79:1,1,0 --sensor-direction 77:0,1,1 --sensor-direction "
                            "77:0,1,-1 --sensor-direction 2:1,1,0 --sensor-direction 2:1,0,0 --uff " + unv.string() +
                            " --json " + sj.string());
    INFO(u.err);
    REQUIRE(u.code == 0);
    const auto js = read_json(sj);
    const auto back = ssid::formats::uff::read_uff(unv.string());
    std::map<long, ssid::formats::uff::Node> node;
    for (const auto& n : back.nodes()) node[n.id] = n;
    int oriented = 0;
    bool grid2 = false;
    for (const auto& x : js["sensors"]) {
      const long g = x["grid"].get<long>();
      if (g == 2) {
        grid2 = true;
        CHECK(x["uff_direction"].is_null());
        continue;
      }
      REQUIRE(x["uff_direction"].is_number());
      const auto e = back.direction_in_global(node.at(g), x["uff_direction"].get<int>());
      for (int k = 0; k < 3; ++k)
        CHECK(e[static_cast<std::size_t>(k)] == Approx(x["direction_basic"][static_cast<std::size_t>(k)].get<double>()).margin(1e-6));
      oriented += node.at(g).displacement_cs != 0;
    }
    CHECK(oriented >= 2);  // 77's pair and 79's single direction
    if (grid2) CHECK_THAT(u.err, Catch::Contains("warning: grid 2: its given sensor directions are not mutually orthogonal"));
  }

  // Refusals: a triax needs three directions; directions must be independent; a
  // grid that is not in the model.
  auto r = run_ssid("pretest " + rod() + " --target-modes 12 --min-hz 1 --sensors 18 --triax" + dirs);
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Catch::EndsWith("ssid: error: --triax: grid 2 has 1 sensor direction(s); a triax needs three (give "
                                    "three --sensor-direction at it)\n"));
  r = run_ssid("pretest " + rod() + " --target-modes 12 --min-hz 1 --sensors 18 --sensor-direction 5:1,1,0 "
               "--sensor-direction 5:2,2,0");
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Catch::Contains("sensor directions at grid 5: the 2 directions are linearly dependent"));
  r = run_ssid("pretest " + rod() + " --target-modes 12 --min-hz 1 --sensors 18 --sensor-direction 5000:1,0,0");
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Catch::Contains("sensor direction at grid 5000: not a candidate grid"));
  r = run_ssid("pretest " + rod() + " --target-modes 12 --min-hz 1 --sensors 18 --sensor-direction 5:1,0");
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Catch::EndsWith("ssid: error: --sensor-direction \"5:1,0\": expected GRID:X,Y,Z (a grid id and three "
                                    "direction cosines)\n"));
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

namespace {

/// Every start tag `<g class="cls" ...>` of `svg`, as its attribute text.
std::vector<std::string> groups_of(const std::string& svg, const std::string& cls) {
  std::vector<std::string> out;
  const std::string start = "<g class=\"" + cls + "\"";
  for (auto a = svg.find(start); a != std::string::npos; a = svg.find(start, a + 1))
    out.push_back(svg.substr(a, svg.find('>', a) - a));
  return out;
}

std::string attribute(const std::string& tag, const std::string& name) {
  const auto a = tag.find(" " + name + "=\"");
  if (a == std::string::npos) return "";
  const auto b = a + name.size() + 3;
  return tag.substr(b, tag.find('"', b) - b);
}

std::string read_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace

TEST_CASE("ssid pretest --svg: one marker per sensor and exciter, in the chosen view", "[cli][pretest][svg]") {
  const fs::path dir = scratch();
  const fs::path svg = dir / "ei.svg", pj = dir / "ei_svg.json";
  auto r = run_ssid("pretest " + rod() + " --target-modes 12 --min-hz 1 --sensors 18 --method ei --exciters 2 --population 6 "
                    "--generations 2 --exciter-at 41:0,1,0 --view z --svg " + svg.string() + " --json " + pj.string());
  INFO(r.err);
  REQUIRE(r.code == 0);
  const auto j = read_json(pj);
  const std::string s = read_text(svg);
  CHECK(s.rfind("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg ", 0) == 0);
  CHECK(s.find("</svg>") != std::string::npos);
  // One view only, the top one (--view z), with its legend.
  CHECK(groups_of(s, "view").size() == 1);
  CHECK(attribute(groups_of(s, "view").at(0), "data-view") == "top");
  CHECK(s.find("<g class=\"legend\">") != std::string::npos);
  // A marker per sensor DOF: exactly the JSON's (grid, component) pairs.
  std::multiset<std::pair<long, int>> want, got;
  for (const auto& x : j["sensors"]) want.insert({x["grid"].get<long>(), x["component"].get<int>()});
  for (const auto& g : groups_of(s, "sensor")) got.insert({std::stol(attribute(g, "data-grid")), std::stoi(attribute(g, "data-component"))});
  CHECK(got == want);
  CHECK(got.size() == 18);
  // The GA's two exciters and the given one, each at its grid with its direction cosines.
  const auto ex = groups_of(s, "exciter"), given = groups_of(s, "exciter-given");
  REQUIRE(ex.size() == 2);
  REQUIRE(given.size() == 1);
  for (std::size_t k = 0; k < 2; ++k) {
    CHECK(std::stol(attribute(ex[k], "data-grid")) == j["exciters"][k]["grid"].get<long>());
    std::stringstream d(attribute(ex[k], "data-direction"));
    for (int c = 0; c < 3; ++c) {
      std::string v;
      std::getline(d, v, ',');
      CHECK(std::stod(v) == j["exciters"][k]["direction"][c].get<double>());
    }
  }
  CHECK(attribute(given[0], "data-grid") == "41");
  CHECK(attribute(given[0], "data-direction") == "0,1,0");
  // The rod deck's grids have CD = 0: a sensor's direction is its component's basic axis.
  for (const auto& x : j["sensors"]) {
    const int c = x["component"];
    for (int k = 0; k < 3; ++k) CHECK(x["direction_basic"][k].get<double>() == (k == c - 1 ? 1.0 : 0.0));
  }

  SECTION("triaxes: one marker per triax, none per DOF") {
    const fs::path tsvg = dir / "triax.svg";
    auto t = run_ssid("pretest " + rod() + " --target-modes 12 --min-hz 1 --sensors 18 --method ei --triax --svg " + tsvg.string());
    REQUIRE(t.code == 0);
    const std::string ts = read_text(tsvg);
    CHECK(groups_of(ts, "triax").size() == 6);
    CHECK(groups_of(ts, "sensor").empty());
    CHECK(groups_of(ts, "exciter").empty());
    CHECK(attribute(groups_of(ts, "view").at(0), "data-view") == "iso");  // the default
  }
  SECTION("a view that is not one is bad input") {
    auto b = run_ssid("pretest " + rod() + " --target-modes 12 --min-hz 1 --sensors 18 --view w --svg " + (dir / "w.svg").string());
    CHECK(b.code == 2);
    CHECK(b.err == "ssid: error: --view: expected iso, x, y or z, got \"w\"\n");
  }
}

TEST_CASE("ssid pretest --uff: the trace lines (82) join sensor grids along the deck's elements and read back",
          "[cli][pretest][uff]") {
  const fs::path dir = scratch();
  const fs::path unv = dir / "wire.unv", pj = dir / "wire.json";
  auto r = run_ssid("pretest " + rod() + " --target-modes 12 --min-hz 1 --sensors 18 --method ei --json " + pj.string() +
                    " --uff " + unv.string());
  INFO(r.err);
  REQUIRE(r.code == 0);
  const auto j = read_json(pj);
  std::set<long> sensor_grids;
  for (const auto& x : j["sensors"]) sensor_grids.insert(x["grid"].get<long>());

  // The deck's grids and CROD lines, read here from the fixed-format bulk data.
  std::map<long, Eigen::Vector3d> at;
  std::map<long, std::vector<long>> adjacent;
  {
    std::ifstream in(rod());
    std::string line;
    auto field = [&](int k) { return line.size() > std::size_t(8 * k) ? line.substr(8 * k, 8) : std::string(); };
    while (std::getline(in, line)) {
      if (line.rfind("GRID    ", 0) == 0)
        at[std::stol(field(1))] = {std::stod(field(3)), std::stod(field(4)), std::stod(field(5))};
      if (line.rfind("CROD    ", 0) == 0) {
        const long a = std::stol(field(3)), b = std::stol(field(4));
        adjacent[a].push_back(b);
        adjacent[b].push_back(a);
      }
    }
  }
  REQUIRE(at.size() == 80);
  // From each sensor grid, the sensor grids reached along elements without passing another sensor grid.
  auto reached = [&](long s) {
    std::set<long> seen{s}, hit;
    std::vector<long> stack{s};
    while (!stack.empty()) {
      const long n = stack.back();
      stack.pop_back();
      for (long m : adjacent[n]) {
        if (!seen.insert(m).second) continue;
        if (sensor_grids.count(m)) hit.insert(m);
        else stack.push_back(m);
      }
    }
    return hit;
  };

  const auto f = ssid::formats::uff::read_uff(unv.string());
  std::vector<const ssid::formats::uff::TraceLine82*> traces;
  for (const auto& d : f.datasets)
    if (auto t = std::get_if<ssid::formats::uff::TraceLine82>(&d)) traces.push_back(t);
  REQUIRE(traces.size() == 1);
  // Segments: node pairs between pen lifts (0).
  std::set<std::pair<long, long>> segments;
  const auto& nodes = traces[0]->nodes;
  for (std::size_t k = 0; k < nodes.size(); k += 3) {
    REQUIRE(k + 1 < nodes.size());
    if (k + 2 < nodes.size()) CHECK(nodes[k + 2] == 0);
    segments.insert({nodes[k], nodes[k + 1]});
  }
  REQUIRE(!segments.empty());
  std::set<long> joined;
  for (const auto& [a, b] : segments) {
    CHECK(sensor_grids.count(a) == 1);  // sensor grids only
    CHECK(sensor_grids.count(b) == 1);
    CHECK(reached(a).count(b) == 1);    // an element path between them that passes no other sensor grid
    // b is among a's three nearest such grids, or a among b's (the rule of docs/pretest.md).
    auto among_nearest = [&](long p, long q) {
      std::vector<std::pair<double, long>> d;
      for (long m : reached(p)) d.push_back({(at[m] - at[p]).norm(), m});
      std::sort(d.begin(), d.end());
      for (std::size_t i = 0; i < d.size() && i < 3; ++i)
        if (d[i].second == q) return true;
      return false;
    };
    CHECK((among_nearest(a, b) || among_nearest(b, a)));
    joined.insert(a), joined.insert(b);
  }
  // Every sensor grid that the elements join to another one has a line.
  for (long s : sensor_grids)
    if (!reached(s).empty()) CHECK(joined.count(s) == 1);
  // The nodes of the trace lines are the file's nodes (15).
  std::set<long> node_ids;
  for (const auto& nd : f.nodes()) node_ids.insert(nd.id);
  for (long g : joined) CHECK(node_ids.count(g) == 1);

  auto l = run_ssid("uff list " + unv.string());
  CHECK(l.code == 0);
  CHECK_THAT(l.out, Catch::Contains("trace lines (82): 1"));
}

TEST_CASE("ssid pretest --report: a method that cannot place the sensors is reported, not fatal", "[cli][pretest][report]") {
  const fs::path dir = scratch();
  const fs::path pj = dir / "ke10.json", html = dir / "ke10.html";
  // 10 sensors for 12 targets: KE ranks them, EI refuses (its Fisher information would be singular).
  auto r = run_ssid("pretest " + rod() + " --target-modes 12 --min-hz 1 --sensors 10 --method ke --json " + pj.string() +
                    " --report " + html.string());
  INFO(r.err);
  REQUIRE(r.code == 0);
  const auto j = read_json(pj);
  REQUIRE(j["methods"].size() == 5);
  CHECK(j["methods"][0]["method"] == "ei");
  CHECK(j["methods"][0]["error"] ==
        "effective independence: 10 sensors cannot resolve 12 target modes (the Fisher information would be singular)");
  // The others place 10 sensors: a singular Fisher information (rank 10 of 12), no log10 det, no condition number.
  for (std::size_t k = 1; k < 5; ++k) {
    CHECK(j["methods"][k]["fisher_determinant"] == 0.0);
    CHECK(j["methods"][k]["fisher_rank"] == 10);
    CHECK(j["methods"][k]["log10_fisher_determinant"].is_null());
  }
  CHECK(j["methods"][1]["method"] == "ke");
  CHECK(j["methods"][1]["sensors"].size() == 10);
  const std::string page = read_text(html);
  CHECK(page.find("<tr class=\"method\" data-method=\"ei\"><td>ei</td><td colspan=\"4\">no set: effective independence: 10 "
                  "sensors cannot resolve 12 target modes") != std::string::npos);
  CHECK(page.find("<tr class=\"method\" data-method=\"ke\">") != std::string::npos);
  // Nothing finite to draw: no bar chart (an empty figure would fail the browser check).
  CHECK(page.find("id=\"fig-fisher-det\"") == std::string::npos);
  CHECK(page.find("id=\"fig-fisher-cond\"") == std::string::npos);
}
