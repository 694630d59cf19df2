#pragma once
/// \file grid.hpp
/// GRID — grid point.
///
/// | 1    | 2  | 3  | 4  | 5  | 6  | 7  | 8  | 9    |
/// |------|----|----|----|----|----|----|----|------|
/// | GRID | ID | CP | X1 | X2 | X3 | CD | PS | SEID |
///
/// ID > 0. CP, CD: coordinate system ids, blank = 0 (basic); NASTRAN's GRDSET
/// defaults are applied by parse_bulk when a GRDSET card is present (coord.hpp).
/// X1-X3: location in CP, blank = 0.0. PS: permanent single-point constraints
/// (components), blank = none. SEID: superelement id, blank = 0.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "formats/card.hpp"
#include "formats/field_reader.hpp"

namespace ssid::formats {

struct Grid {
  std::int64_t id = 0;
  std::int64_t cp = 0;
  std::array<double, 3> x{0.0, 0.0, 0.0};
  std::int64_t cd = 0;
  std::string ps;
  std::int64_t seid = 0;
  /// Whether CP/CD were blank (GRDSET defaults apply to blank fields only).
  bool cp_blank = true, cd_blank = true, ps_blank = true, seid_blank = true;
  std::size_t card = 0;  ///< index in Deck::cards
};

Grid parse_grid(const FieldReader& r);
std::vector<FieldValue> write_grid(const Grid& g);

}  // namespace ssid::formats
