// The card-traits table (formats/card_traits.*): one entry per card, and the
// entries agree with what resolve and the assembly did before the table existed.
#include <algorithm>
#include <cctype>
#include <fstream>
#include <set>
#include <sstream>

#include "card_test_util.hpp"
#include "formats/bulk_catalogue.hpp"
#include "formats/card_traits.hpp"

using namespace card_test;

namespace {

/// The id spaces as resolve scoped them before the table (its define and
/// define_verbatim lists), written out again here by hand: NASTRAN's scoping.
const std::map<std::string, IdSpace>& expected_spaces() {
  static const std::map<std::string, IdSpace> m = [] {
    std::map<std::string, IdSpace> s;
    auto put = [&](IdSpace space, std::initializer_list<const char*> names) {
      for (const char* n : names) s.emplace(n, space);
    };
    put(IdSpace::GridPoint, {"GRID", "SPOINT", "EPOINT"});
    put(IdSpace::Element, {"CROD",   "CONROD", "CBAR",   "CBEAM",  "CELAS1", "CELAS2", "CBUSH",   "CQUAD4", "CQUAD8",
                           "CQUADR", "CTRIA3", "CTRIA6", "CTRIAR", "CSHEAR", "CHEXA",  "CPENTA",  "CTETRA", "CPYRAM",
                           "CTUBE",  "CBEND",  "CGAP",   "CDAMP1", "CDAMP2", "CDAMP3", "CDAMP4",  "CVISC",  "CELAS3",
                           "CELAS4", "CBUSH1D", "CFAST", "CWELD"});
    put(IdSpace::MassElement, {"CONM2", "CMASS1", "CMASS2", "CMASS3", "CMASS4", "CONM1"});
    put(IdSpace::RigidElement, {"RBAR", "RBE2", "RBE3", "RBAR1", "RBE1", "RROD", "RSPLINE", "RSSCON", "RTRPLT"});
    put(IdSpace::PlotElement, {"PLOTEL", "PLOTEL3", "PLOTEL4", "PLOTEL6", "PLOTEL8", "PLOTTET", "PLOTPEN", "PLOTPYR",
                               "PLOTHEX"});
    put(IdSpace::Property, {"PROD",  "PBAR",   "PBARL", "PBEAM", "PBEAML", "PMASS", "PELAS", "PBUSH",
                            "PSHELL", "PCOMP", "PCOMPG", "PSOLID", "PSHEAR", "PTUBE", "PBEND", "PGAP",
                            "PDAMP", "PVISC", "PBUSH1D", "PBCOMP", "PFAST", "PWELD"});
    put(IdSpace::Material, {"MAT1", "MAT2", "MAT3", "MAT8", "MAT9", "MAT10", "MAT4", "MAT5"});
    put(IdSpace::CoordinateSystem, {"CORD2R", "CORD2C", "CORD2S", "CORD1R", "CORD1C", "CORD1S", "CORD3G", "CORD3R"});
    put(IdSpace::SpcSet, {"SPC", "SPC1"});
    put(IdSpace::SpcaddSet, {"SPCADD"});
    put(IdSpace::EigenMethod, {"EIGRL", "EIGR"});
    put(IdSpace::Desvar, {"DESVAR"});
    put(IdSpace::Dvprel, {"DVPREL1", "DVPREL2"});
    put(IdSpace::Dvmrel, {"DVMREL1", "DVMREL2"});
    return s;
  }();
  return m;
}

/// The cards the assembly noted as "ignored: no effect on K or M" before the
/// table (fe_model.cpp's no_effect_cards), less DMIG (typed and assembled, so
/// never among the cards kept verbatim) and CONM1X (no bulk data entry: its
/// card is an unknown-name error before any assembly).
const std::set<std::string>& expected_ignored() {
  static const std::set<std::string> s = {
      "FORCE",   "FORCE1",  "FORCE2",  "MOMENT",  "MOMENT1", "MOMENT2", "LOAD",    "PLOAD",   "PLOAD1",  "PLOAD2",
      "PLOAD4",  "PLOADX",  "MAT4",    "MAT5",    "GRAV",    "RFORCE",  "TEMP",    "TEMPD",   "TEMPP1",  "SPCD",    "DAREA",   "DLOAD",   "RLOAD1",
      "RLOAD2",  "TLOAD1",  "TLOAD2",  "DPHASE",  "DELAY",   "FREQ",    "FREQ1",   "FREQ2",   "FREQ3",   "FREQ4",
      "FREQ5",   "TSTEP",   "TABLED1", "TABLED2", "TABLED3", "TABLED4", "TABDMP1", "RANDPS",  "TABRND1", "EPOINT",
      "TF",      "NOLIN1",  "NOLIN2",  "NOLIN3",  "NOLIN4",  "DRESP1",  "DRESP2",  "DCONSTR", "DOPTPRM", "DEQATN",
      "DTABLE",  "DVPREL2", "DVMREL2", "DLINK",   "DCONADD", "AERO",    "AEROS",   "CAERO1",  "CAERO2",  "CAERO3",
      "CAERO4",  "CAERO5",  "PAERO1",  "PAERO2",  "PAERO3",  "PAERO4",  "PAERO5",  "SPLINE1", "SPLINE2", "SPLINE3",
      "SPLINE4", "SPLINE5", "SPLINE6", "SPLINE7", "SET1",    "SET2",    "AEFACT",  "AELINK",  "AELIST",  "AEPARM",
      "AESTAT",  "AESURF",  "AESURFS", "AECOMP",  "AECOMPL", "AEDW",    "AEFORCE", "AEPRESS", "CSSCHD",  "DIVERG",
      "FLFACT",  "FLUTTER", "GUST",    "MKAERO1", "MKAERO2", "TRIM",    "UXVEC",   "MONPNT1", "MONPNT2", "MONPNT3",
      "MONDSP1", "ENDDATA", "EIGB",    "EIGC",    "SUPORT",  "SUPORT1", "CVISC",   "PVISC",   "CDAMP1",  "CDAMP2",
      "CDAMP3",  "CDAMP4",  "CDAMP5",  "PDAMP",   "PDAMP5",  "NLPARM",  "DMI",     "DMIJ",    "DMIJI",   "DMIK",
      "TABLES1", "MATS1",   "CORD1R",  "CORD1C",  "CORD1S",  "DTI",     "USET",    "USET1",   "SEQGP",   "PLOTEL",
      // MSC's plot elements for faces and solids (display only), added with the corpus sweep
      "PLOTEL3", "PLOTEL4", "PLOTEL6", "PLOTEL8", "PLOTTET", "PLOTPEN", "PLOTPYR", "PLOTHEX"};
  return s;
}

std::vector<std::string> problems_of(const std::string& text) {
  Deck d = read_deck_text(text, "r.bdf");
  BulkModel m = parse_bulk(d);
  resolve(d, m);
  std::vector<std::string> out;
  for (const auto& p : m.problems) out.push_back(p.str());
  return out;
}

}  // namespace

TEST_CASE("card traits: every card the parser knows has exactly one entry", "[card_traits]") {
  std::map<std::string, int> entries;
  for (const CardTraits& t : card_traits()) {
    REQUIRE_FALSE(t.names.empty());
    for (const std::string& n : t.names) ++entries[n];
  }
  for (const auto& [name, count] : entries) {
    INFO(name);
    CHECK(count == 1);
    CHECK(is_bulk_entry_name(name));  // a misspelt name in the table would never match a card
    REQUIRE(find_card_traits(name) != nullptr);
    CHECK(std::count(find_card_traits(name)->names.begin(), find_card_traits(name)->names.end(), name) == 1);
  }
  // Typed: exactly the cards parse_bulk read before the table (its parsers list,
  // written out again here; is_supported_card asks the table itself).
  // CELAS3/4, CMASS3/4: the scalar-point forms, typed since (h-nastran).
  const std::vector<std::string> parsed = {
      "BAROR",  "BEAMOR", "CBAR",   "CBEAM",  "CBUSH",   "CELAS1",  "CELAS2", "CELAS3", "CELAS4", "CMASS1",
      "CMASS2", "CMASS3", "CMASS4", "CONM2",  "CONROD",  "CORD2C",  "CORD2R", "CORD2S", "CROD",   "DESVAR",
      "DMIG",   "DVMREL1", "DVPREL1", "EIGR", "EIGRL",   "GRDSET",  "GRID",   "MAT1",   "MPC",    "PARAM",
      "PBAR",   "PBARL",  "PBEAM",  "PBEAML", "PBUSH",   "PELAS",   "PMASS",  "PROD",   "RBAR",   "RBE2",
      "RBE3",   "SPC",    "SPC1",   "SPCADD", "SPOINT"};
  CHECK(supported_card_names() == parsed);
  for (const std::string& name : parsed) {
    INFO(name);
    const CardTraits* t = find_card_traits(name);
    REQUIRE(t != nullptr);
    CHECK(t->typed());
  }
  for (const std::string_view name : bulk_entry_names()) {
    const CardTraits* t = find_card_traits(std::string(name));
    INFO(name);
    CHECK(is_supported_card(std::string(name)) == (t && t->typed()));
  }
  // A typed card has all its behaviour; DMIG is counted, read by formats/dmig.*.
  for (const CardTraits& t : card_traits()) {
    INFO(t.names.front());
    if (!t.typed()) {
      CHECK_FALSE(static_cast<bool>(t.write));
      CHECK_FALSE(static_cast<bool>(t.each_id));
      CHECK(t.references.empty());
      continue;
    }
    if (t.names.front() == "DMIG") continue;
    CHECK(static_cast<bool>(t.write));
    CHECK(static_cast<bool>(t.resolve));
    CHECK(static_cast<bool>(t.each_id) == (t.space != IdSpace::None));
  }
}

TEST_CASE("card traits: id spaces are NASTRAN's scoping, as resolve kept it before the table", "[card_traits]") {
  std::set<std::string> with_space;
  for (const CardTraits& t : card_traits())
    for (const std::string& n : t.names) {
      INFO(n);
      auto it = expected_spaces().find(n);
      if (t.space == IdSpace::None) {
        CHECK(it == expected_spaces().end());
        continue;
      }
      REQUIRE(it != expected_spaces().end());
      CHECK(t.space == it->second);
      with_space.insert(n);
    }
  CHECK(with_space.size() == expected_spaces().size());
  CHECK(std::string(id_space_noun(IdSpace::Element)) == "element");
  CHECK(std::string(id_space_noun(IdSpace::MassElement)) == "mass element");
}

TEST_CASE("card traits: resolve defines each card's id in the space of its entry", "[card_traits]") {
  // Typed cards: one card of each type from the golden decks, given twice, is a
  // duplicate in the space the hand-written list above names.
  std::map<std::string, std::string> sample;  // name -> one card's text
  for (const char* file : {"cards/elements.bdf", "cards/scalar.bdf", "cards/coord.bdf", "cards/constraints.bdf"}) {
    Deck d = read_deck(std::string(SSID_TEST_DATA) + "/" + file);
    BulkModel m = parse_bulk(d);
    for (const auto& [card, values] : write_bulk(m)) {
      const std::string& name = d.cards[card].name;
      if (!sample.count(name)) sample[name] = format_card(name, values, FieldFormat::Small);
    }
  }
  std::size_t checked = 0;
  for (const CardTraits& t : card_traits()) {
    if (!t.typed() || t.space == IdSpace::None) continue;
    for (const std::string& name : t.names) {
      auto s = sample.find(name);
      if (s == sample.end()) continue;  // not in the golden decks
      INFO(name);
      Deck d = read_deck_text(s->second + s->second, "r.bdf");
      BulkModel m = parse_bulk(d);
      std::int64_t id = 0;
      t.each_id(m, [&](std::int64_t x, std::size_t) { id = x; });
      resolve(d, m);
      std::string lines;
      for (const auto& p : m.problems) lines += p.str() + "\n";
      const IdSpace space = expected_spaces().at(name);
      const std::string duplicate =
          "duplicate " + std::string(id_space_noun(space)) + " " + std::to_string(id) + " (" + name;
      if (t.repeats_allowed) CHECK(lines.find("duplicate") == std::string::npos);
      else CHECK(lines.find(duplicate) != std::string::npos);
      ++checked;
    }
  }
  CHECK(checked >= 30);

  // Cards kept verbatim: one of each with id 7 in one deck; duplicates arise
  // within a space (and in the property space within a family) and never across.
  std::string deck;
  std::map<std::pair<IdSpace, std::string>, std::vector<std::string>> by_space;
  std::size_t line = 0;
  std::map<std::string, std::size_t> line_of;
  for (const CardTraits& t : card_traits()) {
    if (t.typed() || t.space == IdSpace::None) continue;
    deck += t.names.front() + ",7\n";
    line_of[t.names.front()] = ++line;
    const IdSpace space = expected_spaces().at(t.names.front());
    by_space[{space, id_family(space, t.names.front())}].push_back(t.names.front());
  }
  std::vector<std::string> expected;
  for (const auto& [key, names] : by_space)
    for (std::size_t k = 1; k < names.size(); ++k)
      expected.push_back("r.bdf:" + std::to_string(line_of[names[k]]) + ": duplicate " + id_space_noun(key.first) +
                         " 7 (" + names[k] + "; first defined by " + names[0] + " at r.bdf:" +
                         std::to_string(line_of[names[0]]) + ")");
  std::vector<std::string> got = problems_of(deck);
  std::sort(got.begin(), got.end());
  std::sort(expected.begin(), expected.end());
  CHECK(got == expected);
  CHECK(by_space.size() >= 8);
  CHECK(by_space.at({IdSpace::Property, "shell"}) == std::vector<std::string>{"PSHELL", "PCOMP", "PCOMPG"});
}

TEST_CASE("card traits: the cards SOL 103 ignores are those the assembly noted before the table", "[card_traits]") {
  std::set<std::string> ignored;
  for (const CardTraits& t : card_traits())
    if (t.effect == Effect::IgnoredInSol103) {
      INFO(t.names.front());
      CHECK_FALSE(t.typed());
      CHECK(std::string(t.ignored_because).size() > 0);
      ignored.insert(t.names.begin(), t.names.end());
    }
  CHECK(ignored == expected_ignored());
  // What changes K or M is typed, or kept verbatim and refused by the assembly.
  CHECK(find_card_traits("CQUAD4")->effect == Effect::StiffnessAndMass);
  CHECK(find_card_traits("CONM2")->effect == Effect::Mass);
  CHECK(find_card_traits("PELAS")->effect == Effect::Stiffness);
  CHECK(find_card_traits("EIGRL")->effect == Effect::Solution);
}

TEST_CASE("card traits: docs/cards.md lists every typed card", "[card_traits][docs]") {
  std::ifstream in(std::string(SSID_SOURCE_DIR) + "/docs/cards.md");
  REQUIRE(in);
  std::stringstream text;
  text << in.rdbuf();
  const std::string doc = text.str();
  auto names_it = [&](const std::string& name) {  // as a word, not inside a longer name
    auto word = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) != 0; };
    for (auto at = doc.find(name); at != std::string::npos; at = doc.find(name, at + 1))
      if ((at == 0 || !word(doc[at - 1])) && (at + name.size() == doc.size() || !word(doc[at + name.size()])))
        return true;
    return false;
  };
  for (const std::string& name : supported_card_names()) {
    INFO(name);
    CHECK(names_it(name));
  }
}
