#pragma once
/// \file beam.hpp
/// CBEAM — beam element, BEAMOR — its defaults, PBEAM — its property.
///
/// | 1     | 2   | 3   | 4   | 5   | 6     | 7   | 8   | 9        |
/// |-------|-----|-----|-----|-----|-------|-----|-----|----------|
/// | CBEAM | EID | PID | GA  | GB  | X1/G0 | X2  | X3  | OFFT/BIT |
/// |       | PA  | PB  | W1A | W2A | W3A   | W1B | W2B | W3B      |
/// |       | SA  | SB  |     |     |       |     |     |          |
///
/// As CBAR (bar.hpp): PID blank = BEAMOR's PID, else EID; an integer in field 6
/// is G0; blank fields 6-8 and 9 take BEAMOR's values. Field 9 is OFFT (text,
/// default "GGG") or BIT (real, built-in twist). SA, SB: scalar points for
/// warping, blank = none (0).
///
/// | 1      | 2 | 3   | 4 | 5 | 6     | 7  | 8  | 9        |
/// |--------|---|-----|---|---|-------|----|----|----------|
/// | BEAMOR |   | PID |   |   | X1/G0 | X2 | X3 | OFFT/BIT |
///
/// | 1     | 2      | 3      | 4      | 5      | 6       | 7       | 8      | 9      |
/// |-------|--------|--------|--------|--------|---------|---------|--------|--------|
/// | PBEAM | PID    | MID    | A(A)   | I1(A)  | I2(A)   | I12(A)  | J(A)   | NSM(A) |
/// |       | C1(A)  | C2(A)  | D1(A)  | D2(A)  | E1(A)   | E2(A)   | F1(A)  | F2(A)  |
/// |       | SO     | X/XB   | A      | I1     | I2      | I12     | J      | NSM    |
/// |       | C1     | C2     | D1     | D2     | E1      | E2      | F1     | F2     |
/// |       | K1     | K2     | S1     | S2     | NSI(A)  | NSI(B)  | CW(A)  | CW(B)  |
/// |       | M1(A)  | M2(A)  | M1(B)  | M2(B)  | N1(A)   | N2(A)   | N1(B)  | N2(B)  |
///
/// PID, MID > 0; A(A) required; the other end-A values blank = 0.0. The
/// C(A)..F(A) continuation is always present when anything follows. Station
/// rows start with SO (YES, YESA, NO); the C..F row after a station is present
/// only when SO = YES. Blank station values take end A's (a constant section).
/// The last two rows: K1, K2 (shear stiffness factors, blank = 1.0), S1, S2
/// (shear relief, blank = 0.0), NSI, CW (blank: end A = 0.0, end B = end A),
/// M, N (centres of mass and neutral axis; blank: end A = 0.0, end B = end A).
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "formats/card.hpp"
#include "formats/field_reader.hpp"

namespace ssid::formats {

struct Cbeam {
  std::int64_t eid = 0, pid = 0, ga = 0, gb = 0;
  std::int64_t g0 = 0;
  std::array<double, 3> x{0.0, 0.0, 0.0};
  std::string offt = "GGG";
  std::optional<double> bit;  ///< built-in twist when field 9 holds a real (then offt is "GGG")
  std::string pa, pb;
  std::array<double, 3> wa{0.0, 0.0, 0.0}, wb{0.0, 0.0, 0.0};
  std::int64_t sa = 0, sb = 0;
  /// When changing PID, the orientation or OFFT of a parsed card, clear its flag too.
  bool pid_blank = false, orientation_blank = false, offt_blank = true;
  std::size_t card = 0;
};

struct Beamor {
  std::optional<std::int64_t> pid;
  bool has_orientation = false;
  std::int64_t g0 = 0;
  std::array<double, 3> x{0.0, 0.0, 0.0};
  std::string offt;           ///< "" = not given
  std::optional<double> bit;
  std::size_t card = 0;
};

/// One cross-section of a PBEAM: end A, an intermediate station or end B.
struct PbeamStation {
  std::string so = "YES";  ///< stress output option (not used for end A)
  double xxb = 0.0;        ///< 0.0 for end A, 1.0 for end B
  double a = 0.0, i1 = 0.0, i2 = 0.0, i12 = 0.0, j = 0.0, nsm = 0.0;
  double c1 = 0.0, c2 = 0.0, d1 = 0.0, d2 = 0.0, e1 = 0.0, e2 = 0.0, f1 = 0.0, f2 = 0.0;
};

struct Pbeam {
  std::int64_t pid = 0, mid = 0;
  /// End A (the constant section used when there are no stations).
  double a = 0.0, i1 = 0.0, i2 = 0.0, i12 = 0.0, j = 0.0, nsm = 0.0;
  double c1 = 0.0, c2 = 0.0, d1 = 0.0, d2 = 0.0, e1 = 0.0, e2 = 0.0, f1 = 0.0, f2 = 0.0;
  /// Intermediate stations and end B, in the order given (blank values filled from end A).
  std::vector<PbeamStation> stations;
  double k1 = 1.0, k2 = 1.0, s1 = 0.0, s2 = 0.0;
  double nsia = 0.0, nsib = 0.0, cwa = 0.0, cwb = 0.0;
  double m1a = 0.0, m2a = 0.0, m1b = 0.0, m2b = 0.0, n1a = 0.0, n2a = 0.0, n1b = 0.0, n2b = 0.0;
  /// Blank B-end tail values (they follow end A) are written blank.
  bool nsib_blank = true, cwb_blank = true, m1b_blank = true, m2b_blank = true, n1b_blank = true, n2b_blank = true;
  std::size_t card = 0;
};

Cbeam parse_cbeam(const FieldReader& r);
std::vector<FieldValue> write_cbeam(const Cbeam& c);
Beamor parse_beamor(const FieldReader& r);
std::vector<FieldValue> write_beamor(const Beamor& b);
Pbeam parse_pbeam(const FieldReader& r);
std::vector<FieldValue> write_pbeam(const Pbeam& p);

/// Fills a CBEAM's blank fields from BEAMOR; false when the orientation is still missing.
bool apply_beamor(Cbeam& c, const Beamor* b);

}  // namespace ssid::formats
