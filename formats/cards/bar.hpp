#pragma once
/// \file bar.hpp
/// CBAR — simple beam element, BAROR — its defaults, PBAR — its property.
///
/// | 1    | 2   | 3   | 4   | 5   | 6     | 7   | 8   | 9    |
/// |------|-----|-----|-----|-----|-------|-----|-----|------|
/// | CBAR | EID | PID | GA  | GB  | X1/G0 | X2  | X3  | OFFT |
/// |      | PA  | PB  | W1A | W2A | W3A   | W1B | W2B | W3B  |
///
/// EID > 0. PID: PBAR/PBARL id; blank = BAROR's PID, else EID. GA != GB.
/// Orientation: an integer in field 6 is G0 (vector from GA to G0, fields 7-8
/// blank), otherwise X1-X3 (reals, in GA's displacement system). Blank fields
/// 6-8 take BAROR's orientation; OFFT blank takes BAROR's, else "GGG"
/// (one of GGG BGG GGO BGO GOG BOG GOO BOO); the older form of field 9, an
/// integer flag F (1: fields 6-8 are X1-X3, 2: field 6 is G0), is read as OFFT
/// GGG, checked against fields 6-8 and written back. PA, PB: pin flags (components
/// released at each end), blank = none. W1A..W3B: end offsets, blank = 0.0.
///
/// | 1     | 2 | 3   | 4 | 5 | 6     | 7  | 8  | 9    |
/// |-------|---|-----|---|---|-------|----|----|------|
/// | BAROR |   | PID |   |   | X1/G0 | X2 | X3 | OFFT |
///
/// At most one BAROR per deck; its non-blank fields are the defaults of blank CBAR fields.
///
/// | 1    | 2   | 3   | 4  | 5  | 6  | 7  | 8   | 9  |
/// |------|-----|-----|----|----|----|----|-----|----|
/// | PBAR | PID | MID | A  | I1 | I2 | J  | NSM |    |
/// |      | C1  | C2  | D1 | D2 | E1 | E2 | F1  | F2 |
/// |      | K1  | K2  | I12|    |    |    |     |    |
///
/// PID, MID > 0. A, I1, I2, J, NSM, I12, stress points C1..F2: blank = 0.0;
/// I1, I2 >= 0. K1, K2: shear area factors (shear stiffness K·A·G); blank
/// means infinite shear stiffness (no shear flexibility), stored as 0.0 with
/// the same meaning, as NASTRAN treats 0.0.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "formats/card.hpp"
#include "formats/field_reader.hpp"

namespace ssid::formats {

struct Cbar {
  std::int64_t eid = 0, pid = 0, ga = 0, gb = 0;
  std::int64_t g0 = 0;                     ///< > 0: orientation from GA to G0; else x
  std::array<double, 3> x{0.0, 0.0, 0.0};  ///< orientation vector (GA's displacement system)
  std::string offt = "GGG";
  std::int64_t legacy_flag = 0;            ///< field 9 as the older flag F (1 or 2), 0 = not given
  std::string pa, pb;                      ///< pin flags (component digits), "" = none
  std::array<double, 3> wa{0.0, 0.0, 0.0}, wb{0.0, 0.0, 0.0};  ///< end offsets
  /// Fields that were blank (filled from BAROR or the NASTRAN default); written blank.
  /// When changing PID, the orientation or OFFT of a parsed card, clear its flag too.
  bool pid_blank = false, orientation_blank = false, offt_blank = true;
  std::size_t card = 0;
};

struct Baror {
  std::optional<std::int64_t> pid;
  bool has_orientation = false;
  std::int64_t g0 = 0;
  std::array<double, 3> x{0.0, 0.0, 0.0};
  std::string offt;  ///< "" = not given
  std::int64_t legacy_flag = 0;  ///< field 9 as the older flag F (1 or 2), as on CBAR; 0 = not given
  std::size_t card = 0;
};

struct Pbar {
  std::int64_t pid = 0, mid = 0;
  double a = 0.0, i1 = 0.0, i2 = 0.0, i12 = 0.0, j = 0.0, nsm = 0.0;
  double c1 = 0.0, c2 = 0.0, d1 = 0.0, d2 = 0.0, e1 = 0.0, e2 = 0.0, f1 = 0.0, f2 = 0.0;
  double k1 = 0.0, k2 = 0.0;  ///< 0.0 = infinite shear stiffness (the blank default)
  std::size_t card = 0;
};

/// The OFFT words CBAR, CBEAM and BAROR/BEAMOR accept.
extern const std::initializer_list<const char*> k_offt_words;

Cbar parse_cbar(const FieldReader& r);
std::vector<FieldValue> write_cbar(const Cbar& c);
Baror parse_baror(const FieldReader& r);
std::vector<FieldValue> write_baror(const Baror& b);
Pbar parse_pbar(const FieldReader& r);
std::vector<FieldValue> write_pbar(const Pbar& p);

/// Fills a CBAR's blank fields from BAROR (PID, orientation, OFFT); a blank PID
/// with no BAROR PID is the EID. Returns false when the orientation is still
/// missing (blank fields 6-8 and no BAROR orientation).
bool apply_baror(Cbar& c, const Baror* b);

}  // namespace ssid::formats
