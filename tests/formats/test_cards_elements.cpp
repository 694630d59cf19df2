// Group a typed cards: MAT1, PROD, CONROD, PBAR, CBAR (+BAROR), PBARL, CBEAM (+BEAMOR), PBEAM, PBEAML.
#include "card_test_util.hpp"

#include <cmath>

using namespace card_test;

TEST_CASE("MAT1: E, G, NU derivation rule and defaults", "[cards][mat1]") {
  auto m = parse_text("MAT1    1       2.1+11          .3\n", parse_mat1);
  CHECK(m.e == 2.1e11);
  CHECK(m.nu == 0.3);
  CHECK(m.g == Approx(2.1e11 / 2.6).epsilon(1e-15));
  CHECK(m.rho == 0.0);
  CHECK(m.ge == 0.0);
  CHECK_FALSE(m.g_given);
  // G and NU -> E; E and G -> NU.
  auto m2 = parse_text("MAT1    2               8.+10   .25\n", parse_mat1);
  CHECK(m2.e == Approx(2.0e11).epsilon(1e-15));
  auto m3 = parse_text("MAT1    3       2.+11   8.+10\n", parse_mat1);
  CHECK(m3.nu == Approx(0.25).epsilon(1e-14));
  // Only E: G = NU = 0.0 (NASTRAN's rule for two blanks); only G: E = NU = 0.0.
  auto m4 = parse_text("MAT1    4       7.+10\n", parse_mat1);
  CHECK(m4.g == 0.0);
  CHECK(m4.nu == 0.0);
  auto m5 = parse_text("MAT1    5               3.+10\n", parse_mat1);
  CHECK(m5.e == 0.0);
  CHECK(m5.g == 3.0e10);
  // All given: kept as given.
  auto m6 = parse_text("MAT1,6,2.+11,7.+10,.3,7800.,1.-5,20.,.01,+\n+,1.+8,2.+8,3.+8,4\n", parse_mat1);
  CHECK(m6.g == 7.0e10);
  CHECK(m6.rho == 7800.0);
  CHECK(m6.tref == 20.0);
  CHECK(m6.ss == 3.0e8);
  CHECK(m6.mcsid == 4);
  for (const auto& x : {m, m2, m3, m4, m5, m6}) check_roundtrip(x, parse_mat1, write_mat1);
  // Derived values are written blank so a later change of E keeps G derived...
  CHECK(std::holds_alternative<std::monostate>(write_mat1(m)[3]));
  // ...and a derived value changed itself is written once its flag is set.
  Mat1 changed = m2;  // E derived from G and NU
  changed.e = 1.5e11;
  changed.e_given = true;
  CHECK(write_mat1(changed)[2] == FieldValue(1.5e11));
  auto back = parse_text(format_card("MAT1", write_mat1(changed), FieldFormat::Small), parse_mat1);
  CHECK(back.e == 1.5e11);
  CHECK(back.g == m2.g);
  CHECK(back.nu == m2.nu);
}

TEST_CASE("MAT1 errors name the field", "[cards][mat1][errors]") {
  CHECK(error_of("MAT1    1\n", parse_mat1) == "t.bdf:1: MAT1 1: E and G are both blank (give at least one)");
  CHECK(error_of("MAT1    1       2.1+11          .6\n", parse_mat1) ==
        "t.bdf:1: MAT1 1 field 5 (NU): expected real in (-1.0, 0.5] (E or G is derived from it), got \".6\"");
  CHECK(error_of("MAT1    1               8.+10   -1.\n", parse_mat1) ==
        "t.bdf:1: MAT1 1 field 5 (NU): expected real in (-1.0, 0.5] (E or G is derived from it), got \"-1.\"");
  // With E and G given, NU out of range is NASTRAN's warning 2251, not an error (test_resolve.cpp).
  const Mat1 odd = parse_text("MAT1    3       2.06+7  580000. 16.7586 .056\n", parse_mat1);
  CHECK(odd.e == 2.06e7);
  CHECK(odd.g == 580000.0);
  CHECK(odd.nu == Approx(16.7586));
  CHECK(error_of("MAT1    1       -2.\n", parse_mat1) == "t.bdf:1: MAT1 1 field 3 (E): expected real >= 0.0, got \"-2.\"");
  CHECK(error_of("MAT1    1       2.1+11                  STEEL\n", parse_mat1) ==
        "t.bdf:1: MAT1 1 field 6 (RHO): expected real, got \"STEEL\"");
  CHECK(error_of("MAT1    0       2.1+11\n", parse_mat1) ==
        "t.bdf:1: MAT1 0 field 2 (MID): expected positive integer (an id), got \"0\"");
}

TEST_CASE("PROD and CONROD", "[cards][rod]") {
  auto p = parse_text("PROD    7       1       2.5\n", parse_prod);
  CHECK(p.pid == 7);
  CHECK(p.a == 2.5);
  CHECK(p.j == 0.0);
  CHECK(p.nsm == 0.0);
  check_roundtrip(p, parse_prod, write_prod);
  auto c = parse_text("CONROD  3       1       2       5       1.      2.      .5      .1\n", parse_conrod);
  CHECK(c.g2 == 2);
  CHECK(c.mid == 5);
  CHECK(c.c == 0.5);
  CHECK(c.nsm == 0.1);
  check_roundtrip(c, parse_conrod, write_conrod);
  CHECK(error_of("PROD    7       1\n", parse_prod) == "t.bdf:1: PROD 7 field 4 (A): expected real, got blank");
  CHECK(error_of("CONROD  3       1       1       5       1.\n", parse_conrod) ==
        "t.bdf:1: CONROD 3: G1 and G2 must differ (both 1)");
  CHECK(error_of("CONROD,3,1,2,5,1.,2.,.5,.1,+\n+,9\n", parse_conrod) ==
        "t.bdf:2: CONROD 3: too many fields (CONROD has 8 data fields)");
}

TEST_CASE("PBAR: field table, defaults, I12 on the second continuation", "[cards][bar]") {
  auto p = parse_text("PBAR    1       2       3.\n", parse_pbar);
  CHECK(p.a == 3.0);
  CHECK(p.i1 == 0.0);
  CHECK(p.k1 == 0.0);
  auto q = parse_text(
      "PBAR    1       2       3.      4.      5.      6.      7.\n"
      "        .1      .2      .3      .4      .5      .6      .7      .8\n"
      "        .85     .75     1.5\n",
      parse_pbar);
  CHECK(q.i1 == 4.0);
  CHECK(q.i2 == 5.0);
  CHECK(q.j == 6.0);
  CHECK(q.nsm == 7.0);
  CHECK(q.c1 == 0.1);
  CHECK(q.f2 == 0.8);
  CHECK(q.k1 == 0.85);
  CHECK(q.k2 == 0.75);
  CHECK(q.i12 == 1.5);
  check_roundtrip(p, parse_pbar, write_pbar);
  check_roundtrip(q, parse_pbar, write_pbar);
  CHECK(error_of("PBAR    1       2       3.      -4.\n", parse_pbar) ==
        "t.bdf:1: PBAR 1 field 5 (I1): expected real >= 0.0, got \"-4.\"");
  CHECK(error_of("PBAR    1       2       3.      1.      1.\n        0.\n        0.      0.      2.\n", parse_pbar) ==
        "t.bdf:3: PBAR 1 continuation 2 field 4 (I12): expected I1*I2 >= I12^2, got \"2.\"");
}

TEST_CASE("CBAR: X vector or G0 in field 6, OFFT, pins, offsets, BAROR defaults", "[cards][bar]") {
  auto c = parse_text("CBAR    10      20      1       2       0.      1.      0.\n", parse_cbar);
  CHECK(c.g0 == 0);
  CHECK(c.x == std::array<double, 3>{0.0, 1.0, 0.0});
  CHECK(c.offt == "GGG");
  CHECK(c.pa.empty());
  auto g = parse_text("CBAR    10      20      1       2       7                       BGO\n        123     456     .1      .2      .3      .4      .5      .6\n", parse_cbar);
  CHECK(g.g0 == 7);
  CHECK(g.offt == "BGO");
  CHECK(g.pa == "123");
  CHECK(g.pb == "456");
  CHECK(g.wa == std::array<double, 3>{0.1, 0.2, 0.3});
  CHECK(g.wb == std::array<double, 3>{0.4, 0.5, 0.6});
  check_roundtrip(c, parse_cbar, write_cbar);
  check_roundtrip(g, parse_cbar, write_cbar);
  // Blank PID, orientation and OFFT come from BAROR, else PID = EID.
  auto b = parse_text("CBAR    10              1       2\n", parse_cbar);
  CHECK(b.pid_blank);
  CHECK(b.orientation_blank);
  Baror bo = parse_text("BAROR           33                      1.      0.      0.      GOO\n", parse_baror);
  Cbar b1 = b;
  CHECK(apply_baror(b1, &bo));
  CHECK(b1.pid == 33);
  CHECK(b1.x == std::array<double, 3>{1.0, 0.0, 0.0});
  CHECK(b1.offt == "GOO");
  // Written blank again: the values stay BAROR's.
  CHECK(write_cbar(b1) == std::vector<FieldValue>{std::string("CBAR"), std::int64_t{10}, {}, std::int64_t{1}, std::int64_t{2}});
  Cbar b2 = b;
  CHECK_FALSE(apply_baror(b2, nullptr));
  CHECK(b2.pid == 10);
  check_roundtrip(bo, parse_baror, write_baror);

  CHECK(error_of("CBAR    10      20      1       1       0.      1.      0.\n", parse_cbar) ==
        "t.bdf:1: CBAR 10: GA and GB must differ (both 1)");
  CHECK(error_of("CBAR    10      20      1       2       7       1.\n", parse_cbar) ==
        "t.bdf:1: CBAR 10 field 7 (X2): expected blank (field 6 holds G0), got \"1.\"");
  CHECK(error_of("CBAR    10      20      1       2       0.      0.      0.\n", parse_cbar) ==
        "t.bdf:1: CBAR 10: orientation vector X1-X3 is zero (give X1-X3 or G0)");
  CHECK(error_of("CBAR    10      20      1       2       2\n", parse_cbar) ==
        "t.bdf:1: CBAR 10 field 6 (G0): expected a grid other than GA and GB, got \"2\"");
  CHECK(error_of("CBAR    10      20      1       2       0.      1.      0.      XYZ\n", parse_cbar) ==
        "t.bdf:1: CBAR 10 field 9 (OFFT): expected one of GGG, BGG, GGO, BGO, GOG, BOG, GOO, BOO, got \"XYZ\"");
  CHECK(error_of("CBAR    10      20      1       2       0.      1.      0.\n        17\n", parse_cbar) ==
        "t.bdf:2: CBAR 10 continuation 1 field 2 (PA): expected components (digits 1-6, each at most once), got \"17\"");
}

TEST_CASE("CBAR: the older field 9, a flag 1 (X1-X3) or 2 (G0), is read as OFFT GGG and kept", "[cards][bar]") {
  // MSC Nastran runs decks written this way (COSMIC NASTRAN's CBAR: F = 1 when
  // fields 6-8 hold X1-X3, 2 when field 6 holds G0).
  auto x = parse_text("CBAR    1       1       1       2       .0      .0      1.0     1\n", parse_cbar);
  CHECK(x.legacy_flag == 1);
  CHECK(x.offt == "GGG");
  CHECK(x.x == std::array<double, 3>{0.0, 0.0, 1.0});
  auto g = parse_text("CBAR    1       1       1       2       7                       2\n", parse_cbar);
  CHECK(g.legacy_flag == 2);
  CHECK(g.g0 == 7);
  CHECK(g.offt == "GGG");
  check_roundtrip(x, parse_cbar, write_cbar);
  check_roundtrip(g, parse_cbar, write_cbar);
  CHECK(write_cbar(x)[8] == FieldValue(std::int64_t{1}));
  CHECK(error_of("CBAR    1       1       1       2       .0      .0      1.0     3\n", parse_cbar) ==
        "t.bdf:1: CBAR 1 field 9 (OFFT): expected one of GGG, BGG, GGO, BGO, GOG, BOG, GOO, BOO, or the older flag 1 "
        "(X1-X3) or 2 (G0), got \"3\"");
  CHECK(error_of("CBAR    1       1       1       2       .0      .0      1.0     2\n", parse_cbar) ==
        "t.bdf:1: CBAR 1 field 9 (F): expected 1 (fields 6-8 hold X1-X3, not G0), got \"2\"");
  CHECK(error_of("CBAR    1       1       1       2       7                       1\n", parse_cbar) ==
        "t.bdf:1: CBAR 1 field 9 (F): expected 2 (field 6 holds G0, not X1), got \"1\"");
}

TEST_CASE("PBARL: dimension count by type, NSM after the dimensions, unknown types kept", "[cards][section]") {
  auto p = parse_text("PBARL   1       2               I\n        1.      2.      3.      4.      5.      6.      .5\n", parse_pbarl);
  CHECK(p.group == "MSCBML0");
  CHECK(p.type == "I");
  CHECK(p.dims == std::vector<double>{1, 2, 3, 4, 5, 6});
  CHECK(p.nsm == 0.5);
  auto r = parse_text("PBARL   1       2               ROD\n        .1\n", parse_pbarl);
  CHECK(r.dims == std::vector<double>{0.1});
  CHECK(r.nsm == 0.0);
  CHECK(pbarl_dim_count("ROD") == 1);
  CHECK(pbarl_dim_count("TUBE") == 2);
  CHECK(pbarl_dim_count("BAR") == 2);
  CHECK(pbarl_dim_count("BOX") == 4);
  CHECK(pbarl_dim_count("I") == 6);
  CHECK(pbarl_type_sectioned("BOX"));
  CHECK(pbarl_type_sectioned("CHAN"));
  CHECK(pbarl_dim_count("L") == 4);
  CHECK_FALSE(pbarl_type_sectioned("WEIRD"));
  auto u = parse_text("PBARL   1       2               WEIRD\n        1.      2.      3.\n", parse_pbarl);
  CHECK_FALSE(u.known_type);
  CHECK(u.dims == std::vector<double>{1, 2, 3});
  for (const auto& x : {p, r, u}) check_roundtrip(x, parse_pbarl, write_pbarl);
  CHECK(error_of("PBARL   1       2               BOX\n        1.      2.      -3.     4.\n", parse_pbarl) ==
        "t.bdf:2: PBARL 1 continuation 1 field 4 (DIM3): expected real > 0.0, got \"-3.\"");
  CHECK(error_of("PBARL   1       2               BOX\n        1.      2.      3.\n", parse_pbarl) ==
        "t.bdf:2: PBARL 1 continuation 1 field 5 (DIM4): expected real, got blank");
  CHECK(error_of("PBARL   1       2               TUBE\n        1.      .5      0.      9.\n", parse_pbarl) ==
        "t.bdf:2: PBARL 1: too many fields (PBARL has 11 data fields)");
}

TEST_CASE("PBEAML: end A, stations with SO and X/XB, blank dimensions from end A", "[cards][section]") {
  auto p = parse_text(
      "PBEAML  99      21              T\n"
      "        12.     14.8    2.5     26.             NO      .4      6.\n"
      "        7.      1.2     2.6             YES     .6      6.      7.8\n"
      "        5.6     2.3             YES\n",
      parse_pbeaml);
  REQUIRE(p.stations.size() == 4);
  CHECK(p.dims() == std::vector<double>{12, 14.8, 2.5, 26});
  CHECK(p.nsm() == 0.0);
  CHECK(p.stations[1].so == "NO");
  CHECK(p.stations[1].xxb == 0.4);
  CHECK(p.stations[1].dims == std::vector<double>{6, 7, 1.2, 2.6});
  CHECK(p.stations[2].dims == std::vector<double>{6, 7.8, 5.6, 2.3});
  CHECK(p.stations[3].xxb == 1.0);  // blank X/XB = 1.0 (end B)
  CHECK(p.stations[3].dims == p.dims());
  check_roundtrip(p, parse_pbeaml, write_pbeaml);
  auto c = parse_text("PBEAML  1       2               ROD\n        .1      .2\n", parse_pbeaml);
  CHECK(c.stations.size() == 1);
  CHECK(c.nsm() == 0.2);
  check_roundtrip(c, parse_pbeaml, write_pbeaml);
  CHECK(error_of("PBEAML  1       2               ROD\n        .1      .2      MAYBE\n", parse_pbeaml) ==
        "t.bdf:2: PBEAML 1 continuation 1 field 4 (SO): expected one of YES, YESA, NO, got \"MAYBE\"");
}

TEST_CASE("PBEAM: constant section, stations, K/S/NSI/CW/M/N tail", "[cards][beam]") {
  auto c = parse_text("PBEAM   1       2       3.      4.      5.      0.      6.      .1\n", parse_pbeam);
  CHECK(c.a == 3.0);
  CHECK(c.j == 6.0);
  CHECK(c.stations.empty());
  CHECK(c.k1 == 1.0);  // blank K1, K2 = 1.0
  CHECK(c.k2 == 1.0);
  check_roundtrip(c, parse_pbeam, write_pbeam);
  // The NASTRAN QRG example 2: a tapered beam with an intermediate station.
  auto t = parse_text(
      "PBEAM   9       7       9.5     18.073  98.792          .813\n"
      "        0.      2.      0.      -2.\n"
      "        NO      .5      6.5     5.385   35.542          .563\n"
      "        YES     1.      3.5     .698    7.292           .313\n"
      "\n"  // a blank line is not a continuation; the C..F row of end B is absent here
      "        2.1     1.8\n"
      "        .5\n",
      parse_pbeam);
  REQUIRE(t.stations.size() == 2);
  CHECK(t.c2 == 2.0);
  CHECK(t.d2 == -2.0);
  CHECK(t.stations[0].so == "NO");
  CHECK(t.stations[0].a == 6.5);
  CHECK(t.stations[0].i12 == 0.0);
  CHECK(t.stations[1].xxb == 1.0);
  CHECK(t.stations[1].j == 0.313);
  // SO = YES: the row after end B is its C..F row, then K1 K2 and M1(A).
  CHECK(t.stations[1].c1 == 2.1);
  CHECK(t.k1 == 0.5);
  CHECK(t.k2 == 1.0);
  check_roundtrip(t, parse_pbeam, write_pbeam);
  auto tail = parse_text(
      "PBEAM   1       2       3.      4.      5.\n"
      "\n"
      "        .9      .8      .1      .2      1.      2.      3.\n"
      "        .3      .4                      .5      .6\n",
      parse_pbeam);
  // A blank line is no row: the first row is C..F(A), the next one K1 K2 ...
  CHECK(tail.c1 == 0.9);
  CHECK(tail.k1 == 0.3);
  auto tail2 = parse_text(
      "PBEAM   1       2       3.      4.      5.\n"
      "        0.\n"
      "        .9      .8      .1      .2      1.              3.\n"
      "        .3      .4                      .5      .6\n",
      parse_pbeam);
  CHECK(tail2.k1 == 0.9);
  CHECK(tail2.s2 == 0.2);
  CHECK(tail2.nsia == 1.0);
  CHECK(tail2.nsib == 1.0);  // blank NSI(B) = NSI(A)
  CHECK(tail2.cwa == 3.0);
  CHECK(tail2.cwb == 3.0);
  CHECK(tail2.m1a == 0.3);
  CHECK(tail2.m1b == 0.3);
  CHECK(tail2.n1a == 0.5);
  CHECK(tail2.n2b == 0.6);
  check_roundtrip(tail2, parse_pbeam, write_pbeam);
  CHECK(error_of("PBEAM   1       2\n", parse_pbeam) == "t.bdf:1: PBEAM 1 field 4 (A(A)): expected real, got blank");
  CHECK(error_of("PBEAM   1       2       3.\n        0.\n        NO      .5\n", parse_pbeam) ==
        "t.bdf:3: PBEAM 1: the last PBEAM station must be end B (X/XB = 1.0)");
}

TEST_CASE("CBEAM: OFFT or BIT in field 9, SA/SB, BEAMOR defaults", "[cards][beam]") {
  auto c = parse_text("CBEAM   1       2       3       4       0.      0.      1.      .25\n        1       2\n        5       6\n", parse_cbeam);
  REQUIRE(c.bit);
  CHECK(*c.bit == 0.25);
  CHECK(c.pa == "1");
  CHECK(c.sa == 5);
  CHECK(c.sb == 6);
  check_roundtrip(c, parse_cbeam, write_cbeam);
  auto o = parse_text("CBEAM   1       2       3       4       9                       GOO\n", parse_cbeam);
  CHECK(o.g0 == 9);
  CHECK(o.offt == "GOO");
  CHECK_FALSE(o.bit);
  check_roundtrip(o, parse_cbeam, write_cbeam);
  auto b = parse_text("CBEAM   1               3       4\n", parse_cbeam);
  auto bo = parse_text("BEAMOR          7                       0.      1.      0.      .5\n", parse_beamor);
  CHECK(apply_beamor(b, &bo));
  CHECK(b.pid == 7);
  CHECK(b.x[1] == 1.0);
  CHECK(b.bit == 0.5);
  check_roundtrip(bo, parse_beamor, write_beamor);
  CHECK(error_of("CBEAM   1       2       3       4       0.      0.      1.      ABC\n", parse_cbeam) ==
        "t.bdf:1: CBEAM 1 field 9 (OFFT/BIT): expected one of GGG, BGG, GGO, BGO, GOG, BOG, GOO, BOO, got \"ABC\"");
  CHECK(error_of("CBEAM,1,2,3,4,0.,0.,1.,,+\n+,,,,,,,,,+\n+,-5\n", parse_cbeam) ==
        "t.bdf:3: CBEAM 1 continuation 2 field 2 (SA): expected positive integer (an id), got \"-5\"");
}

TEST_CASE("golden deck: materials, rods, bars, beams", "[cards][golden]") {
  check_golden("elements", {});  // PBARL 23 CHAN: sectioned since the full PBARL list
}

TEST_CASE("BAROR/BEAMOR fill blank CBAR/CBEAM fields in parse_bulk; missing orientation is a problem",
          "[cards][bar]") {
  Deck d = read_deck_text(
      "CBAR    1               1       2\n"
      "BAROR           5                       0.      0.      1.\n"
      "CBEAM   2       6       1       2\n"
      "BAROR           5\n",
      "o.bdf");
  BulkModel m = parse_bulk(d);
  REQUIRE(m.cbars.size() == 1);
  CHECK(m.cbars[0].pid == 5);
  CHECK(m.cbars[0].x[2] == 1.0);
  REQUIRE(m.problems.size() == 2);
  CHECK(m.problems[0].str() == "o.bdf:4: more than one BAROR (first at o.bdf:2)");
  CHECK(m.problems[1].str() == "o.bdf:3: CBEAM 2: orientation (fields 6-8) blank and no BEAMOR gives one");
}

TEST_CASE("a changed card is rewritten in its own format with full precision", "[cards][writer]") {
  Deck d = read_deck_text(
      "PBAR    20      1       1.-3    8.333-8 2.-7    1.5-7   .2\n"
      "        .01     .02     -.01    .02     -.01    -.02    .01     -.02\n"
      "MAT1,1,2.1+11,,.3,7850.\n",
      "p.bdf");
  BulkModel m = parse_bulk(d);
  m.pbars[0].a = 0.123456789;
  m.pbars[0].i1 = 1.23456789e-7;
  m.mat1s[0].e = 2.1e11 + 21000.0;
  const auto values = write_bulk(m);
  for (const auto& [i, v] : values) d.set_values(i, v);
  const std::string text = render_file(d, 0);
  INFO(text);
  // The changed PBAR goes to large field (8 columns cannot hold .123456789); unchanged
  // fields keep their text; the free-field MAT1 stays free field.
  CHECK_THAT(text, Catch::StartsWith("PBAR*   20              1               .123456789      1.23456789-7"));
  CHECK_THAT(text, Catch::Contains("*       2.-7            1.5-7"));
  CHECK_THAT(text, Catch::Contains("MAT1*,1,"));
  Deck back = read_deck_text(text, "q.bdf");
  BulkModel m2 = parse_bulk(back);
  REQUIRE(m2.problems.empty());
  CHECK(m2.pbars[0].a == 0.123456789);
  CHECK(m2.pbars[0].i1 == 1.23456789e-7);
  CHECK(m2.pbars[0].i2 == 2.0e-7);
  CHECK(m2.pbars[0].f2 == -0.02);
  CHECK(m2.mat1s[0].e == 2.1e11 + 21000.0);
  CHECK(m2.mat1s[0].nu == 0.3);
  CHECK_FALSE(m2.mat1s[0].g_given);  // G stays derived from the new E
}
