// resolve(): every problem kind, all reported at once with file:line of the referring card.
#include "card_test_util.hpp"
#include "formats/card_traits.hpp"

using namespace card_test;

namespace {
std::vector<std::string> problems_of(const std::string& text) {
  Deck d = read_deck_text(text, "r.bdf");
  BulkModel m = parse_bulk(d);
  resolve(d, m);
  std::vector<std::string> out;
  for (const auto& p : m.problems)
    out.push_back(p.str());
  return out;
}
}  // namespace

TEST_CASE("resolve: duplicate ids in each id space", "[resolve]") {
  auto got = problems_of(
      "GRID    1               0.      0.      0.\n"            // 1
      "GRID    1               1.      0.      0.\n"            // 2
      "SPOINT  2\n"                                              // 3
      "GRID    2               1.      0.      0.\n"            // 4
      "MAT1    1       2.1+11          .3\n"                    // 5
      "MAT1    1       7.+10           .3\n"                    // 6
      "PROD    3       1       1.\n"                            // 7
      "PROD    3       1       1.\n"                            // 8
      "CROD    5       3       1       2\n"                     // 9
      "CONM2   5       1               1.\n"                    // 10
      "RBE2    5       1       123     2\n"                     // 11
      "DESVAR  1       A       1.\n"                            // 12
      "DESVAR  1       B       1.\n"                            // 13
      "DVPREL1 1       PROD    3       A\n        1       1.\n" // 14-15
      "DVPREL1 1       PROD    3       A\n        1       1.\n" // 16-17
      "DVMREL1 1       MAT1    1       E\n        1       1.\n" // 18-19
      "DVMREL1 1       MAT1    1       E\n        1       1.\n" // 20-21
      "EIGRL   1                       5\n"                     // 22
      "EIGR    1       LAN     0.      10.\n"                   // 23
      "SPC     1       1       1\n"                             // 24
      "SPCADD  7       1\n"                                     // 25
      "SPCADD  7       1\n");                                   // 26
  CHECK(got == std::vector<std::string>{
                   "r.bdf:2: duplicate grid or scalar point 1 (GRID; first defined by GRID at r.bdf:1)",
                   "r.bdf:4: duplicate grid or scalar point 2 (GRID; first defined by SPOINT at r.bdf:3)",
                   "r.bdf:8: duplicate property 3 (PROD; first defined by PROD at r.bdf:7)",
                   "r.bdf:6: duplicate material 1 (MAT1; first defined by MAT1 at r.bdf:5)",
                   // Grid 2 is first an SPOINT: structural elements need a GRID.
                   "r.bdf:9: CROD 5 refers to G2 2, which is a SPOINT, expected GRID",
                   "r.bdf:11: RBE2 5 refers to GM 2, which is a SPOINT, expected GRID",
                   "r.bdf:26: duplicate SPCADD set 7 (SPCADD; first defined by SPCADD at r.bdf:25)",
                   "r.bdf:23: duplicate eigenvalue method (EIGRL/EIGR SID) 1 (EIGR; first defined by EIGRL at r.bdf:22)",
                   "r.bdf:13: duplicate DESVAR 1 (DESVAR; first defined by DESVAR at r.bdf:12)",
                   "r.bdf:16: duplicate DVPREL 1 (DVPREL1; first defined by DVPREL1 at r.bdf:14)",
                   "r.bdf:20: duplicate DVMREL 1 (DVMREL1; first defined by DVMREL1 at r.bdf:18)",
               });
}

TEST_CASE("resolve: element ids are unique within each family NASTRAN keeps apart, not across", "[resolve]") {
  // Structural (with springs, dampers, bushings), mass, rigid and plot elements
  // each have their own id space: MSC/NX decks reuse ids across them (an RBE2
  // with the id of a CQUAD4 or a CONM2, a PLOTEL with a CBAR's, a CONM2 with a
  // CVISC's) and NASTRAN runs them.
  auto across = problems_of(
      "GRID    1               0.      0.      0.\n"
      "GRID    2               1.      0.      0.\n"
      "GRID    3               1.      1.      0.\n"
      "GRID    4               0.      1.      0.\n"
      "MAT1    1       2.1+11          .3\n"
      "PBAR    3       1       1.\n"
      "CBAR    7       3       1       2       0.      0.      1.\n"
      "CQUAD4  8       9       1       2       3       4\n"
      "CVISC   9       10      1       2\n"
      "CONM2   7       1               1.\n"
      "CONM2   9       2               1.\n"
      "RBE2    8       3       123     4\n"
      "RBE2    7       4       123     1\n"
      "PLOTEL  7       1       3\n");
  CHECK(across == std::vector<std::string>{});
  auto within = problems_of(
      "GRID    1               0.      0.      0.\n"             // 1
      "GRID    2               1.      0.      0.\n"             // 2
      "CONM2   7       1               1.\n"                     // 3
      "CMASS2  7       1.      2       1\n"                      // 4
      "RBE2    8       1       123     2\n"                      // 5
      "RBAR    8       1       2       123456\n"                 // 6
      "PLOTEL  9       1       2\n"                              // 7
      "PLOTEL  9       2       1\n"                              // 8
      "CELAS2  5       1.      1       1       2       1\n"      // 9
      "CDAMP2  5       1.      1       2       2       2\n");    // 10
  CHECK(within == std::vector<std::string>{
                      "r.bdf:10: duplicate element 5 (CDAMP2; first defined by CELAS2 at r.bdf:9)",
                      "r.bdf:4: duplicate mass element 7 (CMASS2; first defined by CONM2 at r.bdf:3)",
                      "r.bdf:6: duplicate rigid element 8 (RBAR; first defined by RBE2 at r.bdf:5)",
                      "r.bdf:8: duplicate plot element 9 (PLOTEL; first defined by PLOTEL at r.bdf:7)",
                  });
}

TEST_CASE("resolve: a property id is unique among the types one element chooses from, not across", "[resolve]") {
  // An element's property is looked up among the types the element accepts (CBAR:
  // PBAR, PBARL; CBEAM: PBEAM, PBEAML, PBCOMP; CQUAD4: PSHELL, PCOMP, PCOMPG). Decks MSC
  // Nastran ran reuse ids across them: PGAP 1 beside PBEAM 1 (pyNastran's dbxdra7),
  // PSHELL 1 beside PSOLID 1 (rs321h), PSOLID 100 beside PSHELL 100 (ac10901a).
  auto across = problems_of(
      "GRID    1               0.      0.      0.\n"
      "GRID    2               1.      0.      0.\n"
      "MAT1    1       2.1+11          .3\n"
      "PGAP    1       .254\n"
      "PBEAM   1       1       20.     6.67    166.7\n"
      "PROD    1       1       1.\n"
      "PSHELL  1       1       .1\n"
      "PSOLID  1       1\n"
      "PELAS   1       1000.\n"
      "CBEAM   5       1       1       2       0.      0.      1.\n"
      "CROD    6       1       1       2\n"
      "CELAS1  7       1       1       1       2       1\n");
  CHECK(across == std::vector<std::string>{});
  auto within = problems_of(
      "MAT1    1       2.1+11          .3\n"                    // 1
      "PBAR    3       1       1.\n"                            // 2
      "PBARL   3       1               ROD\n        .1\n"      // 3-4
      "PSHELL  4       1       .1\n"                            // 5
      "PCOMP   4\n"                                              // 6
      "PBCOMP  5       1       1.\n"                            // 7
      "PBEAM   5       1       1.\n");                          // 8
  CHECK(within == std::vector<std::string>{
                      "r.bdf:3: duplicate property 3 (PBARL; first defined by PBAR at r.bdf:2)",
                      "r.bdf:6: duplicate property 4 (PCOMP; first defined by PSHELL at r.bdf:5)",
                      "r.bdf:8: duplicate property 5 (PBEAM; first defined by PBCOMP at r.bdf:7)",
                  });
  // The reference still finds the right type among several, and names the first when none fits.
  auto wrong = problems_of(
      "GRID    1               0.      0.      0.\n"
      "GRID    2               1.      0.      0.\n"
      "MAT1    1       2.1+11          .3\n"
      "PGAP    1       .254\n"
      "PSHELL  1       1       .1\n"
      "CBEAM   5       1       1       2       0.      0.      1.\n");
  CHECK(wrong == std::vector<std::string>{
                     "r.bdf:6: CBEAM 5 refers to PID 1, which is a PGAP, expected PBEAM/PBEAML/PBCOMP"});
}

TEST_CASE("resolve: a thermal material may share the id of the structural one, not of another thermal one",
          "[resolve]") {
  // MSC decks give MAT1 1 and MAT4 1 for one material (pyNastran's htrussx, plate_py).
  CHECK(problems_of("MAT1    1       2.1+11          .3\nMAT4    1       200.\nPROD    3       1       1.\n").empty());
  CHECK(problems_of("MAT4    1       200.\nMAT5    1       200.\n") ==
        std::vector<std::string>{"r.bdf:2: duplicate material 1 (MAT5; first defined by MAT4 at r.bdf:1)"});
  CHECK(problems_of("MAT1    1       2.1+11          .3\nMAT8    1       1.+7    1.+7    .3\n") ==
        std::vector<std::string>{"r.bdf:2: duplicate material 1 (MAT8; first defined by MAT1 at r.bdf:1)"});
}

TEST_CASE("card traits: the property types an element accepts are one family", "[resolve]") {
  // Otherwise two of them could share an id and the element could not tell which is meant.
  for (const CardTraits& t : card_traits())
    for (const Reference& r : t.references) {
      if (r.space != IdSpace::Property || r.expected.size() < 2) continue;
      for (const std::string& type : r.expected) {
        INFO(t.names[0] << " " << r.field_name << ": " << type);
        CHECK(id_family(IdSpace::Property, type) == id_family(IdSpace::Property, r.expected[0]));
      }
    }
}

TEST_CASE("resolve: scalar points as NASTRAN defines them — repeated SPOINTs, points named by scalar elements",
          "[resolve]") {
  // SPOINT remarks: "duplicate scalar point numbers are allowed", and a scalar
  // point named on a scalar element's connection "need not appear on an SPOINT
  // entry". A GRID and an SPOINT with one id stay a duplicate.
  Deck d = read_deck_text(
      "SPOINT  5       6\n"                                  // 1
      "SPOINT  5\n"                                          // 2
      "CELAS2  1       1.      100             200\n"        // 3 implies 100, 200
      "CMASS2  2       2.      100\n"                        // 4
      "CDAMP3  3       9       300     5\n"                  // 5 implies 300 (kept verbatim)
      "CELAS4  4       1.      301\n"                        // 6 implies 301
      "SPC1    1       0       300     301     100\n"        // 7 refer to implied points
      "GRID    6               0.      0.      0.\n",        // 8 GRID 6 after SPOINT 6
      "r.bdf");
  BulkModel m = parse_bulk(d);
  resolve(d, m);
  std::vector<std::string> got;
  for (const auto& p : m.problems) got.push_back(p.str());
  CHECK(got == std::vector<std::string>{"r.bdf:8: duplicate grid or scalar point 6 (GRID; first defined by SPOINT at r.bdf:1)"});
  CHECK(m.implied_spoints == std::vector<std::int64_t>{100, 200, 300, 301});
}

TEST_CASE("resolve: CELAS3/4 and CMASS3/4 connect scalar points only", "[resolve]") {
  auto got = problems_of(
      "GRID    1               0.      0.      0.\n"
      "CELAS3  2       7       1       5\n"
      "PELAS   7       10.\n"
      "CMASS4  3       1.      5\n");
  CHECK(got == std::vector<std::string>{"r.bdf:2: CELAS3 2: S1 1 is a GRID; CELAS3 connects scalar points only"});
}

TEST_CASE("resolve: dangling references of every kind and properties of the wrong type", "[resolve]") {
  auto got = problems_of(
      "GRID    1               0.      0.      0.\n"                           // 1
      "GRID    2       4       1.      0.      0.      5\n"                    // 2  CP 4, CD 5 missing
      "SPOINT  9\n"                                                             // 3
      "MAT8    2       1.+10\n"                                                 // 4  (kept verbatim)
      "PBAR    3       7       1.\n"                                            // 5  MID 7 missing
      "PROD    4       2       1.\n"                                            // 6  MID 2 is a MAT8
      "CROD    10      3       1       12\n"                                    // 7  PBAR not PROD; GRID 12
      "CBAR    11      8       1       2       0.      1.      0.\n"            // 8  PID 8 missing
      "CBEAM   12      3       1       2       13\n"                            // 9  PBAR not PBEAM; G0 13
      "CELAS2  13      1.      1               9       3\n"                     // 10 component 0 for a GRID; SPOINT with 3
      "CONM2   14      9               1.\n"                                    // 11 G 9 is an SPOINT
      "CBUSH   15      16      1       2       0.      1.      0.\n"            // 12 PBUSH 16 missing
      "RBAR    16      1       20      123456\n"                                // 13 GRID 20
      "RBE3    17              1       123     1.      123     2       21\n"    // 14 GRID 21
      "SPC1    1       123     1       THRU    3\n"                             // 15 grid or scalar point 3
      "SPCADD  2       1       5\n"                                             // 16 SPC set 5
      "MPC     3       22      1       1.      1       1       1.\n"            // 17 grid 22
      "CORD2R  30      31      0.      0.      0.      0.      0.      1.\n        1.\n"  // 18-19 RID 31
      "DESVAR  1       A       1.\n"                                            // 20
      "DVPREL1 1       PROD    3       A\n        1       1.      2       1.\n" // 21-22 PID 3 is a PBAR; DESVAR 2
      "DVMREL1 1       MAT1    6       E\n        1       1.\n");               // 23-24 MAT1 6
  CHECK(got == std::vector<std::string>{
                   "r.bdf:18: coordinate system 31 required by CORD2R 30 does not exist",
                   "r.bdf:2: coordinate system 4 required by GRID 2 does not exist",
                   "r.bdf:2: coordinate system 5 required by GRID 2 does not exist",
                   "r.bdf:7: GRID 12 required by CROD 10 does not exist",
                   "r.bdf:7: CROD 10 refers to PID 3, which is a PBAR, expected PROD",
                   "r.bdf:8: PBAR/PBARL 8 required by CBAR 11 does not exist",
                   "r.bdf:9: CBEAM 12 refers to PID 3, which is a PBAR, expected PBEAM/PBEAML/PBCOMP",
                   "r.bdf:9: GRID 13 required by CBEAM 12 does not exist",
                   "r.bdf:10: CELAS2 13: G1 1 is a GRID, its component must be 1-6, got blank or 0",
                   "r.bdf:10: CELAS2 13: G2 9 is a scalar point (SPOINT), its component must be 0 or blank, got 3",
                   "r.bdf:11: CONM2 14 refers to G 9, which is a SPOINT, expected GRID",
                   "r.bdf:12: PBUSH 16 required by CBUSH 15 does not exist",
                   // A material of another type: a warning (NASTRAN checks it only against the elements run).
                   "r.bdf:6: warning: PROD 4 refers to MID 2, which is a MAT8, expected MAT1; an element using it "
                   "cannot be assembled",
                   "r.bdf:5: MAT1 7 required by PBAR 3 does not exist",
                   "r.bdf:13: GRID 20 required by RBAR 16 does not exist",
                   "r.bdf:14: GRID 21 required by RBE3 17 does not exist",
                   "r.bdf:15: warning: grid or scalar point 3 required by SPC1 1 does not exist; ignored (NASTRAN: USER WARNING "
                   "MESSAGE 2051)",
                   "r.bdf:16: warning: SPC set 5 required by SPCADD 2 does not exist (no SPC or SPC1 with that SID); it "
                   "adds no constraint",
                   "r.bdf:17: grid or scalar point 22 required by MPC 3 does not exist",
                   "r.bdf:21: DVPREL1 1 refers to PID 3, which is a PBAR, expected PROD",
                   "r.bdf:22: DESVAR 2 required by DVPREL1 1 does not exist",
                   "r.bdf:23: MAT1 6 required by DVMREL1 1 does not exist",
               });
}

TEST_CASE("resolve: warnings — PARAM given twice, MAT1 E/G/NU inconsistent, PBARL type not sectioned", "[resolve]") {
  auto got = problems_of(
      "PARAM   WTMASS  .00259\n"
      "PARAM   WTMASS  1.\n"
      "MAT1    1       2.+11   5.+10   .3\n"
      "PBARL   2       1               HAT9\n        1.      1.      .1      .2\n");
  CHECK(got == std::vector<std::string>{
                   "r.bdf:4: warning: PBARL 2: TYPE HAT9 is not a section type of the PBARL/PBEAML list; kept with its values "
                   "but not sectioned",
                   "r.bdf:2: warning: PARAM WTMASS given again (first at r.bdf:1)",
                   "r.bdf:3: warning: MAT1 1: E, G and NU are not related by E = 2(1+NU)G (E/(2(1+NU)G) = 1.538462)",
               });
}

TEST_CASE("resolve: a MAT1 NU out of range beside a given E and G is NASTRAN's warning 2251", "[resolve]") {
  // pyNastran's models/aero/freedlm (MSC Nastran ran it: USER WARNING MESSAGE 2251, ID 3).
  auto got = problems_of("MAT1    3       2.06+7  580000. 16.7586 .056\n");
  CHECK(got == std::vector<std::string>{
                   "r.bdf:1: warning: MAT1 3: NU = 16.758600 is outside (-1.0, 0.5]; E and G are given and used as "
                   "given (NASTRAN's USER WARNING MESSAGE 2251)",
               });  // E = 2(1 + NU) G holds here (to 1.2e-6): no second warning
}

TEST_CASE("resolve: a clean deck has no problems; DMIG is counted as supported, not parsed", "[resolve]") {
  auto got = problems_of(
      "GRID    1               0.      0.      0.\n"
      "GRID    2               1.      0.      0.\n"
      "MAT1    1       2.1+11          .3      7850.\n"
      "PROD    1       1       1.-4\n"
      "CROD    1       1       1       2\n"
      "DMIG    KAAX    0       6       2\n");
  CHECK(got.empty());
  Deck d = read_deck_text("DMIG    KAAX    0       6       2\n", "d.bdf");
  BulkModel m = parse_bulk(d);
  CHECK(m.supported.at("DMIG") == 1);
  CHECK(m.unsupported.empty());
  CHECK(is_supported_card("DMIG"));
  for (const char* name : {"GRID", "CORD2R", "CORD2C", "CORD2S", "CROD", "CONROD", "PROD", "CBAR", "PBAR", "PBARL",
                           "CBEAM", "PBEAM", "PBEAML", "MAT1", "CONM2", "CMASS1", "CMASS2", "CELAS1", "CELAS2",
                           "PELAS", "CBUSH", "PBUSH", "RBAR", "RBE2", "RBE3", "SPC", "SPC1", "SPCADD", "MPC", "EIGRL",
                           "EIGR", "PARAM", "DESVAR", "DVPREL1", "DVMREL1", "BAROR", "BEAMOR", "GRDSET", "SPOINT",
                           "PMASS"})
    CHECK(is_supported_card(name));
  CHECK_FALSE(is_supported_card("FORCE"));
}

TEST_CASE("resolve: an SPC1 THRU range over missing grids names five and counts the rest", "[resolve]") {
  auto got = problems_of("GRID    1               0.      0.      0.\nSPC1    1       123     1       THRU    100\n");
  REQUIRE(got.size() == 6);
  CHECK(got[0] == "r.bdf:2: warning: grid or scalar point 2 required by SPC1 1 does not exist; ignored (NASTRAN: USER "
                  "WARNING MESSAGE 2051)");
  CHECK(got[4] == "r.bdf:2: warning: grid or scalar point 6 required by SPC1 1 does not exist; ignored (NASTRAN: USER "
                  "WARNING MESSAGE 2051)");
  CHECK(got[5] == "r.bdf:2: warning: ... and 94 more grids or scalar points required by SPC1 1 do not exist; ignored");
}

TEST_CASE("parse errors and resolve problems come together, in one list", "[resolve]") {
  auto got = problems_of(
      "GRID    1               0.      0.      0.\n"
      "GRID    2               1.      0.      X\n"       // field error: GRID 2 is not defined
      "CONROD  5       1       2       1       1.\n"      // GRID 2 and MAT1 1 missing
      "GRDSET          1\n"
      "GRDSET          2\n");
  CHECK(got == std::vector<std::string>{
                   "r.bdf:2: GRID 2 field 6 (X3): expected real, got \"X\"",
                   "r.bdf:5: more than one GRDSET (first at r.bdf:4)",
                   "r.bdf:1: coordinate system 1 required by GRID 1 does not exist",  // CP from GRDSET
                   "r.bdf:3: GRID 2 required by CONROD 5 does not exist",
                   "r.bdf:3: MAT1 1 required by CONROD 5 does not exist",
               });
}
