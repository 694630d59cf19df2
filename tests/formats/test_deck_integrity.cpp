// Deck integrity (docs/deck.md, "Deck integrity"): a missing ENDDATA, a card cut
// by the end of the file, a continuation with no parent, an unknown card name;
// each an error at its file:line, with the exact text.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include "formats/bulk_catalogue.hpp"
#include "formats/bulk_model.hpp"
#include "formats/deck.hpp"

using namespace ssid::formats;
namespace fs = std::filesystem;

namespace {
std::vector<std::string> messages(const std::vector<Problem>& problems) {
  std::vector<std::string> out;
  for (const auto& p : problems) out.push_back(p.str());
  return out;
}
using Lines = std::vector<std::string>;

const char* kHead = "SOL 103\nCEND\nMETHOD = 1\nBEGIN BULK\n";
}  // namespace

TEST_CASE("integrity: a deck with BEGIN BULK and ENDDATA, or bulk data only, has no problem", "[deck][integrity]") {
  const std::string bulk = "GRID    1               0.      0.      0.\nCROD    1       1       1       2\n";
  CHECK(read_deck_text(kHead + bulk + "ENDDATA\n$ after\n", "t.bdf").problems.empty());
  // A file of bulk data only (an INCLUDE file, or what ssid writes) has no ENDDATA to end it.
  CHECK(read_deck_text(bulk, "t.bdf").problems.empty());
  // A one-line large-field card is complete when ENDDATA follows it.
  CHECK(read_deck_text(std::string(kHead) + "CONM2*  1001            1                               1.36\nENDDATA\n", "t.bdf")
            .problems.empty());
  // ENDDATA in free field, lower case, with a comment.
  CHECK(read_deck_text(kHead + bulk + "enddata $ end\n", "t.bdf").problems.empty());
}

TEST_CASE("integrity: a missing ENDDATA is an error at the last line (NASTRAN UFM 219)", "[deck][integrity]") {
  Deck d = read_deck_text(std::string(kHead) + "GRID    1               0.      0.      0.\n$ last line\n", "t.bdf");
  CHECK(messages(d.problems) ==
        Lines{"t.bdf:6: missing ENDDATA: the bulk data begun at line 4 (BEGIN BULK) runs to the end of the file, "
              "as in a deck cut short"});
  CHECK(d.problems[0].severity == Problem::Severity::Error);
  REQUIRE(d.cards.size() == 1);  // the cards read are kept: the deck writes back unchanged
}

TEST_CASE("integrity: ENDDATA in an INCLUDEd file ends the bulk data", "[deck][integrity]") {
  const fs::path dir = fs::temp_directory_path() / "ssid_test_integrity_include";
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "main.bdf") << kHead << "INCLUDE 'tail.bdf'\n";
  std::ofstream(dir / "tail.bdf") << "GRID    1               0.      0.      0.\nENDDATA\n";
  CHECK(read_deck((dir / "main.bdf").string()).problems.empty());
  std::ofstream(dir / "tail.bdf") << "GRID    1               0.      0.      0.\n";
  CHECK(messages(read_deck((dir / "main.bdf").string()).problems) ==
        Lines{(dir / "main.bdf").string() +
              ":5: missing ENDDATA: the bulk data begun at line 4 (BEGIN BULK) runs to the end of the file, as in a "
              "deck cut short"});
}

TEST_CASE("integrity: a large-field card cut after its first line is named, with its line", "[deck][integrity]") {
  // samples/mpi_rod.bdf cut after the first line of a CONM2* card.
  Deck d = read_deck_text(std::string(kHead) +
                              "GRID    1               0.      0.      0.\n"
                              "CONM2*  1001            1                               1.36\n",
                          "cut.bdf");
  CHECK(messages(d.problems) ==
        Lines{"cut.bdf:6: CONM2 1001: card cut by the end of the file: a large-field card with no continuation "
              "line, and no ENDDATA follows",
              "cut.bdf:6: missing ENDDATA: the bulk data begun at line 4 (BEGIN BULK) runs to the end of the file, "
              "as in a deck cut short"});
  // A complete large-field card (first line and its '*' continuation) is not called cut.
  Deck whole = read_deck_text(std::string(kHead) +
                                  "CONM2*  1001            1                               1.36\n"
                                  "*       0.              0.              0.\n",
                              "whole.bdf");
  CHECK(messages(whole.problems) ==
        Lines{"whole.bdf:6: missing ENDDATA: the bulk data begun at line 4 (BEGIN BULK) runs to the end of the file, "
              "as in a deck cut short"});
}

TEST_CASE("integrity: a card cut in the middle of its last line is named", "[deck][integrity]") {
  Deck d = read_deck_text(std::string(kHead) + "GRID    1               0.      0.      0.\nGRID    2               1.", "cut.bdf");
  CHECK(messages(d.problems) ==
        Lines{"cut.bdf:6: GRID 2: card cut by the end of the file: its last line has no line ending, and no ENDDATA "
              "follows",
              "cut.bdf:6: missing ENDDATA: the bulk data begun at line 4 (BEGIN BULK) runs to the end of the file, "
              "as in a deck cut short"});
}

TEST_CASE("integrity: a continuation announced in field 10 that never comes", "[deck][integrity]") {
  Deck d = read_deck_text(std::string(kHead) + "PBAR    1       2       1.      2.      3.      4.      5.              +PB1\n",
                          "cut.bdf");
  CHECK(messages(d.problems) ==
        Lines{"cut.bdf:5: PBAR 1: unterminated continuation: field 10 holds '+PB1' but no continuation line follows",
              "cut.bdf:5: missing ENDDATA: the bulk data begun at line 4 (BEGIN BULK) runs to the end of the file, "
              "as in a deck cut short"});
}

TEST_CASE("integrity: a continuation line with no card before it (NASTRAN UFM 209)", "[deck][integrity]") {
  Deck d = read_deck_text(std::string(kHead) + "+C1     1.      2.\nGRID    1               0.      0.      0.\nENDDATA\n",
                          "orphan.bdf");
  CHECK(messages(d.problems) == Lines{"orphan.bdf:5: continuation line with no card before it (field 1 '+C1'); kept verbatim"});
  CHECK(d.problems[0].severity == Problem::Severity::Error);
  // Right after ENDDATA nothing is read, so nothing is an orphan there.
  CHECK(read_deck_text(std::string(kHead) + "ENDDATA\n+C1     1.\n", "t.bdf").problems.empty());
}

TEST_CASE("integrity: unknown card names are errors with the nearest name (NASTRAN UFM 307)", "[deck][integrity]") {
  Deck d = read_deck_text(std::string(kHead) +
                              "GRID    1               0.      0.      0.\n"
                              "GRID    2               1.      0.      0.\n"
                              "CRDO    10      1       1       2\n"
                              "XYZZY   1\n"
                              "CQUAD4  7       1       1       2       2       1\n"
                              "PSHELL  1       1       .01\n"
                              "ENDDTA\n",
                          "crdo.bdf");
  BulkModel m = parse_bulk(d);
  CHECK(messages(m.problems) == Lines{"crdo.bdf:7: unknown card name CRDO \u2014 did you mean CROD?",
                                      "crdo.bdf:8: unknown card name XYZZY (not a NASTRAN bulk data entry)",
                                      "crdo.bdf:11: unknown card name ENDDTA \u2014 did you mean ENDDATA?"});
  // Real entries ssid keeps verbatim are no problem; they stay counted as such.
  CHECK(m.unsupported.at("CQUAD4") == 1);
  CHECK(m.unsupported.at("PSHELL") == 1);
  CHECK(m.unsupported.at("CRDO") == 1);
  // The misspelt ENDDATA leaves the bulk data unended.
  CHECK(messages(d.problems) ==
        Lines{"crdo.bdf:11: missing ENDDATA: the bulk data begun at line 4 (BEGIN BULK) runs to the end of the file, "
              "as in a deck cut short"});
}

TEST_CASE("integrity: resolved_bulk refuses the deck with every error, file:line each", "[deck][integrity]") {
  Deck d = read_deck_text(std::string(kHead) +
                              "GRID    1               0.      0.      0.\n"
                              "GRID    2               1.      0.      0.\n"
                              "CRDO    10      1       1       2\n",
                          "crdo.bdf");
  try {
    resolved_bulk(d, "crdo.bdf");
    FAIL("resolved_bulk accepted a deck with errors");
  } catch (const ParseError&) {
    FAIL("a deck with several errors is an InputError, not one ParseError");
  } catch (const InputError& e) {
    CHECK(std::string(e.what()) ==
          "crdo.bdf: 2 error(s) in the deck; nothing assembled:\n"
          "  crdo.bdf:7: missing ENDDATA: the bulk data begun at line 4 (BEGIN BULK) runs to the end of the file, as "
          "in a deck cut short\n"
          "  crdo.bdf:7: unknown card name CRDO \u2014 did you mean CROD?");
  }
}

TEST_CASE("catalogue: every typed card and ENDDATA are bulk data entry names", "[deck][catalogue]") {
  for (const auto& name : supported_card_names()) {
    INFO(name);
    CHECK(is_bulk_entry_name(name));
  }
  CHECK(supported_card_names().size() >= 40);
  for (const char* name : {"ENDDATA", "CQUAD4", "CTRIA3", "CHEXA", "PSHELL", "PSOLID", "MAT8", "FORCE", "PLOAD4",
                           "TEMPD", "SUPORT", "ASET1", "CORD1R", "CDAMP1", "RBE3", "DRESP1", "AERO"})
    CHECK(is_bulk_entry_name(name));
  for (const char* name : {"CRDO", "ENDDTA", "GIRD", "XYZZY", "", "GRID*", "grid"}) CHECK_FALSE(is_bulk_entry_name(name));
  const auto& names = bulk_entry_names();
  CHECK(std::is_sorted(names.begin(), names.end()));
  CHECK(std::adjacent_find(names.begin(), names.end()) == names.end());
}

TEST_CASE("catalogue: edit distance with transpositions, nearest name within the limit", "[deck][catalogue]") {
  CHECK(edit_distance("CRDO", "CROD") == 1);     // one transposition
  CHECK(edit_distance("ENDDTA", "ENDDATA") == 1);  // one insertion
  CHECK(edit_distance("KITTEN", "SITTING") == 3);
  CHECK(edit_distance("", "ABC") == 3);
  CHECK(edit_distance("CA", "ABC") == 3);  // optimal string alignment, not unrestricted Damerau (2)
  CHECK(edit_distance("GRID", "GRID") == 0);
  CHECK(nearest_bulk_entry_name("CRDO") == std::optional<std::string>("CROD"));
  CHECK(nearest_bulk_entry_name("GIRD") == std::optional<std::string>("GRID"));
  CHECK(nearest_bulk_entry_name("ENDDTA") == std::optional<std::string>("ENDDATA"));
  CHECK(nearest_bulk_entry_name("PSHEL") == std::optional<std::string>("PSHELL"));
  // Ties go to the card ssid types: CONM3 is one edit from CONM1 and CONM2.
  CHECK(nearest_bulk_entry_name("CONM3") == std::optional<std::string>("CONM2"));
  // Too far: no suggestion rather than a wild one.
  CHECK_FALSE(nearest_bulk_entry_name("XYZZY"));
  CHECK_FALSE(nearest_bulk_entry_name("CRXX"));  // two edits from CROD, a short name allows one
}
