#pragma once
/// \file coord.hpp
/// CORD2R, CORD2C, CORD2S — coordinate systems by three points, and GRDSET —
/// defaults for GRID fields. Plain data: the transformations are in translators/.
///
/// | 1      | 2   | 3   | 4  | 5  | 6  | 7  | 8  | 9  |
/// |--------|-----|-----|----|----|----|----|----|----|
/// | CORD2R | CID | RID | A1 | A2 | A3 | B1 | B2 | B3 |
/// |        | C1  | C2  | C3 |    |    |    |    |    |
///
/// (CORD2C and CORD2S likewise.) CID > 0. RID: the system A, B, C are given in,
/// blank = 0 (basic). A: origin; B: a point on the z axis; C: a point in the
/// x-z plane; blank coordinates = 0.0. A != B and C not on the line AB.
///
/// | 1      | 2 | 3  | 4 | 5 | 6 | 7  | 8  | 9    |
/// |--------|---|----|---|---|---|----|----|------|
/// | GRDSET |   | CP |   |   |   | CD | PS | SEID |
///
/// At most one per deck; its non-blank fields replace blank CP, CD, PS, SEID on every GRID.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "formats/card.hpp"
#include "formats/cards/grid.hpp"
#include "formats/field_reader.hpp"

namespace ssid::formats {

enum class CoordKind : std::uint8_t { Rectangular, Cylindrical, Spherical };

struct Cord2 {
  CoordKind kind = CoordKind::Rectangular;
  std::int64_t cid = 0, rid = 0;
  std::array<double, 3> a{0.0, 0.0, 0.0}, b{0.0, 0.0, 0.0}, c{0.0, 0.0, 0.0};
  std::size_t card = 0;
  /// "CORD2R", "CORD2C" or "CORD2S".
  const char* name() const;
};

struct Grdset {
  std::optional<std::int64_t> cp, cd, seid;
  std::string ps;  ///< "" = not given
  std::size_t card = 0;
};

/// Parses any of CORD2R/C/S (the kind from the card name).
Cord2 parse_cord2(const FieldReader& r);
std::vector<FieldValue> write_cord2(const Cord2& c);
Grdset parse_grdset(const FieldReader& r);
std::vector<FieldValue> write_grdset(const Grdset& g);
/// Fills a GRID's blank CP, CD, PS, SEID from GRDSET. write_grid then writes the
/// values explicitly (the same values whether or not the GRDSET stays).
void apply_grdset(Grid& g, const Grdset& s);

}  // namespace ssid::formats
