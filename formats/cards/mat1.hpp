#pragma once
/// \file mat1.hpp
/// MAT1 — isotropic material.
///
/// | 1    | 2   | 3  | 4  | 5     | 6   | 7 | 8    | 9  |
/// |------|-----|----|----|-------|-----|---|------|----|
/// | MAT1 | MID | E  | G  | NU    | RHO | A | TREF | GE |
/// |      | ST  | SC | SS | MCSID |     |   |      |    |
///
/// MID > 0. E, G >= 0 (not both blank); -1 < NU <= 0.5. When one of E, G, NU
/// is blank it is derived from E = 2 (1 + NU) G; when two are blank (only E or
/// only G given) the other two are 0.0, as the NASTRAN Quick Reference documents.
/// RHO (mass density), A (thermal expansion), TREF, GE (structural damping),
/// ST, SC, SS (stress limits): blank = 0.0. MCSID: blank = 0.
#include <cstdint>
#include <vector>

#include "formats/card.hpp"
#include "formats/field_reader.hpp"

namespace ssid::formats {

/// NU within NASTRAN's range for MAT1, -1.0 < NU <= 0.5 (the QRG's field table).
inline bool mat1_nu_in_range(double nu) { return nu > -1.0 && nu <= 0.5; }

struct Mat1 {
  std::int64_t mid = 0;
  double e = 0.0, g = 0.0, nu = 0.0;  ///< after the derivation rule
  double rho = 0.0, a = 0.0, tref = 0.0, ge = 0.0;
  double st = 0.0, sc = 0.0, ss = 0.0;
  std::int64_t mcsid = 0;
  /// Which of E, G, NU were given; the others were derived and are written blank
  /// (so they follow a changed E, G or NU). To change a derived value itself, set its flag.
  bool e_given = true, g_given = false, nu_given = false;
  std::size_t card = 0;
};

Mat1 parse_mat1(const FieldReader& r);
std::vector<FieldValue> write_mat1(const Mat1& m);

}  // namespace ssid::formats
