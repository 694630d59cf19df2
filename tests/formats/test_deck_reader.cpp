#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include "formats/deck.hpp"
#include "formats/deck_writer.hpp"
#include "formats/field_reader.hpp"

using namespace ssid::formats;
namespace fs = std::filesystem;

namespace {
fs::path scratch(const std::string& name) {
  fs::path p = fs::temp_directory_path() / ("ssid_test_reader_" + name);
  fs::remove_all(p);
  fs::create_directories(p);
  return p;
}
void put(const fs::path& p, const std::string& text) {
  fs::create_directories(p.parent_path());
  std::ofstream(p, std::ios::binary) << text;
}
std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}
}  // namespace

TEST_CASE("small field: columns 1-8, 9-72 in eights, 73-80 marker, 81+ ignored", "[deck]") {
  Deck d = read_deck_text(
      "GRID    1       2       1.5     2.5     3.5     4       123     7       +G1     ignored\n", "t.bdf");
  REQUIRE(d.cards.size() == 1);
  const Card& c = d.cards[0];
  CHECK(c.name == "GRID");
  CHECK(c.format == FieldFormat::Small);
  REQUIRE(c.size() == 9);
  CHECK(c.field(1) == "1");
  CHECK(c.field(2) == "2");
  CHECK(c.field(3) == "1.5");
  CHECK(c.field(8) == "7");
  CHECK(c.line == 1);
}

TEST_CASE("continuations: explicit markers, blank field 1, '+' and '*'", "[deck]") {
  const char* text =
      "$ comment before\n"
      "PBAR    1       2       1.      2.      3.      4.      5.              +PB1\n"
      "+PB1    1.      2.      3.      4.\n"
      "$ a comment inside the card\n"
      "        9.      8.\n"
      "CROD    7       1       1       2\n";
  Deck d = read_deck_text(text, "t.bdf");
  REQUIRE(d.cards.size() == 2);
  const Card& p = d.cards[0];
  CHECK(p.field(7) == "5.");
  CHECK(p.field(9) == "1.");
  CHECK(p.field(12) == "4.");
  CHECK(p.field(17) == "9.");
  CHECK(p.field(18) == "8.");
  CHECK(p.line_of(18) == 5);
  CHECK(p.line_of(10) == 3);
  CHECK(d.cards[1].line == 6);
  CHECK(d.problems.empty());
}

TEST_CASE("large field: NAME* with four 16-column fields and '*' continuations", "[deck]") {
  const char* text =
      "GRID*                  1               0             1.5             2.5*G1\n"
      "*G1                  3.5               0\n";
  Deck d = read_deck_text(text, "t.bdf");
  REQUIRE(d.cards.size() == 1);
  const Card& c = d.cards[0];
  CHECK(c.name == "GRID");
  CHECK(c.format == FieldFormat::Large);
  CHECK(c.field(1) == "1");
  CHECK(c.field(3) == "1.5");
  CHECK(c.field(4) == "2.5");
  CHECK(c.field(5) == "3.5");
  CHECK(c.field(6) == "0");
}

TEST_CASE("NASTRAN's tolerated forms: a blank before the large-field '*', text after ENDDATA's name", "[deck]") {
  // "CORD2R *" in field 1 (a deck MSC ran: pyNastran's se_test_n11.asm) is the
  // large-field CORD2R; "ENDDATA 58e050da" (pyNastran writes a checksum there)
  // ends the bulk data as ENDDATA does: NASTRAN reads field 1 only.
  const char* text =
      "SOL 103\nCEND\nBEGIN BULK\n"
      "CORD2R *               5               0              0.              0.\n"
      "*                     0.              0.              0.              1.\n"
      "*                     1.              0.              0.\n"
      "ENDDATA 58e050da\n";
  Deck d = read_deck_text(text, "t.bdf");
  REQUIRE(d.cards.size() == 1);
  CHECK(d.cards[0].name == "CORD2R");
  CHECK(d.cards[0].format == FieldFormat::Large);
  CHECK(d.cards[0].field(1) == "5");
  CHECK(d.cards[0].field(8) == "1.");
  CHECK(d.cards[0].field(9) == "1.");
  CHECK(d.problems.empty());
}

TEST_CASE("free field, lower case, tabs, and mixed formats in one deck", "[deck]") {
  const char* text =
      "grid,1,,1.,2.,3.\n"
      "GRID\t2\t\t4.\t5.\t6.\n"
      "cbar,5,1,1,2,0.,1.,0.,,+\n"
      "+,,,,1.\n"
      "GRID*,3,,7.,8.\n"
      "*,9.\n";
  Deck d = read_deck_text(text, "t.bdf");
  REQUIRE(d.cards.size() == 4);
  CHECK(d.cards[0].format == FieldFormat::Free);
  CHECK(d.cards[0].field(3) == "1.");
  CHECK(d.cards[1].field(3) == "4.");
  CHECK(d.cards[1].field(5) == "6.");
  CHECK(d.cards[2].name == "CBAR");
  CHECK(d.cards[2].field(7) == "0.");
  CHECK(d.cards[2].field(12) == "1.");
  CHECK(d.cards[3].field(3) == "7.");
  CHECK(d.cards[3].field(5) == "9.");
}

TEST_CASE("free field: a line ended by a comma after its continuation marker", "[deck]") {
  // As in a deck MSC Nastran ran (pyNastran's models/other/conedg01e.bdf): field 10 holds
  // the marker and a comma follows it. Something after field 10 is still a field too many.
  const char* text =
      "CORD2R, 5, , 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, +C1,\n"
      "+C1, 0.0, 1.0, 1.0\n"
      "GRID,7,,1.,2.,3.,,,,,\n";
  Deck d = read_deck_text(text, "t.bdf");
  REQUIRE(d.cards.size() == 2);
  CHECK(d.cards[0].name == "CORD2R");
  CHECK(d.cards[0].field(8) == "1.0");
  CHECK(d.cards[0].field(9) == "0.0");  // the continuation's first field
  CHECK(d.cards[0].field(11) == "1.0");
  CHECK(d.cards[0].field(12).empty());
  CHECK(d.cards[1].field(5) == "3.");
  CHECK(render_file(d, 0) == text);  // written back as read
  // A value after field 10 is kept as data (the card's reader then finds a field too many).
  const Deck e = read_deck_text("CORD2R, 5, , 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, +C1, 7\n+C1, 0.0, 1.0, 1.0\n", "t.bdf");
  REQUIRE(e.cards.size() == 1);
  CHECK(e.cards[0].field(9) == "7");
}

TEST_CASE("a free-field line ended by a comma is continued by a line of bare values", "[deck]") {
  // As in a deck MSC Nastran ran (pyNastran's models/contact/contact.bdf): a BSURF list whose
  // lines end with a comma and continue as rows of eight ids, no markers.
  const char* text =
      "BSURF, 1,1050,1133,1146,1125,1143,1055,$ first row\n"
      "1054,1002,1025,1077,1194,1157,1164,1131,$\n"
      "2118,1476,1216\n"
      "GRID,7,,1.,2.,3.,\n"
      "GRID,8,,4.,5.,6.\n";
  Deck d = read_deck_text(text, "t.bdf");
  REQUIRE(d.cards.size() == 3);
  CHECK(d.problems.empty());
  const Card& b = d.cards[0];
  CHECK(b.name == "BSURF");
  CHECK(b.field(1) == "1");
  CHECK(b.field(7) == "1055");
  CHECK(b.field(8).empty());       // the first line's trailing comma: an empty field 9
  CHECK(b.field(9) == "1054");     // the next row's field 2
  CHECK(b.field(16) == "1131");    // its field 9
  CHECK(b.field(17) == "2118");    // the third row's field 2
  CHECK(b.field(19) == "1216");
  CHECK(b.fields().size() == 20);
  // A card name never starts with a digit: a trailing comma before a card is only an empty field.
  CHECK(d.cards[1].name == "GRID");
  CHECK(d.cards[1].field(5) == "3.");
  CHECK(d.cards[2].field(1) == "8");
  CHECK(render_file(d, 0) == text);  // written back as read
  // Ten bare values: the ninth is the row's field 10 (a marker no line answers), the tenth
  // stays data; none is dropped.
  const Deck f = read_deck_text("BSURF, 1,1050,\n1,2,3,4,5,6,7,8,9,10\n", "t.bdf");
  REQUIRE(f.cards.size() == 1);
  CHECK(f.cards[0].field(16) == "8");
  CHECK(f.cards[0].field(17) == "10");
  REQUIRE(f.problems.size() == 1);
  CHECK(f.problems[0].message.find("field 10 holds '9'") != std::string::npos);
  // A line of bare values after a line with no trailing comma is what it was: an unknown card.
  const Deck e = read_deck_text("BSURF, 1,1050,1133\n1054,1002\n", "t.bdf");
  REQUIRE(e.cards.size() == 2);
  CHECK(e.cards[1].name == "1054");
}

namespace {
std::vector<std::string> fields_of(const Card& c) {
  std::vector<std::string> out;
  for (std::string_view f : c.fields()) out.emplace_back(f);
  return out;
}
using Fields = std::vector<std::string>;
}  // namespace

TEST_CASE("free-field replication: =, ==, *x and *(x), =n and =(n) lines", "[deck][replication]") {
  // The rules of the Quick Reference Guide's free field format, values worked by hand:
  // "=" copies a field, "==" it and all after it, "*x" adds x, "=n" makes n more entries
  // with the last "=" line's increments; fields a line does not reach are blank.
  const std::string text =
      "GRID,101,17,1.0,10.5,,17,3456\n"
      "=,*1,=,*0.2,==\n"
      "=2\n"
      "CBEAM,  201,    1,      201,    202,    10.,    45.,    0.\n"
      "=,      *(1),   =,      *(1),   *(1),   ==\n"
      "=(2) $ two more\n"
      "$ a comment between\n"
      "GRID,   123,    1,      25.,    -60.4,  0.,\n"
      "=,      *(1),   =,      =,      *(14.8),=,      *(1)\n"
      "RINGAX,1000,,5.0,0.0,,,123456\n"
      "=,*(1),,=,*(0.2)\n"
      "MAT1,1,1.0+7,,0.3\n";
  Deck d = read_deck_text(text, "r.bdf");
  INFO((d.problems.empty() ? std::string() : d.problems[0].str()));
  CHECK(d.problems.empty());
  REQUIRE(d.cards.size() == 13);
  CHECK(fields_of(d.cards[1]) == Fields{"GRID", "102", "17", "1.2", "10.5", "", "17", "3456"});
  CHECK(fields_of(d.cards[2]) == Fields{"GRID", "103", "17", "1.4", "10.5", "", "17", "3456"});
  CHECK(fields_of(d.cards[3]) == Fields{"GRID", "104", "17", "1.6", "10.5", "", "17", "3456"});
  CHECK(fields_of(d.cards[5]) == Fields{"CBEAM", "202", "1", "202", "203", "10.", "45.", "0."});
  CHECK(fields_of(d.cards[7]) == Fields{"CBEAM", "204", "1", "204", "205", "10.", "45.", "0."});
  // A blank field incremented counts as zero (CD of GRID 124); -60.4 + 14.8 = -45.6 exactly
  // as a decimal sum, not the double's -45.599999999999994.
  CHECK(fields_of(d.cards[9]) == Fields{"GRID", "124", "1", "25.", "-45.6", "0.", "1"});
  // The field the line leaves blank is blank, the fields it does not reach too.
  CHECK(fields_of(d.cards[11]) == Fields{"RINGAX", "1001", "", "5.0", ".2"});
  CHECK(d.cards[12].name == "MAT1");  // a one-line card after a replication is a card
  // Each replicated entry is a card at its line; the first of an "=n" line owns the
  // line's text, so the deck is written back byte for byte.
  CHECK(d.cards[2].line == 3);
  CHECK(d.cards[3].line == 3);
  CHECK(d.cards[7].line == 6);
  CHECK(d.location(d.cards[7], 4).str() == "r.bdf:6");
  CHECK(render_file(d, 0) == text);
  CHECK(d.cards[0].replication_root == 0);
  CHECK(d.cards[3].replication_root == 0);
  CHECK(d.cards[4].replication_root == 4);
  CHECK(d.cards[12].replication_root == -1);
}

TEST_CASE("a changed replicated card: its chain is written out in full, the values kept", "[deck][replication][writer]") {
  const std::string text =
      "GRID,1,,0.,0.,0.\n"
      "=,*1,=,*1.5,==\n"
      "=(2)\n"
      "GRID,9,,9.,9.,9.\n";
  Deck d = read_deck_text(text, "c.bdf");
  REQUIRE(d.cards.size() == 5);
  d.set_values(1, {std::string("GRID"), std::int64_t{2}, std::monostate{}, 1.5, 7.0, 0.0});
  const std::string out = render_file(d, 0);
  CHECK(out ==
        "GRID,1,,0.,0.,0.\n"
        "GRID,2,,1.5,7.,0.\n"
        "GRID,3,,3.,0.,0.\n"
        "GRID,4,,4.5,0.,0.\n"
        "GRID,9,,9.,9.,9.\n");
  // Re-read: the cards after the change keep the values they had, not values derived anew.
  const Deck back = read_deck_text(out, "c2.bdf");
  REQUIRE(back.cards.size() == 5);
  CHECK(fields_of(back.cards[3]) == fields_of(d.cards[3]));
}

TEST_CASE("replication errors: file:line and what was expected, nothing made up", "[deck][replication][errors]") {
  auto first_problem = [](const std::string& text) {
    const Deck d = read_deck_text(text, "e.bdf");
    return d.problems.empty() ? std::string() : d.problems[0].str();
  };
  CHECK(first_problem("=,*1\n") == "e.bdf:1: replication line '=': no card before it to replicate; not read");
  CHECK(first_problem("GRID,1,,0.,0.,0.\n=(3)\n") ==
        "e.bdf:2: replication line '=(3)': no \"=\" line before it whose increments it could repeat; not read");
  CHECK(first_problem("GRID,1,,0.,0.,0.\n=,*1,=,=\n=(0)\n") ==
        "e.bdf:3: replication line '=(0)': expected =, =n or =(n) with n from 1 to 100000; not read");
  CHECK(first_problem("GRID,1,,0.,0.,0.\n=,*1,=,*1\n") ==
        "e.bdf:2: replication line '=': field 4: an integer increment '*1' on the field '0.' of the entry "
        "before, a real (NASTRAN: a real increment for a real field, an integer for an integer field); not read");
  CHECK(first_problem("GRID,1,,0.,0.,0.\n=,*A\n") ==
        "e.bdf:2: replication line '=': field 2: '*A' is not an increment (expected *x or *(x), x a number); not read");
  CHECK(first_problem("CBAR,1,2,3,4,0.,0.,1.,,+B\n+B,,,,,\n=,*1,==\n") ==
        "e.bdf:3: replication line '=': the card before it, CBAR 1 at line 1, has continuation lines, which ssid "
        "does not replicate; not read");
  // After a line that failed, the lines replicating from it fail too; an ordinary card resets.
  const Deck d = read_deck_text("GRID,1,,0.,0.,0.\n=,*A\n=(2)\nGRID,5,,0.,0.,0.\n=,*1,==\n", "e.bdf");
  REQUIRE(d.problems.size() == 2);
  CHECK(d.problems[1].str() == "e.bdf:3: replication line '=(2)': the replication line before it was not read; not read");
  REQUIRE(d.cards.size() == 3);
  CHECK(d.cards[2].field(1) == "6");
  CHECK(render_file(d, 0) == "GRID,1,,0.,0.,0.\n=,*A\n=(2)\nGRID,5,,0.,0.,0.\n=,*1,==\n");
}

TEST_CASE("partitioned bulk data: BEGIN SUPER and the part's cards kept verbatim, the line a statement", "[deck]") {
  const std::string text =
      "SOL 103\nCEND\nBEGIN BULK\n"
      "GRID    1               0.      0.      0.\n"
      "begin bulk super = 1\n"   // 5
      "GRID    1               5.      0.      0.\n"
      "BEGIN SUPER=2 $ another part\n"   // 7
      "XYZZY   1\n"
      "ENDDATA\n";
  const Deck d = read_deck_text(text, "p.bdf");
  CHECK(d.problems.empty());
  REQUIRE(d.cards.size() == 1);  // the residual's GRID only
  std::vector<std::pair<std::string, std::uint32_t>> parts;
  for (const Statement& st : d.statements)
    if (st.section == Section::Bulk) parts.emplace_back(st.text, st.line);
  CHECK(parts == std::vector<std::pair<std::string, std::uint32_t>>{{"BEGIN BULK SUPER = 1", 5}, {"BEGIN SUPER=2", 7}});
  CHECK(render_file(d, 0) == text);
  // Cut inside a part: the missing ENDDATA is still an error.
  const Deck cut = read_deck_text("CEND\nBEGIN BULK\nGRID    1\nBEGIN SUPER = 1\nGRID    1\n", "c.bdf");
  REQUIRE(cut.problems.size() == 1);
  CHECK(cut.problems[0].message.rfind("missing ENDDATA", 0) == 0);
}

TEST_CASE("a continuation matched by its marker to an earlier card, as NASTRAN matches it", "[deck]") {
  // As in a deck MSC Nastran ran (pyNastran's cqra00366): RBE1's continuation after two GRIDs.
  const std::string text =
      "RBE1    10201   10201   234     10202   123                             +R10201\n"
      "GRID    10201           1.0     2.0     3.0             234\n"
      "GRID    10202           4.0     6.0     15.0            123\n"
      "+R10201 UM      10201   156     10202   456\n"
      "FORCE   1       10201           1.0     1.0\n";
  Deck d = read_deck_text(text, "m.bdf");
  CHECK(d.problems.empty());
  REQUIRE(d.cards.size() == 4);
  CHECK(d.cards[0].name == "RBE1");
  CHECK(d.cards[0].field(9) == "UM");
  CHECK(d.cards[0].field(13) == "456");
  CHECK(d.cards[0].line_of(9) == 4);
  CHECK(d.cards[2].size() == 8);  // GRID 10202 keeps its own fields only
  CHECK(d.cards[3].name == "FORCE");
  CHECK(render_file(d, 0) == text);
  // Changed, the card is written whole at its place and the detached line not at all.
  std::vector<FieldValue> v{std::string("RBE1")};
  for (std::size_t i = 1; i < d.cards[0].size(); ++i)
    v.push_back(d.cards[0].field(i).empty() ? FieldValue{} : FieldValue{std::string(d.cards[0].field(i))});
  v[2] = std::int64_t{10202};
  d.set_values(0, v);
  const Deck back = read_deck_text(render_file(d, 0), "m2.bdf");
  REQUIRE(back.cards.size() == 4);
  CHECK(back.cards[0].field(2) == "10202");
  CHECK(back.cards[0].field(13) == "456");
  CHECK(back.cards[2].size() == 8);
  // A generic marker ("+") or the field 10 of the card above continues the card above, as before.
  const Deck g = read_deck_text("RBE1    1       1       234     2       123                             +A\n"
                                "GRID    2\n+       1.\n", "g.bdf");
  REQUIRE(g.cards.size() == 2);
  CHECK(g.cards[1].field(9) == "1.");
}

TEST_CASE("replication and marker matching on hostile input: bounded, and errors not exceptions",
          "[deck][replication][errors]") {
  // An increment past the largest double is an error at its line.
  const Deck inf = read_deck_text("GRID,1,,1.E308\n=,*1,,*1.E308\n", "i.bdf");
  REQUIRE(inf.problems.size() == 1);
  CHECK(inf.problems[0].message.find("is not a finite real") != std::string::npos);
  // At most 200 000 entries made by replication in a deck.
  std::string many = "GRID,1\n=,*1\n";
  for (int k = 0; k < 3; ++k) many += "=(100000)\n";
  const Deck m = read_deck_text(many, "m.bdf");
  REQUIRE(m.problems.size() == 2);  // 1 + 100000 made, the next 100000 would pass the bound
  CHECK(m.problems[0].str() == "m.bdf:4: replication line '=(100000)': more than 200000 entries made by replication "
                               "in this deck; not read");
  CHECK(m.cards.size() == 100002);
  // At most 256 continuation lines matched by marker to one earlier card.
  std::string rows = "SET1,1,2,3,4,5,6,7,8,+A\nGRID,9\n";
  for (int k = 0; k < 257; ++k) rows += "+A,1,,,,,,,,+A\n";
  const Deck r = read_deck_text(rows, "r.bdf");
  REQUIRE(r.problems.size() == 1);
  CHECK(r.problems[0].str() == "r.bdf:259: continuation line '+A': more than 256 continuation lines matched by "
                               "marker to SET1 at line 1; not read");
  CHECK(render_file(r, 0) == rows);
  // Markers match whatever their case; a large-field card takes no detached row.
  const Deck lc = read_deck_text("RBE1    1       1       234     2       123                             +r1\n"
                                 "GRID    2\n+r1     UM      1       156\n", "l.bdf");
  REQUIRE(lc.cards.size() == 2);
  CHECK(lc.cards[0].field(9) == "UM");
  const Deck lg = read_deck_text("GRID*,1,,1.,2.,+G1\nGRID,2\n+G1,3.\n", "g.bdf");
  REQUIRE(lg.cards.size() == 2);
  CHECK(lg.cards[1].field(9) == "3.");  // not the large card's: continues the card above, as before
  // A changed chain whose first card has a detached row: the row is written with its card, once.
  Deck ch = read_deck_text("SET1,1,2,3,4,5,6,7,8,+A\n=,*1,==\nGRID,9\n+A,10\n", "c.bdf");
  REQUIRE(ch.cards.size() == 3);
  std::vector<FieldValue> v{std::string("SET1"), std::int64_t{5}};
  ch.set_values(1, v);
  const Deck back = read_deck_text(render_file(ch, 0), "c2.bdf");
  REQUIRE(back.cards.size() == 3);
  CHECK(back.cards[0].field(9) == "10");
  CHECK(back.cards[2].name == "GRID");
  CHECK(back.cards[2].size() == 2);
  // BEGIN BULK inside the bulk data names no partition: a warning, the cards after it read.
  const Deck bb = read_deck_text("CEND\nBEGIN BULK\nGRID,1\nBEGIN BULK\nGRID,2\nENDDATA\n", "b.bdf");
  REQUIRE(bb.problems.size() == 1);
  CHECK(bb.problems[0].str() == "b.bdf:4: warning: 'BEGIN BULK' inside the bulk data (no SUPER, AUXMODEL, ... "
                                "partition named): ignored");
  CHECK(bb.cards.size() == 2);
}

TEST_CASE("executive, case control and bulk sections; text after ENDDATA kept", "[deck]") {
  const char* text =
      "ID TEST\nSOL 103\nCEND\nTITLE = X\nSPC = 1\nMETHOD=10\nBEGIN BULK\n"
      "GRID    1\nENDDATA\nafter enddata is ignored\n";
  Deck d = read_deck_text(text, "t.bdf");
  CHECK(d.has_bulk_marker);
  REQUIRE(d.cards.size() == 1);
  REQUIRE(d.statements.size() == 7);
  CHECK(d.statements[1].text == "SOL 103");
  CHECK(d.statements[1].section == Section::Executive);
  CHECK(d.statements[4].text == "SPC = 1");
  CHECK(d.statements[4].section == Section::CaseControl);
  CHECK(render_file(d, 0) == text);
}

TEST_CASE("a deck that is bulk data only", "[deck]") {
  Deck d = read_deck_text("GRID    1\nGRID    2\n", "t.bdf");
  CHECK_FALSE(d.has_bulk_marker);
  CHECK(d.cards.size() == 2);
}

TEST_CASE("INCLUDE: quoted, relative to the including file, nested, split over lines", "[deck]") {
  fs::path dir = scratch("include");
  put(dir / "main.bdf", "SOL 103\nCEND\nBEGIN BULK\nINCLUDE 'sub/a.bdf'\nGRID    1\nINCLUDE 'sub/\n    b.bdf'\nENDDATA\n");
  put(dir / "sub/a.bdf", "GRID    2\ninclude \"deeper/c.bdf\"\n");
  put(dir / "sub/deeper/c.bdf", "GRID    3\n");
  put(dir / "sub/b.bdf", "GRID    4\n");
  Deck d = read_deck((dir / "main.bdf").string());
  REQUIRE(d.files.size() == 4);
  REQUIRE(d.cards.size() == 4);
  CHECK(d.cards[0].field(1) == "2");
  CHECK(d.cards[1].field(1) == "3");
  CHECK(d.cards[2].field(1) == "1");
  CHECK(d.cards[3].field(1) == "4");
  CHECK(d.files[3].include_name == "sub/b.bdf");
  // Locations carry the include chain.
  auto loc = d.location(d.cards[1], 1);
  CHECK(loc.line == 1);
  REQUIRE(loc.included_from.size() == 2);
  // Round trip of all files.
  fs::path out = dir / "out";
  auto written = write_deck(d, (out / "main.bdf").string());
  CHECK(written.size() == 4);
  for (const char* f : {"main.bdf", "sub/a.bdf", "sub/deeper/c.bdf", "sub/b.bdf"})
    CHECK(slurp(out / f) == slurp(dir / f));
}

TEST_CASE("bad input: clear errors with file and line, never a crash", "[deck][errors]") {
  fs::path dir = scratch("errors");
  SECTION("missing INCLUDE file names the INCLUDE line") {
    put(dir / "m.bdf", "GRID    1\nINCLUDE 'nope.bdf'\n");
    try {
      read_deck((dir / "m.bdf").string());
      FAIL("no error");
    } catch (const ParseError& e) {
      CHECK(e.where().line == 2);
      CHECK_THAT(e.what(), Catch::Contains("m.bdf:2") && Catch::Contains("nope.bdf") && Catch::Contains("not found"));
    }
  }
  SECTION("missing main file") {
    CHECK_THROWS_WITH(read_deck((dir / "absent.bdf").string()), Catch::Contains("absent.bdf") && Catch::Contains("not found"));
  }
  SECTION("empty file") {
    put(dir / "e.bdf", "");
    CHECK_THROWS_WITH(read_deck((dir / "e.bdf").string()), Catch::Contains("e.bdf") && Catch::Contains("empty file"));
  }
  SECTION("binary garbage") {
    std::string junk = "GRID    1\n";
    junk += std::string("\x7f" "ELF\x02\x01\x01\x00\x00", 9);
    put(dir / "b.bdf", junk);
    CHECK_THROWS_WITH(read_deck((dir / "b.bdf").string()), Catch::Contains("b.bdf:2") && Catch::Contains("binary data"));
  }
  SECTION("10 MB line") {
    put(dir / "l.bdf", "GRID    1\n" + std::string(10 * 1024 * 1024, 'x') + "\n");
    CHECK_THROWS_WITH(read_deck((dir / "l.bdf").string()), Catch::Contains("l.bdf:2") && Catch::Contains("characters long"));
  }
  SECTION("unterminated INCLUDE quote") {
    put(dir / "q.bdf", "INCLUDE 'abc\n   def\n");
    CHECK_THROWS_WITH(read_deck((dir / "q.bdf").string()), Catch::Contains("q.bdf:1") && Catch::Contains("unterminated"));
  }
  SECTION("INCLUDE cycle") {
    put(dir / "c1.bdf", "INCLUDE 'c2.bdf'\n");
    put(dir / "c2.bdf", "INCLUDE 'c1.bdf'\n");
    CHECK_THROWS_WITH(read_deck((dir / "c1.bdf").string()), Catch::Contains("cycle"));
  }
  SECTION("unterminated continuation at end of file is a problem") {
    Deck d = read_deck_text("PBAR    1       2       1.                                              +P1\n", "u.bdf");
    REQUIRE(d.problems.size() == 1);
    CHECK_THAT(d.problems[0].str(), Catch::Contains("u.bdf:1") && Catch::Contains("unterminated continuation"));
  }
  SECTION("orphan continuation is reported and kept verbatim") {
    const std::string text = "+C1     1.      2.\nGRID    1\n";
    Deck d = read_deck_text(text, "o.bdf");
    REQUIRE(d.problems.size() == 1);
    CHECK_THAT(d.problems[0].str(), Catch::Contains("o.bdf:1") && Catch::Contains("continuation line with no card"));
    CHECK(render_file(d, 0) == text);
  }
}

TEST_CASE("typed field readers name file, line, card, field and what was expected", "[deck][errors]") {
  Deck d = read_deck_text("$\nCROD    10      1       1.5     2\n", "truss.bdf");
  FieldReader r(d, d.cards[0]);
  CHECK(r.integer(1, "EID") == 10);
  CHECK_THROWS_WITH(r.integer(3, "G1"), "truss.bdf:2: CROD 10 field 4 (G1): expected integer, got \"1.5\"");
  CHECK_THROWS_WITH(r.real(7, "X"), "truss.bdf:2: CROD 10 field 8 (X): expected real, got blank");
  CHECK(r.real_or(7, "X", 3.0) == 3.0);
  Deck d2 = read_deck_text("PBAR    1       2\n        ABC\n", "p.bdf");
  FieldReader r2(d2, d2.cards[0]);
  CHECK_THROWS_WITH(r2.real(9, "C1"), "p.bdf:2: PBAR 1 continuation 1 field 2 (C1): expected real, got \"ABC\"");
}

TEST_CASE("writing: changed cards in their own format, unchanged fields keep their text", "[deck][writer]") {
  const std::string text =
      "GRID    1               1.-3    0.      0.\n"
      "GRID*                  2                             1.5             2.5\n"
      "*                    3.5\n"
      "GRID,3,,1.,2.,3.\n";
  Deck d = read_deck_text(text, "w.bdf");
  CHECK(render_file(d, 0) == text);
  d.set_values(0, {std::string("GRID"), std::int64_t{1}, std::monostate{}, 1e-3, 0.25, 0.0});
  d.set_values(1, {std::string("GRID"), std::int64_t{2}, std::monostate{}, 1.5, 2.5, 4.0});
  d.set_values(2, {std::string("GRID"), std::int64_t{3}, std::monostate{}, 1.0, 2.0, 0.123456789012});
  const std::string expect =
      "GRID    1               1.-3    .25     0.\n"
      "GRID*   2                               1.5             2.5\n"
      "*       4.\n"
      "GRID*,3,,1.,2.\n"
      "*,.123456789012\n";
  CHECK(render_file(d, 0) == expect);
  Deck back = read_deck_text(render_file(d, 0), "w2.bdf");
  CHECK(back.cards[2].field(5) == ".123456789012");
}

TEST_CASE("writing from scratch: small field, large where precision needs it", "[deck][writer]") {
  CHECK(format_card("GRID", {std::string("GRID"), std::int64_t{12}, std::monostate{}, 1.0, 0.5, -2.25}, FieldFormat::Small) ==
        "GRID    12              1.      .5      -2.25\n");
  CHECK(format_card("GRID", {std::string("GRID"), std::int64_t{12}, std::monostate{}, 0.1, 1.0 / 3.0, 0.0}, FieldFormat::Small) ==
        "GRID*   12                              .1              .333333333333333\n*       0.\n");
  // Continuation rows are always marked so an all-blank row cannot vanish.
  std::vector<FieldValue> v(20);
  v[0] = std::string("RBE3");
  v[1] = std::int64_t{1};
  v[17] = std::int64_t{7};
  CHECK(format_card("RBE3", v, FieldFormat::Small) == "RBE3    1\n+\n+       7\n");
  Deck back = read_deck_text(format_card("RBE3", v, FieldFormat::Small), "x.bdf");
  CHECK(back.cards[0].field(17) == "7");
}

TEST_CASE("CRLF line endings round-trip and are used for rewritten cards", "[deck][writer]") {
  const std::string text = "GRID    1               0.      0.      0.\r\nGRID    2\r\n";
  Deck d = read_deck_text(text, "crlf.bdf");
  CHECK(d.cards[0].field(3) == "0.");
  CHECK(render_file(d, 0) == text);
  d.set_values(1, {std::string("GRID"), std::int64_t{2}, std::monostate{}, 1.0});
  CHECK(render_file(d, 0) == "GRID    1               0.      0.      0.\r\nGRID    2               1.\r\n");
}
