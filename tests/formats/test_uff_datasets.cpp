/// Datasets 58b, 1858, 2414, 2412, 82, 18 and 2420 from hand-built bytes: values
/// read, located errors, and byte-for-byte round trips of files laid out as the
/// writer lays them out.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>

#include "formats/uff.hpp"

using namespace ssid::formats;
using namespace ssid::formats::uff;

namespace {

std::string error_of(const std::string& text) {
  try {
    parse_uff(text, "bad.unv");
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

bool host_is_little_endian() {
  const std::uint16_t one = 1;
  unsigned char b[2];
  std::memcpy(b, &one, 2);
  return b[0] == 1;
}

/// The bytes of v as a float (size 4) or double (size 8), in byte order 1 (little)
/// or 2 (big): the host's representation, reversed where the host differs.
std::string ieee(double v, int size, int order) {
  char b[8];
  if (size == 4) {
    const float f = static_cast<float>(v);
    std::memcpy(b, &f, 4);
  } else {
    std::memcpy(b, &v, 8);
  }
  std::string s(b, static_cast<std::size_t>(size));
  if ((order == 1) != host_is_little_endian()) std::reverse(s.begin(), s.end());
  return s;
}

const std::string kAxes =
    "        18    0    0    0 Frequency            Hz                  \n"
    "        12    0    0    0 Acceleration         m/s^2               \n"
    "        13    0    0    0 Force                N                   \n"
    "         0    0    0    0 NONE                 NONE                \n";
const std::string kR6 = "    4         1    0         0 NONE               1   3 NONE               2   3\n";

/// A 58b as the writer lays it out: header, ID lines, R6, `r7`, axes, then `bytes`.
std::string file_58b(int order, const std::string& r7, const std::string& bytes) {
  char head[128];
  std::snprintf(head, sizeof head, "    58b%6d%6d%12d%12zu     0     0           0           0\n", order, 2, 11,
                bytes.size());
  return std::string("    -1\n") + head + "Pt 1 +Z / Hammer\nNONE\n27-Nov-26 05:57:00\nNONE\nNONE\n" + kR6 + r7 +
         kAxes + bytes + "    -1\n";
}

}  // namespace

TEST_CASE("UFF 58b: both byte orders, 4- and 8-byte values, real and complex, even and uneven", "[uff][58b]") {
  SECTION("complex double, even, big endian") {
    const std::vector<std::complex<double>> y{{1.5, -2.25}, {1e-300, 3.0}, {-0.0, 123456.789}};
    std::string bytes;
    for (const auto& v : y) bytes += ieee(v.real(), 8, 2) + ieee(v.imag(), 8, 2);
    const std::string text =
        file_58b(2, "         6         3         1  0.00000E+00  5.00000E-01  0.00000E+00\n", bytes);
    UffFile f = parse_uff(text, "b.unv");
    REQUIRE(f.functions().size() == 1);
    const Function58& fn = *f.functions()[0];
    CHECK(fn.binary);
    CHECK(fn.byte_order == 2);
    CHECK(fn.ordinate_type == 6);
    CHECK(fn.function_type == 4);
    CHECK(fn.response_node == 1);
    CHECK(fn.reference_direction == 3);
    CHECK(fn.y == y);
    CHECK(fn.x == std::vector<double>{0.0, 0.5, 1.0});
    CHECK(std::signbit(fn.y[2].real()));
    CHECK(format_uff(f) == text);
  }
  SECTION("real single, uneven, little endian: the abscissa is 4 bytes too") {
    const std::vector<double> x{0.5, 1.25, 3.0};
    const std::vector<float> y{1.0f, -2.5f, 1e-3f};
    std::string bytes;
    for (std::size_t i = 0; i < 3; ++i) bytes += ieee(x[i], 4, 1) + ieee(y[i], 4, 1);
    const std::string text =
        file_58b(1, "         2         3         0  0.00000E+00  0.00000E+00  0.00000E+00\n", bytes);
    UffFile f = parse_uff(text, "b.unv");
    const Function58& fn = *f.functions()[0];
    CHECK(fn.byte_order == 1);
    CHECK_FALSE(fn.even);
    CHECK(fn.x == x);
    for (std::size_t i = 0; i < 3; ++i) CHECK(fn.y[i] == std::complex<double>(y[i], 0.0));
    CHECK(format_uff(f) == text);
  }
  SECTION("real double, even, little endian; complex single, uneven, big endian") {
    std::string bytes = ieee(-7.0e-5, 8, 1) + ieee(M_PI, 8, 1);
    std::string text = file_58b(1, "         4         2         1  1.00000E+00  2.50000E-01  0.00000E+00\n", bytes);
    UffFile f = parse_uff(text, "b.unv");
    CHECK(f.functions()[0]->y == std::vector<std::complex<double>>{{-7.0e-5, 0}, {M_PI, 0}});
    CHECK(f.functions()[0]->x == std::vector<double>{1.0, 1.25});
    CHECK(format_uff(f) == text);

    bytes = ieee(10.0, 4, 2) + ieee(0.5, 4, 2) + ieee(-0.25, 4, 2);
    text = file_58b(2, "         5         1         0  0.00000E+00  0.00000E+00  0.00000E+00\n", bytes);
    UffFile g = parse_uff(text, "b.unv");
    CHECK(g.functions()[0]->x == std::vector<double>{10.0});
    CHECK(g.functions()[0]->y == std::vector<std::complex<double>>{{0.5, -0.25}});
    CHECK(format_uff(g) == text);
  }
  SECTION("bytes that look like delimiters and line ends are data; a line end before the delimiter is tolerated") {
    const std::string bytes = "\n    -1\n    55\n\x01\x02\x03\x04\x05";  // 20 bytes: 5 floats
    REQUIRE(bytes.size() == 20);
    std::string text = file_58b(1, "         2         5         1  0.00000E+00  1.00000E+00  0.00000E+00\n", bytes);
    text.insert(text.size() - 7, "\r\n");  // as some writers put one before "    -1"
    text += "    -1\n  2467\nkept\n    -1\n";
    UffFile f = parse_uff(text, "b.unv");
    REQUIRE(f.datasets.size() == 2);
    const Function58& fn = *f.functions()[0];
    REQUIRE(fn.y.size() == 5);
    for (std::size_t i = 0; i < 5; ++i) {
      float v;
      std::string b = bytes.substr(4 * i, 4);
      if (!host_is_little_endian()) std::reverse(b.begin(), b.end());
      std::memcpy(&v, b.data(), 4);
      CHECK((fn.y[i].real() == static_cast<double>(v) || (std::isnan(v) && std::isnan(fn.y[i].real()))));
    }
    CHECK(f.skipped() == std::map<int, std::size_t>{{2467, 1}});
  }
}

TEST_CASE("UFF 58b: located errors", "[uff][58b][errors]") {
  const std::string r7 = "         2         3         1  0.00000E+00  1.00000E+00  0.00000E+00\n";
  const std::string bytes = ieee(1, 4, 1) + ieee(2, 4, 1) + ieee(3, 4, 1);
  std::string text = file_58b(1, r7, bytes);

  std::string t = text;
  t.replace(7 + 7, 6, "     3");
  CHECK(error_of(t) == "bad.unv:2: dataset 58b header field 3 (byte ordering): expected 1 (little endian) or 2 (big "
                       "endian), got \"3\"");
  t = text;
  t.replace(7 + 13, 6, "     1");
  CHECK(error_of(t) == "bad.unv:2: dataset 58b header field 4 (floating point format): expected 2 (IEEE 754; 1 DEC "
                       "VMS and 3 IBM 370 are not read), got \"1\"");
  t = text;
  t.replace(7 + 19, 12, "          10");
  CHECK(error_of(t) == "bad.unv:2: dataset 58b header field 5 (number of ASCII lines): expected 11 (records 1-11 of "
                       "dataset 58), got \"10\"");
  // The header declares more bytes than the file holds.
  t = text.substr(0, text.size() - bytes.size() - 7);
  t.replace(7 + 31, 12, "         400");
  CHECK(error_of(t) == "bad.unv:2: dataset 58 record 12: the 58b header declares 400 bytes of binary data after the "
                       "ASCII records, the file holds only 0");
  // Record 7's count and the header's bytes disagree.
  CHECK(error_of(file_58b(1, "         2         4         1  0.00000E+00  1.00000E+00  0.00000E+00\n", bytes)) ==
        "bad.unv:9: dataset 58 record 7 field 2 (number of data values): expected 3 (the 58b header at line 2 "
        "declares 12 bytes; a point is 1 value(s) of 4 bytes), got \"4\"");
  CHECK(error_of(file_58b(1, "         2 999999999         1  0.00000E+00  1.00000E+00  0.00000E+00\n", bytes)) ==
        "bad.unv:9: dataset 58 record 7 field 2 (number of data values): expected 3 (the 58b header at line 2 "
        "declares 12 bytes; a point is 1 value(s) of 4 bytes), got \"999999999\"");
  // Something other than a line end between the bytes and the delimiter: the byte count is wrong.
  t = text;
  t.insert(t.size() - 7, "junk\n");
  CHECK(error_of(t) == "bad.unv:14: dataset 58b (opened at line 2): expected the closing delimiter \"    -1\" right "
                       "after the 12 bytes of binary data the header declares, got \"junk\"");
  // Too few ASCII records before the end of the file.
  CHECK(error_of("    -1\n    58b     1     2          11           0     0     0           0           0\nA\nB\n") ==
        "bad.unv:4: dataset 58b opened at line 2 ends after 2 of its 11 ASCII records");
}

TEST_CASE("UFF 58 ASCII: every ordinate type with even and uneven abscissa, every function type", "[uff][58]") {
  // Values with 6 significant digits survive the single-precision layouts; 13 the double ones.
  const int function_types[] = {1, 2, 3, 4, 6};
  for (int ot : {2, 4, 5, 6})
    for (bool even : {true, false})
      for (int ft : function_types) {
        Function58 fn;
        fn.id_lines = {"ID", "NONE", "NONE", "NONE", "NONE"};
        fn.function_type = ft;
        fn.response_node = 3;
        fn.response_direction = -2;
        fn.reference_node = 1;
        fn.reference_direction = 3;
        fn.ordinate_type = ot;
        fn.even = even;
        fn.abscissa_min = 0.5;
        fn.abscissa_increment = 0.25;
        const bool cplx = ot == 5 || ot == 6;
        for (int i = 0; i < 7; ++i) {
          fn.x.push_back(even ? 0.5 + 0.25 * i : 1.5 * i + 0.125);
          fn.y.push_back({1.25 * i - 2.5, cplx ? -0.75 * i : 0.0});
        }
        UffFile f;
        f.datasets.push_back(fn);
        UffFile g = parse_uff(format_uff(f), "58.unv");
        const Function58& r = *g.functions()[0];
        CHECK(r.function_type == ft);
        CHECK(r.ordinate_type == ot);
        CHECK(r.even == even);
        CHECK(r.x == fn.x);
        CHECK(r.y == fn.y);
        CHECK(format_uff(g) == format_uff(f));
      }
}

TEST_CASE("UFF 58 ASCII: double uneven layouts by hand, records not filled to the last column", "[uff][58]") {
  const std::string head = "    -1\n    58\nA\nB\nC\nD\nE\n" + kR6;
  // Type 4 uneven: 2(E13.5,E20.12); type 6 uneven: E13.5,2E20.12.
  UffFile f = parse_uff(head + "         4         3         0  0.00000E+00  0.00000E+00  0.00000E+00\n" + kAxes +
                            "  1.00000E+00  1.234567890123E+00  2.00000E+00 -2.000000000001E-03\n"
                            "  4.00000E+00  3.000000000000D+00\n    -1\n",
                        "u.unv");
  CHECK(f.functions()[0]->x == std::vector<double>{1.0, 2.0, 4.0});
  CHECK(f.functions()[0]->y[1].real() == -2.000000000001e-3);
  CHECK(f.functions()[0]->y[2].real() == 3.0);
  UffFile g = parse_uff(head + "         6         2         0  0.00000E+00  0.00000E+00  0.00000E+00\n" + kAxes +
                            "  1.00000E+00  1.234567890123E+00 -2.000000000001E-03\n"
                            "  2.00000E+00  5.000000000000E-01  2.500000000000E-01\n    -1\n",
                        "u.unv");
  CHECK(g.functions()[0]->y == std::vector<std::complex<double>>{{1.234567890123, -2.000000000001e-3}, {0.5, 0.25}});
  // A time history whose last line holds fewer than 6 values, the line not padded.
  UffFile h = parse_uff(head + "         2         8         1  0.00000E+00  1.00000E-03  0.00000E+00\n" + kAxes +
                            "  1.00000E+00  2.00000E+00  3.00000E+00  4.00000E+00  5.00000E+00  6.00000E+00\n"
                            "  7.00000E+00  8.00000E+00\n    -1\n",
                        "u.unv");
  CHECK(h.functions()[0]->y.back().real() == 8.0);
}

TEST_CASE("UFF 1858: function qualifiers read and written back byte for byte", "[uff][1858]") {
  const std::string text =
      "    -1\n  1858\n"
      "           1           3           2           0           0           0\n"
      "     0     5     3     2     0     0     0     0     0     0     0     0\n"
      "  0.0000000E+00  0.0000000E+00  0.0000000E+00  2.0480000E+03  0.0000000E+00\n"
      "  0.0000000E+00  0.0000000E+00  0.0000000E+00  0.0000000E+00  5.2706007E-02\n"
      "  0.0000000E+00  0.0000000E+00  0.0000000E+00  0.0000000E+00  0.0000000E+00\n"
      "Z+    X+\n"
      "NONE\n"
      "    -1\n";
  UffFile f = parse_uff(text, "q.unv");
  const auto& q = std::get<Qualifiers1858>(f.datasets.at(0));
  CHECK(q.r1[1] == 3);
  CHECK(q.window() == 5);
  CHECK(q.r2[2] == 3);
  CHECK(q.samples() == 2048.0);
  CHECK(q.exponential_damping() == 5.2706007e-2);
  CHECK(q.directions == "Z+    X+");
  CHECK(format_uff(f) == text);
  CHECK(error_of("    -1\n  1858\n           1           x\n    -1\n") ==
        "bad.unv:3: dataset 1858 record 1 field 2 (record 1 integer): expected integer (I12, columns 13-24), got \"  "
        "         x\"");
}

namespace {

const std::string k2414 =
    "    -1\n  2414\n"
    "         1\nMode 2\n         1\nID1\nID2\nID3\nID4\nID5\n"
    "         1         2         3         8         2         6\n"
    "         0         0         1         0         5         2         0         0\n"
    "         0         0\n"
    "  0.00000E+00  1.25000E+01  0.00000E+00  2.00000E+00  1.00000E-02  0.00000E+00\n"
    "  0.00000E+00  0.00000E+00  0.00000E+00  0.00000E+00  0.00000E+00  0.00000E+00\n"
    "         7\n"
    "  1.00000E+00 -5.00000E-01  0.00000E+00  0.00000E+00  0.00000E+00  2.50000E-01\n"
    "         9\n"
    " -1.00000E+00  5.00000E-01  1.00000E-03  0.00000E+00  0.00000E+00  0.00000E+00\n"
    "    -1\n";

}  // namespace

TEST_CASE("UFF 2414: nodal results read as modes in the 55 structure", "[uff][2414]") {
  UffFile f = parse_uff(k2414, "r.unv");
  REQUIRE(f.nodal_data().size() == 1);
  const NodalData55& m = *f.nodal_data()[0];
  CHECK(dataset_number(f.datasets[0]) == 2414);
  CHECK(m.is_normal_mode());
  CHECK(m.mode_number() == 2);
  CHECK(m.load_case() == 5);
  CHECK(m.frequency_hz() == 12.5);
  CHECK(m.modal_mass() == 2.0);
  CHECK(m.viscous_damping() == 0.01);
  CHECK(m.nodes == std::vector<std::int64_t>{7, 9});
  REQUIRE(m.values.rows() == 2);
  REQUIRE(m.values.cols() == 6);
  CHECK(m.values(0, 1) == -0.5);
  CHECK(m.values(0, 5) == 0.25);
  CHECK(m.values(1, 2) == 0.001);
  REQUIRE(m.analysis2414);
  CHECK(m.analysis2414->name == "Mode 2");
  CHECK(format_uff(f) == k2414);
  // Double precision values (data type 4) in D25.16, three to a line.
  std::string dbl = k2414;
  dbl.replace(dbl.find("         2         6\n"), 21, "         4         6\n");
  const std::string single_rows =
      "  1.00000E+00 -5.00000E-01  0.00000E+00  0.00000E+00  0.00000E+00  2.50000E-01\n";
  dbl.replace(dbl.find(single_rows), single_rows.size(),
              "   1.0000000000000000D+00  -5.0000000000000000D-01   0.0000000000000000D+00\n"
              "   0.0000000000000000D+00   0.0000000000000000D+00   1.2345678901234566D-01\n");
  dbl.replace(dbl.find(" -1.00000E+00  5.00000E-01  1.00000E-03  0.00000E+00  0.00000E+00  0.00000E+00\n"), 79,
              "  -1.0000000000000000D+00   5.0000000000000000D-01   1.0000000000000000D-03\n"
              "   0.0000000000000000D+00   0.0000000000000000D+00   0.0000000000000000D+00\n");
  UffFile g = parse_uff(dbl, "r.unv");
  CHECK(g.nodal_data()[0]->values(0, 5) == 0.12345678901234566);
  CHECK(format_uff(g) == dbl);
  // Data on elements (location 2) is kept verbatim.
  std::string elements = k2414;
  elements.replace(elements.find("Mode 2\n         1\n"), 18, "Mode 2\n         2\n");
  UffFile e = parse_uff(elements, "r.unv");
  CHECK(e.skipped() == std::map<int, std::size_t>{{2414, 1}});
  CHECK(format_uff(e) == elements);
  std::string bad = k2414;
  bad.replace(bad.find("         2         6\n"), 21, "         3         6\n");
  CHECK(error_of(bad) == "bad.unv:11: dataset 2414 record 9 field 5 (data type): expected 2, 4 (real) or 5, 6 "
                         "(complex), got \"3\"");
}

TEST_CASE("UFF 2412 and 82: test geometry lines, written back byte for byte", "[uff][2412][82]") {
  const std::string text =
      "    -1\n  2412\n"
      "         1        21         1         1         7         2\n"
      "         0         1         1\n"
      "         3         4\n"
      "         2        41         1         1         7         3\n"
      "         3         4         5\n"
      "         3       118         2         2         7        10\n"
      "         1         2         3         4         5         6         7         8\n"
      "         9        10\n"
      "    -1\n"
      "    -1\n    82\n"
      "         4         9         8\n"
      "Stator\n"
      "         2         5         6         3         4         1         2         3\n"
      "         0\n"
      "    -1\n";
  UffFile f = parse_uff(text, "g.unv");
  const auto& e = std::get<ElementSet2412>(f.datasets.at(0));
  REQUIRE(e.elements.size() == 3);
  CHECK(e.elements[0].beam == std::array<std::int64_t, 3>{0, 1, 1});
  CHECK(e.elements[0].nodes == std::vector<std::int64_t>{3, 4});
  CHECK_FALSE(e.elements[1].beam);
  CHECK(e.elements[2].descriptor == 118);
  CHECK(e.elements[2].nodes.size() == 10);
  const auto& t = std::get<TraceLine82>(f.datasets.at(1));
  CHECK(t.id == 4);
  CHECK(t.label == "Stator");
  CHECK(t.nodes == std::vector<std::int64_t>{2, 5, 6, 3, 4, 1, 2, 3, 0});
  CHECK(format_uff(f) == text);
  // Test.Lab fills the last line of the nodes with zeros past the count.
  UffFile z = parse_uff("    -1\n    82\n         1         2         8\nL\n         1         2         0         0\n"
                        "         0         0         0         0         0         0         0         0\n    -1\n",
                        "g.unv");
  CHECK(std::get<TraceLine82>(z.datasets.at(0)).nodes == std::vector<std::int64_t>{1, 2});
  CHECK(error_of("    -1\n    82\n         1         3         8\nL\n         1         x\n    -1\n") ==
        "bad.unv:5: dataset 82 record 3 field 2 (trace line node): expected integer (I10, columns 11-20), got \"         "
        "x\"");
}

TEST_CASE("UFF 18 and 2420: coordinate systems applied to node positions and measured directions", "[uff][18][2420]") {
  const std::string text =
      "    -1\n    18\n"
      "         1         0         0         8         1\n"
      "SYS1\n"
      " -2.40000E+00 -9.50000E-01  0.00000E+00 -3.40000E+00 -9.50000E-01  0.00000E+00\n"
      " -3.40000E+00 -9.50000E-01 -1.00000E+00\n"
      "         2         0         1         8         1\n"
      "SYS2 in SYS1\n"
      "  1.00000E+00  0.00000E+00  0.00000E+00  1.00000E+00  1.00000E+00  0.00000E+00\n"
      "  1.00000E+00  0.00000E+00  1.00000E+00\n"
      "    -1\n"
      "    -1\n  2420\n"
      "         1\nPART\n"
      "         5         1         2\n"
      "CYL\n"
      "   1.0000000000000000D+00   0.0000000000000000D+00   0.0000000000000000D+00\n"
      "   0.0000000000000000D+00   1.0000000000000000D+00   0.0000000000000000D+00\n"
      "   0.0000000000000000D+00   0.0000000000000000D+00   1.0000000000000000D+00\n"
      "   1.0000000000000000D+00   0.0000000000000000D+00   0.0000000000000000D+00\n"
      "    -1\n"
      "    -1\n    15\n"
      "        11         1         1         0  1.00000E+00  2.00000E+00  3.00000E+00\n"
      "        12         5         5         0  2.00000E+00  9.00000E+01  1.00000E+00\n"
      "        13         2         0         0  1.00000E+00  0.00000E+00  0.00000E+00\n"
      "    -1\n";
  UffFile f = parse_uff(text, "cs.unv");
  CHECK(format_uff(f) == text);
  const auto cs = f.coordinate_systems();
  REQUIRE(cs.size() == 3);
  // SYS1: origin (-2.4, -0.95, 0); +X towards (-3.4, -0.95, 0); the XZ plane through (-3.4, -0.95, -1):
  // axes x = (-1, 0, 0), z = (0, 0, -1), y = z × x = (0, 1, 0).
  const auto nodes = f.nodes_in_global();
  auto near = [](const std::array<double, 3>& a, const std::array<double, 3>& b) {
    return std::abs(a[0] - b[0]) < 1e-12 && std::abs(a[1] - b[1]) < 1e-12 && std::abs(a[2] - b[2]) < 1e-12;
  };
  CHECK(near(nodes[0].xyz, {-2.4 - 1.0, -0.95 + 2.0, -3.0}));
  // Cylindrical 2420 system 5 at (1, 0, 0): r = 2, θ = 90°, z = 1.
  CHECK(near(nodes[1].xyz, {1.0, 2.0, 1.0}));
  // SYS2 is defined in SYS1: origin (1,0,0) in SYS1 = (-3.4, -0.95, 0); its +X is SYS1's +Y = global +Y.
  CHECK(near(nodes[2].xyz, {-3.4, -0.95 + 1.0, 0.0}));
  CHECK(near(f.direction_in_global(f.nodes()[0], 3), {0, 0, -1}));
  CHECK(near(f.direction_in_global(f.nodes()[0], -1), {1, 0, 0}));
  CHECK(near(f.direction_in_global(f.nodes()[0], 6), {0, 0, -1}));
  // Radial and tangential at θ = 90°.
  CHECK(near(f.direction_in_global(f.nodes()[1], 1), {0, 1, 0}));
  CHECK(near(f.direction_in_global(f.nodes()[1], 2), {-1, 0, 0}));
  // A node in a system the file does not define.
  UffFile g = parse_uff("    -1\n    15\n        11         4         0         0  1.0E+00  2.0E+00  3.0E+00\n    -1\n",
                        "cs.unv");
  try {
    g.nodes_in_global();
    FAIL("no error");
  } catch (const InputError& e) {
    CHECK(std::string(e.what()) ==
          "node 11: definition coordinate system 4 is not defined in the file (datasets 18, 2420)");
  }
  CHECK(error_of("    -1\n    18\n         1         3         0         8         1\nX\n    -1\n") ==
        "bad.unv:3: dataset 18 record 1 field 2 (coordinate system type): expected 0 (Cartesian), 1 (cylindrical) or "
        "2 (spherical), got \"3\"");
}

TEST_CASE("UFF: stray characters of real files: a byte-order mark, a DOS end-of-file mark", "[uff]") {
  UffFile f = parse_uff("\xEF\xBB\xBF    -1\n  2467\nx\n    -1\n\x1a", "s.unv");
  REQUIRE(f.datasets.size() == 1);
  CHECK(f.skipped() == std::map<int, std::size_t>{{2467, 1}});
  UffFile g = parse_uff("    -1\n  2467\nx\n    -1\r\n\x1a\r\n", "s.unv");
  CHECK(g.datasets.size() == 1);
  // Anywhere else the mark is a byte that is not text.
  CHECK(error_of("    -1\n  2467\nx\n    -1\n\x1a\n    -1\n  2467\ny\n    -1\n") ==
        "bad.unv:5: byte 0x1A at column 1 is not text (where a dataset delimiter is expected)");
}
