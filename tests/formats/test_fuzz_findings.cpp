/// Regression tests for what fuzzing found (docs/fuzzing.md, "Findings"): each
/// crashing input is written here as bytes. Under the sanitizer build
/// (scripts/sanitize-tests) the original defect would be reported; in any build the
/// outcome is checked: the project's bad-input error with its exact message, or
/// the data read.
#include <catch2/catch.hpp>

#include <string>

#include "formats/op4.hpp"
#include "formats/uff.hpp"
#include "formats/parse_error.hpp"
#include "op4_test_util.hpp"

using namespace ssid::formats;

namespace {

std::string op4_error(const std::string& s) {
  try {
    read_op4_buffer(s.data(), s.size(), "fuzz.op4");
  } catch (const ParseError& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace

TEST_CASE("fuzz finding op4-1: an ASCII header's Fortran format with a huge width", "[fuzz][op4]") {
  // fuzz_op4, 30 s: "1P,3E2000000000000..." overflowed the int that reads the declared
  // width (a reserve hint only): UBSan "signed integer overflow: 2000000000 * 10".
  const std::string header = "         1         1         6         2KAA     1P,3E2000000000000000.16\n";
  const std::string column = "         1         1         1\n 1.0000000000000000E+00\n";
  const std::string end = "         2         1         1\n 1.0000000000000000E+00\n";
  const auto m = read_op4_buffer((header + column + end).data(), (header + column + end).size(), "fuzz.op4");
  REQUIRE(m.size() == 1);
  CHECK(m[0].real.coeff(0, 0) == 1.0);
  // The crashing input itself (314 bytes).
  const std::string crash =
      std::string("       3       3       6       2KAA     1P,3E2000000000000000+E00-1.000000000000>0000E+00 "
                  "0.00000000000+00-1.0000000000000") +
      std::string(121, '\x9e') +
      std::string("000E+00 0.0000000000000000000000000E+0\0\0\0\0\0\0\0\x01"
                  "000000000000E+03\n 0 10906",
                  71);
  REQUIRE(crash.size() == 314);
  CHECK(op4_error(crash) == "fuzz.op4:2: matrix KAA: expected a column record ICOL IROW NW (3 integers), got \"0 10906\"");
}

TEST_CASE("review of fuzz finding op4-1: a 64-bit header row count of -2^63", "[fuzz][op4]") {
  // std::llabs(INT64_MIN) is undefined: the row count is now range-checked first.
  op4test::Bytes h;
  h.word = 8;
  h.i(1).i(INT64_MIN).i(2).i(2).text("KAA     ");
  CHECK(op4_error(op4test::record(h)) ==
        "fuzz.op4: matrix KAA: byte offset 0: header gives 1 columns and -9223372036854775808 rows");
}

TEST_CASE("review during fuzzing: an identity stored without terms cannot make a small file allocate gigabytes",
          "[fuzz][op4]") {
  // 114 bytes declaring a 60 M x 60 M identity (form 8) with no terms: building its
  // diagonal took 3.4 GB and 32 s (ssid op4 list). Refused like a lying column count.
  const std::string id = "  60000000  60000000         8         2KAA     1P,3E23.16\n"
                         "  60000001         1         1\n 1.0000000000000000E+00\n";
  CHECK(op4_error(id) == "fuzz.op4:1: matrix KAA: identity matrix stored without terms: its 60000000 diagonal terms "
                         "are implausible for a file of 114 bytes (more than 8 M terms and 1 per 2 bytes of the file)");
  // Binary, pseudo-identity (form 9): the same rule.
  op4test::Bytes h, c;
  h.i(40000000).i(-50000000).i(9).i(2).text("PID     ");
  c.i(40000001).i(1).i(2).f64(1.0);
  CHECK(op4_error(op4test::record(h) + op4test::record(c)) ==
        "fuzz.op4: matrix PID: byte offset 0: pseudo-identity matrix stored without terms: its 40000000 diagonal "
        "terms are implausible for a file of 60 bytes (more than 8 M terms and 1 per 2 bytes of the file)");
  // A plausible identity is still built.
  const std::string small = "         3         3         8         2I3      1P,3E23.16\n"
                            "         4         1         1\n 1.0000000000000000E+00\n";
  const auto m = read_op4_buffer(small.data(), small.size(), "fuzz.op4");
  REQUIRE(m.size() == 1);
  CHECK(m[0].dense_real() == Eigen::MatrixXd::Identity(3, 3));
}

TEST_CASE("fuzz finding op4-2: a matrix of 10^8 rows and one column took seconds and 1 GB", "[fuzz][op4]") {
  // fuzz_op4 (second 12-minute run): a timeout (> 10 s). A pseudo-identity (form 9)
  // of 1 column and 99 999 999 rows, stored without terms, was built through
  // setFromTriplets, whose transposed copy costs O(rows); now O(columns + terms).
  // The input also showed a matrix name with a raw byte (0xD2) in the message.
  const std::string timeout("           1      99999999 9    3    \xff"
                            "2       2KAA   E23.160\n       2       4      2\n 1       1    3       3    \xd2"
                            "0\n       2     -  2      2\n 1       1    3       3             6 \xff ",
                            180);
  CHECK(op4_error(timeout) == "fuzz.op4:4: matrix \\xD20: expected a column record ICOL IROW NW (3 integers), got "
                              "\"2     -  2      2\"");
  // The largest row count a header may give, one column: built at once.
  const std::string pid = "         1 2147483647         9         2PI       1P,3E23.16\n"
                          "         2         1         1\n 1.0000000000000000E+00\n";
  const auto p = read_op4_buffer(pid.data(), pid.size(), "fuzz.op4");
  REQUIRE(p.size() == 1);
  CHECK(p[0].real.rows() == 2147483647);
  CHECK(p[0].real.nonZeros() == 1);
  CHECK(p[0].real.coeff(0, 0) == 1.0);
  // Strings out of row order in a column of 2e9 rows (BIGMAT): sorted column by
  // column, a row given twice keeping its last value, without an O(rows) copy.
  op4test::Bytes h, c, e;
  h.i(1).i(-2000000000).i(2).i(2).text("BIG     ");
  c.i(1).i(0).i(12).i(3).i(100).f64(1.5).i(3).i(5).f64(2.5).i(3).i(100).f64(7.0);
  e.i(2).i(1).i(2).f64(0.0);
  const std::string big = op4test::record(h) + op4test::record(c) + op4test::record(e);
  const auto b = read_op4_buffer(big.data(), big.size(), "fuzz.op4");
  REQUIRE(b.size() == 1);
  CHECK(b[0].real.rows() == 2000000000);
  CHECK(b[0].real.nonZeros() == 2);
  CHECK(b[0].real.coeff(4, 0) == 2.5);
  CHECK(b[0].real.coeff(99, 0) == 7.0);
}

TEST_CASE("fuzz finding uff-1: an integer wider than its I10 field was written and did not read back", "[fuzz][uff]") {
  // fuzz_uff, 26 minutes of the hour run on 2026-11-28: record 7's columns cut a number,
  // so the reader took its values as whitespace-separated tokens and read the
  // type-specific integer 14444444444444444; the writer put it in I10 as 17 characters,
  // which ran into the field before it ("414444444444444444" read back as NREAL).
  const std::string crash =
      "    -1\n    55\nNONE\nNONE\nNONE\nNONE\nNONE\n"
      "         0         2         2         8         2        3\n"
      "         2         4         14444444444444444\n"
      "-8.14913E-03 -202  7.97702 -2.81973E-02\n    -1\n";
  const uff::UffFile file = uff::parse_uff(crash, "fuzz.unv");
  try {
    const std::string written = uff::format_uff(file, uff::Precision::Extended);
    FAIL("written without an error:\n" << written);
  } catch (const InputError& e) {
    CHECK(std::string(e.what()) ==
          "universal file: the integer 14444444444444444 does not fit its I10 field (17 characters)");
  }
}
