// DMIG: header and column entries in small, large and free field; forms 1, 2, 6, 9;
// real, complex, polar; symmetric expansion by hand values; errors; round trips.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>

#include "formats/deck_writer.hpp"
#include "formats/dmig.hpp"

using namespace ssid::formats;

namespace {

std::vector<Dmig> dmigs(const std::string& text) { return read_dmigs(read_deck_text(text, "t.bdf")); }

std::string error_of(const std::string& text) {
  try {
    Deck d = read_deck_text(text, "t.bdf");
    for (const Dmig& m : read_dmigs(d)) expand_dmig(m, &d);
  } catch (const ParseError& e) {
    return e.what();
  }
  return "(no error)";
}

/// Large-field line: the name field (8 chars) then 16-character fields.
std::string large(const std::string& first, std::initializer_list<std::string> fields) {
  std::string s = first;
  s.resize(8, ' ');
  for (const std::string& f : fields) {
    std::string g = f;
    g.resize(16, ' ');
    s += g;
  }
  return s + "\n";
}

using Key = std::pair<std::int64_t, int>;
std::map<std::pair<Key, Key>, std::complex<double>> as_map(const std::vector<DmigEntry>& e) {
  std::map<std::pair<Key, Key>, std::complex<double>> m;
  for (const DmigEntry& x : e) m[{{x.row.point, x.row.component}, {x.col.point, x.col.component}}] = x.value;
  return m;
}

}  // namespace

TEST_CASE("DMIG symmetric (IFO 6): mixed upper and lower triangle terms expand to the full matrix", "[dmig]") {
  // K on DOFs a=(10,1), b=(10,2), c=(20,0 scalar point):
  //   [ 4  -1  .5 ]
  //   [-1   3   2 ]
  //   [.5   2   5 ]
  // given as: column a rows a,b (lower); column b row b; column c rows a, c, b (upper).
  const std::string text =
      "DMIG    KSYM    0       6       2\n"
      "DMIG    KSYM    10      1               10      1       4.0\n"
      "DMIG    KSYM    10      1               10      2       -1.0\n"
      "DMIG    KSYM    10      2               10      2       3.\n"
      "DMIG    KSYM    20      0               10      1       .5\n"
      "        20              5.0             10      2       2.0\n";
  auto v = dmigs(text);
  REQUIRE(v.size() == 1);
  const Dmig& m = v[0];
  CHECK(m.name == "KSYM");
  CHECK(m.ifo == 6);
  CHECK(m.tin == 2);
  CHECK(m.tout == 0);
  CHECK_FALSE(m.polar);
  REQUIRE(m.columns.size() == 4);
  CHECK(m.columns[3].terms.size() == 3);
  CHECK(m.columns[3].terms[1].row == DmigKey{20, 0});
  auto e = expand_dmig(m);
  CHECK(e.size() == 9);
  auto k = as_map(e);
  const Key a{10, 1}, b{10, 2}, c{20, 0};
  CHECK(k[{a, a}] == 4.0);
  CHECK(k[{b, a}] == -1.0);
  CHECK(k[{a, b}] == -1.0);
  CHECK(k[{b, b}] == 3.0);
  CHECK(k[{a, c}] == 0.5);
  CHECK(k[{c, a}] == 0.5);
  CHECK(k[{b, c}] == 2.0);
  CHECK(k[{c, b}] == 2.0);
  CHECK(k[{c, c}] == 5.0);
  // Sorted by column then row.
  for (std::size_t i = 1; i < e.size(); ++i)
    CHECK((e[i - 1].col < e[i].col || (e[i - 1].col == e[i].col && e[i - 1].row < e[i].row)));
}

TEST_CASE("DMIG symmetric: a term given above and below the diagonal is an error with both locations", "[dmig]") {
  CHECK(error_of("DMIG    K       0       6       2\n"
                 "DMIG    K       1       1               2       1       4.0\n"
                 "DMIG    K       2       1               1       1       4.0\n") ==
        "t.bdf:3: DMIG K: term at row (1,1) column (2,1) given twice (both above and below the diagonal of a symmetric "
        "matrix); first at t.bdf:2");
  Deck d = read_deck_text(
      "DMIG    K       0       1       2\n"
      "DMIG    K       1       1               2       1       4.0\n"
      "DMIG    K       1       1               2       1       5.0\n",
      "t.bdf");
  auto v = read_dmigs(d);
  try {
    expand_dmig(v[0], &d);
    FAIL("no error");
  } catch (const ParseError& e) {
    CHECK(std::string(e.what()) == "t.bdf:3: DMIG K: term at row (2,1) column (1,1) given twice; first at t.bdf:2");
  }
}

TEST_CASE("DMIG complex polar (POLAR 1): magnitude and phase in degrees by hand values", "[dmig]") {
  const std::string text =
      "DMIG    BP      0       2       3       3       1\n"
      "DMIG    BP      5       3               5       3       2.0     30.0\n"
      "        6       1       1.5     90.     7       0       3.      -180.\n"
      "DMIG    BP      6       1               5       3       4.      0.\n";
  auto v = dmigs(text);
  REQUIRE(v.size() == 1);
  CHECK(v[0].polar);
  CHECK(v[0].tin == 3);
  CHECK(v[0].tout == 3);
  auto k = as_map(expand_dmig(v[0]));
  REQUIRE(k.size() == 4);
  const std::complex<double> z = k[{{5, 3}, {5, 3}}];
  CHECK(z.real() == Approx(std::sqrt(3.0)).epsilon(1e-15));
  CHECK(z.imag() == Approx(1.0).epsilon(1e-15));
  CHECK(k[{{6, 1}, {5, 3}}] == std::complex<double>(0.0, 1.5));  // 90 degrees: exactly imaginary
  CHECK(k[{{7, 0}, {5, 3}}] == std::complex<double>(-3.0, 0.0));
  CHECK(k[{{5, 3}, {6, 1}}] == std::complex<double>(4.0, 0.0));
  // |value| is the magnitude whatever the phase.
  CHECK(std::abs(z) == Approx(2.0).epsilon(1e-15));
}

TEST_CASE("DMIG complex real/imaginary, rectangular IFO 2 and IFO 9 by column number", "[dmig]") {
  auto v = dmigs(
      "DMIG    C       0       2       4\n"
      "DMIG    C       1       2               3       4       1.5     -2.5\n"
      "DMIG    C       1       2               4       4       1.5\n"  // B blank = 0
      "DMIG    R9      0       9       2                               3\n"
      "DMIG    R9      3                       101     2       7.\n");
  REQUIRE(v.size() == 2);
  auto c = as_map(expand_dmig(v[0]));
  CHECK(c[{{3, 4}, {1, 2}}] == std::complex<double>(1.5, -2.5));
  CHECK(c[{{4, 4}, {1, 2}}] == std::complex<double>(1.5, 0.0));
  CHECK(v[1].ifo == 9);
  CHECK(v[1].ncol == 3);
  CHECK(v[1].columns[0].col == DmigKey{3, 0});
  CHECK(as_map(expand_dmig(v[1]))[{{101, 2}, {3, 0}}] == 7.0);
}

TEST_CASE("DMIG in large field as NASTRAN punches it (.pch), D exponents, free field", "[dmig]") {
  const std::string pch = "$ punched by a test\n" + large("DMIG*", {"KAAX", "0", "1", "2"}) + large("*", {"0"}) +
                          large("DMIG*", {"KAAX", "11", "1"}) + large("*", {"11", "1", "1.000000000D+00"}) +
                          large("*", {"12", "3", "-2.500000000D-01"}) + large("DMIG*", {"KAAX", "12", "3"}) +
                          large("*", {"12", "3", "1.2345678901D+05"});
  const auto path = std::filesystem::temp_directory_path() / "ssid_test_dmig.pch";
  {
    std::ofstream(path) << pch;
  }
  auto v = read_dmig_file(path.string());
  std::filesystem::remove(path);
  REQUIRE(v.size() == 1);
  CHECK(v[0].ifo == 1);
  REQUIRE(v[0].columns.size() == 2);
  CHECK(v[0].columns[0].terms.size() == 2);
  CHECK(v[0].columns[0].terms[1].a == -0.25);
  CHECK(v[0].columns[1].terms[0].a == 123456.78901);

  auto f = dmigs("DMIG,KF,0,1,2\nDMIG,KF,1,0,,1,0,2.5\n");
  REQUIRE(f.size() == 1);
  CHECK(f[0].columns[0].terms[0].a == 2.5);
  CHECK(f[0].columns[0].col == DmigKey{1, 0});
}

TEST_CASE("DMIG errors name the file, line, card and field", "[dmig]") {
  CHECK(error_of("DMIG    K       1       1               2       1       4.0\n") ==
        "t.bdf:1: DMIG K: column entry of matrix K which has no header entry (DMIG K 0 IFO TIN ...)");
  CHECK(error_of("DMIG    K       0       3       2\n") ==
        "t.bdf:1: DMIG K field 4 (IFO): expected a form 1 (square), 2 or 9 (rectangular), 6 (symmetric), got \"3\"");
  CHECK(error_of("DMIG    K       0       1       5\n") ==
        "t.bdf:1: DMIG K field 5 (TIN): expected a precision 1-4 (real single, real double, complex single, complex "
        "double), got \"5\"");
  CHECK(error_of("DMIG    K       0       1       2               1\n") ==
        "t.bdf:1: DMIG K field 7 (POLAR): expected 0 or blank for a real matrix (TIN 1 or 2), got \"1\"");
  CHECK(error_of("DMIG    K       0       1       2\nDMIG    K       1       7               2       1       4.0\n") ==
        "t.bdf:2: DMIG K field 4 (CJ): expected a component 1-6 (0 or blank for a scalar point), got \"7\"");
  CHECK(error_of("DMIG    K       0       1       2\nDMIG    K       1       1               2       1       X\n") ==
        "t.bdf:2: DMIG K field 8 (Ai): expected real, got \"X\"");
  CHECK(error_of("DMIG    K       0       1       2\nDMIG    K       1       1               2       1       1.0     2.0\n") ==
        "t.bdf:2: DMIG K field 9 (Bi): expected blank (the matrix is real: TIN = 2), got \"2.0\"");
  CHECK(error_of("DMIG    K       0       1       2\n"
                 "DMIG    K       1       1               2       1       1.0\n"
                 "        3       1\n") == "t.bdf:3: DMIG K continuation 1 field 4 (Ai): expected real, got blank");
  CHECK(error_of("DMIG    K       0       9       2\n") ==
        "t.bdf:1: DMIG K field 9 (NCOL): expected integer, got blank");
  CHECK(error_of("DMIG    K       0       9       2                               2\n"
                 "DMIG    K       3                       1       1       1.0\n") ==
        "t.bdf:2: DMIG K field 3 (GJ): expected a column number 1..2 (NCOL of the header), got \"3\"");
  CHECK(error_of("DMIG    K       0       1       2\nDMIG    K       0       1       2\n") ==
        "t.bdf:2: DMIG K: second header for matrix K (first at t.bdf:1)");
}

TEST_CASE("DMIG write -> read round trip in small and large field, exact values", "[dmig]") {
  Dmig m;
  m.name = "KBIG";
  m.ifo = 6;
  m.tin = 4;
  m.tout = 4;
  m.polar = true;
  m.columns.push_back({{1, 1}, {{{1, 1}, 0.3333333333333, 12.5}, {{2, 0}, -7.0e-12, -170.0}}, 0});
  m.columns.push_back({{2, 0}, {{{2, 0}, 6.02214076e23, 0.0}}, 0});
  for (FieldFormat f : {FieldFormat::Small, FieldFormat::Large}) {
    const std::string text = format_dmig(m, f);
    INFO(text);
    auto v = dmigs(text);
    REQUIRE(v.size() == 1);
    const Dmig& r = v[0];
    CHECK(r.name == m.name);
    CHECK(r.ifo == m.ifo);
    CHECK(r.tin == m.tin);
    CHECK(r.tout == m.tout);
    CHECK(r.polar == m.polar);
    REQUIRE(r.columns.size() == 2);
    for (std::size_t c = 0; c < 2; ++c) {
      CHECK(r.columns[c].col == m.columns[c].col);
      REQUIRE(r.columns[c].terms.size() == m.columns[c].terms.size());
      for (std::size_t t = 0; t < m.columns[c].terms.size(); ++t) {
        CHECK(r.columns[c].terms[t].row == m.columns[c].terms[t].row);
        CHECK(r.columns[c].terms[t].a == m.columns[c].terms[t].a);
        CHECK(r.columns[c].terms[t].b == m.columns[c].terms[t].b);
      }
    }
  }
  // A double that needs 17 significant digits cannot be held by a 16-character
  // field: it is rounded to the most digits that fit (15 here), documented in docs/op4.md.
  Dmig third = m;
  third.columns[0].terms[0].a = 1.0 / 3.0;
  auto t3 = dmigs(format_dmig(third, FieldFormat::Large));
  CHECK(t3[0].columns[0].terms[0].a == 0.333333333333333);
  // A real matrix writes no B fields (golden small-field text).
  Dmig k;
  k.name = "K";
  k.ifo = 1;
  k.columns.push_back({{3, 2}, {{{3, 2}, 2.5}, {{4, 0}, -1.0}, {{5, 6}, 8.0}}, 0});
  CHECK(format_dmig(k) ==
        "DMIG    K       0       1       2\n"
        "DMIG    K       3       2               3       2       2.5\n"
        "+       4               -1.             5       6       8.\n");
}
