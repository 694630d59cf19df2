/// OP4 round trips: every storage x precision x encoding x byte order x marker and
/// word size, and the same matrix read from its ASCII and binary encodings.
#include <catch2/catch.hpp>

#include <filesystem>
#include <iomanip>
#include <random>

#include "formats/op4.hpp"
#include "formats/parse_error.hpp"

using namespace ssid::formats;

namespace {

/// A random sparse matrix with runs of consecutive rows, gaps, null columns, values
/// spanning many decades (and exponents beyond two digits), negative zero excluded.
SparseComplex sample(int rows, int cols, unsigned seed) {
  std::mt19937 g(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  std::uniform_int_distribution<int> e(-30, 30);
  std::vector<Eigen::Triplet<std::complex<double>>> t;
  for (int c = 0; c < cols; ++c) {
    if (c % 4 == 2) continue;  // null column
    for (int r = 0; r < rows; ++r) {
      if ((r * 7 + c * 3) % 5 < 2) continue;
      const double a = u(g) * std::pow(10.0, e(g)), b = u(g) * std::pow(10.0, e(g) / 4);
      t.emplace_back(r, c, std::complex<double>(a, b));
    }
  }
  SparseComplex m(rows, cols);
  m.setFromTriplets(t.begin(), t.end());
  return m;
}

/// The matrix as it must come back at precision p (values rounded to float for 1 and 3).
Op4Matrix expected(const SparseComplex& a, int p) {
  SparseComplex b = a;
  for (int k = 0; k < b.nonZeros(); ++k) {
    double re = b.valuePtr()[k].real(), im = b.valuePtr()[k].imag();
    if (p == 1 || p == 3) {
      re = static_cast<float>(re);
      im = static_cast<float>(im);
    }
    if (p <= 2) im = 0.0;
    b.valuePtr()[k] = std::complex<double>(re, im);
  }
  b.prune(std::complex<double>(0.0));
  if (p <= 2) return Op4Matrix::from_real("A", b.real(), 2, static_cast<Op4Precision>(p));
  return Op4Matrix::from_complex("A", b, 2, static_cast<Op4Precision>(p));
}

bool same(const Op4Matrix& x, const Op4Matrix& y) {
  if (x.rows != y.rows || x.cols != y.cols || x.precision != y.precision || x.nonzeros() != y.nonzeros()) {
    UNSCOPED_INFO("shape/precision/nonzeros differ: " << x.rows << "x" << x.cols << " p" << int(x.precision) << " nnz "
                                                      << x.nonzeros() << " vs " << y.rows << "x" << y.cols << " p"
                                                      << int(y.precision) << " nnz " << y.nonzeros());
    return false;
  }
  SparseComplex a = x.as_complex(), b = y.as_complex();
  for (int c = 0; c < a.outerSize(); ++c) {
    SparseComplex::InnerIterator i(a, c), j(b, c);
    for (; i && j; ++i, ++j)
      if (i.row() != j.row() || i.value() != j.value()) {
        UNSCOPED_INFO(std::setprecision(17) << "column " << c << ": row " << i.row() << " value " << i.value() << " vs row " << j.row() << " value "
                                << j.value());
        return false;
      }
    if (i || j) return false;
  }
  return true;
}

}  // namespace

TEST_CASE("round trip of every storage x precision x encoding x byte order x marker x word size", "[op4]") {
  const SparseComplex a = sample(37, 11, 7);
  int combos = 0;
  for (int p = 1; p <= 4; ++p) {
    const Op4Matrix m = expected(a, p);
    for (Op4Storage s : {Op4Storage::Dense, Op4Storage::Sparse, Op4Storage::BigMat})
      for (Op4Encoding enc : {Op4Encoding::Ascii, Op4Encoding::Binary})
        for (Endian e : {Endian::Little, Endian::Big})
          for (int mb : {4, 8})
            for (int wb : {4, 8}) {
              if (enc == Op4Encoding::Ascii && (e == Endian::Big || mb == 8 || wb == 8)) continue;
              if (wb == 8 && (p == 1 || p == 3)) {
                // 64-bit files hold single precision in 8-byte reals: still exact for float values.
              }
              Op4WriteOptions o;
              o.encoding = enc;
              o.storage = s;
              o.endian = e;
              o.marker_bytes = mb;
              o.word_bytes = wb;
              const std::string bytes = write_op4_string({m, m}, o);
              Op4FileInfo info;
              auto back = read_op4_buffer(bytes.data(), bytes.size(), "rt.op4", {}, &info);
              INFO("precision " << p << " storage " << int(s) << " encoding " << int(enc) << " endian " << int(e)
                                << " markers " << mb << " words " << wb);
              REQUIRE(back.size() == 2);
              CHECK(info.encoding == enc);
              if (enc == Op4Encoding::Binary) {
                CHECK(info.endian == e);
                CHECK(info.marker_bytes == mb);
                CHECK(info.word_bytes == wb);
              }
              CHECK(back[0].storage == s);
              CHECK(same(back[0], m));
              CHECK(same(back[1], m));
              ++combos;
            }
  }
  CHECK(combos == 4 * 3 * (1 + 8));
}

TEST_CASE("the same matrix read from its ASCII and binary encodings is identical", "[op4]") {
  for (int p = 1; p <= 4; ++p) {
    const Op4Matrix m = expected(sample(23, 9, 11 + p), p);
    Op4WriteOptions a, b;
    a.encoding = Op4Encoding::Ascii;
    b.encoding = Op4Encoding::Binary;
    const std::string ta = write_op4_string({m}, a), tb = write_op4_string({m}, b);
    auto ra = read_op4_buffer(ta.data(), ta.size(), "a.op4"), rb = read_op4_buffer(tb.data(), tb.size(), "b.op4");
    INFO("precision " << p);
    CHECK(same(ra[0], rb[0]));
    CHECK(same(ra[0], m));
  }
}

TEST_CASE("extreme doubles survive ASCII exactly (3-digit exponents written as Fortran does)", "[op4]") {
  SparseReal a(6, 1);
  const double v[] = {1e-300, -2.5e250, 1.2345678901234567e-100, 4.9e-324, -1.7976931348623157e308, 0.1};
  for (int i = 0; i < 6; ++i) a.insert(i, 0) = v[i];
  Op4WriteOptions o;
  o.encoding = Op4Encoding::Ascii;
  for (Op4Storage s : {Op4Storage::Dense, Op4Storage::Sparse}) {
    o.storage = s;
    const std::string t = write_op4_string({Op4Matrix::from_real("X", a)}, o);
    CHECK(t.find("E+250") == std::string::npos);
    CHECK(t.find("-2.50000000000000") != std::string::npos);
    CHECK(t.find("+250") != std::string::npos);
    auto r = read_op4_buffer(t.data(), t.size(), "x.op4").at(0);
    for (int i = 0; i < 6; ++i) CHECK(r.real.coeff(i, 0) == v[i]);
  }
  // Single precision cannot hold 1e250: refused rather than written as infinity.
  o.precision = 1;
  CHECK_THROWS_AS(write_op4_string({Op4Matrix::from_real("X", a)}, o), ssid::formats::InputError);
}

TEST_CASE("precision conversion on write; complex to real is refused", "[op4]") {
  const Op4Matrix m = expected(sample(5, 4, 3), 2);
  Op4WriteOptions o;
  o.precision = 1;
  const std::string t = write_op4_string({m}, o);
  auto r = read_op4_buffer(t.data(), t.size(), "p.op4").at(0);
  CHECK(r.precision == Op4Precision::RealSingle);
  CHECK(same(r, expected(m.as_complex(), 1)));
  o.precision = 4;  // real promoted to complex double
  const std::string t4 = write_op4_string({m}, o);
  CHECK(read_op4_buffer(t4.data(), t4.size(), "p4.op4").at(0).dense_complex() == m.dense_complex());
  const Op4Matrix c = expected(sample(5, 4, 3), 4);
  o.precision = 2;
  CHECK_THROWS_AS(write_op4_string({c}, o), ssid::formats::InputError);
}

TEST_CASE("sparse storage of 65536 or more rows is written as BIGMAT; long strings are split", "[op4]") {
  SparseReal a(70000, 2);
  std::vector<Eigen::Triplet<double>> t;
  for (int r = 0; r < 40000; ++r) t.emplace_back(r, 0, 1.0 + r);  // one run longer than a non-BIGMAT string
  t.emplace_back(69999, 1, -3.0);
  a.setFromTriplets(t.begin(), t.end());
  const Op4Matrix m = Op4Matrix::from_real("BIG", a);
  Op4WriteOptions o;
  o.storage = Op4Storage::Sparse;
  const std::string s = write_op4_string({m}, o);
  auto r = read_op4_buffer(s.data(), s.size(), "big.op4").at(0);
  CHECK(r.storage == Op4Storage::BigMat);
  CHECK(same(r, m));
  // Non-BIGMAT strings must be cut below L = 32766 words.
  SparseReal b(60000, 1);
  std::vector<Eigen::Triplet<double>> tb;
  for (int i = 0; i < 50000; ++i) tb.emplace_back(i, 0, 0.5 * i + 1);
  b.setFromTriplets(tb.begin(), tb.end());
  const Op4Matrix mb = Op4Matrix::from_real("LONG", b);
  for (Op4Encoding enc : {Op4Encoding::Binary, Op4Encoding::Ascii}) {
    o.encoding = enc;
    const std::string sb = write_op4_string({mb}, o);
    auto rb = read_op4_buffer(sb.data(), sb.size(), "long.op4").at(0);
    CHECK(rb.storage == Op4Storage::Sparse);
    CHECK(same(rb, mb));
  }
}

TEST_CASE("write_op4 and read_op4 through a file", "[op4]") {
  const auto path = std::filesystem::temp_directory_path() / "ssid_test_op4_file.op4";
  const Op4Matrix m = expected(sample(8, 8, 5), 2);
  write_op4(path.string(), {m});
  CHECK(same(read_op4(path.string()).at(0), m));
  std::filesystem::remove(path);
  CHECK_THROWS_AS(read_op4(path.string()), ParseError);
}
