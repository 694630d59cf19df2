#pragma once
/// \file bush.hpp
/// CBUSH — generalized spring-damper, and PBUSH — its property.
///
/// | 1     | 2   | 3    | 4  | 5  | 6     | 7  | 8  | 9   |
/// |-------|-----|------|----|----|-------|----|----|-----|
/// | CBUSH | EID | PID  | GA | GB | X1/G0 | X2 | X3 | CID |
/// |       | S   | OCID | S1 | S2 | S3    |    |    |     |
///
/// EID > 0. PID: PBUSH id, blank = EID. GB blank = grounded (0). Orientation as
/// CBAR (an integer in field 6 is G0), used only when CID is blank; blank when
/// CID is given or the grids coincide. CID: element coordinate system, blank
/// (stored as -1) = use the orientation. S: spring-damper location along GA-GB,
/// blank = 0.5 (0 <= S <= 1). OCID: system of the offset S1-S3, blank = -1
/// (offset along the line GA-GB); S1-S3 used when OCID >= 0, blank = 0.0.
///
/// | 1     | 2   | 3     | 4   | 5   | 6   | 7   | 8   | 9   |
/// |-------|-----|-------|-----|-----|-----|-----|-----|-----|
/// | PBUSH | PID | "K"   | K1  | K2  | K3  | K4  | K5  | K6  |
/// |       |     | "B"   | B1  | B2  | B3  | B4  | B5  | B6  |
/// |       |     | "GE"  | GE1 | GE2 | GE3 | GE4 | GE5 | GE6 |
/// |       |     | "RCV" | SA  | ST  | EA  | ET  |     |     |
///
/// Each row starts with its flag (in field 3; field 2 of a continuation is
/// blank); rows may come in any order, each at most once. Ki (stiffness), Bi
/// (viscous damping), GEi (structural damping): blank = 0.0. NASTRAN uses GE1
/// for all six when only GE1 is given; this struct keeps the values as given.
/// SA, ST, EA, ET (stress and strain recovery coefficients): blank = 1.0.
#include <array>
#include <cstdint>
#include <vector>

#include "formats/card.hpp"
#include "formats/field_reader.hpp"

namespace ssid::formats {

struct Cbush {
  std::int64_t eid = 0, pid = 0, ga = 0, gb = 0;  ///< gb = 0: grounded
  std::int64_t g0 = 0;
  std::array<double, 3> x{0.0, 0.0, 0.0};
  bool orientation_blank = true;
  std::int64_t cid = -1;  ///< -1: blank (use the orientation)
  double s = 0.5;
  std::int64_t ocid = -1;
  std::array<double, 3> si{0.0, 0.0, 0.0};  ///< S1, S2, S3
  bool pid_blank = false;
  std::size_t card = 0;
};

struct Pbush {
  std::int64_t pid = 0;
  std::array<double, 6> k{}, b{}, ge{};
  double sa = 1.0, st = 1.0, ea = 1.0, et = 1.0;
  /// Which flag rows the card has, so they are written back.
  bool has_k = false, has_b = false, has_ge = false, has_rcv = false;
  std::size_t card = 0;
};

Cbush parse_cbush(const FieldReader& r);
std::vector<FieldValue> write_cbush(const Cbush& c);
Pbush parse_pbush(const FieldReader& r);
std::vector<FieldValue> write_pbush(const Pbush& p);

}  // namespace ssid::formats
