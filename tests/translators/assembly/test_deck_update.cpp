// update-deck (SD2NAS analogue): estimated DESVAR values into the deck, through
// DVPREL1/DVMREL1 into property, material and element fields; nothing else moves.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <unistd.h>

#include "formats/bulk_model.hpp"
#include "formats/deck_writer.hpp"
#include "translators/assembly/deck_update.hpp"
#include "translators/assembly/fe_model.hpp"

using namespace ssid;

namespace {

namespace fs = std::filesystem;

const char* deck_text =
    "$ three rods, a tip mass and a spring: parameters for the area, the modulus, the mass\n"
    "SOL 103\n"
    "CEND\n"
    "SPC = 1\n"
    "METHOD = 1\n"
    "BEGIN BULK\n"
    "EIGRL   1                       4\n"
    "GRID    1               0.      0.      0.\n"
    "GRID    2               1.      0.      0.\n"
    "GRID    3               2.      0.      0.\n"
    "GRID    4               3.      0.      0.\n"
    "CROD    10      1       1       2\n"
    "CROD    11      1       2       3\n"
    "CROD    12      2       3       4\n"
    "$ PROD 1 is designed; PROD 2 is not\n"
    "PROD    1       5       1.-4\n"
    "PROD    2       5       2.-4\n"
    "MAT1    5       7.+10           .3      2700.\n"
    "CONM2   100     4               2.5\n"
    "CELAS2  200     1000.   4       2\n"
    "SPC1    1       123456  1\n"
    "SPC1    1       23      2       3       4\n"
    "DESVAR  1       AREA    1.-4    1.-5    1.-3\n"
    "DESVAR  2       EMOD    7.+10   1.+10   1.+12\n"
    "DESVAR  3       TIPM    1.      .1      10.\n"
    "DVPREL1 10      PROD    1       A\n"
    "+       1       1.\n"
    "DVMREL1 11      MAT1    5       E\n"
    "+       2       1.\n"
    "DVPREL1 12      CONM2   100     M                       .5\n"
    "+       3       2.\n"
    "ENDDATA\n";

struct Loaded {
  formats::Deck deck;
  std::unique_ptr<translators::FeModel> fe;
};

Loaded load(const formats::Deck& source_like, const std::string& path) {
  Loaded l{formats::read_deck(path), nullptr};
  formats::BulkModel b = formats::parse_bulk(l.deck);
  formats::resolve(l.deck, b);
  REQUIRE(b.problems.empty());
  l.fe = std::make_unique<translators::FeModel>(l.deck, std::move(b));
  return l;
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::string line;
  for (char c : text) {
    if (c == '\n') {
      out.push_back(line);
      line.clear();
    } else {
      line += c;
    }
  }
  return out;
}

fs::path scratch() {
  const fs::path p = fs::temp_directory_path() / ("ssid_deck_update_" + std::to_string(::getpid()));
  fs::create_directories(p);
  return p;
}

}  // namespace

TEST_CASE("update-deck: DESVARs and designed fields take the new values, every other line is byte-identical",
          "[assembly][deck_update]") {
  const fs::path dir = scratch();
  const fs::path in = dir / "in.bdf", out = dir / "out.bdf";
  std::ofstream(in) << deck_text;
  formats::Deck deck = formats::read_deck(in.string());
  const auto rep = translators::update_deck(deck, {{"AREA", 1.234567891234e-4}, {"tipm", 1.3}, {"EMOD", 7e10}});
  if (fs::exists(out)) fs::remove(out);
  formats::write_deck(deck, out.string());
  CHECK(rep.parameters.size() == 2);  // EMOD unchanged
  CHECK(rep.cards_changed == 4);      // DESVAR 1, DESVAR 3, PROD 1, CONM2 100

  std::ifstream a(in), b(out);
  const std::string ta((std::istreambuf_iterator<char>(a)), {}), tb((std::istreambuf_iterator<char>(b)), {});
  const auto la = lines_of(ta), lb = lines_of(tb);
  // Lines of the four changed cards differ (a value that does not fit 8 columns
  // promotes its card to large field: two lines); every other line is the same.
  std::vector<std::string> kept_a, kept_b;
  auto changed = [](const std::string& l) {
    return l.rfind("DESVAR  1", 0) == 0 || l.rfind("DESVAR* 1", 0) == 0 || l.rfind("DESVAR  3", 0) == 0 ||
           l.rfind("PROD    1", 0) == 0 || l.rfind("PROD*   1", 0) == 0 || l.rfind("CONM2   100", 0) == 0 ||
           l.rfind("CONM2*  100", 0) == 0 || l.rfind("*", 0) == 0;
  };
  for (const auto& l : la)
    if (!changed(l)) kept_a.push_back(l);
  for (const auto& l : lb)
    if (!changed(l)) kept_b.push_back(l);
  CHECK(kept_a == kept_b);
  CHECK(kept_a.size() == la.size() - 4);

  // Values as the assembly derives them: PROD A = AREA, CONM2 M = 0.5 + 2 TIPM.
  const Loaded n = load(deck, out.string());
  const auto& bulk = n.fe->bulk();
  CHECK(bulk.prods[0].a == 1.234567891234e-4);
  CHECK(bulk.prods[1].a == 2e-4);
  CHECK(bulk.conm2s[0].m == 0.5 + 2 * 1.3);
  CHECK(bulk.desvars[0].xinit == 1.234567891234e-4);
  CHECK(bulk.desvars[1].xinit == 7e10);
  CHECK(bulk.desvars[2].xinit == 1.3);
  CHECK(bulk.mat1s[0].e == 7e10);

  // The written deck assembles to the operators of the old deck at the new values.
  const Loaded o = load(deck, in.string());
  Eigen::VectorXd x = o.fe->initial_parameters();
  x(0) = 1.234567891234e-4;
  x(2) = 1.3;
  const auto old_at_x = o.fe->operators(x, false);
  const auto new_at_init = n.fe->operators(n.fe->initial_parameters(), false);
  CHECK((Eigen::MatrixXd(old_at_x.K) - Eigen::MatrixXd(new_at_init.K)).norm() == 0.0);
  CHECK((Eigen::MatrixXd(old_at_x.M) - Eigen::MatrixXd(new_at_init.M)).norm() == 0.0);
}

TEST_CASE("update-deck: unchanged values leave the deck byte for byte; bad names and values are refused",
          "[assembly][deck_update]") {
  const fs::path dir = scratch();
  const fs::path in = dir / "same.bdf", out = dir / "same_out.bdf";
  std::ofstream(in) << deck_text;
  formats::Deck deck = formats::read_deck(in.string());
  const auto rep = translators::update_deck(deck, {{"AREA", 1e-4}, {"EMOD", 7e10}});
  CHECK(rep.cards_changed == 0);
  if (fs::exists(out)) fs::remove(out);
  formats::write_deck(deck, out.string());
  std::ifstream b(out);
  CHECK(std::string((std::istreambuf_iterator<char>(b)), {}) == deck_text);

  formats::Deck d2 = formats::read_deck(in.string());
  CHECK_THROWS_WITH(translators::update_deck(d2, {{"THICK", 1.0}}),
                    Catch::Contains("'THICK' is not a DESVAR label") && Catch::Contains("AREA, EMOD, TIPM"));
  CHECK_THROWS_WITH(translators::update_deck(d2, {{"AREA", 2e-3}}),
                    Catch::Contains("outside its DESVAR 1 bounds [1e-05, 0.001]"));
  CHECK_THROWS_WITH(translators::update_deck(d2, {{"AREA", NAN}}), Catch::Contains("not a finite number"));
}

TEST_CASE("update-deck reads only parameters[].name and .estimate from the JSON", "[assembly][deck_update]") {
  const auto v = translators::parameter_values_from_json(
      R"({"converged": true, "parameters": [{"name": "AREA", "estimate": 2e-4, "prior_std": 1}, {"name": "TIPM", "estimate": 1.5}],
          "pairs": "whatever"})",
      "r.json");
  CHECK(v.size() == 2);
  CHECK(v.at("AREA") == 2e-4);
  CHECK_THROWS_WITH(translators::parameter_values_from_json("{", "r.json"), Catch::Contains("r.json: not valid JSON"));
  CHECK_THROWS_WITH(translators::parameter_values_from_json(R"({"params": []})", "r.json"),
                    Catch::Contains("\"parameters\" array"));
  CHECK_THROWS_WITH(translators::parameter_values_from_json(R"({"parameters": [{"name": "A"}]})", "r.json"),
                    Catch::Contains("r.json: parameters[0] (A): expected a number \"estimate\""));
  CHECK_THROWS_WITH(translators::parameter_values_from_json(R"({"parameters": [{"estimate": 1}]})", "r.json"),
                    Catch::Contains("string \"name\""));
  CHECK_THROWS_WITH(
      translators::parameter_values_from_json(R"({"parameters": [{"name": "A", "estimate": 1}, {"name": "a", "estimate": 2}]})",
                                              "r.json"),
      Catch::Contains("given twice"));
  CHECK_THROWS_WITH(translators::parameter_values_from_json(R"({"parameters": []})", "r.json"), Catch::Contains("empty"));
}
