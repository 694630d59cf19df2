#pragma once
/// \file rod.hpp
/// PROD — rod property, and CONROD — rod element with its property on the card.
/// (CROD, the connection, is in crod.hpp.)
///
/// | 1    | 2   | 3   | 4 | 5 | 6 | 7   |
/// |------|-----|-----|---|---|---|-----|
/// | PROD | PID | MID | A | J | C | NSM |
///
/// | 1      | 2   | 3  | 4  | 5   | 6 | 7 | 8 | 9   |
/// |--------|-----|----|----|-----|---|---|---|-----|
/// | CONROD | EID | G1 | G2 | MID | A | J | C | NSM |
///
/// PID, EID, MID > 0; G1 != G2. A (area) required. J (torsional constant),
/// C (stress recovery coefficient), NSM (non-structural mass per length): blank = 0.0.
#include <cstdint>
#include <vector>

#include "formats/card.hpp"
#include "formats/field_reader.hpp"

namespace ssid::formats {

struct Prod {
  std::int64_t pid = 0, mid = 0;
  double a = 0.0, j = 0.0, c = 0.0, nsm = 0.0;
  std::size_t card = 0;
};

struct Conrod {
  std::int64_t eid = 0, g1 = 0, g2 = 0, mid = 0;
  double a = 0.0, j = 0.0, c = 0.0, nsm = 0.0;
  std::size_t card = 0;
};

Prod parse_prod(const FieldReader& r);
std::vector<FieldValue> write_prod(const Prod& p);
Conrod parse_conrod(const FieldReader& r);
std::vector<FieldValue> write_conrod(const Conrod& c);

}  // namespace ssid::formats
