// --report FILE.html (issue 24): the reports of the shipped samples, their
// structure checked against the JSON the same run writes, and their rendering
// in headless Chromium (Debian's `chromium`, installed by scripts/install-deps).
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cctype>
#include <tuple>
#include <cstdio>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <unistd.h>

#include "chain_frf.hpp"
#include "cli_run.hpp"
#include "formats/uff.hpp"

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

fs::path scratch() { return cli_scratch("report"); }

std::string src(const std::string& rel) { return std::string(SSID_SOURCE_DIR) + "/" + rel; }

using Attributes = std::map<std::string, std::string>;

/// The attributes `name="value"` of a start tag's text (what lies between the tag's
/// name and its `>`).
Attributes attributes_of(const std::string& body) {
  Attributes a;
  for (std::size_t eq = body.find("=\""); eq != std::string::npos; eq = body.find("=\"", eq)) {
    std::size_t name = eq;
    while (name > 0 && (std::islower(static_cast<unsigned char>(body[name - 1])) || body[name - 1] == '-')) --name;
    const std::size_t close = body.find('"', eq + 2);
    if (close == std::string::npos) break;
    if (name < eq) a[body.substr(name, eq - name)] = body.substr(eq + 2, close - eq - 2);
    eq = close + 1;
  }
  return a;
}

/// Every start tag `<tag class="cls" ...>` of `html`, with its attributes (class
/// aside). Scanned by hand: std::regex's matcher recurses once per character, and the
/// long `points`/`d` attributes of the figures overflowed the stack under ASan.
std::vector<Attributes> marks(const std::string& html, const std::string& tag, const std::string& cls) {
  std::vector<Attributes> out;
  const std::string open = "<" + tag + " ";
  for (std::size_t at = html.find(open); at != std::string::npos; at = html.find(open, at + 1)) {
    const std::size_t end = html.find('>', at);
    if (end == std::string::npos) break;
    Attributes a = attributes_of(html.substr(at + open.size(), end - at - open.size()));
    const auto c = a.find("class");
    if (c == a.end() || c->second != cls) continue;
    a.erase(c);
    out.push_back(a);
  }
  return out;
}

/// The markup of one figure (from `<figure id="id">` to its `</figure>`).
std::string figure(const std::string& html, const std::string& id) {
  const auto a = html.find("<figure id=\"" + id + "\"");
  if (a == std::string::npos) return "";
  return html.substr(a, html.find("</figure>", a) - a);
}

double num(const Attributes& a, const std::string& key) {
  REQUIRE(a.count(key));
  return std::stod(a.at(key));
}

/// What a shell command prints (stdout).
std::string output_of(const std::string& cmd) {
  std::string out;
  FILE* p = ::popen(cmd.c_str(), "r");
  if (!p) return out;
  std::array<char, 4096> buf{};
  while (std::size_t n = std::fread(buf.data(), 1, buf.size(), p)) out.append(buf.data(), n);
  ::pclose(p);
  return out;
}

/// The run's header: inputs with the SHA-256 that sha256sum gives, the version `ssid --version` prints.
void check_run(const json& j, const std::string& html, const std::vector<std::string>& inputs) {
  REQUIRE(j.contains("run"));
  CHECK(output_of(std::string(SSID_EXE) + " --version") == "ssid " + j["run"]["version"].get<std::string>() + "\n");
  REQUIRE(j["run"]["inputs"].size() == inputs.size());
  for (std::size_t k = 0; k < inputs.size(); ++k) {
    const auto& in = j["run"]["inputs"][k];
    CHECK(in["path"] == inputs[k]);
    const std::string sum = output_of("sha256sum " + inputs[k]).substr(0, 64);
    CHECK(in["sha256"] == sum);
    CHECK(html.find(sum) != std::string::npos);
    CHECK(in["bytes"] == fs::file_size(inputs[k]));
  }
  CHECK(std::regex_match(j["run"]["date"].get<std::string>(), std::regex(R"(\d{4}-\d\d-\d\dT\d\d:\d\d:\d\dZ)")));
  CHECK(html.find(j["run"]["command"].get<std::string>()) != std::string::npos);
  // Self-contained: nothing fetched (the only URL is the SVG namespace).
  std::string rest = std::regex_replace(html, std::regex("http://www\\.w3\\.org/2000/svg"), "");
  CHECK(rest.find("http://") == std::string::npos);
  CHECK(rest.find("https://") == std::string::npos);
  CHECK(rest.find("<script src") == std::string::npos);
  CHECK(rest.find("<link") == std::string::npos);
}

/// The heat map's cells against a JSON matrix, and its outlined cells.
void check_heat_map(const std::string& fig, const json& m, const std::set<std::pair<int, int>>& marked) {
  const auto cells = marks(fig, "rect", "cell");
  REQUIRE(cells.size() == m.size() * m[0].size());
  for (const auto& c : cells) {
    const auto i = static_cast<std::size_t>(num(c, "data-i")), k = static_cast<std::size_t>(num(c, "data-k"));
    CHECK(num(c, "data-v") == m[i][k].get<double>());
  }
  std::set<std::pair<int, int>> drawn;
  for (const auto& c : marks(fig, "rect", "pair"))
    drawn.insert({static_cast<int>(num(c, "data-i")), static_cast<int>(num(c, "data-k"))});
  CHECK(drawn == marked);
}

/// The mode-shape figures against the JSON's pairs and shapes.
void check_shapes(const std::string& html, const json& j, const json& pairs) {
  REQUIRE(j.contains("geometry"));
  CHECK(j["geometry"]["grids"].size() == 80);  // the MPI truss: 80 balls
  CHECK(j["geometry"]["lines"].size() > 100);
  CHECK(!j["geometry"]["test_lines"].empty());
  const auto figs = marks(html, "figure", "shape");
  REQUIRE(figs.size() == pairs.size());
  REQUIRE(j["shapes"].size() == pairs.size());
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    CHECK(num(figs[k], "data-fe-mode") == pairs[k]["fe_mode"].get<int>());
    CHECK(num(figs[k], "data-test-mode") == pairs[k]["test_mode"].get<int>());
    CHECK(num(figs[k], "data-fe-hz") == pairs[k]["fe_hz"].get<double>());
    CHECK(num(figs[k], "data-test-hz") == pairs[k]["test_hz"].get<double>());
    CHECK(num(figs[k], "data-mac") == pairs[k]["mac"].get<double>());
    CHECK(j["shapes"][k]["fe"].size() == 80);
    // Four views, each an analysis and a test drawing, each animated.
    const std::string f = figure(html, "shape-" + std::to_string(k));
    CHECK(marks(f, "g", "view").size() == 4);
    CHECK(marks(f, "path", "deformed fe").size() == 4);
    CHECK(marks(f, "path", "deformed test").size() == 4);
  }
}

/// The MEMS figure of each pair (the seed's Figure 4) against the JSON, and what
/// least squares guarantees of it: with the pair's test shape alone e² = 1 − MAC;
/// with every test shape e² is no larger and the superposition's MAC no smaller; the
/// error mode ê is orthogonal to the pair's test shape and its norm gives e².
void check_mems(const std::string& html, const json& j) {
  REQUIRE(!j["shapes"].empty());
  for (std::size_t k = 0; k < j["shapes"].size(); ++k) {
    const json& sh = j["shapes"][k];
    const json& m = sh["mems"];
    const std::string f = figure(html, "mems-" + std::to_string(k));
    REQUIRE(!f.empty());
    const auto fig = marks(html, "figure", "mems");
    REQUIRE(fig.size() == j["shapes"].size());
    CHECK(num(fig[k], "data-pair") == static_cast<double>(k));
    CHECK(num(fig[k], "data-error-squared") == m["error_squared"].get<double>());
    CHECK(num(fig[k], "data-mac-superposition") == m["mac_superposition"].get<double>());
    CHECK(num(fig[k], "data-pair-error-squared") == m["pair_error_squared"].get<double>());
    CHECK(marks(f, "path", "deformed error").size() == 4);
    const auto bars = marks(f, "rect", "alpha");
    REQUIRE(bars.size() == m["alpha"].size());
    for (std::size_t i = 0; i < bars.size(); ++i) {
      CHECK(num(bars[i], "data-test-mode") == m["alpha"][i][0].get<double>());
      CHECK(num(bars[i], "data-v") == m["alpha"][i][1].get<double>());
    }
    const double mac = sh["mac"];
    CHECK(m["pair_error_squared"].get<double>() == Approx(1 - mac).margin(1e-12));
    CHECK(m["error_squared"].get<double>() <= m["pair_error_squared"].get<double>() + 1e-12);
    CHECK(m["mac_superposition"].get<double>() >= mac - 1e-12);
    // ê against the analysis shape and the pair's test shape at the measured nodes.
    std::map<long, std::array<double, 3>> fe, test;
    for (const auto& r : sh["fe"]) fe[r[0]] = {r[1], r[2], r[3]};
    for (const auto& r : sh["test"]) test[r[0]] = {r[1], r[2], r[3]};
    double ee = 0, aa = 0, et = 0, tt = 0;
    for (const auto& r : m["error"]) {
      const long node = r[0];
      REQUIRE(fe.count(node));
      REQUIRE(test.count(node));
      for (std::size_t c = 0; c < 3; ++c) {
        const double e = r[c + 1];
        ee += e * e, aa += fe[node][c] * fe[node][c], et += e * test[node][c], tt += test[node][c] * test[node][c];
      }
    }
    CHECK(ee / aa == Approx(m["error_squared"].get<double>()).epsilon(1e-9));
    CHECK(std::abs(et) <= 1e-9 * std::sqrt(ee * tt));
  }
}

/// The cross-orthogonality heat map against the JSON (`rows_are_test`: drawn transposed,
/// as estimate's MAC), its pairs outlined, each pair's acceptance as the JSON's thresholds say.
void check_xor(const std::string& html, const json& x, bool rows_are_test) {
  REQUIRE(!x.contains("unavailable"));
  std::set<std::pair<int, int>> pairs;
  const auto rows = x["fe_modes"].get<std::vector<int>>(), cols = x["test_modes"].get<std::vector<int>>();
  for (const auto& p : x["pairs"]) {
    const int i = static_cast<int>(std::find(rows.begin(), rows.end(), p["fe_mode"].get<int>()) - rows.begin());
    const int k = static_cast<int>(std::find(cols.begin(), cols.end(), p["test_mode"].get<int>()) - cols.begin());
    pairs.insert(rows_are_test ? std::make_pair(k, i) : std::make_pair(i, k));
    CHECK(p["xor"].get<double>() == x["matrix"][static_cast<std::size_t>(i)][static_cast<std::size_t>(k)].get<double>());
    CHECK(p["accepted"].get<bool>() ==
          (p["xor"].get<double>() > x["min_diagonal"].get<double>() &&
           p["largest_off_diagonal"].get<double>() < x["max_off_diagonal"].get<double>()));
  }
  json drawn = x["matrix"];
  if (rows_are_test) {
    drawn = json::array();
    for (std::size_t k = 0; k < cols.size(); ++k) {
      json row = json::array();
      for (std::size_t i = 0; i < rows.size(); ++i) row.push_back(x["matrix"][i][k]);
      drawn.push_back(row);
    }
  }
  check_heat_map(figure(html, "fig-xor"), drawn, pairs);
  const auto rowsdrawn = marks(html, "tr", "xor-pair");
  REQUIRE(rowsdrawn.size() == x["pairs"].size());
  for (std::size_t k = 0; k < rowsdrawn.size(); ++k) {
    CHECK(num(rowsdrawn[k], "data-v") == x["pairs"][k]["xor"].get<double>());
    CHECK(num(rowsdrawn[k], "data-off") == x["pairs"][k]["largest_off_diagonal"].get<double>());
  }
}

/// Headless Chromium: the page renders, no script error, every figure drawn, a screenshot.
void check_in_browser(const fs::path& html, std::size_t min_figures, unsigned long min_height = 1500) {
  REQUIRE(std::system("command -v chromium >/dev/null 2>&1") == 0);  // scripts/install-deps installs it
  const fs::path profile = html.parent_path() / ("chromium-" + html.stem().string());
  const std::string common = "timeout 120 chromium --headless=new --no-sandbox --disable-gpu --disable-dev-shm-usage "
                             "--no-first-run --user-data-dir=" + profile.string() + " --virtual-time-budget=3000 ";
  const std::string dom = output_of(common + "--dump-dom file://" + fs::absolute(html).string() + " 2>/dev/null");
  INFO(dom.substr(0, 400));
  const std::string root = dom.substr(0, dom.find("<head>"));  // the <html> tag: the page's script sets its attributes
  CHECK(root.find("data-rendered=\"1\"") != std::string::npos);
  CHECK(root.find("data-script-errors") == std::string::npos);
  std::smatch m;
  REQUIRE(std::regex_search(root, m, std::regex("data-figures=\"(\\d+)\"")));
  CHECK(std::stoul(m[1]) >= min_figures);
  REQUIRE(std::regex_search(root, m, std::regex("data-empty-figures=\"([^\"]*)\"")));
  CHECK(m[1] == "");
  REQUIRE(std::regex_search(root, m, std::regex("data-page-height=\"(\\d+)\"")));
  CHECK(std::stoul(m[1]) > min_height);
  const fs::path png = html.parent_path() / (html.stem().string() + ".png");
  fs::remove(png);
  std::system((common + "--window-size=1200,1600 --screenshot=" + png.string() + " file://" + fs::absolute(html).string() +
               " >/dev/null 2>&1").c_str());
  REQUIRE(fs::exists(png));
  CHECK(fs::file_size(png) > 20000);
  CHECK(cli_slurp(png).substr(1, 3) == "PNG");
}

struct Report {
  json j;
  std::string html;
  fs::path path;
};

Report run_report(const std::string& name, const std::string& args) {
  const fs::path dir = scratch();
  const fs::path js = dir / (name + ".json"), html = dir / (name + ".html");
  fs::remove(js), fs::remove(html);
  const auto r = run_ssid(args + " --json " + js.string() + " --report " + html.string());
  INFO(r.err);
  REQUIRE(r.code == 0);
  return {json::parse(cli_slurp(js)), cli_slurp(html), html};
}

Report correlate_report() {
  return run_report("correlate", "correlate " + src("samples/mpi_rod.bdf") + " " + src("samples/estimate/measured.unv"));
}

/// The estimate sample's report, with FRFs laid over "measured" ones: those of the truth
/// deck (samples/estimate/truth.json) by `ssid frf`, as docs/report.md makes them. They
/// stand in for a measurement so the report draws its FRF figures (the overlay itself is
/// checked against dense solves in test_cli_frf_comparison.cpp).
Report estimate_report() {
  const fs::path truth = scratch() / "truth.bdf", frf = scratch() / "truth_frf.unv";
  REQUIRE(run_ssid("update-deck " + src("samples/mpi_rod.bdf") + " " + src("samples/estimate/truth.json") + " -o " +
                   truth.string()).code == 0);
  REQUIRE(run_ssid("frf " + truth.string() + " --drive 41,2 --response 41,2 79,3 --damping 0.01 --band 2:60 --lines 581 "
                   "--uff " + frf.string()).code == 0);
  return run_report("estimate", "estimate -q " + src("samples/mpi_rod.bdf") + " " + src("samples/estimate/measured.unv") +
                                    " --study " + src("samples/estimate/study.json") + " --frf " + frf.string() +
                                    " --frf-damping 0.01");
}

Report diagnose_report() {
  return run_report("diagnose", "diagnose -q " + src("samples/mpi_rod.bdf") + " " + src("samples/mpi_rod_hidden_mass.unv"));
}

Report pretest_report() {
  return run_report("pretest", "pretest " + src("samples/mpi_rod.bdf") +
                                   " --target-modes 12 --min-hz 1 --sensors 18 --method ei --exciters 2 --population 8 "
                                   "--generations 4 --exciter-at 41:0,1,0 --exciter-at 79:0,0,1 --evaluate");
}

/// The chain's test geometry as a universal file: nodes 1, 2, 3 at x = 0, 1, 2 m, one
/// trace line through them, and node 2's displacement system (2420, system 5) turned
/// 90° about Z, so that its measured +X is the global +Y.
fs::path chain_geometry() {
  namespace uff = ssid::formats::uff;
  uff::UffFile f;
  uff::CoordinateSystems2420 cs;
  uff::Cs2420 turned;
  turned.id = 5;
  turned.rows = {{{0, 1, 0}, {-1, 0, 0}, {0, 0, 1}}};
  cs.systems.push_back(turned);
  f.datasets.emplace_back(cs);
  uff::NodeSet ns;
  ns.dataset = 2411;
  for (int n = 1; n <= 3; ++n) {
    uff::Node node;
    node.id = n;
    node.displacement_cs = n == 2 ? 5 : 0;
    node.xyz = {static_cast<double>(n - 1), 0, 0};
    ns.nodes.push_back(node);
  }
  f.datasets.emplace_back(ns);
  uff::TraceLine82 t;
  t.id = 1;
  t.label = "chain";
  t.nodes = {1, 2, 3};
  f.datasets.emplace_back(t);
  const fs::path p = scratch() / "chain_geometry.unv";
  uff::write_uff(f, p.string());
  return p;
}

Report identify_report() {
  const fs::path in = scratch() / "chain_frf.unv";
  write_chain_frf(ident_test::chain_model(true, {0}), in.string());
  return run_report("identify", "identify modes " + in.string() + " --svg " + (scratch() / "stabilisation.svg").string() +
                                    " --geometry " + chain_geometry().string());
}

}  // namespace

TEST_CASE("ssid correlate --report: MAC, frequencies and shapes are the JSON's", "[cli][report]") {
  const Report r = correlate_report();
  const json& j = r.j;
  check_run(j, r.html, {src("samples/mpi_rod.bdf"), src("samples/estimate/measured.unv")});
  // MAC: rows the analysis modes, columns the test modes; the accepted pairs outlined.
  std::set<std::pair<int, int>> accepted;
  json acc = json::array();
  auto index = [](const json& modes, int m) {
    for (std::size_t k = 0; k < modes.size(); ++k)
      if (modes[k]["mode"] == m) return static_cast<int>(k);
    return -1;
  };
  for (const auto& p : j["pairs"])
    if (p["accepted"]) {
      accepted.insert({index(j["fe_modes"], p["fe_mode"]), index(j["test_modes"], p["test_mode"])});
      acc.push_back(p);
    }
  REQUIRE(acc.size() == 24);
  check_heat_map(figure(r.html, "fig-mac"), j["mac"], accepted);
  // Frequencies: one point per accepted pair at (test, analysis), one error bar each.
  const auto pts = marks(figure(r.html, "fig-frequencies"), "circle", "freq-after");
  REQUIRE(pts.size() == acc.size());
  for (std::size_t k = 0; k < pts.size(); ++k) {
    CHECK(num(pts[k], "data-x") == acc[k]["test_hz"].get<double>());
    CHECK(num(pts[k], "data-y") == acc[k]["fe_hz"].get<double>());
  }
  const auto bars = marks(figure(r.html, "fig-errors"), "rect", "err-after");
  REQUIRE(bars.size() == acc.size());
  for (std::size_t k = 0; k < bars.size(); ++k) CHECK(num(bars[k], "data-v") == acc[k]["error_pct"].get<double>());
  check_shapes(r.html, j, acc);
  check_mems(r.html, j);
  check_xor(r.html, j["cross_orthogonality"], false);
  CHECK(j["cross_orthogonality"]["basis"] == "every analysis mode");
  // The pair selector and the anchors: one option and one link per pair.
  for (std::size_t k = 0; k < j["shapes"].size(); ++k) {
    CHECK(r.html.find("<option value=\"" + std::to_string(k) + "\">") != std::string::npos);
    CHECK(r.html.find("href=\"#mems-" + std::to_string(k) + "\"") != std::string::npos);
  }
}

TEST_CASE("ssid correlate and estimate --report: a test file's own trace lines are the test shapes' wire frame",
          "[cli][report]") {
  // The sample test with a trace line (dataset 82) through four of its nodes, a pen lift,
  // and a segment to a node that is not in the test: the segments between mapped nodes,
  // in grid ids, replace the wire frame derived from the deck.
  namespace uff = ssid::formats::uff;
  uff::UffFile f = uff::read_uff(src("samples/estimate/measured.unv"));
  std::vector<std::int64_t> ids;
  for (const auto& n : f.nodes()) ids.push_back(n.id);
  REQUIRE(ids.size() >= 5);
  uff::TraceLine82 t;
  t.id = 1;
  t.label = "lab wire frame";
  t.nodes = {ids[0], ids[1], ids[2], 0, ids[3], ids[4], 999999};
  f.datasets.emplace_back(t);
  const fs::path test = scratch() / "measured_with_trace.unv";
  uff::write_uff(f, test.string());
  const Report r = run_report("correlate_trace", "correlate " + src("samples/mpi_rod.bdf") + " " + test.string());
  const json& g = r.j["geometry"];
  CHECK(g["test_lines_from"] == "the test file's trace lines (dataset 82)");
  std::set<std::pair<std::int64_t, std::int64_t>> want{std::minmax(ids[0], ids[1]), std::minmax(ids[1], ids[2]),
                                                       std::minmax(ids[3], ids[4])};
  std::set<std::pair<std::int64_t, std::int64_t>> got;
  for (const auto& l : g["test_lines"]) got.insert({l[0].get<std::int64_t>(), l[1].get<std::int64_t>()});
  CHECK(got == want);  // the rod's test nodes are its grids' ids (mapped by id)
  // The estimate's report draws the same lines (the study maps the nodes the same way).
  const Report e = run_report("estimate_trace", "estimate -q " + src("samples/mpi_rod.bdf") + " " + test.string() +
                                                    " --study " + src("samples/estimate/study.json"));
  CHECK(e.j["geometry"]["test_lines_from"] == "the test file's trace lines (dataset 82)");
  CHECK(e.j["geometry"]["test_lines"] == g["test_lines"]);
  // Without trace lines the report says the wire frame comes from the deck.
  CHECK(correlate_report().j["geometry"]["test_lines_from"] == "the deck's elements between the test grids");
}

TEST_CASE("ssid correlate: the cross-orthogonality of a deck's modes with themselves is the identity", "[cli][report]") {
  // SEREP's reduced mass makes the analysis modes orthonormal at the test DOFs: a test
  // that is the deck's own modes (ssid modes --uff) gives X = I, whatever the sensors.
  const fs::path dir = scratch();
  const fs::path own = dir / "own_modes.unv", js = dir / "own.json";
  const auto m = run_ssid("modes " + src("samples/mpi_rod.bdf") + " --nmodes 12 --uff " + own.string() +
                          " --sensors 1,3,5,7,9,11,13,15,17,19,21,23");
  INFO(m.err);
  REQUIRE(m.code == 0);
  const auto r = run_ssid("correlate " + src("samples/mpi_rod.bdf") + " " + own.string() + " --nmodes 12 --json " + js.string());
  INFO(r.err);
  REQUIRE(r.code == 0);
  const json x = json::parse(cli_slurp(js))["cross_orthogonality"];
  REQUIRE(!x.contains("unavailable"));
  REQUIRE(x["fe_modes"].size() == 12);
  REQUIRE(x["test_modes"].size() == 12);
  double worst_diag = 0, worst_off = 0;
  for (std::size_t i = 0; i < 12; ++i)
    for (std::size_t k = 0; k < 12; ++k) {
      const double v = x["matrix"][i][k];
      if (i == k) worst_diag = std::max(worst_diag, std::abs(v - 1));
      else worst_off = std::max(worst_off, v);
    }
  INFO("diagonal off 1 by " << worst_diag << ", largest off-diagonal " << worst_off);
  CHECK(worst_diag < 1e-6);
  CHECK(worst_off < 1e-6);
  for (const auto& p : x["pairs"]) CHECK(p["accepted"].get<bool>());
}

TEST_CASE("ssid estimate --report: before and after, parameters, convergence and shapes are the JSON's", "[cli][report]") {
  const Report r = estimate_report();
  const json& j = r.j;
  check_run(j, r.html,
            {src("samples/mpi_rod.bdf"), src("samples/estimate/measured.unv"), src("samples/estimate/study.json"),
             (scratch() / "truth_frf.unv").string()});
  // The FRF figures carry the JSON's FRAC before and after the update.
  REQUIRE(j["frf_comparison"]["frfs"].size() == 2);
  for (std::size_t k = 0; k < 2; ++k) {
    const std::string fig = "<figure id=\"fig-frfc-" + std::to_string(k) + "\"";
    const auto at = r.html.find(fig);
    REQUIRE(at != std::string::npos);
    const Attributes a = attributes_of(r.html.substr(at + 8, r.html.find('>', at) - at - 8));
    const auto& x = j["frf_comparison"]["frfs"][k]["analyses"];
    CHECK(std::stod(a.at("data-frac-before")) == x[0]["frac"].get<double>());
    CHECK(std::stod(a.at("data-frac")) == x[1]["frac"].get<double>());
    CHECK(x[1]["frac"].get<double>() > x[0]["frac"].get<double>());  // the update brings the FRFs closer
  }
  const json& c0 = j["configurations"][0];
  std::set<std::pair<int, int>> paired;
  for (const auto& p : c0["pairs"]) {
    const auto& tm = c0["test_modes"];
    const int row = static_cast<int>(std::find(tm.begin(), tm.end(), p["test_mode"]) - tm.begin());
    paired.insert({row, p["fe_mode"].get<int>() - 1});
  }
  REQUIRE(paired.size() == 20);
  check_heat_map(figure(r.html, "fig-mac"), c0["correlation"], paired);
  // Before (the first cycle's pairs) and after (at the estimate).
  REQUIRE(j["initial_pairs"].size() == 20);
  const std::string errs = figure(r.html, "fig-errors");
  const auto after = marks(errs, "rect", "err-after"), before = marks(errs, "rect", "err-before");
  REQUIRE(after.size() == j["pairs"].size());
  REQUIRE(before.size() == j["initial_pairs"].size());
  for (std::size_t k = 0; k < after.size(); ++k) CHECK(num(after[k], "data-v") == j["pairs"][k]["error_pct"].get<double>());
  std::map<int, double> initial;
  for (const auto& p : j["initial_pairs"]) initial[p["test_mode"]] = p["error_pct"];
  for (const auto& b : before) CHECK(num(b, "data-v") == initial.at(static_cast<int>(num(b, "data-test-mode"))));
  const auto hollow = marks(figure(r.html, "fig-frequencies"), "circle", "freq-before");
  CHECK(hollow.size() == j["initial_pairs"].size());
  // Parameters: prior and posterior mean ± σ.
  const std::string pf = figure(r.html, "fig-parameters");
  const auto prior = marks(pf, "g", "prior"), post = marks(pf, "g", "posterior");
  REQUIRE(post.size() == j["parameters"].size());
  REQUIRE(prior.size() == j["parameters"].size());
  for (std::size_t k = 0; k < post.size(); ++k) {
    const auto& p = j["parameters"][k];
    CHECK(post[k].at("data-name") == p["name"].get<std::string>());
    CHECK(num(post[k], "data-v") == p["estimate"].get<double>());
    CHECK(num(post[k], "data-s") == p["posterior_std"].get<double>());
    CHECK(num(prior[k], "data-v") == p["initial"].get<double>());
    CHECK(num(prior[k], "data-s") == p["prior_std"].get<double>());
  }
  check_heat_map(figure(r.html, "fig-correlation"), j["identifiability"]["posterior_correlation"], {});
  // Convergence: every parameter at every cycle, and J per cycle.
  const auto conv = marks(figure(r.html, "fig-convergence"), "circle", "conv");
  REQUIRE(conv.size() == j["iterations"].size() * j["parameters"].size());
  for (const auto& c : conv) {
    const int cycle = static_cast<int>(num(c, "data-cycle"));
    const json* it = nullptr;
    for (const auto& i : j["iterations"])
      if (i["cycle"] == cycle) it = &i;
    REQUIRE(it);
    CHECK(num(c, "data-v") == (*it)["parameters"][c.at("data-name")].get<double>());
  }
  const auto obj = marks(figure(r.html, "fig-objective"), "circle", "objective");
  REQUIRE(obj.size() == j["iterations"].size());
  for (std::size_t k = 0; k < obj.size(); ++k) CHECK(num(obj[k], "data-v") == j["iterations"][k]["objective"].get<double>());
  check_shapes(r.html, j, c0["pairs"]);
  check_mems(r.html, j);
  check_xor(r.html, j["cross_orthogonality"], true);
}

TEST_CASE("ssid identify modes --report and --svg: the stabilisation diagram and the modes are the JSON's",
          "[cli][report][identify]") {
  const Report r = identify_report();
  const json& j = r.j;
  check_run(j, r.html, {(scratch() / "chain_frf.unv").string(), (scratch() / "chain_geometry.unv").string()});
  REQUIRE(j["modes"].size() == 3);
  const json& st = j["stabilisation"];
  // One symbol per pole of the diagram, at its frequency and order, of its class.
  const std::string svg = cli_slurp(scratch() / "stabilisation.svg");
  CHECK(svg.rfind("<?xml", 0) == 0);
  for (const std::string& drawing : {figure(r.html, "fig-stabilisation"), svg}) {
    std::vector<Attributes> poles;
    for (const char* tag : {"circle", "rect", "path"})
      for (const auto& a : marks(drawing, tag, "pole")) poles.push_back(a);
    REQUIRE(poles.size() == st["poles"].size());
    std::multiset<std::tuple<double, double, std::string>> drawn, listed;
    for (const auto& a : poles) drawn.insert({num(a, "data-x"), num(a, "data-y"), a.at("data-cls")});
    for (const auto& p : st["poles"]) listed.insert({p["hz"].get<double>(), p["order"].get<double>(), p["class"].get<std::string>()});
    CHECK(drawn == listed);
    const auto chosen = marks(drawing, "line", "chosen");
    REQUIRE(chosen.size() == 3);
    for (std::size_t m = 0; m < 3; ++m) CHECK(num(chosen[m], "data-x") == j["modes"][m]["hz"].get<double>());
    // Σ|H| behind: one point per FRF line.
    const auto sum = marks(drawing, "polyline", "frf-sum");
    REQUIRE(sum.size() == 1);
    const std::string pts = sum[0].at("points");
    CHECK(static_cast<std::size_t>(std::count(pts.begin(), pts.end(), ',')) == st["frf_sum"]["hz"].size());
  }
  // Σ|H|: the sum of the moduli of the three FRFs, at every line of the file.
  CHECK(st["frf_sum"]["hz"].size() == 2001);
  CHECK(st["frf_sum"]["hz"][40].get<double>() == 10.0);
  {
    const auto model = ident_test::chain_model(true, {0});
    const double w = 2 * M_PI * 10.0;
    using cd = std::complex<double>;
    const Eigen::MatrixXcd H = (model.K.cast<cd>() - w * w * model.M.cast<cd>() + cd(0, w) * model.C.cast<cd>()).inverse();
    CHECK(st["frf_sum"]["magnitude"][40].get<double>() == Approx(H.col(0).cwiseAbs().sum()).epsilon(1e-12));
  }
  // The FRFs of the identified modes (LSFD on ERA's poles) against the measured ones:
  // at 10 Hz both equal the chain's exact receptance (K − ω²M + iωC)⁻¹, a dense solve
  // here; the figure of each FRF carries the JSON's FRAC and one point per line.
  {
    const json& fit = j["frf_fit"];
    REQUIRE(fit["records"].size() == 3);
    const auto hz = fit["hz"].get<std::vector<double>>();
    CHECK(hz.size() == 2000);  // the lines above 0 Hz
    const auto at10 = static_cast<std::size_t>(std::find(hz.begin(), hz.end(), 10.0) - hz.begin());
    REQUIRE(at10 < hz.size());
    const auto model = ident_test::chain_model(true, {0});
    const double w = 2 * M_PI * 10.0;
    using cd = std::complex<double>;
    const Eigen::MatrixXcd H = (model.K.cast<cd>() - w * w * model.M.cast<cd>() + cd(0, w) * model.C.cast<cd>()).inverse();
    const auto figures = marks(r.html, "figure", "frf");
    REQUIRE(figures.size() == 3);
    for (std::size_t o = 0; o < 3; ++o) {
      const json& rec = fit["records"][o];
      CHECK(rec["response"][0].get<int>() == static_cast<int>(o) + 1);
      const cd exact = H(static_cast<Eigen::Index>(o), 0);
      for (const char* which : {"measured", "synthesized"}) {
        const cd v(rec[which]["re"][at10].get<double>(), rec[which]["im"][at10].get<double>());
        INFO(which << ", response " << o + 1);
        CHECK(std::abs(v - exact) < 1e-6 * std::abs(exact));
      }
      CHECK(rec["frac"].get<double>() > 0.99999);
      CHECK(num(figures[o], "data-frac") == rec["frac"].get<double>());
      const std::string fig = figure(r.html, "fig-frf-" + std::to_string(o));
      for (const char* cls : {"measured", "synthesized"}) {
        const auto lines = marks(fig, "polyline", cls);
        REQUIRE(lines.size() == 2);  // magnitude and phase
        const std::string pts = lines[1].at("points");
        CHECK(static_cast<std::size_t>(std::count(pts.begin(), pts.end(), ',')) == hz.size());
      }
    }
  }
  // Each chosen mode's poles: stable ones, as many as the mode's "orders".
  for (std::size_t m = 0; m < 3; ++m) {
    std::size_t n = 0;
    for (const auto& p : st["poles"])
      if (p["mode"] == static_cast<int>(m) + 1) {
        CHECK(p["class"] == "s");
        ++n;
      }
    CHECK(n == j["modes"][m]["orders"].get<std::size_t>());
  }
  // The table: frequency, damping, their σ, MPC, MPD.
  const auto rows = marks(r.html, "tr", "mode");
  REQUIRE(rows.size() == 3);
  for (std::size_t m = 0; m < 3; ++m) {
    const json& md = j["modes"][m];
    CHECK(num(rows[m], "data-hz") == md["hz"].get<double>());
    CHECK(num(rows[m], "data-hz-std") == md["hz_std"].get<double>());
    CHECK(num(rows[m], "data-zeta") == md["zeta"].get<double>());
    CHECK(num(rows[m], "data-zeta-std") == md["zeta_std"].get<double>());
    CHECK(num(rows[m], "data-mpc") == md["mpc"].get<double>());
    CHECK(num(rows[m], "data-mpd") == md["mpd_deg"].get<double>());
    // Real modes of a proportionally damped chain: collinear, no phase scatter.
    CHECK(md["mpc"].get<double>() > 0.9999);
    CHECK(md["mpd_deg"].get<double>() < 0.01);
  }
}

TEST_CASE("ssid identify modes --report --geometry: the identified shapes on the test's trace lines",
          "[cli][report][identify]") {
  const Report r = identify_report();
  const json& j = r.j;
  const json& g = j["geometry"];
  CHECK(g["grids"] == json::parse("[[1, 0.0, 0.0, 0.0], [2, 1.0, 0.0, 0.0], [3, 2.0, 0.0, 0.0]]"));
  CHECK(g["test_lines"] == json::parse("[[1, 2], [2, 3]]"));
  REQUIRE(j["identified_shapes"].size() == 3);
  const auto figures = marks(r.html, "figure", "identified-shape");
  REQUIRE(figures.size() == 3);
  for (std::size_t m = 0; m < 3; ++m) {
    const json& sh = j["identified_shapes"][m];
    const json& mode = j["modes"][m];
    CHECK(sh["mode"] == static_cast<int>(m) + 1);
    CHECK(sh["hz"] == mode["hz"]);
    CHECK(num(figures[m], "data-hz") == mode["hz"].get<double>());
    // Each node moves by the shape's real part along its measured direction in global:
    // +X at nodes 1 and 3, +Y at node 2 (its displacement system turned 90° about Z).
    REQUIRE(sh["points"].size() == 3);
    for (std::size_t o = 0; o < 3; ++o) {
      const double v = mode["shape"][o][2].get<double>();
      const json& p = sh["points"][o];
      CHECK(p[0] == static_cast<int>(o) + 1);
      const Eigen::Vector3d expected = o == 1 ? Eigen::Vector3d(0, v, 0) : Eigen::Vector3d(v, 0, 0);
      for (int k = 0; k < 3; ++k) CHECK(p[static_cast<std::size_t>(k) + 1].get<double>() == Approx(expected(k)).margin(1e-15));
    }
    // The drawing: one deformed wire frame per view, the undeformed one behind.
    const std::string fig = figure(r.html, "identified-" + std::to_string(m + 1));
    CHECK(marks(fig, "path", "deformed test").size() == 4);
  }
  // Without a geometry (the FRF file has no nodes) the report says why there are no shapes.
  const fs::path in = scratch() / "chain_frf.unv";
  const Report bare = run_report("identify_bare", "identify modes " + in.string());
  CHECK(!bare.j.contains("identified_shapes"));
  CHECK_THAT(bare.j["geometry_note"].get<std::string>(), Catch::Contains("no nodes; the identified shapes are not drawn"));
  CHECK(bare.html.find("no nodes; the identified shapes are not drawn") != std::string::npos);
}

TEST_CASE("ssid identify modes --svg needs ERA", "[cli][identify]") {
  const fs::path in = scratch() / "chain_frf.unv";
  write_chain_frf(ident_test::chain_model(true, {0}), in.string());
  const auto r = run_ssid("identify modes " + in.string() + " --method armax --svg " + (scratch() / "x.svg").string());
  CHECK(r.code == 2);
  CHECK(r.err == "ssid: error: --svg: the stabilisation diagram is ERA's and pLSCF's (--method era|plscf); ARMAX's modes "
                 "come from runs, not orders\n");
}

TEST_CASE("ssid diagnose --report: residuals, ranking, cause and gain are the JSON's", "[cli][report][slow]") {
  const Report r = diagnose_report();
  const json& j = r.j;
  check_run(j, r.html, {src("samples/mpi_rod.bdf"), src("samples/mpi_rod_hidden_mass.unv")});
  const json& e = j["evidence"];
  const auto mems = marks(figure(r.html, "fig-mems"), "rect", "mems");
  REQUIRE(mems.size() == e["modes"].size());
  for (std::size_t k = 0; k < mems.size(); ++k) CHECK(num(mems[k], "data-v") == e["modes"][k]["mems_error"].get<double>());
  const auto grid = marks(figure(r.html, "fig-grid-misfit"), "rect", "grid-misfit");
  REQUIRE(grid.size() == e["grid_misfit"].size());
  for (std::size_t k = 0; k < grid.size(); ++k) {
    CHECK(num(grid[k], "data-grid") == e["grid_misfit"][k]["grid"].get<double>());
    CHECK(num(grid[k], "data-v") == e["grid_misfit"][k]["share"].get<double>());
  }
  const auto rank = marks(figure(r.html, "fig-ranking"), "rect", "rank");
  REQUIRE(rank.size() == std::min<std::size_t>(12, j["ranking"].size()));
  for (std::size_t k = 0; k < rank.size(); ++k) CHECK(num(rank[k], "data-v") == j["ranking"][k]["log_evidence"].get<double>());
  // The cause on the structure: its grids marked.
  std::set<long> cause_grids, drawn;
  for (const auto& g : j["cause"]["location"]["grids"]) cause_grids.insert(g.get<long>());
  for (const auto& c : marks(figure(r.html, "fig-cause"), "circle", "cause")) drawn.insert(static_cast<long>(num(c, "data-grid")));
  CHECK(!cause_grids.empty());
  CHECK(drawn == cause_grids);
  const auto rms = marks(figure(r.html, "fig-gain-rms"), "rect", "gain");
  REQUIRE(rms.size() == 2);
  CHECK(num(rms[0], "data-v") == j["gain"]["before"]["freq_rms_pct"].get<double>());
  CHECK(num(rms[1], "data-v") == j["gain"]["after"]["freq_rms_pct"].get<double>());
}

TEST_CASE("ssid pretest --report: sensors, Fisher figures, cross-orthogonality, MIF/GA and the simulated test are the JSON's",
          "[cli][report]") {
  const Report r = pretest_report();
  const json& j = r.j;
  check_run(j, r.html, {src("samples/mpi_rod.bdf")});
  // The picture: four views, each with a marker per sensor DOF, per GA exciter and per given exciter.
  const std::string pic = figure(r.html, "fig-placement");
  CHECK(marks(pic, "g", "view").size() == 4);
  const auto sensors = marks(pic, "g", "sensor");
  REQUIRE(sensors.size() == 4 * j["sensors"].size());
  for (std::size_t k = 0; k < j["sensors"].size(); ++k) {
    CHECK(num(sensors[k], "data-grid") == j["sensors"][k]["grid"].get<double>());
    CHECK(num(sensors[k], "data-component") == j["sensors"][k]["component"].get<double>());
  }
  CHECK(marks(pic, "g", "exciter").size() == 4 * j["exciters"].size());
  CHECK(marks(pic, "g", "exciter-given").size() == 4 * 2);
  // Fisher determinant and condition number of every method; this run's is the top level's.
  REQUIRE(j["methods"].size() == 5);
  const auto det = marks(figure(r.html, "fig-fisher-det"), "rect", "fisher-det");
  const auto cond = marks(figure(r.html, "fig-fisher-cond"), "rect", "fisher-cond");
  REQUIRE(det.size() == 5);
  REQUIRE(cond.size() == 5);
  for (std::size_t k = 0; k < 5; ++k) {
    const json& m = j["methods"][k];
    CHECK(det[k].at("data-method") == m["method"].get<std::string>());
    CHECK(num(det[k], "data-v") == m["fisher_determinant"].get<double>());
    CHECK(num(cond[k], "data-v") == m["condition_number"].get<double>());
    if (m["method"] == j["method"]) {
      CHECK(m["fisher_determinant"] == j["fisher_determinant"]);
      CHECK(m["sensors"].size() == j["sensors"].size());
    }
  }
  // The target modes' cross-orthogonality for each TAM, the diagonal outlined.
  std::set<std::pair<int, int>> diagonal;
  for (int k = 0; k < 12; ++k) diagonal.insert({k, k});
  for (const char* tam : {"guyan", "irs", "serep"})
    check_heat_map(figure(r.html, std::string("fig-tam-") + tam), j["tam"][tam]["xor"], diagonal);
  // MIF drop-offs of the GA's and the given exciters; the GA per generation.
  check_heat_map(figure(r.html, "fig-mif"), j["mif_dropoff"], {});
  check_heat_map(figure(r.html, "fig-mif-given"), j["given_exciters"]["mif_dropoff"], {});
  const auto ga = marks(figure(r.html, "fig-ga"), "circle", "ga");
  REQUIRE(ga.size() == j["ga"]["best_per_generation"].size());
  for (std::size_t k = 0; k < ga.size(); ++k) CHECK(num(ga[k], "data-v") == j["ga"]["best_per_generation"][k].get<double>());
  // The simulated test: a row per target, the identified frequency where identified; its cross-orthogonality.
  const json& e = j["evaluation"];
  const auto rows = marks(r.html, "tr", "target");
  REQUIRE(rows.size() == 2 * e["targets"].size());  // the GA's and the given exciters' tests
  for (std::size_t k = 0; k < e["targets"].size(); ++k) CHECK(num(rows[k], "data-mode") == e["targets"][k]["mode"].get<double>());
  REQUIRE(e.contains("xor"));
  check_heat_map(figure(r.html, "fig-evaluation-xor"), e["xor"], {});
}

TEST_CASE("the samples' reports render in headless Chromium", "[cli][report][browser][slow]") {
  check_in_browser(correlate_report().path, 27);
  check_in_browser(estimate_report().path, 30);  // 28 and the two FRF figures
  check_in_browser(diagnose_report().path, 7);
  check_in_browser(pretest_report().path, 10);
  check_in_browser(identify_report().path, 1, 600);
}

TEST_CASE("ssid estimate --tam: Guyan and IRS cross-orthogonality at the estimate, as correlate gives the updated deck",
          "[cli][report][tam]") {
  // correlate --tam is checked against a dense condensation (test_cli_correlate_deck.cpp);
  // the estimate's figures must be the same on the deck update-deck writes from its result.
  const Report e = run_report("estimate_tam", "estimate -q " + src("samples/mpi_rod.bdf") + " " +
                                                  src("samples/estimate/measured.unv") + " --study " +
                                                  src("samples/estimate/study.json") + " --tam guyan,irs");
  const fs::path updated = scratch() / "estimate_tam_updated.bdf", cj = scratch() / "estimate_tam_correlate.json";
  REQUIRE(run_ssid("update-deck " + src("samples/mpi_rod.bdf") + " " + (scratch() / "estimate_tam.json").string() +
                   " -o " + updated.string()).code == 0);
  REQUIRE(run_ssid("correlate " + updated.string() + " " + src("samples/estimate/measured.unv") +
                   " --tam guyan,irs --json " + cj.string()).code == 0);
  const json c = json::parse(cli_slurp(cj));
  for (const char* tam : {"guyan", "irs"}) {
    INFO(tam);
    const json& xe = e.j["cross_orthogonality_tam"][tam];
    const json& xc = c["cross_orthogonality_tam"][tam];
    REQUIRE(!xe.contains("unavailable"));
    REQUIRE(!xc.contains("unavailable"));
    CHECK(xe["pairs"].size() == e.j["configurations"][0]["pairs"].size());
    const auto fe_e = xe["fe_modes"].get<std::vector<int>>(), fe_c = xc["fe_modes"].get<std::vector<int>>();
    const auto t_e = xe["test_modes"].get<std::vector<int>>(), t_c = xc["test_modes"].get<std::vector<int>>();
    std::size_t compared = 0;
    for (std::size_t i = 0; i < fe_e.size(); ++i) {
      const auto ic = std::find(fe_c.begin(), fe_c.end(), fe_e[i]) - fe_c.begin();
      if (ic == static_cast<long>(fe_c.size())) continue;
      for (std::size_t k = 0; k < t_e.size(); ++k) {
        const auto kc = std::find(t_c.begin(), t_c.end(), t_e[k]) - t_c.begin();
        if (kc == static_cast<long>(t_c.size())) continue;
        // The updated deck's DESVARs are written to the card's digits: 1e-8 absolute.
        CHECK(xe["matrix"][i][k].get<double>() ==
              Approx(xc["matrix"][static_cast<std::size_t>(ic)][static_cast<std::size_t>(kc)].get<double>()).margin(1e-8));
        ++compared;
      }
    }
    CHECK(compared >= 20 * 20);
    CHECK(e.html.find(std::string("id=\"fig-xor-") + tam + "\"") != std::string::npos);
  }
}

TEST_CASE("ssid estimate --report: the shapes of every configuration", "[cli][report][configurations]") {
  // Two configurations sharing the parameters: the sample (bare) and the same truss with
  // 5 kg at ball 41, its "measured" modes the truth deck's with that mass (ssid modes --uff,
  // as the sample's script writes them).
  const fs::path dir = scratch();
  const fs::path truth = dir / "cfg_truth.bdf", mass_truth = dir / "cfg_truth_mass.bdf", mass_deck = dir / "cfg_mass.bdf",
                 mass_unv = dir / "cfg_mass.unv", study = dir / "cfg_study.json";
  REQUIRE(run_ssid("update-deck " + src("samples/mpi_rod.bdf") + " " + src("samples/estimate/truth.json") + " -o " +
                   truth.string()).code == 0);
  auto with_mass = [](const std::string& deck) {
    const auto at = deck.rfind("ENDDATA");
    REQUIRE(at != std::string::npos);
    return deck.substr(0, at) + "CONM2   9001    41              5.0\n" + deck.substr(at);
  };
  std::ofstream(mass_truth) << with_mass(cli_slurp(truth));
  std::ofstream(mass_deck) << with_mass(cli_slurp(src("samples/mpi_rod.bdf")));
  std::string sensors;
  for (int g = 1; g <= 79; g += 2) sensors += (sensors.empty() ? "" : ",") + std::to_string(g);
  REQUIRE(run_ssid("modes " + mass_truth.string() + " --uff " + mass_unv.string() + " --sensors " + sensors).code == 0);
  json s = json::parse(cli_slurp(src("samples/estimate/study.json")));
  s["configurations"] = json::array({{{"name", "bare"}, {"deck", src("samples/mpi_rod.bdf")},
                                      {"measured", src("samples/estimate/measured.unv")}},
                                     {{"name", "mass"}, {"deck", mass_deck.string()}, {"measured", mass_unv.string()}}});
  std::ofstream(study) << s.dump(2);
  const Report r = run_report("estimate_configurations", "estimate -q " + src("samples/mpi_rod.bdf") + " " +
                                                             src("samples/estimate/measured.unv") + " --study " + study.string());
  const json& j = r.j;
  REQUIRE(j["configurations"].size() == 2);
  REQUIRE(j["configuration_shapes"].size() == 1);
  const json& c2 = j["configuration_shapes"][0];
  CHECK(c2["configuration"] == "mass");
  REQUIRE(c2["shapes"].size() == j["configurations"][1]["pairs"].size());
  for (std::size_t k = 0; k < c2["shapes"].size(); ++k) {
    CHECK(c2["shapes"][k]["fe_mode"] == j["configurations"][1]["pairs"][k]["fe_mode"]);
    CHECK(c2["shapes"][k]["test_mode"] == j["configurations"][1]["pairs"][k]["test_mode"]);
    // Drawn in its own section, with ids of its own and out of the first configuration's pair menu.
    const std::string id = "<figure id=\"c2-shape-" + std::to_string(k) + "\"";
    const auto at = r.html.find(id);
    REQUIRE(at != std::string::npos);
    const Attributes a = attributes_of(r.html.substr(at + 8, r.html.find('>', at) - at - 8));
    CHECK(num(a, "data-mac") == c2["shapes"][k]["mac"].get<double>());
    CHECK(a.count("data-pair") == 0);
  }
  CHECK(r.html.find("<section id=\"c2-shapes\">") != std::string::npos);
  CHECK(r.html.find("Mode shapes: configuration 2 (mass)") != std::string::npos);
  // Every deformed drawing's base exists (the animation swings each about it).
  for (std::size_t at = r.html.find("data-base=\""); at != std::string::npos; at = r.html.find("data-base=\"", at + 1)) {
    const std::string base = r.html.substr(at + 11, r.html.find('"', at + 11) - at - 11);
    CHECK(r.html.find("id=\"" + base + "\"") != std::string::npos);
  }
  // The first configuration's shapes are as without a second one.
  CHECK(j["shapes"].size() == j["configurations"][0]["pairs"].size());
  check_in_browser(r.path, 30);
}
