#pragma once
/// \file dmig.hpp
/// Direct matrix input at grid points: the DMIG bulk data entry, read from decks
/// and punch (`.pch`) files in small, large or free field, and written back.
///
/// Header entry (one per matrix):
///
/// | 1    | 2    | 3   | 4   | 5   | 6    | 7     | 8 | 9    |
/// |------|------|-----|-----|-----|------|-------|---|------|
/// | DMIG | NAME | "0" | IFO | TIN | TOUT | POLAR |   | NCOL |
///
/// Column entries (any number, one per column GJ/CJ; a column may be split over
/// several entries):
///
/// | 1    | 2    | 3  | 4  | 5  | 6  | 7  | 8  | 9  |
/// |------|------|----|----|----|----|----|----|----|
/// | DMIG | NAME | GJ | CJ |    | G1 | C1 | A1 | B1 |
/// |      | G2   | C2 | A2 | B2 | G3 | C3 | A3 | B3 |
///
/// NAME: up to 8 characters, the same on every entry of the matrix.
/// Field 3 of the header is the integer 0 (that is how the header is told apart).
/// IFO (form): 1 square, 2 or 9 rectangular, 6 symmetric.
/// TIN (precision of the input): 1 real single, 2 real double, 3 complex single,
/// 4 complex double. TOUT: precision of the matrix NASTRAN forms, 0 or blank =
/// set by the PRECISION system cell (kept as given).
/// POLAR: 0 or blank = Ai, Bi are real and imaginary parts; 1 = magnitude and
/// phase in degrees, A e^{i B pi/180} (complex TIN only).
/// NCOL: number of columns; used (and required) only for IFO = 9.
/// GJ, CJ: the column's grid or scalar point and component (1-6; 0 or blank for
/// a scalar point). For IFO = 9, GJ is the column number 1..NCOL and CJ is 0/blank.
/// Gi, Ci: a row's grid or scalar point and component. Ai: real part (or
/// magnitude); Bi: imaginary part (or phase), complex TIN only (blank = 0.0 there,
/// must be blank or 0.0 for real TIN).
/// IFO = 6: each off-diagonal term is given once, above or below the diagonal
/// (the two may be mixed); giving both (i,j) and (j,i) is an error. The full
/// matrix is A + A^T - diag(A) (expand_dmig).
/// Field 5 of a column entry (after CJ) is blank.
#include <complex>
#include <cstdint>
#include <string>
#include <vector>

#include "formats/card.hpp"
#include "formats/deck.hpp"
#include "formats/field_reader.hpp"

namespace ssid::formats {

/// A row or column key: grid/scalar point and component (0 for a scalar point,
/// and for IFO = 9 columns, where `point` is the column number).
struct DmigKey {
  std::int64_t point = 0;
  int component = 0;
  bool operator==(const DmigKey& o) const { return point == o.point && component == o.component; }
  bool operator!=(const DmigKey& o) const { return !(*this == o); }
  bool operator<(const DmigKey& o) const { return point != o.point ? point < o.point : component < o.component; }
};

/// One term of a column, as written (a, b are real/imag, or magnitude/phase in degrees when POLAR = 1).
struct DmigTerm {
  DmigKey row;
  double a = 0.0;
  double b = 0.0;
};

struct DmigColumn {
  DmigKey col;
  std::vector<DmigTerm> terms;
  std::size_t card = 0;  ///< index into Deck::cards (or the order of generation)
};

namespace dmig_form {
constexpr int Square = 1, Rectangular = 2, Symmetric = 6, RectangularByColumnNumber = 9;
}

struct Dmig {
  std::string name;
  int ifo = dmig_form::Square;
  int tin = 2;
  int tout = 0;
  bool polar = false;
  std::int64_t ncol = 0;  ///< IFO = 9 only (0 = blank)
  std::vector<DmigColumn> columns;
  std::size_t card = 0;  ///< the header's index into Deck::cards

  bool is_complex() const { return tin == 3 || tin == 4; }
  /// Number of terms as given.
  std::size_t terms() const;
};

/// Term value as a complex number: (a, b), or a*(cos b, sin b) with b in degrees when polar.
std::complex<double> dmig_value(const Dmig& m, const DmigTerm& t);

/// One stored entry of the complete matrix.
struct DmigEntry {
  DmigKey row, col;
  std::complex<double> value;
  std::size_t source = 0;  ///< index into Dmig::columns of the entry that gave the term
};

/// The complete matrix as (row, column, value) entries, sorted by column then row:
/// polar terms converted, a symmetric matrix (IFO 6) mirrored. Terms given twice
/// at the same position (or at (i,j) and (j,i) of a symmetric matrix) are an error,
/// reported through `deck` when given (for the card location), else with the matrix name.
std::vector<DmigEntry> expand_dmig(const Dmig& m, const Deck* deck = nullptr);

/// Parses the header entry (field 3 = 0). Throws ParseError.
Dmig parse_dmig_header(const FieldReader& r);
/// Parses a column entry of matrix `m` (its IFO decides how GJ is read). Throws ParseError.
DmigColumn parse_dmig_column(const FieldReader& r, const Dmig& m);

/// Every DMIG matrix of a deck (or punch file) in the order of their headers.
/// Column entries may come before or after their header. Throws ParseError with
/// the card location for a malformed entry, a column without a header, a second header.
std::vector<Dmig> read_dmigs(const Deck& deck);
/// Reads a deck or punch file and returns its DMIG matrices.
std::vector<Dmig> read_dmig_file(const std::string& path);

/// Card values (values[0] = "DMIG") of the header and of one entry per column.
std::vector<FieldValue> write_dmig_header(const Dmig& m);
std::vector<FieldValue> write_dmig_column(const Dmig& m, const DmigColumn& c);
/// The whole matrix as card text (header, then columns), in `format`. Reals are
/// written exactly (promoted to large field where 8 characters cannot hold them).
std::string format_dmig(const Dmig& m, FieldFormat format = FieldFormat::Small);

}  // namespace ssid::formats
