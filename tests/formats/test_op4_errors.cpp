/// Bad OP4 input: every error names the file, the matrix, the column and the line
/// (ASCII) or byte offset (binary). Never a crash, never a silently wrong matrix.
#include <catch2/catch.hpp>

#include "formats/op4.hpp"
#include "formats/parse_error.hpp"
#include "op4_test_util.hpp"

using namespace ssid::formats;
using Catch::Matchers::Contains;
using op4test::Bytes;
using op4test::record;

namespace {
std::string error_of(const std::string& s, const std::string& name) {
  try {
    read_op4_buffer(s.data(), s.size(), name);
  } catch (const ParseError& e) {
    return e.what();
  }
  return "(no error)";
}
/// True when `got` is the first got.size() matrices of `whole`, each complete and
/// equal: what a file cut between two matrices may read as. A cut inside a matrix
/// must never read as a (smaller or zero-filled) matrix.
bool complete_prefix(const std::vector<Op4Matrix>& got, const std::vector<Op4Matrix>& whole) {
  if (got.size() > whole.size()) return false;
  for (std::size_t i = 0; i < got.size(); ++i) {
    const Op4Matrix &g = got[i], &m = whole[i];
    if (g.name != m.name || g.rows != m.rows || g.cols != m.cols || g.is_complex() != m.is_complex()) return false;
    if (g.is_complex() ? (g.complex - m.complex).norm() != 0.0 : (g.real - m.real).norm() != 0.0) return false;
  }
  return true;
}
Bytes w(int word = 4) {
  Bytes b;
  b.word = word;
  return b;
}
}  // namespace

TEST_CASE("binary errors: truncated file, wrong markers, lying headers, indices out of range", "[op4]") {
  // Fix the sparse string: L = 2 words (one double) -> IS = 3*65536 + 3.
  std::string f;
  f += record(w().i(2).i(3).i(2).i(2).text("KAA     "));
  f += record(w().i(1).i(1).i(4).f64(1.0).f64(2.0));
  f += record(w().i(2).i(0).i(3).i(3 * 65536 + 3).f64(5.0));
  f += record(w().i(3).i(1).i(2).f64(1.0));
  auto ok = read_op4_buffer(f.data(), f.size(), "ok.op4").at(0);
  CHECK(ok.real.coeff(2, 1) == 5.0);

  SECTION("truncated in the middle of a column") {
    const std::string t = f.substr(0, 60);
    const std::string e = error_of(t, "trunc.op4");
    CHECK_THAT(e, Contains("trunc.op4") && Contains("matrix KAA") && Contains("byte offset 32") &&
                      Contains("truncated"));
  }
  SECTION("file ends after a column without the closing record") {
    const std::string t = f.substr(0, f.size() - 28);
    CHECK_THAT(error_of(t, "noend.op4"), Contains("noend.op4") && Contains("matrix KAA") &&
                                             Contains("after column 2") && Contains("no closing record"));
  }
  SECTION("record markers that disagree") {
    std::string t = f;
    t[32 + 4 + 28] = 0x7f;  // trailing marker of the first column record
    CHECK_THAT(error_of(t, "mark.op4"), Contains("mark.op4") && Contains("matrix KAA") && Contains("byte offset 32") &&
                                            Contains("markers disagree"));
  }
  SECTION("NW that does not match the record length") {
    std::string g;
    g += record(w().i(2).i(3).i(2).i(2).text("KAA     "));
    g += record(w().i(1).i(1).i(6).f64(1.0).f64(2.0));
    g += record(w().i(3).i(1).i(2).f64(1.0));
    CHECK_THAT(error_of(g, "nw.op4"), Contains("nw.op4") && Contains("column 1") && Contains("NW=6") &&
                                          Contains("byte offset 32"));
  }
  SECTION("rows beyond NROW") {
    std::string g;
    g += record(w().i(2).i(3).i(2).i(2).text("KAA     "));
    g += record(w().i(2).i(3).i(4).f64(1.0).f64(2.0));
    g += record(w().i(3).i(1).i(2).f64(1.0));
    CHECK_THAT(error_of(g, "rows.op4"), Contains("column 2") && Contains("rows 3..4") && Contains("1..3"));
  }
  SECTION("column index out of range and out of order") {
    std::string g;
    g += record(w().i(2).i(3).i(2).i(2).text("KAA     "));
    g += record(w().i(5).i(1).i(2).f64(1.0));
    CHECK_THAT(error_of(g, "col.op4"), Contains("column 5 out of range 1..2") && Contains("byte offset 32"));
    std::string h;
    h += record(w().i(2).i(3).i(2).i(2).text("KAA     "));
    h += record(w().i(2).i(1).i(2).f64(1.0));
    h += record(w().i(1).i(1).i(2).f64(1.0));
    CHECK_THAT(error_of(h, "order.op4"), Contains("column 1 follows column 2"));
  }
  SECTION("a sparse string longer than its record") {
    std::string g;
    g += record(w().i(1).i(3).i(2).i(2).text("KAA     "));
    g += record(w().i(1).i(0).i(3).i(9 * 65536 + 1).f64(1.0));
    CHECK_THAT(error_of(g, "str.op4"), Contains("column 1") && Contains("string of 8 words") && Contains("byte offset 48"));
  }
  SECTION("bad TYPE, garbage files, empty files") {
    std::string g = record(w().i(1).i(3).i(2).i(7).text("KAA     "));
    CHECK_THAT(error_of(g, "type.op4"), Contains("TYPE must be 1-4"));
    CHECK_THAT(error_of(std::string("\x01\x02\x03\x04garbage!", 12), "junk.op4"),
               Contains("junk.op4") && Contains("not an OP4 file"));
    CHECK_THAT(error_of("", "empty.op4"), Contains("empty.op4") && Contains("empty"));
  }
}

TEST_CASE("ASCII errors: non-numeric fields, short columns, lying counts, with the line number", "[op4]") {
  const std::string head = "       2       3       2       2KAA     1P,3E23.16\n";
  SECTION("a non-numeric value") {
    const std::string f = head +
                          "       1       1       2\n"
                          " 1.0000000000000000E+00 2.00000X0000000000E+00\n"
                          "       3       1       1\n"
                          " 1.0000000000000000E+00\n";
    CHECK_THAT(error_of(f, "nan.op4"), Contains("nan.op4:3:") && Contains("matrix KAA") && Contains("expected a number"));
  }
  SECTION("NW larger than the values given") {
    const std::string f = head +
                          "       1       1       3\n"
                          " 1.0000000000000000E+00 2.0000000000000000E+00\n"
                          "       3       1       1\n"
                          " 1.0000000000000000E+00\n";
    CHECK_THAT(error_of(f, "nw.op4"), Contains("nw.op4:2:") && Contains("column 1") && Contains("NW=3") &&
                                          Contains("2 numbers follow"));
  }
  SECTION("a column index out of range") {
    const std::string f = head +
                          "       7       1       1\n"
                          " 1.0000000000000000E+00\n";
    CHECK_THAT(error_of(f, "c.op4"), Contains("c.op4:2:") && Contains("column 7 out of range 1..2"));
  }
  SECTION("a truncated file") {
    const std::string f = head +
                          "       1       1       2\n"
                          " 1.0000000000000000E+00 2.0000000000000000E+00\n";
    CHECK_THAT(error_of(f, "t.op4"), Contains("t.op4") && Contains("matrix KAA") && Contains("no closing record"));
  }
  SECTION("a sparse column whose strings run short") {
    const std::string f = head +
                          "       1       0       9\n"
                          "  196609\n"
                          " 1.0000000000000000E+00\n"
                          "       3       1       1\n"
                          " 1.0000000000000000E+00\n";
    CHECK_THAT(error_of(f, "s.op4"), Contains("s.op4:5:") && Contains("column 1") && Contains("string header"));
  }
  SECTION("a garbled header") {
    CHECK_THAT(error_of("       2     abc       2       2KAA\n", "h.op4"), Contains("h.op4:1:") && Contains("matrix header"));
  }
}

TEST_CASE("every truncation of valid files: complete matrices or a ParseError; every corrupted byte: a result or a ParseError, never a crash", "[op4]") {
  // A file of two matrices (dense real, sparse complex) in several encodings.
  SparseReal a(4, 3);
  a.insert(0, 0) = 1.5;
  a.insert(3, 0) = -2.0;
  a.insert(1, 2) = 1e-300;
  a.makeCompressed();
  SparseComplex z(70000, 2);
  z.insert(69998, 1) = {1.0, -1.0};
  z.insert(69999, 1) = {0.5, 2.0};
  z.makeCompressed();
  const std::vector<Op4Matrix> ms{Op4Matrix::from_real("A", a, 1), Op4Matrix::from_complex("Z", z)};
  std::vector<std::string> files;
  for (int enc = 0; enc < 2; ++enc)
    for (Op4Storage st : {Op4Storage::Dense, Op4Storage::Sparse, Op4Storage::BigMat}) {
      Op4WriteOptions o;
      o.encoding = enc ? Op4Encoding::Binary : Op4Encoding::Ascii;
      o.storage = st;
      if (st == Op4Storage::Dense) {
        files.push_back(write_op4_string({ms[0]}, o));
        continue;
      }
      o.endian = st == Op4Storage::BigMat ? Endian::Big : Endian::Little;
      o.marker_bytes = st == Op4Storage::BigMat ? 8 : 4;
      files.push_back(write_op4_string(ms, o));
    }
  std::size_t errors = 0, reads = 0, cut_reads = 0;
  for (const std::string& f : files) {
    const std::vector<Op4Matrix> whole = read_op4_buffer(f.data(), f.size(), "whole.op4");
    REQUIRE(!whole.empty());
    for (std::size_t n = 0; n < f.size(); ++n) {
      try {
        const std::vector<Op4Matrix> got = read_op4_buffer(f.data(), n, "cut.op4");
        INFO("file " << (&f - files.data()) << " cut to " << n << " of " << f.size() << " bytes: " << got.size()
                     << " matrix(es) read");
        CHECK(complete_prefix(got, whole));
        ++cut_reads;
      } catch (const ParseError& e) {
        ++errors;
      }
    }
    for (std::size_t i = 0; i < f.size(); ++i)
      for (unsigned char flip : {0xFFu, 0x01u, 0x80u}) {
        std::string g = f;
        g[i] = static_cast<char>(static_cast<unsigned char>(g[i]) ^ flip);
        try {
          read_op4_buffer(g.data(), g.size(), "bad.op4");
          ++reads;
        } catch (const ParseError& e) {
          ++errors;
        }
      }
  }
  INFO("cut files read " << cut_reads << ", corrupted files read " << reads << ", errors " << errors);
  CHECK(errors > 0);
}

TEST_CASE("a header claiming billions of columns in a tiny file is refused before allocating", "[op4]") {
  const std::string f =
      "99999999       3       8       2I       1P,3E23.16\n"
      "100000000       1       1\n"
      " 1.0000000000000000E+00\n";
  CHECK(error_of(f, "huge.op4") ==
        "huge.op4:1: matrix I: header gives 99999999 columns, implausible for a file of 101 bytes (more than 64 M "
        "columns and 4 per byte of the file)");
  std::string b = record(w().i(1).i(1500000000).i(3).i(2).text("D       "));
  b += record(w().i(2).i(1).i(2).f64(1.0));
  CHECK(error_of(b, "diag.op4") ==
        "diag.op4: matrix D: byte offset 0: header gives 1500000000 columns, implausible for a file of 60 bytes (more "
        "than 64 M columns and 4 per byte of the file)");
}
