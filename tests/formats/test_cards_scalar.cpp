// Group b typed cards: CONM2, CMASS1/2 (+PMASS), CELAS1/2, PELAS, CBUSH, PBUSH, SPOINT.
#include "card_test_util.hpp"

using namespace card_test;

TEST_CASE("CONM2: mass, offset, inertia, CID default and -1", "[cards][mass]") {
  auto c = parse_text("CONM2   1       2               5.      .1      .2      .3\n        1.      .5      2.      .6      .7      3.\n",
                      parse_conm2);
  CHECK(c.cid == 0);
  CHECK(c.m == 5.0);
  CHECK(c.x == std::array<double, 3>{0.1, 0.2, 0.3});
  CHECK(c.i11 == 1.0);
  CHECK(c.i21 == 0.5);
  CHECK(c.i22 == 2.0);
  CHECK(c.i31 == 0.6);
  CHECK(c.i32 == 0.7);
  CHECK(c.i33 == 3.0);
  check_roundtrip(c, parse_conm2, write_conm2);
  auto b = parse_text("CONM2   1       2       -1      5.\n", parse_conm2);
  CHECK(b.cid == -1);
  CHECK(b.i11 == 0.0);
  check_roundtrip(b, parse_conm2, write_conm2);
  CHECK(error_of("CONM2   1       2       -2      5.\n", parse_conm2) ==
        "t.bdf:1: CONM2 1 field 4 (CID): expected integer >= -1, got \"-2\"");
  CHECK(error_of("CONM2   1       2               5.\n        1.      X\n", parse_conm2) ==
        "t.bdf:2: CONM2 1 continuation 1 field 3 (I21): expected real, got \"X\"");
}

TEST_CASE("CMASS1/CMASS2/CELAS1/CELAS2: ends, components, PID default", "[cards][scalar]") {
  auto m1 = parse_text("CMASS1  7               3       2\n", parse_cmass1);
  CHECK(m1.pid == 7);  // blank PID = EID
  CHECK(m1.g1 == 3);
  CHECK(m1.c1 == 2);
  CHECK(m1.g2 == 0);  // grounded
  check_roundtrip(m1, parse_cmass1, write_cmass1);
  auto m2 = parse_text("CMASS2  8       .5      3       2       4       2\n", parse_cmass2);
  CHECK(m2.m == 0.5);
  CHECK(m2.g2 == 4);
  check_roundtrip(m2, parse_cmass2, write_cmass2);
  auto e1 = parse_text("CELAS1  9       19      101             102\n", parse_celas1);
  CHECK(e1.pid == 19);
  CHECK(e1.c1 == 0);
  check_roundtrip(e1, parse_celas1, write_celas1);
  auto e2 = parse_text("CELAS2  10      1.+4    1       1       2       1       .02     3.\n", parse_celas2);
  CHECK(e2.k == 1e4);
  CHECK(e2.ge == 0.02);
  CHECK(e2.s == 3.0);
  check_roundtrip(e2, parse_celas2, write_celas2);
  CHECK(error_of("CELAS2  10      1.+4    1       7\n", parse_celas2) ==
        "t.bdf:1: CELAS2 10 field 5 (C1): expected a component 0-6 (0 or blank for a scalar point), got \"7\"");
  CHECK(error_of("CELAS2  10      1.+4\n", parse_celas2) ==
        "t.bdf:1: CELAS2 10 field 4 (G1): expected a grid or scalar point (G1 and G2 both blank), got blank");
  CHECK(error_of("CMASS2  10      1.      1       1       1       1\n", parse_cmass2) ==
        "t.bdf:1: CMASS2 10: G1/C1 and G2/C2 are the same degree of freedom");
  CHECK(error_of("CMASS1  10      1.\n", parse_cmass1) ==
        "t.bdf:1: CMASS1 10 field 3 (PID): expected integer, got \"1.\"");
}

TEST_CASE("CMASS3/CMASS4/CELAS3/CELAS4: the scalar-point forms", "[cards][scalar]") {
  // QRG: EID, PID (CMASS3/CELAS3; blank = EID) or M/K (CMASS4/CELAS4), S1, S2.
  auto m3 = parse_text("CMASS3  7               31      32\n", parse_cmass3);
  CHECK(m3.pid == 7);
  CHECK(m3.g1 == 31);
  CHECK(m3.g2 == 32);
  CHECK(m3.c1 == 0);
  CHECK(m3.scalar_form);
  check_roundtrip(m3, parse_cmass3, write_cmass1);
  CHECK(write_cmass1(m3) == std::vector<FieldValue>{std::string("CMASS3"), std::int64_t{7}, FieldValue(),
                                                    std::int64_t{31}, std::int64_t{32}});
  auto m4 = parse_text("CMASS4  8       .5              33\n", parse_cmass4);
  CHECK(m4.m == 0.5);
  CHECK(m4.g1 == 0);  // grounded
  CHECK(m4.g2 == 33);
  check_roundtrip(m4, parse_cmass4, write_cmass2);
  CHECK(std::get<std::string>(write_cmass2(m4)[0]) == "CMASS4");
  auto e3 = parse_text("CELAS3  9       19      101\n", parse_celas3);
  CHECK(e3.pid == 19);
  check_roundtrip(e3, parse_celas3, write_celas1);
  CHECK(std::get<std::string>(write_celas1(e3)[0]) == "CELAS3");
  auto e4 = parse_text("CELAS4  10      1.+4    101     102\n", parse_celas4);
  CHECK(e4.k == 1e4);
  check_roundtrip(e4, parse_celas4, write_celas2);
  CHECK(write_celas2(e4).size() == 5u);  // no GE, S
  CHECK(error_of("CELAS4  10      1.+4\n", parse_celas4) ==
        "t.bdf:1: CELAS4 10 field 4 (S1): expected a scalar point (S1 and S2 both blank), got blank");
  CHECK(error_of("CMASS4  10      1.      5       5\n", parse_cmass4) ==
        "t.bdf:1: CMASS4 10: S1 and S2 are the same scalar point");
  CHECK(error_of("CELAS3  10      1       5       6       7\n", parse_celas3) ==
        "t.bdf:1: CELAS3 10: too many fields (CELAS3 has 4 data fields)");
}

TEST_CASE("PELAS and PMASS: several properties per card", "[cards][scalar]") {
  auto p = parse_text("PELAS   1       1.+3    .1      2.      2       2.+3\n", parse_pelas);
  REQUIRE(p.size() == 2);
  CHECK(p[0].ge == 0.1);
  CHECK(p[0].s == 2.0);
  CHECK(p[1].pid == 2);
  CHECK(p[1].k == 2000.0);
  CHECK(p[1].ge == 0.0);
  auto one = parse_text("PELAS   1       1.+3\n", parse_pelas);
  CHECK(one.size() == 1);
  auto q = parse_text("PMASS   1       1.      2       2.      3       3.\n", parse_pmass);
  REQUIRE(q.size() == 3);
  CHECK(q[2].m == 3.0);
  CHECK(error_of("PELAS   1\n", parse_pelas) == "t.bdf:1: PELAS 1 field 3 (K1): expected real, got blank");
  CHECK(error_of("PMASS   1       1.      2\n", parse_pmass) == "t.bdf:1: PMASS 1 field 5 (M2): expected real, got blank");
}

TEST_CASE("SPOINT: list and THRU", "[cards][scalar]") {
  auto s = parse_text("SPOINT  5       THRU    8\n", parse_spoint);
  CHECK(s.ids == std::vector<std::int64_t>{5, 6, 7, 8});
  check_roundtrip(s, parse_spoint, write_spoint);
  auto l = parse_text("SPOINT  5       9               12\n", parse_spoint);
  CHECK(l.ids == std::vector<std::int64_t>{5, 9, 12});
  check_roundtrip(l, parse_spoint, write_spoint);
  CHECK(error_of("SPOINT  5       THRU    2\n", parse_spoint) ==
        "t.bdf:1: SPOINT 5 field 4 (ID2): expected an id >= ID1, got \"2\"");
}

TEST_CASE("CBUSH: orientation, CID, S, OCID offsets", "[cards][bush]") {
  auto c = parse_text("CBUSH   1       2       3       4       0.      1.      0.\n", parse_cbush);
  CHECK(c.cid == -1);
  CHECK(c.s == 0.5);
  CHECK(c.ocid == -1);
  CHECK(c.x[1] == 1.0);
  check_roundtrip(c, parse_cbush, write_cbush);
  auto g = parse_text("CBUSH   1       2       3                                       5\n        .2      7       .1      .2      .3\n", parse_cbush);
  CHECK(g.gb == 0);
  CHECK(g.orientation_blank);
  CHECK(g.cid == 5);
  CHECK(g.s == 0.2);
  CHECK(g.ocid == 7);
  CHECK(g.si == std::array<double, 3>{0.1, 0.2, 0.3});
  check_roundtrip(g, parse_cbush, write_cbush);
  CHECK(error_of("CBUSH   1       2       3       4       0.      1.      0.\n        1.5\n", parse_cbush) ==
        "t.bdf:2: CBUSH 1 continuation 1 field 2 (S): expected real in [0.0, 1.0], got \"1.5\"");
  CHECK(error_of("CBUSH   1       2       3       4                               -1\n", parse_cbush) ==
        "t.bdf:1: CBUSH 1 field 9 (CID): expected integer >= 0, got \"-1\"");
}

TEST_CASE("PBUSH: K, B, GE, RCV rows in any order", "[cards][bush]") {
  auto p = parse_text(
      "PBUSH   1       K       1.      2.      3.      4.      5.      6.\n"
      "                RCV     .5\n"
      "                GE      .01\n",
      parse_pbush);
  CHECK(p.k == std::array<double, 6>{1, 2, 3, 4, 5, 6});
  CHECK(p.has_rcv);
  CHECK(p.sa == 0.5);
  CHECK(p.st == 1.0);
  CHECK(p.ge[0] == 0.01);
  CHECK(p.ge[1] == 0.0);
  CHECK_FALSE(p.has_b);
  check_roundtrip(p, parse_pbush, write_pbush);
  auto e = parse_text("PBUSH,1,K,1.,,,,,,+\n+,,,,,,,,,+\n+,,B,2.\n", parse_pbush);  // an all-blank row is skipped
  CHECK(e.b[0] == 2.0);
  CHECK(error_of("PBUSH,1,K,1.,,,,,,+\n+,7\n", parse_pbush) ==
        "t.bdf:2: PBUSH 1 continuation 1 field 2 ((blank)): expected blank (the flag goes in field 3), got \"7\"");
  CHECK(error_of("PBUSH   1       X       1.\n", parse_pbush) ==
        "t.bdf:1: PBUSH 1 field 3 (flag): expected one of K, B, GE, RCV, got \"X\"");
  CHECK(error_of("PBUSH   1       K       1.\n                K       2.\n", parse_pbush) ==
        "t.bdf:2: PBUSH 1 continuation 1 field 3 (flag): expected each flag once (K repeated), got \"K\"");
  CHECK(error_of("PBUSH   1       K       1.\n                B       2.      Q\n", parse_pbush) ==
        "t.bdf:2: PBUSH 1 continuation 1 field 5 (B2): expected real, got \"Q\"");
}

TEST_CASE("golden deck: masses, springs, bushes", "[cards][golden]") { check_golden("scalar", {}); }
