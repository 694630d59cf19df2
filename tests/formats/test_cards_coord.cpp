// Group c typed cards: CORD2R, CORD2C, CORD2S, GRDSET; coordinate-system checks of resolve.
#include "card_test_util.hpp"

using namespace card_test;

TEST_CASE("CORD2R/C/S: kind from the name, RID default, three points", "[cards][coord]") {
  auto r = parse_text("CORD2R  5               1.      2.      3.      1.      2.      4.\n        2.      2.      3.\n", parse_cord2);
  CHECK(r.kind == CoordKind::Rectangular);
  CHECK(r.rid == 0);
  CHECK(r.a == std::array<double, 3>{1, 2, 3});
  CHECK(r.b == std::array<double, 3>{1, 2, 4});
  CHECK(r.c == std::array<double, 3>{2, 2, 3});
  check_roundtrip(r, parse_cord2, write_cord2);
  auto c = parse_text("CORD2C  6       5       0.      0.      0.      0.      0.      1.\n        1.\n", parse_cord2);
  CHECK(c.kind == CoordKind::Cylindrical);
  CHECK(std::string(c.name()) == "CORD2C");
  CHECK(c.rid == 5);
  check_roundtrip(c, parse_cord2, write_cord2);
  auto s = parse_text("CORD2S  7               0.      0.      0.      0.      0.      1.\n        1.\n", parse_cord2);
  CHECK(s.kind == CoordKind::Spherical);
  check_roundtrip(s, parse_cord2, write_cord2);
  CHECK(error_of("CORD2R  5               1.      2.      3.      1.      2.      3.\n        2.\n", parse_cord2) ==
        "t.bdf:1: CORD2R 5: points A and B coincide (no z axis)");
  CHECK(error_of("CORD2R  5               0.      0.      0.      0.      0.      1.\n        0.      0.      7.\n", parse_cord2) ==
        "t.bdf:2: CORD2R 5: point C lies on the line AB (no x-z plane)");
  CHECK(error_of("CORD2R  5       -1\n", parse_cord2) == "t.bdf:1: CORD2R 5 field 3 (RID): expected integer >= 0, got \"-1\"");
  CHECK(error_of("CORD2R  5               0.      0.      0.      0.      0.      1.\n        1.      0.      C3\n", parse_cord2) ==
        "t.bdf:2: CORD2R 5 continuation 1 field 4 (C3): expected real, got \"C3\"");
}

TEST_CASE("GRDSET fills blank GRID CP, CD, PS, SEID", "[cards][coord]") {
  auto g = parse_text("GRDSET          3                               4       345     2\n", parse_grdset);
  CHECK(g.cp == 3);
  CHECK(g.cd == 4);
  CHECK(g.ps == "345");
  CHECK(g.seid == 2);
  check_roundtrip(g, parse_grdset, write_grdset);
  Deck d = read_deck_text(
      "GRDSET          3                               4       345\n"
      "GRID    1               0.      0.      0.\n"
      "GRID    2       0       0.      0.      0.      0       1\n"
      "CORD2R  3               0.      0.      0.      0.      0.      1.\n        1.\n"
      "CORD2R  4               0.      0.      0.      0.      0.      1.\n        1.\n",
      "g.bdf");
  BulkModel m = parse_bulk(d);
  REQUIRE(m.grids.size() == 2);
  CHECK(m.grids[0].cp == 3);
  CHECK(m.grids[0].cd == 4);
  CHECK(m.grids[0].ps == "345");
  CHECK(m.grids[1].cp == 0);  // given fields keep their values
  CHECK(m.grids[1].cd == 0);
  CHECK(m.grids[1].ps == "1");
  resolve(d, m);
  CHECK(m.problems.empty());
  CHECK(error_of("GRDSET  1\n", parse_grdset) == "t.bdf:1: GRDSET 1 field 2 ((blank)): expected blank, got \"1\"");
}

TEST_CASE("resolve: coordinate systems — dangling CP/CD/RID, RID cycles, duplicates", "[cards][resolve]") {
  Deck d = read_deck_text(
      "CORD2R  1       2       0.      0.      0.      0.      0.      1.\n        1.\n"
      "CORD2R  2       1       0.      0.      0.      0.      0.      1.\n        1.\n"
      "CORD2C  3       9       0.      0.      0.      0.      0.      1.\n        1.\n"
      "CORD2S  3               0.      0.      0.      0.      0.      1.\n        1.\n"
      "GRID    1       8       0.      0.      0.      7\n"
      "CONM2   5       1       6       1.\n",
      "c.bdf");
  BulkModel m = parse_bulk(d);
  resolve(d, m);
  std::vector<std::string> got;
  for (const auto& p : m.problems) got.push_back(p.str());
  CHECK(got == std::vector<std::string>{
                   "c.bdf:7: duplicate coordinate system 3 (CORD2S; first defined by CORD2C at c.bdf:5)",
                   "c.bdf:1: CORD2R 1: RID chain 1 -> 2 -> 1 is a cycle (it must end in the basic system)",
                   "c.bdf:5: coordinate system 9 required by CORD2C 3 does not exist",
                   "c.bdf:9: coordinate system 8 required by GRID 1 does not exist",
                   "c.bdf:9: coordinate system 7 required by GRID 1 does not exist",
                   "c.bdf:10: coordinate system 6 required by CONM2 5 does not exist",
               });
}

TEST_CASE("golden deck: coordinate systems and GRDSET", "[cards][golden]") { check_golden("coord", {}); }
