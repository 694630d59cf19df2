// Deck integrity through the commands (issue 20): a cut deck, a misspelt card, a
// card ssid cannot assemble and test nodes that are not grids stop modes, assemble,
// estimate, correlate and diagnose with the file and line, exit 2 (bad input).
// Each test writes its own small decks.
#include <catch2/catch.hpp>

#include <fstream>
#include <iterator>

#include <nlohmann/json.hpp>
#include <sstream>
#include <unistd.h>

#include "cli_run.hpp"

namespace fs = std::filesystem;

namespace {

fs::path scratch() { return cli_scratch("integrity"); }

fs::path write(const fs::path& p, const std::string& text) {
  std::ofstream(p, std::ios::binary) << text;
  return p;
}

/// A fixed-free rod chain along x on the grids `ids` (the first clamped), one
/// DESVAR on the rods' area, small field. Lines: the bulk data starts at line 6.
std::string rod_deck(const std::vector<int>& ids, const std::string& extra = "", bool enddata = true) {
  std::ostringstream s;
  s << "SOL 103\nCEND\nSPC = 1\nMETHOD = 1\nBEGIN BULK\n";
  char b[96];
  for (std::size_t i = 0; i < ids.size(); ++i) {
    std::snprintf(b, sizeof b, "GRID    %-8d        %-8.3f0.      0.\n", ids[i], 0.25 * static_cast<double>(i));
    s << b;
  }
  for (std::size_t i = 0; i + 1 < ids.size(); ++i) {
    std::snprintf(b, sizeof b, "CROD    %-8zu1       %-8d%-8d\n", 100 + i, ids[i], ids[i + 1]);
    s << b;
  }
  s << "PROD    1       2       1.-4\n"
       "MAT1    2       7.+10           .3      2700.\n"
       "SPC1    1       123456  "
    << ids[0] << "\n"
    << "EIGRL   1                       4\n"
       "DESVAR  1       AREA    1.-4    1.-5    1.-3\n"
       "DVPREL1 10      PROD    1       A\n"
       "+       1       1.\n"
    << extra << (enddata ? "ENDDATA\n" : "");
  return s.str();
}

std::vector<int> ids(int n, int skip = -1, int instead = -1) {
  std::vector<int> v;
  for (int i = 1; i <= n; ++i) v.push_back(i == skip ? instead : i);
  return v;
}

/// The line of `text` (1-based) that starts with `prefix`.
int line_of(const std::string& text, const std::string& prefix) {
  std::istringstream in(text);
  std::string l;
  for (int n = 1; std::getline(in, l); ++n)
    if (l.rfind(prefix, 0) == 0) return n;
  return 0;
}

int line_count(const std::string& text) {
  return static_cast<int>(std::count(text.begin(), text.end(), '\n')) + (text.empty() || text.back() == '\n' ? 0 : 1);
}

/// A measured test (UFF 2411 + 55) of the chain on grids 1..n, from ssid modes.
fs::path measured(const fs::path& dir, int n) {
  const fs::path deck = write(dir / "truth.bdf", rod_deck(ids(n)));
  const fs::path unv = dir / "test.unv";
  fs::remove(unv);
  auto r = run_ssid("modes " + deck.string() + " --uff " + unv.string());
  INFO(r.err);
  REQUIRE(r.code == 0);
  return unv;
}

}  // namespace

TEST_CASE("cut deck: deck summary lists the cut card and the missing ENDDATA, exit 2; modes and assemble refuse it",
          "[cli][integrity]") {
  const fs::path dir = scratch();
  // The deck cut after the first line of a large-field CONM2 card, as a cut file ends.
  const std::string text = rod_deck(ids(11), "CONM2*  1001            11                              1.36\n", false);
  const fs::path deck = write(dir / "cut.bdf", text);
  const std::string at = deck.string() + ":" + std::to_string(line_count(text)) + ": ";
  const std::string cut = at + "CONM2 1001: card cut by the end of the file: a large-field card with no continuation "
                               "line, and no ENDDATA follows";
  const std::string missing = at + "missing ENDDATA: the bulk data begun at line 5 (BEGIN BULK) runs to the end of "
                                   "the file, as in a deck cut short";

  auto s = run_ssid("deck summary " + deck.string());
  CHECK(s.code == 2);
  CHECK_THAT(s.out, Catch::Contains("problems: 2 (2 error(s), 0 warning(s); listed on stderr)"));
  CHECK(s.err == cut + "\n" + missing + "\n");

  const std::string refused = "ssid: error: " + deck.string() + ": 2 error(s) in the deck; nothing assembled:\n  " + cut +
                              "\n  " + missing + "\n";
  auto m = run_ssid("modes " + deck.string());
  CHECK(m.code == 2);
  CHECK(m.out.empty());
  CHECK_THAT(m.err, Catch::EndsWith(refused));
  auto a = run_ssid("assemble " + deck.string() + " -o " + (dir / "op4").string());
  CHECK(a.code == 2);
  CHECK_THAT(a.err, Catch::EndsWith(refused));

  // The same deck with ENDDATA after the one-line CONM2* is whole: no problem, exit 0.
  const fs::path whole = write(dir / "whole.bdf", text + "ENDDATA\n");
  auto w = run_ssid("deck summary " + whole.string());
  CHECK(w.code == 0);
  CHECK_THAT(w.out, Catch::Contains("problems: 0 (0 error(s), 0 warning(s); listed on stderr)"));
  CHECK(w.err.empty());
}

TEST_CASE("misspelt cards: CRDO and ENDDTA named with the nearest real name; modes and estimate refuse the deck",
          "[cli][integrity]") {
  const fs::path dir = scratch();
  const fs::path unv = measured(dir, 6);
  std::string text = rod_deck(ids(6), "", false);
  text.replace(text.find("CROD    104"), 4, "CRDO");
  text += "ENDDTA\n";
  const fs::path deck = write(dir / "crdo.bdf", text);
  const std::string p = deck.string() + ":";
  const int crdo = line_of(text, "CRDO"), enddta = line_of(text, "ENDDTA");
  const std::string missing = p + std::to_string(enddta) +
                              ": missing ENDDATA: the bulk data begun at line 5 (BEGIN BULK) runs to the end of the "
                              "file, as in a deck cut short";
  const std::string crdo_msg = p + std::to_string(crdo) + ": unknown card name CRDO \u2014 did you mean CROD?";
  const std::string enddta_msg = p + std::to_string(enddta) + ": unknown card name ENDDTA \u2014 did you mean ENDDATA?";

  auto s = run_ssid("deck summary " + deck.string());
  CHECK(s.code == 2);
  CHECK_THAT(s.out, Catch::Contains("  CRDO      1  (unknown name: an error)\n"));
  CHECK_THAT(s.out, Catch::Contains("problems: 3 (3 error(s), 0 warning(s); listed on stderr)"));
  CHECK(s.err == missing + "\n" + crdo_msg + "\n" + enddta_msg + "\n");
  auto sj = run_ssid("deck summary " + deck.string() + " --json -");
  CHECK(sj.code == 2);
  const auto j = nlohmann::json::parse(sj.out);
  CHECK(j["unknown"] == nlohmann::json::array({"CRDO", "ENDDTA"}));
  CHECK(j["unsupported"]["CRDO"] == 1);
  CHECK(j["problems"].size() == 3);

  const std::string refused = deck.string() + ": 3 error(s) in the deck; nothing assembled:\n  " + missing + "\n  " +
                              crdo_msg + "\n  " + enddta_msg + "\n";
  auto m = run_ssid("modes " + deck.string());
  CHECK(m.code == 2);
  CHECK_THAT(m.err, Catch::EndsWith("ssid: error: " + refused));
  auto e = run_ssid("estimate " + deck.string() + " " + unv.string());
  CHECK(e.code == 2);
  CHECK_THAT(e.err, Catch::EndsWith("ssid: error: " + refused));
  auto d = run_ssid("diagnose " + deck.string() + " " + unv.string());
  CHECK(d.code == 2);
  CHECK_THAT(d.err, Catch::Contains(refused));
}

TEST_CASE("an orphan continuation line: deck summary names it, exit 2", "[cli][integrity]") {
  const fs::path dir = scratch();
  std::string text = rod_deck(ids(4));
  text.insert(text.find("BEGIN BULK\n") + 11, "+       1.      2.\n");  // before any card
  const fs::path deck = write(dir / "orphan.bdf", text);
  auto s = run_ssid("deck summary " + deck.string());
  CHECK(s.code == 2);
  CHECK(s.err == deck.string() + ":" + std::to_string(line_of(text, "+       1.      2.")) +
                     ": continuation line with no card before it (field 1 '+'); kept verbatim\n");
}

TEST_CASE("a card ssid cannot assemble: every command names the first one's file and line", "[cli][integrity]") {
  const fs::path dir = scratch();
  const fs::path unv = measured(dir, 6);
  const std::string text = rod_deck(ids(6), "PSHELL  3       2       .01\n"
                                            "CQUAD4  7       3       1       2       3       4\n"
                                            "CQUAD4  8       3       2       3       4       5\n");
  const fs::path deck = write(dir / "quad.bdf", text);
  const std::string at = deck.string() + ":" + std::to_string(line_of(text, "CQUAD4  7"));
  const std::string msg = at + ": cannot assemble the model: CQUAD4 (2 cards, first at " + at +
                          "): ssid cannot assemble this card and it may change K or M; remove it, model it with "
                          "supported cards, or export K and M from NASTRAN (OP4 or DMIG) and build the operators with "
                          "`ssid assemble --import SPEC.json`\n";
  // A real card kept verbatim is no problem for deck summary.
  auto s = run_ssid("deck summary " + deck.string());
  CHECK(s.code == 0);
  CHECK_THAT(s.out, Catch::Contains("  CQUAD4    2  (kept verbatim)\n"));
  for (const std::string& cmd : {"modes " + deck.string(), "assemble " + deck.string() + " -o " + (dir / "q").string(),
                                "estimate " + deck.string() + " " + unv.string(),
                                "correlate " + deck.string() + " " + unv.string(),
                                "diagnose " + deck.string() + " " + unv.string()}) {
    INFO(cmd);
    auto r = run_ssid(cmd);
    CHECK(r.code == 2);
    CHECK_THAT(r.err, Catch::EndsWith("ssid: error: " + msg));
  }
}

TEST_CASE("part superelement bulk data: deck summary reads the deck, modes names the BEGIN line", "[cli][integrity]") {
  // As in decks MSC Nastran ran (pyNastran's see101ta, see101nd): the residual's bulk data,
  // then BEGIN BULK SUPER = n and each part's cards, with ids of their own (GRID 1 again).
  const fs::path dir = scratch();
  const std::string text = rod_deck(ids(4), "BEGIN BULK SUPER = 1\n"
                                            "GRID    1               5.      0.      0.\n"
                                            "CRDO    100     1       1       2\n");
  const fs::path deck = write(dir / "parts.bdf", text);
  const std::string at = deck.string() + ":" + std::to_string(line_of(text, "BEGIN BULK SUPER"));
  auto s = run_ssid("deck summary " + deck.string());
  CHECK(s.code == 0);
  CHECK(s.err.empty());  // the part's cards are not read: no duplicate GRID 1, no unknown CRDO
  CHECK_THAT(s.out, Catch::Contains("partition BEGIN BULK SUPER = 1 at " + at +
                                    ": its bulk data kept verbatim, not read (ssid modes refuses it)\n"));
  auto m = run_ssid("modes " + deck.string());
  CHECK(m.code == 2);
  CHECK_THAT(m.err, Catch::EndsWith("ssid: error: " + at +
                                    ": cannot assemble the model: BEGIN BULK SUPER = 1: the bulk data after it (a part "
                                    "superelement or another partition) is kept verbatim and not assembled; ssid "
                                    "assembles one structure: export K and M from NASTRAN (OP4 or DMIG) and build the "
                                    "operators with `ssid assemble --import SPEC.json`\n"));
  // Written back byte for byte, the part included.
  auto w = run_ssid("deck write " + deck.string() + " -o " + (dir / "out" / "parts.bdf").string());
  CHECK(w.code == 0);
  std::ifstream in(dir / "out" / "parts.bdf", std::ios::binary);
  CHECK(std::string(std::istreambuf_iterator<char>(in), {}) == text);
  // A part that runs to the end of the file still lacks its ENDDATA.
  const fs::path cut = write(dir / "cut.bdf", rod_deck(ids(4), "BEGIN SUPER = 2\nGRID    1\n", false));
  auto c = run_ssid("deck summary " + cut.string());
  CHECK(c.code == 2);
  CHECK_THAT(c.err, Catch::Contains("missing ENDDATA"));
}

TEST_CASE("a case control selection with no card: the statement's file and line", "[cli][integrity]") {
  const fs::path dir = scratch();
  std::string text = rod_deck(ids(4));
  text.replace(text.find("METHOD = 1"), 10, "METHOD = 7");
  const fs::path deck = write(dir / "method.bdf", text);
  auto r = run_ssid("modes " + deck.string());
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Catch::EndsWith("ssid: error: " + deck.string() +
                                    ":4: cannot assemble the model: METHOD = 7: no EIGRL or EIGR with that SID\n"));
}

TEST_CASE("test nodes that are not grids of the deck: estimate, correlate, diagnose name the node", "[cli][integrity]") {
  const fs::path dir = scratch();
  const fs::path unv = measured(dir, 6);
  // The same chain with grid 5 numbered 50: test node 5 is no grid of it.
  const fs::path deck = write(dir / "renumbered.bdf", rod_deck(ids(6, 5, 50)));
  const std::string msg = unv.string() + ": test node 5: no grid with this id in the deck " + deck.string() + "\n";
  for (const std::string cmd : {"estimate", "correlate"}) {
    INFO(cmd);
    auto r = run_ssid(cmd + " " + deck.string() + " " + unv.string());
    CHECK(r.code == 2);
    CHECK_THAT(r.err, Catch::EndsWith("ssid: error: " + msg));
  }
  auto d = run_ssid("diagnose " + deck.string() + " " + unv.string());
  CHECK(d.code == 2);
  CHECK_THAT(d.err, Catch::EndsWith("test node 5: no grid with this id in the deck " + deck.string() + "\n"));

  // Two nodes: each listed.
  const fs::path two = write(dir / "two.bdf", rod_deck({1, 2, 3, 40, 50, 6}));
  auto t = run_ssid("estimate " + two.string() + " " + unv.string());
  CHECK(t.code == 2);
  CHECK_THAT(t.err, Catch::EndsWith("ssid: error: " + unv.string() + ": 2 measured test nodes map to no grid of the deck " +
                                    two.string() +
                                    ":\n  test node 4: no grid with this id\n  test node 5: no grid with this id\n"));
}
