#pragma once
/// \file eigen.hpp
/// Real eigenvalue extraction requests: EIGRL (Lanczos) and EIGR.
///
/// | 1     | 2   | 3  | 4  | 5  | 6      | 7      | 8      | 9    |
/// |-------|-----|----|----|----|--------|--------|--------|------|
/// | EIGRL | SID | V1 | V2 | ND | MSGLVL | MAXSET | SHFSCL | NORM |
///
/// SID > 0. V1, V2: frequency range (cycles per unit time), blank = open;
/// V1 < V2. ND: number of roots wanted, blank = all in the range. MSGLVL:
/// blank = 0. MAXSET: block size, blank = 7. SHFSCL: estimate of the first
/// flexible mode, blank = none. NORM: MASS (unit generalized mass, the
/// default) or MAX (largest component 1).
///
/// | 1    | 2    | 3      | 4  | 5  | 6  | 7  | 8 | 9 |
/// |------|------|--------|----|----|----|----|---|---|
/// | EIGR | SID  | METHOD | F1 | F2 | NE | ND |   |   |
/// |      | NORM | G      | C  |    |    |    |   |   |
///
/// METHOD: LAN (blank), AHOU, HOU, MHOU, INV, SINV, GIV, MGIV, AGIV. F1, F2:
/// frequency range, blank = open. NE: estimate of the number of roots, ND:
/// number wanted, blank = none given. NORM: MASS (blank), MAX or POINT; with
/// POINT, G and C name the grid and component scaled to 1.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "formats/card.hpp"
#include "formats/field_reader.hpp"

namespace ssid::formats {

struct Eigrl {
  std::int64_t sid = 0;
  std::optional<double> v1, v2;
  std::optional<std::int64_t> nd;
  std::int64_t msglvl = 0, maxset = 7;
  std::optional<double> shfscl;
  std::string norm = "MASS";
  std::size_t card = 0;
};

struct Eigr {
  std::int64_t sid = 0;
  std::string method = "LAN";
  std::optional<double> f1, f2;
  std::optional<std::int64_t> ne, nd;
  std::string norm = "MASS";
  std::int64_t g = 0, c = 0;  ///< NORM = POINT
  std::size_t card = 0;
};

Eigrl parse_eigrl(const FieldReader& r);
std::vector<FieldValue> write_eigrl(const Eigrl& e);
Eigr parse_eigr(const FieldReader& r);
std::vector<FieldValue> write_eigr(const Eigr& e);

}  // namespace ssid::formats
