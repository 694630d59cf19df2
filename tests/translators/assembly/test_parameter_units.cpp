// What a DESVAR designs and its unit (parameter_units.hpp): from the deck's own
// "$ units:" comment, the designed fields, the coefficients and XINIT.
#include <catch2/catch.hpp>

#include "formats/bulk_model.hpp"
#include "formats/deck.hpp"
#include "translators/assembly/fe_model.hpp"
#include "translators/assembly/parameter_units.hpp"

using namespace ssid;
using translators::FeModel;

namespace {

/// A cantilever bar with a tip spring on a translation and one on a rotation,
/// and DESVARs of every kind of relation; `head` comes before SOL.
std::string deck(const std::string& head) {
  return head +
         "SOL 103\nCEND\nSPC = 1\nBEGIN BULK\n"
         "GRID,1,,0.,0.,0.\nGRID,2,,1.,0.,0.\nGRID,3,,2.,0.,0.\n"
         "CBAR,1,1,1,2,0.,1.,0.\nCBAR,2,1,2,3,0.,1.,0.\n"
         "CBUSH,3,7,2,3,0.,0.,1.\n"
         "CELAS2,4,5.0E5,3,3\n"
         "CELAS1,5,9,3,4\nPELAS,9,1.0E3\n"
         "PBAR,1,2,1.0E-3,2.0E-7,8.0E-7,1.0E-7\n"
         "PBUSH,7,K,1.0E5,2.0E5,3.0E5,1.0E3,2.0E3,3.0E3\n"
         "MAT1,2,7.0E10,,0.3,2700.\n"
         "SPC1,1,123456,1\n"
         "DESVAR,1,AREA,1.0E-3,1.0E-5,1.0\nDVPREL1,11,PBAR,1,A,,,,\n,1,0.5\n"
         "DESVAR,2,BUSHK,1.0\nDVPREL1,12,PBUSH,7,K1,,,,\n,2,1.0E5\nDVPREL1,13,PBUSH,7,K4,,,,\n,2,1.0E3\n"
         "DESVAR,3,SPRING,5.0E5\nDVPREL1,14,CELAS2,4,K,,,,\n,3,1.0\n"
         "DESVAR,4,TWIST,1.0E3\nDVPREL1,15,PELAS,9,K,,,,\n,4,1.0\n"
         "DESVAR,5,EAL,7.0E10\nDVMREL1,16,MAT1,2,E,,,,\n,5,1.0\n"
         "DESVAR,6,RHO,2700.\nDVMREL1,17,MAT1,2,RHO,,,,\n,6,1.0\n"
         "DESVAR,7,SECT,1.0\nDVPREL1,18,PBAR,1,I1,,,,\n,7,1.0\nDVPREL1,19,PBAR,1,A,,,,\n,7,1.0E-4\n"
         "ENDDATA\n";
}

struct Loaded {
  formats::Deck deck;
  formats::BulkModel bulk;
  std::unique_ptr<FeModel> model;
};

Loaded load(const std::string& text) {
  Loaded l{formats::read_deck_text(text, "units.bdf"), {}, nullptr};
  l.bulk = formats::parse_bulk(l.deck);
  formats::resolve(l.deck, l.bulk);
  REQUIRE(l.bulk.problems.empty());
  l.model = std::make_unique<FeModel>(l.deck, l.bulk);
  return l;
}

}  // namespace

TEST_CASE("a deck's \"$ units:\" comment names the parameters' units", "[assembly][units]") {
  const Loaded l = load(deck("$ MPI-like test deck\n$ units: SI (m, kg, N, Pa, s)\n"));
  const translators::DeckUnits u = translators::deck_units(l.deck);
  CHECK(u.si);
  CHECK(u.source == "units.bdf:2");
  CHECK(u.text == "SI (m, kg, N, Pa, s)");
  const auto& p = l.model->parameters();
  REQUIRE(p.size() == 7);
  auto unit = [&](std::size_t j) { return translators::parameter_unit(p[j], u, l.bulk); };
  // A coefficient that is a share (0.5) keeps the field's unit.
  CHECK(unit(0).unit == "m^2");
  CHECK(unit(0).designs == "PBAR A (1 card)");
  // XINIT 1 and no coefficient 1: a scale factor of the nominal values the coefficients carry.
  CHECK(unit(1).unit == "scale factor");
  CHECK(unit(1).designs == "PBUSH K1 (1 card), PBUSH K4 (1 card)");
  // Springs: N/m on a translation (CELAS2 on component 3), N m/rad on a rotation (CELAS1 on 4).
  CHECK(unit(2).unit == "N/m");
  CHECK(unit(3).unit == "N m/rad");
  CHECK(unit(4).unit == "Pa");
  CHECK(unit(5).unit == "kg/m^3");
  // One DESVAR on fields of two units, one coefficient 1: each unit named.
  CHECK(unit(6).unit == "m^4 | m^2");
  CHECK(unit(6).designs == "PBAR I1 (1 card), PBAR A (1 card)");
}

TEST_CASE("a deck without a unit system: deck units, with the quantity", "[assembly][units]") {
  for (const std::string& head : {std::string("$ no units stated\n"), std::string("$ Units: mm, t, s, N, MPa\n")}) {
    const Loaded l = load(deck(head));
    const translators::DeckUnits u = translators::deck_units(l.deck);
    CHECK(!u.si);
    CHECK(u.source == (head.find("Units") != std::string::npos ? "units.bdf:1" : ""));
    const auto& p = l.model->parameters();
    CHECK(translators::parameter_unit(p[0], u, l.bulk).unit == "deck units (area)");
    CHECK(translators::parameter_unit(p[1], u, l.bulk).unit == "scale factor");
    CHECK(translators::parameter_unit(p[2], u, l.bulk).unit == "deck units (translational stiffness)");
    CHECK(translators::parameter_unit(p[4], u, l.bulk).unit == "deck units (modulus)");
  }
  CHECK(translators::si_unit("PROD", "A") == "m^2");
  CHECK(translators::si_unit("CONM2", "M") == "kg");
  CHECK(translators::si_unit("PSOLID", "X").empty());
}
