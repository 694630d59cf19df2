// translators::assemble_deck: the one way from a read deck to its model; what it
// refuses and how each refusal names its place.
#include <catch2/catch.hpp>

#include "formats/deck.hpp"
#include "translators/assembly/fe_model.hpp"

using namespace ssid;

namespace {
const char* kRods =
    "GRID    1               0.      0.      0.\n"
    "GRID    2               1.      0.      0.\n"
    "CROD    10      1       1       2\n"
    "PROD    1       2       1.-4\n"
    "MAT1    2       7.+10           .3      2700.\n"
    "SPC1    1       123456  1\n"
    "EIGRL   1                       2\n";

std::string refusal(const std::string& text) {
  const formats::Deck deck = formats::read_deck_text(text, "d.bdf");
  try {
    translators::assemble_deck(deck, "d.bdf");
  } catch (const formats::InputError& e) {
    return e.what();
  }
  return "assembled";
}
}  // namespace

TEST_CASE("assemble_deck: a whole deck assembles, its warnings passed on", "[assembly][integrity]") {
  const formats::Deck deck =
      formats::read_deck_text(std::string("SOL 103\nCEND\nSPC = 1\nMETHOD = 1\nBEGIN BULK\n") + kRods + "ENDDATA\n", "d.bdf");
  std::vector<std::string> warnings;
  const auto fe = translators::assemble_deck(deck, "d.bdf", {}, &warnings);
  REQUIRE(fe);
  CHECK(fe->bulk().crods.size() == 1);
  CHECK(fe->eigrl() != nullptr);
  CHECK(warnings.empty());
}

TEST_CASE("assemble_deck: what it refuses names the first card or statement at fault", "[assembly][integrity]") {
  const std::string head = "SOL 103\nCEND\nSPC = 1\nMETHOD = 1\nBEGIN BULK\n";
  // Deck errors: all of them, file:line each.
  CHECK(refusal(head + kRods + "CRDO    11      1       1       2\n") ==
        "d.bdf: 2 error(s) in the deck; nothing assembled:\n"
        "  d.bdf:13: missing ENDDATA: the bulk data begun at line 5 (BEGIN BULK) runs to the end of the file, as in a "
        "deck cut short\n"
        "  d.bdf:13: unknown card name CRDO \u2014 did you mean CROD?");
  // A real card ssid does not assemble: its first card.
  CHECK(refusal(head + kRods + "PSHELL  3       2       .01\nCQUAD4  7       3       1       2       2       1\n"
                    "CQUAD4  8       3       1       2       2       1\nENDDATA\n") ==
        "d.bdf:14: cannot assemble the model: CQUAD4 (2 cards, first at d.bdf:14): ssid cannot assemble this card and "
        "it may change K or M; remove it, model it with supported cards, or export K and M from NASTRAN (OP4 or "
        "DMIG) and build the operators with `ssid assemble --import SPEC.json`");
  // A case control selection with no card: the statement.
  CHECK(refusal("SOL 103\nCEND\nSPC = 1\nMETHOD = 7\nBEGIN BULK\n" + std::string(kRods) + "ENDDATA\n") ==
        "d.bdf:4: cannot assemble the model: METHOD = 7: no EIGRL or EIGR with that SID");
  CHECK(refusal("SOL 103\nCEND\nSUBCASE 1\n  SPC = 9\nMETHOD = 1\nBEGIN BULK\n" + std::string(kRods) + "ENDDATA\n") ==
        "d.bdf:4: cannot assemble the model: SPC = 9: no SPC, SPC1 or SPCADD with that SID");
  // An error the card's own label places: after the deck's name.
  CHECK(refusal(head + kRods + "PBARL   5       2               BOX9\n        1.      1.      .1      .1\n"
                    "CBAR    20      5       1       2       0.      1.      0.\nENDDATA\n") ==
        "d.bdf: cannot assemble the model: d.bdf:15: CBAR 20: section type BOX9 is not supported (ROD, TUBE, BAR, BOX, "
        "I, TUBE2, I1, CHAN, CHAN1, CHAN2, T, T1, T2, L, BOX1, CROSS, H, Z, HEXA, HAT, HAT1, DBOX are)");
  // Two assembled property types with one id: NASTRAN keeps them apart, ssid's values by id would not.
  CHECK(refusal(head + kRods + "PBEAM   1       2       1.-4    1.-8    1.-8            2.-8\n"
                    "CBEAM   20      1       1       2       0.      1.      0.\nENDDATA\n") ==
        "d.bdf:13: cannot assemble the model: PBEAM 1 shares its id with PROD 1 at d.bdf:9: NASTRAN keeps the two "
        "apart (an element looks its property up among its own types), ssid's assembly keys properties by id "
        "alone; give one of them another id");
  // A material of another type: a warning for the reader, a refusal for an element that uses it.
  const std::string thermal = "GRID    1               0.      0.      0.\n"
                              "GRID    2               1.      0.      0.\n"
                              "CROD    10      1       1       2\n"
                              "PROD    1       4       1.-4\n"
                              "MAT4    4       200.\n"
                              "EIGRL   1                       2\nENDDATA\n";
  CHECK(refusal("SOL 103\nCEND\nMETHOD = 1\nBEGIN BULK\n" + thermal) ==
        "d.bdf: cannot assemble the model: d.bdf:7: CROD 10: MAT1 4 (of PROD 1) does not exist (only MAT1 materials are "
        "assembled)");
}
