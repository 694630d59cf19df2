#pragma once
/// \file op4.hpp
/// NASTRAN OUTPUT4 / INPUTT4 matrix files (".op4"), ASCII and binary, read and write.
///
/// File layout (see docs/op4.md for the byte-level description):
///  - one header record per matrix: NCOL, NROW, FORM, TYPE, NAME (8 characters);
///    ASCII adds the Fortran number format (`1P,3E23.16`). NROW < 0 flags BIGMAT.
///  - one record per non-null column: ICOL, IROW, NW, then data.
///      IROW > 0: dense column, NW words starting at row IROW;
///      IROW = 0: sparse column made of strings; each string starts with
///      IS = (L+1)*65536 + IROW (non-BIGMAT) or the two words L+1, IROW (BIGMAT),
///      followed by L words of values.
///  - a closing record with ICOL = NCOL+1 and one value.
/// Binary files are Fortran unformatted sequential: each record is framed by a
/// length marker of 4 or 8 bytes, little- or big-endian, with 4-byte words (32-bit
/// NASTRAN) or 8-byte words (64-bit "ILP64" NASTRAN, where every real is 8 bytes).
/// All of this is detected from the file itself.
#include <complex>
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Dense>
#include <Eigen/SparseCore>

namespace ssid::formats {

/// NASTRAN matrix type (the TYPE word): 1 real single, 2 real double, 3 complex single, 4 complex double.
enum class Op4Precision : int { RealSingle = 1, RealDouble = 2, ComplexSingle = 3, ComplexDouble = 4 };

/// How columns are stored in the file.
enum class Op4Storage { Dense, Sparse, BigMat };
enum class Op4Encoding { Ascii, Binary };
enum class Endian { Little, Big };

/// NASTRAN matrix forms (the FORM word). Values outside this list are kept as read.
namespace op4_form {
constexpr int Square = 1, Rectangular = 2, Diagonal = 3, LowerTriangular = 4, UpperTriangular = 5, Symmetric = 6,
              RowVector = 7, Identity = 8, PseudoIdentity = 9, CholeskyFactor = 10, Trapezoidal = 11,
              SparseLowerTriangular = 13, SparseUpperTriangular = 15;
/// "square", "symmetric", ... or "form N" for an unknown value.
std::string name(int form);
}  // namespace op4_form

using SparseReal = Eigen::SparseMatrix<double>;
using SparseComplex = Eigen::SparseMatrix<std::complex<double>>;

/// One matrix of an OP4 file. Values are held in double precision whatever the
/// file's precision (single-precision values are exactly representable); exactly
/// one of `real` / `complex` is used, following `precision`.
struct Op4Matrix {
  std::string name;
  Eigen::Index rows = 0, cols = 0;
  int form = op4_form::Rectangular;
  Op4Precision precision = Op4Precision::RealDouble;
  Op4Storage storage = Op4Storage::Sparse;  ///< as read (for a matrix built in memory: a hint only)
  SparseReal real;
  SparseComplex complex;

  Op4Matrix() = default;
  Op4Matrix(const Op4Matrix&) = default;
  Op4Matrix& operator=(const Op4Matrix&) = default;
  /// Moves swap the storage: Eigen 3.4's SparseMatrix has no move constructor,
  /// and copying a matrix of hundreds of MB on every vector growth costs seconds.
  Op4Matrix(Op4Matrix&& o) noexcept { swap(o); }
  Op4Matrix& operator=(Op4Matrix&& o) noexcept {
    swap(o);
    return *this;
  }
  void swap(Op4Matrix& o) noexcept {
    name.swap(o.name);
    std::swap(rows, o.rows);
    std::swap(cols, o.cols);
    std::swap(form, o.form);
    std::swap(precision, o.precision);
    std::swap(storage, o.storage);
    real.swap(o.real);
    complex.swap(o.complex);
  }

  bool is_complex() const { return precision == Op4Precision::ComplexSingle || precision == Op4Precision::ComplexDouble; }
  /// Stored non-zero terms (a complex term counts once).
  Eigen::Index nonzeros() const { return is_complex() ? complex.nonZeros() : real.nonZeros(); }
  /// Dense copies. `dense_real` of a complex matrix throws; `dense_complex` of a real one promotes.
  Eigen::MatrixXd dense_real() const;
  Eigen::MatrixXcd dense_complex() const;
  /// The values as complex whatever the precision (real matrices get zero imaginary parts).
  SparseComplex as_complex() const;

  static Op4Matrix from_real(std::string name, const SparseReal& m, int form = op4_form::Rectangular,
                             Op4Precision precision = Op4Precision::RealDouble);
  static Op4Matrix from_complex(std::string name, const SparseComplex& m, int form = op4_form::Rectangular,
                                Op4Precision precision = Op4Precision::ComplexDouble);
};

/// What the file itself said about its encoding (filled by read_op4 when asked).
struct Op4FileInfo {
  Op4Encoding encoding = Op4Encoding::Ascii;
  Endian endian = Endian::Little;
  int marker_bytes = 4;  ///< binary: Fortran record-length marker size
  int word_bytes = 4;    ///< binary: 4 (32-bit NASTRAN) or 8 (64-bit)
};

struct Op4ReadOptions {
  /// Form 6 stored as one triangle only (some non-NASTRAN writers): mirror it so
  /// the matrix is complete. NASTRAN itself writes all terms; those are kept as read.
  bool expand_symmetric = true;
  /// Form 8 (identity) written without terms: build the identity; form 9
  /// (pseudo-identity, rectangular) without terms: ones on the leading diagonal.
  bool expand_identity = true;
  /// Form 3 (diagonal) declared with one column of N rows (NASTRAN keeps a
  /// diagonal matrix as the column of its diagonal terms): build the N x N
  /// diagonal matrix. A square form 3 matrix is kept as stored.
  bool expand_diagonal = true;
};

/// Reads every matrix of an OP4 file, in file order (repeated names are kept).
/// Throws ParseError naming the file, the matrix, the column and the line (ASCII)
/// or byte offset (binary) on any malformed input.
std::vector<Op4Matrix> read_op4(const std::string& path, const Op4ReadOptions& options = {},
                                Op4FileInfo* info = nullptr);
/// Reads OP4 content held in memory; `name` is used in messages.
std::vector<Op4Matrix> read_op4_buffer(const char* data, std::size_t size, const std::string& name,
                                       const Op4ReadOptions& options = {}, Op4FileInfo* info = nullptr);

struct Op4WriteOptions {
  Op4Encoding encoding = Op4Encoding::Binary;
  Op4Storage storage = Op4Storage::Sparse;
  /// 0 keeps each matrix's own precision; 1-4 forces one (complex -> real is refused).
  int precision = 0;
  Endian endian = Endian::Little;
  int marker_bytes = 4;  ///< 4 or 8
  int word_bytes = 4;    ///< 4, or 8 for 64-bit NASTRAN files
  /// ASCII significant digits after the point: 0 = 9 for single, 16 for double precision
  /// (1P,5E16.9 and 1P,3E23.16, exact for float and double).
  int digits = 0;
};

/// Writes matrices to an OP4 file. Sparse storage of a matrix with 65536 rows or
/// more is written as BIGMAT (non-BIGMAT strings cannot address those rows).
/// Throws std::runtime_error when the file cannot be written, std::invalid_argument
/// for options that cannot be honoured.
void write_op4(const std::string& path, const std::vector<Op4Matrix>& matrices, const Op4WriteOptions& options = {});
/// The same, into a string (used by tests and for small outputs).
std::string write_op4_string(const std::vector<Op4Matrix>& matrices, const Op4WriteOptions& options = {});

}  // namespace ssid::formats
