#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <random>

#include "formats/uff.hpp"

using namespace ssid::formats;
using namespace ssid::formats::uff;

namespace {

const std::string kMixed = std::string(SSID_TEST_DATA) + "/uff/testlab_mixed.unv";

template <class T>
const T& nth(const UffFile& f, std::size_t k) {
  std::size_t seen = 0;
  for (const auto& d : f.datasets)
    if (auto p = std::get_if<T>(&d))
      if (seen++ == k) return *p;
  throw std::runtime_error("dataset not found");
}

std::string error_of(const std::string& text) {
  try {
    parse_uff(text, "bad.unv");
  } catch (const ParseError& e) {
    return e.what();
  }
  return "no error";
}

/// Field-by-field equality of two files (exact doubles).
void require_same(const UffFile& a, const UffFile& b) {
  REQUIRE(a.datasets.size() == b.datasets.size());
  for (std::size_t k = 0; k < a.datasets.size(); ++k) {
    REQUIRE(dataset_number(a.datasets[k]) == dataset_number(b.datasets[k]));
    const auto& x = a.datasets[k];
    const auto& y = b.datasets[k];
    if (auto h = std::get_if<Header151>(&x)) {
      CHECK(h->lines == std::get<Header151>(y).lines);
    } else if (auto u = std::get_if<Units164>(&x)) {
      const auto& v = std::get<Units164>(y);
      CHECK(u->code == v.code);
      CHECK(u->description == v.description);
      CHECK(u->temperature_mode == v.temperature_mode);
      CHECK(u->length == v.length);
      CHECK(u->force == v.force);
      CHECK(u->temperature == v.temperature);
      CHECK(u->temperature_offset == v.temperature_offset);
    } else if (auto s = std::get_if<NodeSet>(&x)) {
      const auto& t = std::get<NodeSet>(y);
      REQUIRE(s->nodes.size() == t.nodes.size());
      for (std::size_t i = 0; i < s->nodes.size(); ++i) {
        CHECK(s->nodes[i].id == t.nodes[i].id);
        CHECK(s->nodes[i].definition_cs == t.nodes[i].definition_cs);
        CHECK(s->nodes[i].displacement_cs == t.nodes[i].displacement_cs);
        CHECK(s->nodes[i].color == t.nodes[i].color);
        CHECK(s->nodes[i].xyz == t.nodes[i].xyz);
      }
    } else if (auto m = std::get_if<NodalData55>(&x)) {
      const auto& n = std::get<NodalData55>(y);
      CHECK(m->id_lines == n.id_lines);
      CHECK(m->analysis_type == n.analysis_type);
      CHECK(m->data_characteristic == n.data_characteristic);
      CHECK(m->specific_data_type == n.specific_data_type);
      CHECK(m->is_complex() == n.is_complex());
      CHECK(m->values_per_node == n.values_per_node);
      CHECK(m->int_params == n.int_params);
      CHECK(m->real_params == n.real_params);
      CHECK(m->nodes == n.nodes);
      CHECK(m->values == n.values);
      CHECK(m->complex_values == n.complex_values);
    } else if (auto f = std::get_if<Function58>(&x)) {
      const auto& g = std::get<Function58>(y);
      CHECK(f->id_lines == g.id_lines);
      CHECK(f->function_type == g.function_type);
      CHECK(f->response_node == g.response_node);
      CHECK(f->response_direction == g.response_direction);
      CHECK(f->reference_node == g.reference_node);
      CHECK(f->reference_direction == g.reference_direction);
      CHECK(f->ordinate_type == g.ordinate_type);
      CHECK(f->even == g.even);
      CHECK(f->x == g.x);
      CHECK(f->y == g.y);
      for (int a = 0; a < 4; ++a) {
        CHECK(f->axes[a].specific_data_type == g.axes[a].specific_data_type);
        CHECK(f->axes[a].label == g.axes[a].label);
        CHECK(f->axes[a].units == g.axes[a].units);
        CHECK(f->axes[a].length_exponent == g.axes[a].length_exponent);
        CHECK(f->axes[a].force_exponent == g.axes[a].force_exponent);
      }
    } else if (auto t = std::get_if<TraceLine82>(&x)) {
      const auto& u = std::get<TraceLine82>(y);
      CHECK(t->id == u.id);
      CHECK(t->color == u.color);
      CHECK(t->label == u.label);
      CHECK(t->nodes == u.nodes);
    } else {
      const auto& u1 = std::get<UnknownDataset>(x);
      const auto& u2 = std::get<UnknownDataset>(y);
      CHECK(u1.header_line == u2.header_line);
      // Verbatim bodies keep their line ends; compare the content.
      auto no_cr = [](std::string t) {
        t.erase(std::remove(t.begin(), t.end(), '\r'), t.end());
        return t;
      };
      CHECK(no_cr(u1.body) == no_cr(u2.body));
    }
  }
}

}  // namespace

TEST_CASE("UFF: a hand-laid test-lab file with every supported dataset", "[uff]") {
  UffFile f = read_uff(kMixed);
  std::vector<int> numbers;
  for (const auto& d : f.datasets) numbers.push_back(dataset_number(d));
  CHECK(numbers == std::vector<int>{151, 164, 15, 2411, 82, 55, 55, 55, 58, 58});
  CHECK(f.skipped().empty());
  const auto& trace = nth<TraceLine82>(f, 0);
  CHECK(trace.id == 1);
  CHECK(trace.color == 8);
  CHECK(trace.label == "Trace");
  CHECK(trace.nodes == std::vector<std::int64_t>{1, 2, 3});

  const auto& h = nth<Header151>(f, 0);
  CHECK(h.model_name() == "MPI truss modal test");
  CHECK(h.program() == "LMS Test.Lab 15A");
  CHECK(h.lines.size() == 7);

  const auto& u = nth<Units164>(f, 0);
  CHECK(u.code == 1);
  CHECK(u.description == "SI - mks (m/kg/s)");
  CHECK(u.temperature_mode == 2);
  CHECK(u.length == 1.0);
  CHECK(u.temperature_offset == 273.15);  // D exponent

  // Dataset 15: touching E13.6 values split by column, lower-case e and d exponents.
  const auto& n15 = nth<NodeSet>(f, 0);
  CHECK(n15.dataset == 15);
  REQUIRE(n15.nodes.size() == 3);
  CHECK(n15.nodes[1].xyz == std::array<double, 3>{-1.25, -0.25, 3.0});
  CHECK(n15.nodes[2].xyz == std::array<double, 3>{1.0, 2.0, 0.3});
  CHECK(n15.nodes[0].color == 8);

  // Dataset 2411: double precision to the last bit.
  const auto& n2411 = nth<NodeSet>(f, 1);
  CHECK(n2411.dataset == 2411);
  REQUIRE(n2411.nodes.size() == 2);
  CHECK(n2411.nodes[0].id == 101);
  CHECK(n2411.nodes[0].definition_cs == 1);
  CHECK(n2411.nodes[0].xyz[2] == -M_PI);
  CHECK(n2411.nodes[1].xyz[1] == 123.45678901234567);
  CHECK(f.nodes().size() == 5);

  const auto modes = f.nodal_data();
  REQUIRE(modes.size() == 3);
  const auto& m1 = *modes[0];
  CHECK(m1.is_normal_mode());
  CHECK_FALSE(m1.is_complex());
  CHECK(m1.mode_number() == 1);
  CHECK(m1.load_case() == 1);
  CHECK(m1.frequency_hz() == 7.75);
  CHECK(m1.modal_mass() == 1.0);
  CHECK(m1.viscous_damping() == 0.012);
  CHECK(m1.id_lines[0] == "MODE 1");
  CHECK(m1.nodes == std::vector<std::int64_t>{1, 2, 3});
  REQUIRE(m1.values.rows() == 3);
  REQUIRE(m1.values.cols() == 3);
  CHECK(m1.values(0, 1) == -0.5);
  CHECK(m1.values(1, 0) == -0.125);  // touching E13.6 fields
  CHECK(m1.values(1, 2) == 0.03125);
  CHECK(m1.values(2, 0) == 1e-3);  // D exponent
  const auto& m2 = *modes[1];
  CHECK(m2.values_per_node == 6);
  CHECK(m2.data_characteristic == 3);
  CHECK(m2.values(2, 5) == 7.5);
  CHECK(m2.values(1, 3) == -4.0);
  CHECK(m2.mode_number() == 2);
  const auto& c = *modes[2];
  CHECK(c.is_complex_mode());
  CHECK(c.is_complex());
  CHECK(c.eigenvalue() == std::complex<double>(-0.5, 48.0));
  CHECK(c.frequency_hz() == Approx(std::hypot(0.5, 48.0) / (2 * M_PI)).epsilon(1e-15));
  CHECK(c.complex_values(0, 1) == std::complex<double>(-1.0, -0.5));
  CHECK(c.complex_values(1, 2) == std::complex<double>(2.0, 2.0));

  const auto fn = f.functions();
  REQUIRE(fn.size() == 2);
  const auto& frf = *fn[0];
  CHECK(frf.function_type == 4);
  CHECK(frf.response_node == 1);
  CHECK(frf.response_direction == 1);
  CHECK(frf.reference_node == 2);
  CHECK(frf.reference_direction == 3);
  CHECK(frf.is_complex());
  CHECK(frf.even);
  CHECK(frf.x == std::vector<double>{0.0, 0.5, 1.0});
  CHECK(frf.y[0] == std::complex<double>(1.0, -2.0));
  CHECK(frf.y[2] == std::complex<double>(-1.5e-3, 300.0));
  CHECK(frf.axes[0].label == "Frequency");
  CHECK(frf.axes[1].units == "m/s^2");
  CHECK(frf.axes[2].force_exponent == 1);
  const auto& th = *fn[1];
  CHECK(th.function_type == 1);
  CHECK(th.response_direction == -2);
  CHECK_FALSE(th.even);
  CHECK_FALSE(th.is_complex());
  CHECK(th.x == std::vector<double>{0.0, 0.1, 0.25, 0.3});
  CHECK(th.y[3] == std::complex<double>(2.0, 0.0));
  CHECK(th.y[1] == std::complex<double>(-1.0, 0.0));
}

TEST_CASE("UFF: CR-LF line ends read the same", "[uff]") {
  UffFile f = read_uff(kMixed);
  std::ifstream in(kMixed);
  std::string text((std::istreambuf_iterator<char>(in)), {}), crlf;
  for (char ch : text) {
    if (ch == '\n') crlf += '\r';
    crlf += ch;
  }
  UffFile g = parse_uff(crlf, "crlf.unv");
  require_same(f, g);
}

TEST_CASE("UFF: write then read gives the same data; writing is idempotent", "[uff][roundtrip]") {
  // Every value in the hand-laid file has at most 6 significant digits except 2411
  // (D25.16) and the 58 double data (E20.12): the standard layouts keep them all.
  UffFile f = read_uff(kMixed);
  const std::string once = format_uff(f);
  UffFile g = parse_uff(once, "once.unv");
  require_same(f, g);
  CHECK(format_uff(g) == once);
  // The trace line is written in its layout (3I10, 80A1, 8I10).
  CHECK(once.find("    82\n         1         3         8\nTrace\n         1         2         3\n    -1\n") !=
        std::string::npos);
}

TEST_CASE("UFF: extended precision round trip is exact for arbitrary doubles", "[uff][roundtrip]") {
  std::mt19937 rng(42);
  std::normal_distribution<double> g(0.0, 1.0);
  Eigen::MatrixXd v(5, 6);
  for (Eigen::Index i = 0; i < v.size(); ++i) v(i) = g(rng) * std::pow(10.0, static_cast<int>(g(rng) * 5));
  UffFile f;
  NodeSet s;
  s.dataset = 15;
  for (int i = 0; i < 5; ++i) s.nodes.push_back(Node{i + 1, 0, 0, 1, {g(rng), g(rng), 1e-7 * g(rng)}});
  f.datasets.push_back(s);
  f.datasets.push_back(NodalData55::normal_mode(3, 12.345678912345, {1, 2, 3, 4, 5}, v, 0.987654321, 0.01));
  UffFile back = parse_uff(format_uff(f, Precision::Extended), "ext.unv");
  require_same(f, back);
  // Standard precision keeps 6 significant digits.
  UffFile std6 = parse_uff(format_uff(f), "std.unv");
  const auto& m = *std6.nodal_data()[0];
  CHECK((m.values - v).cwiseAbs().maxCoeff() <= 5e-6 * v.cwiseAbs().maxCoeff());
  CHECK(m.values(0, 0) != v(0, 0));
}

TEST_CASE("UFF: writer output is the fixed-column layout of the dataset definitions", "[uff][golden]") {
  UffFile f;
  Eigen::MatrixXd v(2, 3);
  v << 1.0, -0.5, 0.25, 1e-3, 0.0, -2.0;
  f.datasets.push_back(NodalData55::normal_mode(1, 7.75, {1, 22}, v, 1.0, 0.012));
  NodeSet s;
  s.dataset = 2411;
  s.nodes.push_back(Node{101, 1, 1, 11, {1.0, 0.25, -2.5}});
  f.datasets.push_back(s);
  const std::string expected =
      "    -1\n"
      "    55\n"
      "NONE\nNONE\nNONE\nNONE\nNONE\n"
      "         1         2         2         8         2         3\n"
      "         2         4         1         1\n"
      "  7.75000E+00  1.00000E+00  1.20000E-02  0.00000E+00\n"
      "         1\n"
      "  1.00000E+00 -5.00000E-01  2.50000E-01\n"
      "        22\n"
      "  1.00000E-03  0.00000E+00 -2.00000E+00\n"
      "    -1\n"
      "    -1\n"
      "  2411\n"
      "       101         1         1        11\n"
      "   1.0000000000000000D+00   2.5000000000000000D-01  -2.5000000000000000D+00\n"
      "    -1\n";
  CHECK(format_uff(f) == expected);
}

TEST_CASE("UFF: free-format numeric records are accepted", "[uff]") {
  // A writer that widened the fields (values blank-separated, more digits).
  const std::string text =
      "    -1\n    55\nfree\nNONE\nNONE\nNONE\nNONE\n"
      "1 2 2 8 2 3\n"
      "2 4 1 5\n"
      "  12.5   0.0 0.0 0.0\n"
      "         7\n"
      "  1.000000000000000E+00   -2.500000000000000E-01   3.3333333333333331E-01\n"
      "    -1\n";
  UffFile f = parse_uff(text, "free.unv");
  const auto& m = *f.nodal_data()[0];
  CHECK(m.mode_number() == 5);
  CHECK(m.frequency_hz() == 12.5);
  CHECK(m.values(0, 2) == 0.33333333333333331);
}

TEST_CASE("UFF: a binary dataset other than 58b is skipped by its byte count, even when the bytes look like a delimiter",
          "[uff]") {
  std::string ascii = "    -1\n  9999b     1     2           2          17     0     0           0           0\n";
  for (int i = 0; i < 2; ++i) ascii += "x\n";
  std::string bytes = "\n    -1\n    55\n\x01\x02";  // 17 bytes
  REQUIRE(bytes.size() == 17);
  std::string text = ascii + bytes + "\n    -1\n    -1\n   164\n         1SI                           2\n"
                                     "  1.0D+00  1.0D+00  1.0D+00\n  0.0D+00\n    -1\n";
  UffFile f = parse_uff(text, "bin.unv");
  REQUIRE(f.datasets.size() == 2);
  CHECK(f.skipped() == std::map<int, std::size_t>{{9999, 1}});
  CHECK(dataset_number(f.datasets[1]) == 164);
  // Written back verbatim.
  CHECK(format_uff(f).substr(0, ascii.size() + bytes.size()) == ascii + bytes);
}

TEST_CASE("UFF: errors name file, line, dataset, record, field and what was expected", "[uff][errors]") {
  const std::string head = "    -1\n    55\nA\nB\nC\nD\nE\n         1         2         2         8         2         3\n";
  // line 10: record 8, field 1
  CHECK_THAT(error_of(head + "         2         4         1         1\n  7.7500X+00  1.00000E+00  0.0  0.0\n    -1\n"),
             Catch::Contains("bad.unv:10: dataset 55 record 8 field 1 (type-specific real): expected real (E13, "
                             "columns 1-13), value 1 of 4, got \"  7.7500X+00\""));
  CHECK_THAT(error_of(head + "         2         4         1         1\n  7.75000E+00  1.00000E+00  0.0  0.0\n"
                             "       1.5\n  1.0 2.0 3.0\n    -1\n"),
             Catch::Contains("bad.unv:11: dataset 55 record 9 field 1 (node number): expected integer (I10, columns "
                             "1-10), got \"       1.5\""));
  CHECK_THAT(error_of(head + "         2         4         1         1\n  7.75000E+00  1.00000E+00  0.0  0.0\n"
                             "         1\n    -1\n"),
             Catch::Contains("bad.unv:12: dataset 55 record 10: dataset ended after 0 of 3 values (data at node)"));
  CHECK_THAT(error_of("    -1\n    55\nA\n"), Catch::Contains("bad.unv:3: dataset 55 (opened at line 2) has no closing delimiter"));
  CHECK_THAT(error_of("garbage\n"), Catch::Contains("bad.unv:1: expected the dataset delimiter"));
  CHECK_THAT(error_of("    -1\n  abc\n    -1\n"), Catch::Contains("bad.unv:2: expected a dataset number"));
  CHECK_THAT(error_of("    -1\n    55\nA\nB\nC\nD\nE\n         1         2         2         8         7         3\n"
                      "    -1\n"),
             Catch::Contains("bad.unv:8: dataset 55 record 6 field 5 (data type): expected 2 (real) or 5 (complex)"));
  CHECK_THAT(error_of("    -1\n    15\n         1         0         0         0  1.0  2.0\n    -1\n"),
             Catch::Contains("bad.unv:3: dataset 15 record 1 field 5 (X): expected real (E13, columns 41-53), got \"  1.0  2.0\""));
  CHECK_THAT(error_of("    -1\n  2411\n         1         0         0         0\n    -1\n"),
             Catch::Contains("bad.unv:4: dataset 2411 record 2: dataset ended after 0 of 3 values (node coordinates)"));
  CHECK_THAT(error_of("    -1\n    58\nA\nB\nC\nD\nE\n    4         1    0         0 NONE               1   1 NONE  "
                      "             2   3\n         6         3         1  0.0  0.5  0.0\n"),
             Catch::Contains("no closing delimiter"));
  try {
    read_uff("/nonexistent/x.unv");
    FAIL("no error");
  } catch (const ParseError& e) {
    CHECK_THAT(std::string(e.what()), Catch::Contains("/nonexistent/x.unv") && Catch::Contains("not found"));
  }
}

TEST_CASE("UFF: delimiter recognition", "[uff]") {
  // A `-1` outside columns 1-6 is data, not a delimiter: dataset 15 with node -1 would be
  // " -1" in an I10 field ending at column 10.
  UffFile f = parse_uff("    -1\n  2467\n        -1\n    -1\n", "d.unv");
  REQUIRE(f.datasets.size() == 1);
  CHECK(std::get<UnknownDataset>(f.datasets[0]).body == "        -1\n");
  // Trailing blanks after delimiters and blank lines between datasets are tolerated.
  UffFile g = parse_uff("    -1   \n  2467   \nx\n    -1      \n\n    -1\n  2400\n    -1\n", "d.unv");
  CHECK(g.datasets.size() == 2);
  CHECK((g.skipped() == std::map<int, std::size_t>{{2400, 1}, {2467, 1}}));
  // An empty delimiter pair is tolerated.
  UffFile h = parse_uff("    -1\n    -1\n  2467\nx\n    -1\n", "d.unv");
  CHECK(h.datasets.size() == 1);
}

TEST_CASE("UFF: Fortran exponents past 99 (no letter) and 3-digit exponents that fill the field", "[uff]") {
  // E13.5 of 1.5e-100 is "  1.50000-100"; C's %13.5E gives " 1.50000E-100"; 1P E13.6 of -2e+100
  // fills all 13 columns and touches its neighbour.
  const std::string text =
      "    -1\n    55\nA\nB\nC\nD\nE\n         1         2         2         8         2         3\n"
      "         2         4         1         1\n  7.75000E+00  1.00000E+00  0.00000E+00  0.00000E+00\n"
      "         1\n  1.50000-100 1.50000E-100-2.000000+100\n    -1\n";
  UffFile f = parse_uff(text, "exp.unv");
  const auto& m = *f.nodal_data()[0];
  CHECK(m.values(0, 0) == 1.5e-100);
  CHECK(m.values(0, 1) == 1.5e-100);
  CHECK(m.values(0, 2) == -2e100);
}

namespace {

/// Dataset 55 up to record 8 (a real normal mode, 3 values per node): lines 1-10.
const std::string kHead55 =
    "    -1\n    55\nA\nB\nC\nD\nE\n         1         2         2         8         2         3\n"
    "         2         4         1         1\n  7.75000E+00  1.00000E+00  1.20000E-02  0.00000E+00\n";

/// True when `s` holds only printable ASCII: no byte of a damaged file is echoed.
bool printable(const std::string& s) {
  return std::all_of(s.begin(), s.end(), [](char c) { return c >= 0x20 && c < 0x7f; });
}

}  // namespace

TEST_CASE("UFF: a binary file is called one; no raw byte reaches a message", "[uff][errors]") {
  // A zip archive: text, then a control byte in column 3 of line 1.
  std::string zip("PK\x03\x04\x14\x00\x00\x00\x08\x00", 10);
  for (int i = 0; i < 300; ++i) zip += static_cast<char>((i * 37) & 0xff);
  CHECK(error_of(zip) == "bad.unv: not a universal file: byte 0x03 at line 1, column 3 is not text");
  // A PNG: its first line ("\x89PNG") holds no control byte, its second does.
  const std::string png("\x89PNG\r\n\x1a\n\0\0\0\rIHDR\0\0\0\x10", 20);
  CHECK(error_of(png) == "bad.unv: not a universal file: byte 0x1A at line 2, column 1 is not text");
  // A control byte after a delimiter and a dataset number: the file is a universal
  // file with a damaged (or unmarked binary) dataset, located by line and column.
  CHECK(error_of(kHead55 + std::string("         1\n  1.0\0", 17)) ==
        "bad.unv:12: byte 0x00 at column 6 is not text (dataset 55 opened at line 2, not marked binary)");
  // Quoted text is escaped and shortened.
  CHECK(error_of("    -1\n  5\xe9x\n    -1\n") ==
        "bad.unv:2: expected a dataset number (I6, columns 1-6) after the delimiter, got \"  5\\xE9x\"");
  const std::string long_line = "This is a text file with a long first line, not a universal file at all.\n";
  CHECK(error_of(long_line) == "bad.unv:1: expected the dataset delimiter \"    -1\" (-1 in columns 1-6), got "
                               "\"This is a text file with a long first li...\"");
  for (const auto& text : {zip, png, long_line, std::string("    -1\n  2467\n\xff\xfe\x01\n    -1\n")})
    CHECK(printable(error_of(text)));
  // Bytes of 0x80 and above are text in ID lines (a unit "\xb5m", UTF-8 names).
  UffFile f = parse_uff("    -1\n   151\nmodel \xc2\xb5m\n    -1\n", "latin.unv");
  CHECK(std::get<Header151>(f.datasets[0]).model_name() == "model \xc2\xb5m");
}

TEST_CASE("UFF: a line missing a value is blamed on that line, naming record, field and format", "[uff][errors]") {
  // Standard columns (6E13.5): the line ends after two of its three values.
  CHECK(error_of(kHead55 + "         1\n  1.00000E+00 -5.00000E-01\n         2\n"
                           "  1.00000E+00  2.00000E+00  3.00000E+00\n    -1\n") ==
        "bad.unv:12: dataset 55 record 10 field 3 (data at node): expected real (E13, columns 27-39), value 3 of "
        "3, got \"\"");
  // Record 8 holds 4 values: its one line ends after three.
  CHECK(error_of("    -1\n    55\nA\nB\nC\nD\nE\n         1         2         2         8         2         3\n"
                 "         2         4         1         1\n  7.75000E+00  1.00000E+00  1.20000E-02\n"
                 "         1\n  1.00000E+00 -5.00000E-01  0.00000E+00\n    -1\n") ==
        "bad.unv:10: dataset 55 record 8 field 4 (type-specific real): expected real (E13, columns 40-52), value 4 "
        "of 4, got \"\"");
  // Widened columns (ssid's extended 1P E25.16, three to a line): blamed in those.
  CHECK(error_of(kHead55 + "         1\n   1.0000000000000000E+00  -5.0000000000000000E-01\n         2\n"
                           "   1.0000000000000000E+00   2.0000000000000000E+00   3.0000000000000000E+00\n    -1\n") ==
        "bad.unv:12: dataset 55 record 10 field 3 (data at node): expected real (E25, columns 51-75), value 3 of "
        "3, got \"\"");
  // 2411 coordinates (3D25.16) and 164 factors (3D25.17).
  CHECK(error_of("    -1\n  2411\n         1         0         0         0\n"
                 "   1.0000000000000000D+00   2.0000000000000000D+00\n         2         0         0         0\n"
                 "   1.0000000000000000D+00   2.0000000000000000D+00   3.0000000000000000D+00\n    -1\n") ==
        "bad.unv:4: dataset 2411 record 2 field 3 (node coordinates): expected real (E25, columns 51-75), value 3 "
        "of 3, got \"\"");
  CHECK(error_of("    -1\n   164\n         1SI                           2\n"
                 "   1.0000000000000000D+00   1.0000000000000000D+00\n   2.7315000000000000D+02\n    -1\n") ==
        "bad.unv:4: dataset 164 record 2 field 3 (length, force and temperature factors): expected real (E25, "
        "columns 51-75), value 3 of 3, got \"\"");
  // Dataset 15 written with widened reals (4I10, 3E25.16): Z missing.
  CHECK(error_of("    -1\n    15\n         1         0         0         0   1.0000000000000000E+00   "
                 "2.0000000000000000E+00\n    -1\n") ==
        "bad.unv:3: dataset 15 record 1 field 7 (Z): expected real (E25, columns 91-115), got \"\"");
  // Blank-separated values may continue on the next line, but only with more of them:
  // where they stop short, that line is blamed.
  CHECK(error_of(kHead55 + "         1\n  1.0 2.0\n    -1\n") ==
        "bad.unv:12: dataset 55 record 10: 2 of the 3 values (data at node) by the end of this line; the dataset "
        "ends after it");
  CHECK(error_of(kHead55 + "         1\n  1.0 2.0\n         2\n  1.0 2.0 3.0\n    -1\n") ==
        "bad.unv:12: dataset 55 record 10: 2 of the 3 values (data at node) by the end of this line; line 13 (\"  "
        "       2\") does not continue them");
  // A record's last line missing altogether: the next record's node number does not
  // continue it; the line before is blamed.
  CHECK(error_of("    -1\n    55\nA\nB\nC\nD\nE\n         1         2         2         8         2         3\n"
                 "         2         4         1         1\n"
                 "   7.7500000000000000E+00   1.0000000000000000E+00   1.2000000000000000E-02\n"
                 "         1\n   1.0000000000000000E+00   2.0000000000000000E+00   3.0000000000000000E+00\n"
                 "    -1\n") ==
        "bad.unv:10: dataset 55 record 8: 3 of the 4 values (type-specific real) by the end of this line; line 11 "
        "(\"         1\") does not continue them");
  // ... and continue when they do.
  UffFile f = parse_uff(kHead55 + "         1\n  1.0 2.0\n  3.0\n    -1\n", "free.unv");
  CHECK(f.nodal_data()[0]->values(0, 2) == 3.0);
  // A line with more values than the record needs.
  CHECK(error_of(kHead55 + "         1\n  1.00000E+00  2.00000E+00  3.00000E+00  4.00000E+00\n    -1\n") ==
        "bad.unv:12: dataset 55 record 10 field 4 (data at node): expected the end of the line: the record needs 3 "
        "more value(s), got \"4.00000E+00\"");
}

TEST_CASE("UFF: a bad value is quoted in the columns its record was written in", "[uff][errors]") {
  // Extended 1P E25.16: the E25 column, not 13 columns cut through two numbers.
  CHECK(error_of(kHead55 + "         1\n   8.7154703714023962X-03  -2.1614874763479825E-04   "
                           "3.9332540273438098E-02\n    -1\n") ==
        "bad.unv:12: dataset 55 record 10 field 1 (data at node): expected real (E25, columns 1-25), value 1 of 3, "
        "got \"   8.7154703714023962X-03\"");
  CHECK(error_of("    -1\n    15\n         1         0         0         0   1.0000000000000000E+00   "
                 "-2.000000000000000X+00   3.0000000000000000E+00\n    -1\n") ==
        "bad.unv:3: dataset 15 record 1 field 6 (Y): expected real (E25, columns 66-90), got \"   "
        "-2.000000000000000X+00\"");
  // The second line of an extended record is read in the first line's columns.
  CHECK(error_of("    -1\n    55\nA\nB\nC\nD\nE\n         1         2         2         8         2         3\n"
                 "         2         4         1         1\n"
                 "   7.7500000000000000E+00   1.0000000000000000E+00   1.2000000000000000E-02\n"
                 "   0.0000000000000000E+0X\n    -1\n") ==
        "bad.unv:11: dataset 55 record 8 field 1 (type-specific real): expected real (E25, columns 1-25), value 4 "
        "of 4, got \"   0.0000000000000000E+0X\"");
  // Standard columns stay E13.
  CHECK(error_of(kHead55 + "         1\n  1.00000E+00  2.000X0E+00  3.00000E+00\n    -1\n") ==
        "bad.unv:12: dataset 55 record 10 field 2 (data at node): expected real (E13, columns 14-26), value 2 of 3, "
        "got \"  2.000X0E+00\"");
}

TEST_CASE("UFF: an empty file, or one without a dataset, is an error", "[uff][errors]") {
  const std::string why = ": a universal file holds datasets, each opened by a line \"    -1\" and its dataset number "
                          "and closed by a line \"    -1\"";
  CHECK(error_of("") == "bad.unv: empty file" + why);
  CHECK(error_of("\n   \n") == "bad.unv: no dataset in the file" + why);
  CHECK(error_of("    -1\n") == "bad.unv: no dataset in the file" + why);
  CHECK(error_of("    -1\n    -1\n") == "bad.unv: no dataset in the file" + why);
  CHECK(error_of("    -1\n    -1\n\n  \n") == "bad.unv: no dataset in the file" + why);
}
