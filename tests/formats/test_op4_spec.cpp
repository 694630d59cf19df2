/// Byte-level OP4 tests: hand-made ASCII and binary files written from the format
/// description, read back, and the writer's output compared with them byte for byte.
#include <catch2/catch.hpp>

#include "formats/op4.hpp"
#include "formats/parse_error.hpp"
#include "op4_test_util.hpp"

using namespace ssid::formats;
using op4test::Bytes;
using op4test::record;

namespace {
std::vector<Op4Matrix> read_text(const std::string& s, const std::string& name = "t.op4") {
  return read_op4_buffer(s.data(), s.size(), name);
}
}  // namespace

TEST_CASE("ASCII dense real double: header, column records, closing record", "[op4]") {
  // 3x3, column 1 rows 1-2, column 2 null, column 3 rows 2-3 with an explicit zero
  const std::string f =
      "       3       3       1       2KAA     1P,3E23.16\n"
      "       1       1       2\n"
      " 1.0000000000000000E+00-2.5000000000000000E+00\n"
      "       3       2       2\n"
      " 0.0000000000000000E+00 1.2500000000000000E+10\n"
      "       4       1       1\n"
      " 1.0000000000000000E+00\n";
  auto ms = read_text(f);
  REQUIRE(ms.size() == 1);
  const Op4Matrix& m = ms[0];
  CHECK(m.name == "KAA");
  CHECK(m.rows == 3);
  CHECK(m.cols == 3);
  CHECK(m.form == 1);
  CHECK(m.precision == Op4Precision::RealDouble);
  CHECK(m.storage == Op4Storage::Dense);
  CHECK(m.nonzeros() == 3);  // the stored zero is not a term
  Eigen::MatrixXd d = m.dense_real();
  CHECK(d(0, 0) == 1.0);
  CHECK(d(1, 0) == -2.5);
  CHECK(d(2, 2) == 1.25e10);
  CHECK(d.col(1).isZero());

  // The writer produces the same text.
  Op4WriteOptions o;
  o.encoding = Op4Encoding::Ascii;
  o.storage = Op4Storage::Dense;
  std::string w = write_op4_string(ms, o);
  // It starts the last column at its first non-zero (row 3), so compare after re-reading.
  CHECK(read_text(w)[0].dense_real() == d);
  CHECK(w.substr(0, 51) == "       3       3       1       2KAA     1P,3E23.16\n");
  CHECK(w.find("       3       3       1\n 1.2500000000000000E+10\n") != std::string::npos);
  CHECK(w.substr(w.size() - 49) == "       4       1       1\n 1.0000000000000000E+00\n");
}

TEST_CASE("ASCII sparse non-BIGMAT: IS = (L+1)*65536 + IROW, L in words", "[op4]") {
  // 5x2 real double. Column 1: rows 2-3 (L = 4 words) and row 5 (L = 2).
  // IS = 5*65536+2 = 327682 and 3*65536+5 = 196613; NW = 1+4+1+2 = 8.
  const std::string f =
      "       2       5       2       2B       1P,3E23.16\n"
      "       1       0       8\n"
      "  327682\n"
      " 1.0000000000000000E+00 2.0000000000000000E+00\n"
      "  196613\n"
      " 3.0000000000000000E+00\n"
      "       3       1       1\n"
      " 1.0000000000000000E+00\n";
  auto m = read_text(f).at(0);
  CHECK(m.storage == Op4Storage::Sparse);
  CHECK(m.nonzeros() == 3);
  CHECK(m.real.coeff(1, 0) == 1.0);
  CHECK(m.real.coeff(2, 0) == 2.0);
  CHECK(m.real.coeff(4, 0) == 3.0);
  Op4WriteOptions o;
  o.encoding = Op4Encoding::Ascii;
  o.storage = Op4Storage::Sparse;
  CHECK(write_op4_string({m}, o) == f);
}

TEST_CASE("ASCII BIGMAT complex double: negative NROW, string header L+1 IROW", "[op4]") {
  // 4x1 complex double: rows 3-4. L = 2 terms * 4 words = 8 -> "9 3"; NW = 2 + 8 = 10.
  const std::string f =
      "       1      -4       2       4C       1P,3E23.16\n"
      "       1       0      10\n"
      "       9       3\n"
      " 1.0000000000000000E+00-1.0000000000000000E+00 2.0000000000000000E+00\n"
      " 5.0000000000000000E-01\n"
      "       2       1       1\n"
      " 1.0000000000000000E+00\n";
  auto m = read_text(f).at(0);
  CHECK(m.storage == Op4Storage::BigMat);
  CHECK(m.rows == 4);
  CHECK(m.is_complex());
  CHECK(m.complex.coeff(2, 0) == std::complex<double>(1, -1));
  CHECK(m.complex.coeff(3, 0) == std::complex<double>(2, 0.5));
  Op4WriteOptions o;
  o.encoding = Op4Encoding::Ascii;
  o.storage = Op4Storage::BigMat;
  CHECK(write_op4_string({m}, o) == f);
}

TEST_CASE("ASCII number forms: 5E16.9, D exponents, letterless 3-digit exponents, abutting and wider values", "[op4]") {
  const std::string f =
      "       1       6       2       1S       1P,5E16.9\n"
      "       1       1       6\n"
      " 1.000000000E+00-2.500000000D-01 1.5-100 3.000000000E+00-4.00000000000000E+00\n"
      "+5.0000000000000000000E+00\n"
      "       2       1       1\n"
      " 1.000000000E+00\n";
  auto m = read_text(f).at(0);
  Eigen::MatrixXd d = m.dense_real();
  CHECK(d(0, 0) == 1.0);
  CHECK(d(1, 0) == -0.25);
  CHECK(d(2, 0) == static_cast<float>(1.5e-100));  // single precision: rounded to float (underflows to 0)
  CHECK(d(3, 0) == 3.0);
  CHECK(d(4, 0) == -4.0);
  CHECK(d(5, 0) == 5.0);
  // Single precision values are rounded to float as NASTRAN holds them.
  const std::string g =
      "       1       1       2       1S       1P,5E16.9\n"
      "       1       1       1\n"
      " 1.000000001E-01\n"
      "       2       1       1\n"
      " 1.000000000E+00\n";
  CHECK(read_text(g).at(0).real.coeff(0, 0) == static_cast<double>(0.1f));
}

TEST_CASE("ASCII: several matrices, repeated names, long names, null and all-zero matrices, identity", "[op4]") {
  const std::string f =
      "       2       2       6       2VERYLONGNAME  1P,3E23.16\n"
      "       1       1       1\n"
      " 4.0000000000000000E+00\n"
      "       3       1       1\n"
      " 1.0000000000000000E+00\n"
      "       2       3       2       2Z       1P,3E23.16\n"
      "       3       1       1\n"
      " 1.0000000000000000E+00\n"
      "       3       3       8       2I       1P,3E23.16\n"
      "       4       1       1\n"
      " 1.0000000000000000E+00\n"
      "       2       3       2       2Z       1P,3E23.16\n"
      "       2       3       1\n"
      " 7.0000000000000000E+00\n"
      "       3       1       1\n"
      " 1.0000000000000000E+00\n";
  auto ms = read_text(f);
  REQUIRE(ms.size() == 4);
  CHECK(ms[0].name == "VERYLONGNAME");
  CHECK(ms[0].form == op4_form::Symmetric);
  CHECK(ms[1].name == "Z");
  CHECK(ms[1].nonzeros() == 0);
  CHECK(ms[1].rows == 3);
  CHECK(ms[2].dense_real() == Eigen::MatrixXd::Identity(3, 3));  // form 8 without terms
  CHECK(ms[3].name == "Z");
  CHECK(ms[3].real.coeff(2, 1) == 7.0);
}

TEST_CASE("symmetric form 6 given as one triangle is mirrored; complete ones are kept", "[op4]") {
  // Lower triangle of [[2,1],[1,3]] only.
  const std::string f =
      "       2       2       6       2S       1P,3E23.16\n"
      "       1       1       2\n"
      " 2.0000000000000000E+00 1.0000000000000000E+00\n"
      "       2       2       1\n"
      " 3.0000000000000000E+00\n"
      "       3       1       1\n"
      " 1.0000000000000000E+00\n";
  Eigen::MatrixXd want(2, 2);
  want << 2, 1, 1, 3;
  CHECK(read_text(f)[0].dense_real() == want);
  Op4ReadOptions keep;
  keep.expand_symmetric = false;
  Eigen::MatrixXd lower(2, 2);
  lower << 2, 0, 1, 3;
  CHECK(read_op4_buffer(f.data(), f.size(), "s.op4", keep)[0].dense_real() == lower);
}

// ---------------------------------------------------------------------------
// Binary, hand-made

namespace {
/// Header record payload: NCOL NROW FORM TYPE NAME.
Bytes header(bool big, int word, std::int64_t ncol, std::int64_t nrow, int form, int type, const std::string& name) {
  Bytes b;
  b.big = big;
  b.word = word;
  b.i(ncol).i(nrow).i(form).i(type);
  std::string n = name;
  n.resize(word == 4 ? 8 : 16, ' ');
  b.text(n);
  return b;
}
Bytes words(bool big, int word) {
  Bytes b;
  b.big = big;
  b.word = word;
  return b;
}
}  // namespace

TEST_CASE("binary little-endian dense real double: the writer's bytes equal the hand-made file", "[op4]") {
  // 2x2: [[1,0],[2,3]] -> column 1 rows 1-2, column 2 row 2.
  std::string f;
  f += record(header(false, 4, 2, 2, 1, 2, "KAA"));
  f += record(words(false, 4).i(1).i(1).i(4).f64(1.0).f64(2.0));
  f += record(words(false, 4).i(2).i(2).i(2).f64(3.0));
  f += record(words(false, 4).i(3).i(1).i(2).f64(1.0));
  CHECK(f.substr(0, 4) == std::string("\x18\0\0\0", 4));  // 24-byte header record
  Op4FileInfo info;
  auto ms = read_op4_buffer(f.data(), f.size(), "b.op4", {}, &info);
  CHECK(info.encoding == Op4Encoding::Binary);
  CHECK(info.endian == Endian::Little);
  CHECK(info.marker_bytes == 4);
  CHECK(info.word_bytes == 4);
  Eigen::MatrixXd want(2, 2);
  want << 1, 0, 2, 3;
  REQUIRE(ms.size() == 1);
  CHECK(ms[0].dense_real() == want);
  CHECK(ms[0].storage == Op4Storage::Dense);
  Op4WriteOptions o;
  o.storage = Op4Storage::Dense;
  CHECK(write_op4_string(ms, o) == f);
}

TEST_CASE("binary big-endian sparse real single, non-BIGMAT strings", "[op4]") {
  // 3x1: rows 1 and 3 (two strings of L=1 word): IS = 2*65536+1, 2*65536+3; NW = 4.
  std::string f;
  f += record(header(true, 4, 1, 3, 2, 1, "M"));
  f += record(words(true, 4).i(1).i(0).i(4).i(2 * 65536 + 1).f32(0.5f).i(2 * 65536 + 3).f32(-8.0f));
  f += record(words(true, 4).i(2).i(1).i(1).f32(1.0f));
  Op4FileInfo info;
  auto m = read_op4_buffer(f.data(), f.size(), "be.op4", {}, &info).at(0);
  CHECK(info.endian == Endian::Big);
  CHECK(m.storage == Op4Storage::Sparse);
  CHECK(m.precision == Op4Precision::RealSingle);
  CHECK(m.real.coeff(0, 0) == 0.5);
  CHECK(m.real.coeff(2, 0) == -8.0);
  Op4WriteOptions o;
  o.endian = Endian::Big;
  CHECK(write_op4_string({m}, o) == f);
}

TEST_CASE("binary BIGMAT complex single with 8-byte record markers", "[op4]") {
  // 2x2 complex single; column 2 rows 1-2: L = 2 terms * 2 words = 4 -> words L+1=5, IROW=1; NW = 6.
  std::string f;
  f += record(header(false, 4, 2, -2, 2, 3, "CX"), 8);
  f += record(words(false, 4).i(2).i(0).i(6).i(5).i(1).f32(1).f32(2).f32(3).f32(4), 8);
  f += record(words(false, 4).i(3).i(1).i(1).f32(1), 8);
  Op4FileInfo info;
  auto m = read_op4_buffer(f.data(), f.size(), "m8.op4", {}, &info).at(0);
  CHECK(info.marker_bytes == 8);
  CHECK(m.storage == Op4Storage::BigMat);
  CHECK(m.complex.coeff(0, 1) == std::complex<double>(1, 2));
  CHECK(m.complex.coeff(1, 1) == std::complex<double>(3, 4));
  CHECK(m.complex.col(0).nonZeros() == 0);
  Op4WriteOptions o;
  o.storage = Op4Storage::BigMat;
  o.marker_bytes = 8;
  CHECK(write_op4_string({m}, o) == f);
}

TEST_CASE("binary 64-bit NASTRAN: 8-byte words, 48-byte header, every number 8 bytes", "[op4]") {
  // Real single (TYPE 1) in 64-bit mode: one 8-byte word per number.
  std::string f;
  f += record(header(false, 8, 1, 2, 2, 1, "W8"));
  CHECK(f.substr(0, 4) == std::string("\x30\0\0\0", 4));
  f += record(words(false, 8).i(1).i(1).i(2).f64(0.25).f64(4.0));
  f += record(words(false, 8).i(2).i(1).i(1).f64(1.0));
  Op4FileInfo info;
  auto m = read_op4_buffer(f.data(), f.size(), "w8.op4", {}, &info).at(0);
  CHECK(info.word_bytes == 8);
  CHECK(m.real.coeff(0, 0) == 0.25);
  CHECK(m.real.coeff(1, 0) == 4.0);
  Op4WriteOptions o;
  o.storage = Op4Storage::Dense;
  o.word_bytes = 8;
  CHECK(write_op4_string({m}, o) == f);
}

TEST_CASE("forms 3 (diagonal as one column), 9 (pseudo-identity without terms), 8-character name abutting the format",
          "[op4]") {
  const std::string f =
      // Diagonal 3x3 kept as the column of its diagonal terms (NCOL 1).
      "       1       3       3       2D       1P,3E23.16\n"
      "       1       1       3\n"
      " 2.0000000000000000E+00 0.0000000000000000E+00-5.0000000000000000E-01\n"
      "       2       1       1\n"
      " 1.0000000000000000E+00\n"
      // Pseudo-identity 2x3 written without terms.
      "       3       2       9       1P       1P,5E16.9\n"
      "       4       1       1\n"
      " 1.000000000E+00\n"
      // Name of 8 characters touching the format; values wider than 5E16.9 declares.
      "       1       1       6       2ABCDEFGH1P,5E16.9\n"
      "       1       1       1\n"
      " 1.00000000000000000E+01\n"
      "       2       1       1\n"
      " 2.00000000000000000E+00\n"
      " \n";
  auto ms = read_text(f);
  REQUIRE(ms.size() == 3);
  Eigen::MatrixXd d = Eigen::MatrixXd::Zero(3, 3);
  d(0, 0) = 2.0;
  d(2, 2) = -0.5;
  CHECK(ms[0].cols == 3);
  CHECK(ms[0].dense_real() == d);
  Eigen::MatrixXd p = Eigen::MatrixXd::Zero(2, 3);
  p(0, 0) = p(1, 1) = 1.0;
  CHECK(ms[1].dense_real() == p);
  CHECK(ms[2].name == "ABCDEFGH");
  CHECK(ms[2].real.coeff(0, 0) == 10.0);
  // Expansion can be switched off: the matrix as stored.
  Op4ReadOptions raw;
  raw.expand_diagonal = raw.expand_identity = false;
  auto r = read_op4_buffer(f.data(), f.size(), "f.op4", raw);
  CHECK(r[0].cols == 1);
  CHECK(r[1].nonzeros() == 0);
}

TEST_CASE("binary header with a name longer than 8 characters (12 bytes), big-endian, 8-byte markers", "[op4]") {
  Bytes h;
  h.big = true;
  h.word = 4;
  h.i(1).i(2).i(2).i(2).text("STIFFNESS_AB");  // 28-byte header record
  std::string f = record(h, 8);
  f += record(words(true, 4).i(1).i(2).i(2).f64(-1.25), 8);
  f += record(words(true, 4).i(2).i(1).i(2).f64(1.0), 8);
  Op4FileInfo info;
  auto m = read_op4_buffer(f.data(), f.size(), "long.op4", {}, &info).at(0);
  CHECK(info.encoding == Op4Encoding::Binary);
  CHECK(info.word_bytes == 4);
  CHECK(m.name == "STIFFNESS_AB");
  CHECK(m.real.coeff(1, 0) == -1.25);
  CHECK(m.real.nonZeros() == 1);
}

TEST_CASE("ASCII number text: shortest exact digits padded to the field, Fortran 3-digit exponents", "[op4]") {
  // Golden text of one dense column; every value reads back bit for bit.
  SparseReal a(6, 1);
  const double v[] = {0.1, -1e-300, 6.02214076e23, 5e-324, 1.0 / 3.0, -0.0};
  for (int i = 0; i < 6; ++i) a.insert(i, 0) = v[i] == 0.0 ? 1.0 : v[i];
  a.coeffRef(5, 0) = 123456789.0;
  Op4WriteOptions o;
  o.encoding = Op4Encoding::Ascii;
  o.storage = Op4Storage::Dense;
  const std::string w = write_op4_string({Op4Matrix::from_real("N", a)}, o);
  CHECK(w ==
        "       1       6       2       2N       1P,3E23.16\n"
        "       1       1       6\n"
        " 1.0000000000000000E-01-1.0000000000000000-300 6.0221407600000000E+23\n"
        " 5.0000000000000000-324 3.3333333333333330E-01 1.2345678900000000E+08\n"
        "       2       1       1\n"
        " 1.0000000000000000E+00\n");
  CHECK(read_text(w)[0].real.isApprox(a, 0.0));
  for (int i = 0; i < 6; ++i) CHECK(read_text(w)[0].real.coeff(i, 0) == a.coeff(i, 0));
  // Single precision: the float's shortest digits (0.1f is written 1.000000000E-01 and read back as 0.1f).
  o.precision = 1;
  const std::string s = write_op4_string({Op4Matrix::from_real("N", a)}, o);
  CHECK(s.find(" 1.000000000E-01") != std::string::npos);
  CHECK(read_text(s)[0].real.coeff(0, 0) == static_cast<double>(0.1f));
}
