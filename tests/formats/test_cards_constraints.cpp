// Group d typed cards: RBAR, RBE2, RBE3, SPC, SPC1, SPCADD, MPC, EIGRL, EIGR, PARAM, DESVAR, DVPREL1, DVMREL1.
#include "card_test_util.hpp"

using namespace card_test;

TEST_CASE("RBAR: six independent components, ALPHA", "[cards][rigid]") {
  auto e = parse_text("RBAR    1       2       3       123456                  123     .5\n", parse_rbar);
  CHECK(e.cna == "123456");
  CHECK(e.cnb.empty());
  CHECK(e.cmb == "123");
  CHECK(e.alpha == 0.5);
  check_roundtrip(e, parse_rbar, write_rbar);
  CHECK(error_of("RBAR    1       2       3       123     12\n", parse_rbar) ==
        "t.bdf:1: RBAR 1: CNA and CNB must list six independent components together (got \"123\" and \"12\")");
  CHECK(error_of("RBAR    1       2       3       1233\n", parse_rbar) ==
        "t.bdf:1: RBAR 1 field 5 (CNA): expected components (digits 1-6, each at most once), got \"1233\"");
}

TEST_CASE("RBE2: dependent grids over continuations, ALPHA last", "[cards][rigid]") {
  auto e = parse_text("RBE2    1       2       123456  3       4               5\n        6       7       1.-5\n", parse_rbe2);
  CHECK(e.gn == 2);
  CHECK(e.cm == "123456");
  CHECK(e.gm == std::vector<std::int64_t>{3, 4, 5, 6, 7});
  CHECK(e.alpha == 1e-5);
  check_roundtrip(e, parse_rbe2, write_rbe2);
  auto n = parse_text("RBE2    1       2       12      3\n", parse_rbe2);
  CHECK(n.alpha == 0.0);
  CHECK(error_of("RBE2    1       2       123\n", parse_rbe2) == "t.bdf:1: RBE2 1 field 5 (GM1): expected a dependent grid, got blank");
  CHECK(error_of("RBE2    1       2       123     3       2\n", parse_rbe2) ==
        "t.bdf:1: RBE2 1: GN 2 is also listed as a dependent grid");
  CHECK(error_of("RBE2    1       2       123     3       X\n", parse_rbe2) ==
        "t.bdf:1: RBE2 1 field 6 (GMi): expected integer, got \"X\"");
}

TEST_CASE("RBE3: weight groups, UM, ALPHA", "[cards][rigid]") {
  auto e = parse_text(
      "RBE3    1               10      123456  1.      123     1       2\n"
      "        3       .5      12      4       5\n"
      "        UM      1       3       2       3\n"
      "        ALPHA   2.-6\n",
      parse_rbe3);
  CHECK(e.refgrid == 10);
  CHECK(e.refc == "123456");
  REQUIRE(e.groups.size() == 2);
  CHECK(e.groups[0].weight == 1.0);
  CHECK(e.groups[0].components == "123");
  CHECK(e.groups[0].grids == std::vector<std::int64_t>{1, 2, 3});
  CHECK(e.groups[1].weight == 0.5);
  CHECK(e.groups[1].grids == std::vector<std::int64_t>{4, 5});
  REQUIRE(e.um.size() == 2);
  CHECK(e.um[1] == std::pair<std::int64_t, std::string>{2, "3"});
  CHECK(e.has_alpha);
  CHECK(e.alpha == 2e-6);
  check_roundtrip(e, parse_rbe3, write_rbe3);
  CHECK(error_of("RBE3    1               10      123     A       123     1\n", parse_rbe3) ==
        "t.bdf:1: RBE3 1 field 6 (WT1): expected real (a weight), got \"A\"");
  CHECK(error_of("RBE3    1               10      123     1.      123\n", parse_rbe3) ==
        "t.bdf:1: RBE3 1: the last weight group has no grids");
  CHECK(error_of("RBE3    1               10      123     1.      123     1       2.\n        123\n", parse_rbe3) ==
        "t.bdf:2: RBE3 1: the last weight group has no grids");
}

TEST_CASE("SPC, SPC1 (list and THRU), SPCADD", "[cards][spc]") {
  auto s = parse_text("SPC     1       2       123     .5      3               \n", parse_spc);
  REQUIRE(s.entries.size() == 2);
  CHECK(s.entries[0].c == "123");
  CHECK(s.entries[0].d == 0.5);
  CHECK(s.entries[1].g == 3);
  CHECK(s.entries[1].c.empty());  // a scalar point
  check_roundtrip(s, parse_spc, write_spc);
  auto t = parse_text("SPC1    1       123     10      THRU    14\n", parse_spc1);
  CHECK(t.grids == std::vector<std::int64_t>{10, 11, 12, 13, 14});
  check_roundtrip(t, parse_spc1, write_spc1);
  CHECK(write_spc1(t) == std::vector<FieldValue>{std::string("SPC1"), std::int64_t{1}, std::string("123"),
                                                   std::int64_t{10}, std::string("THRU"), std::int64_t{14}});
  auto l = parse_text("SPC1    1       3       10      12              14      15      16\n        17      18\n", parse_spc1);
  CHECK(l.grids == std::vector<std::int64_t>{10, 12, 14, 15, 16, 17, 18});
  check_roundtrip(l, parse_spc1, write_spc1);
  auto a = parse_text("SPCADD  5       1       2               3\n", parse_spcadd);
  CHECK(a.sets == std::vector<std::int64_t>{1, 2, 3});
  check_roundtrip(a, parse_spcadd, write_spcadd);
  CHECK(error_of("SPC     1       2       7\n", parse_spc) ==
        "t.bdf:1: SPC 1 field 4 (C1): expected components (digits 1-6, each at most once), got \"7\"");
  CHECK(error_of("SPC1    1       123     10      THRU    5\n", parse_spc1) ==
        "t.bdf:1: SPC1 1 field 6 (G2): expected an id >= G1, got \"5\"");
  CHECK(error_of("SPCADD  5\n", parse_spcadd) == "t.bdf:1: SPCADD 5 field 3 (S1): expected an SPC set id, got blank");
}

TEST_CASE("MPC: terms two per row, dependent first", "[cards][spc]") {
  auto m = parse_text("MPC     1       2       3       1.      4       3       -.5\n                5       1       -.5     6               2.\n", parse_mpc);
  REQUIRE(m.terms.size() == 4);
  CHECK(m.terms[0].g == 2);
  CHECK(m.terms[0].c == 3);
  CHECK(m.terms[0].a == 1.0);
  CHECK(m.terms[2].g == 5);
  CHECK(m.terms[3].c == 0);
  CHECK(m.terms[3].a == 2.0);
  check_roundtrip(m, parse_mpc, write_mpc);
  CHECK(error_of("MPC     1       2       3       0.\n", parse_mpc) ==
        "t.bdf:1: MPC 1 field 5 (A1): expected a nonzero coefficient for the dependent DOF, got \"0.\"");
  CHECK(error_of("MPC     1       2       3       1.\n        7       5       1       -.5\n", parse_mpc) ==
        "t.bdf:2: MPC 1 continuation 1 field 2 ((blank)): expected blank (terms start in field 3), got \"7\"");
  CHECK(error_of("MPC     1       2       12      1.\n", parse_mpc) ==
        "t.bdf:1: MPC 1 field 4 (Cj): expected a component 0-6 (0 or blank for a scalar point), got \"12\"");
}

TEST_CASE("EIGRL and EIGR: defaults and NORM", "[cards][eigen]") {
  auto l = parse_text("EIGRL   1                       10\n", parse_eigrl);
  CHECK_FALSE(l.v1);
  CHECK_FALSE(l.v2);
  CHECK(l.nd == 10);
  CHECK(l.msglvl == 0);
  CHECK(l.maxset == 7);
  CHECK(l.norm == "MASS");
  check_roundtrip(l, parse_eigrl, write_eigrl);
  auto m = parse_text("EIGRL   1       .1      100.            1       4       5.      MAX\n", parse_eigrl);
  CHECK(m.v1 == 0.1);
  CHECK(m.v2 == 100.0);
  CHECK(m.shfscl == 5.0);
  CHECK(m.norm == "MAX");
  check_roundtrip(m, parse_eigrl, write_eigrl);
  auto r = parse_text("EIGR    2               0.      50.             6\n", parse_eigr);
  CHECK(r.method == "LAN");
  CHECK(r.nd == 6);
  CHECK_FALSE(r.ne);
  CHECK(r.norm == "MASS");
  check_roundtrip(r, parse_eigr, write_eigr);
  auto p = parse_text("EIGR    2       SINV    0.      50.\n        POINT   7       3\n", parse_eigr);
  CHECK(p.norm == "POINT");
  CHECK(p.g == 7);
  CHECK(p.c == 3);
  check_roundtrip(p, parse_eigr, write_eigr);
  CHECK(error_of("EIGRL   1       100.    10.\n", parse_eigrl) ==
        "t.bdf:1: EIGRL 1 field 4 (V2): expected a frequency above V1, got \"10.\"");
  CHECK(error_of("EIGRL   1                                                       MODAL\n", parse_eigrl) ==
        "t.bdf:1: EIGRL 1 field 9 (NORM): expected one of MASS, MAX, got \"MODAL\"");
  CHECK(error_of("EIGR    2       QR\n", parse_eigr) ==
        "t.bdf:1: EIGR 2 field 3 (METHOD): expected one of LAN, AHOU, HOU, MHOU, INV, SINV, GIV, MGIV, AGIV, got \"QR\"");
  CHECK(error_of("EIGR    2       LAN\n        POINT\n", parse_eigr) ==
        "t.bdf:2: EIGR 2 continuation 1 field 3 (G): expected integer, got blank");
}

TEST_CASE("PARAM: typed values and accessors", "[cards][param]") {
  auto w = parse_text("PARAM   WTMASS  .00259\n", parse_param);
  CHECK(w.name == "WTMASS");
  CHECK(w.real() == 0.00259);
  CHECK_FALSE(w.integer());
  CHECK_FALSE(w.text());
  auto a = parse_text("PARAM,AUTOSPC,YES\n", parse_param);
  CHECK(a.text() == std::string("YES"));
  CHECK_FALSE(a.real());
  auto g = parse_text("PARAM   GRDPNT  0\n", parse_param);
  CHECK(g.integer() == 0);
  CHECK(g.real() == 0.0);  // an integer is accepted where a real is wanted
  auto c = parse_text("PARAM   G       .02     .5\n", parse_param);
  CHECK(c.values.size() == 2);
  for (const auto& x : {w, a, g, c}) check_roundtrip(x, parse_param, write_param);
  CHECK(error_of("PARAM   WTMASS\n", parse_param) == "t.bdf:1: PARAM WTMASS field 3 (V1): expected a value, got blank");
  CHECK(error_of("PARAM   12      1.\n", parse_param) == "t.bdf:1: PARAM 12 field 2 (N): expected a parameter name, got \"12\"");
}

TEST_CASE("DESVAR: bounds default to -1e20/1e20", "[cards][design]") {
  auto d = parse_text("DESVAR  1       THICK   1.\n", parse_desvar);
  CHECK(d.label == "THICK");
  CHECK(d.xinit == 1.0);
  CHECK(d.xlb == -1e20);
  CHECK(d.xub == 1e20);
  CHECK_FALSE(d.delxv);
  CHECK_FALSE(d.ddval);
  check_roundtrip(d, parse_desvar, write_desvar);
  auto e = parse_text("DESVAR  2       E       2.1+11  1.+11   3.+11   .5      7\n", parse_desvar);
  CHECK(e.xlb == 1e11);
  CHECK(e.delxv == 0.5);
  CHECK(e.ddval == 7);
  check_roundtrip(e, parse_desvar, write_desvar);
  CHECK(error_of("DESVAR  1       THICK   3.      .5      2.\n", parse_desvar) ==
        "t.bdf:1: DESVAR 1 field 4 (XINIT): expected a value within [XLB, XUB], got \"3.\"");
  CHECK(error_of("DESVAR  1       THICK   1.      2.      .5\n", parse_desvar) ==
        "t.bdf:1: DESVAR 1 field 6 (XUB): expected a bound >= XLB, got \".5\"");
  CHECK(error_of("DESVAR  1\n", parse_desvar) == "t.bdf:1: DESVAR 1 field 3 (LABEL): expected a name, got blank");
}

TEST_CASE("DVPREL1 and DVMREL1: PNAME or FID, bounds, DVID/COEF pairs", "[cards][design]") {
  auto p = parse_text("DVPREL1 5       PBAR    20      A       1.-6            .1\n        1       1.-3    2       2.\n", parse_dvprel1);
  CHECK(p.type == "PBAR");
  CHECK(p.pid == 20);
  CHECK(p.pname == "A");
  CHECK(p.fid == 0);
  CHECK(p.pmin == 1e-6);
  CHECK(p.pmax == 1e20);
  CHECK(p.c0 == 0.1);
  CHECK(p.terms == std::vector<std::pair<std::int64_t, double>>{{1, 1e-3}, {2, 2.0}});
  check_roundtrip(p, parse_dvprel1, write_dvprel1);
  auto f = parse_text("DVPREL1 6       PBAR    20      5\n        1       1.\n", parse_dvprel1);
  CHECK(f.fid == 5);
  CHECK(f.pname.empty());
  CHECK_FALSE(f.pmin);
  check_roundtrip(f, parse_dvprel1, write_dvprel1);
  auto m = parse_text("DVMREL1 7       MAT1    1       E               1.+12\n        2       1.\n", parse_dvmrel1);
  CHECK(m.mpname == "E");
  CHECK_FALSE(m.mpmin);
  CHECK(m.mpmax == 1e12);
  CHECK(m.terms.size() == 1);
  check_roundtrip(m, parse_dvmrel1, write_dvmrel1);
  CHECK(error_of("DVPREL1 5       PBAR    20      A\n", parse_dvprel1) ==
        "t.bdf:1: DVPREL1 5 continuation 1 field 2 (DVID1): expected at least one DVID/COEF pair on the continuation, got blank");
  CHECK(error_of("DVPREL1 5       PBAR    20      A\n        1\n", parse_dvprel1) ==
        "t.bdf:2: DVPREL1 5 continuation 1 field 3 (COEFi): expected real, got blank");
  CHECK(error_of("DVMREL1 7       MAT1    1       2.\n        2       1.\n", parse_dvmrel1) ==
        "t.bdf:1: DVMREL1 7 field 5 (MPNAME): expected a material property name (E, G, NU, RHO, ...), got \"2.\"");
}

TEST_CASE("golden deck: rigid elements, constraints, solution and design cards", "[cards][golden]") {
  check_golden("constraints", {});
}
