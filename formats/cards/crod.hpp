#pragma once
/// \file crod.hpp
/// CROD — rod element connection.
///
/// | 1    | 2   | 3   | 4  | 5  |
/// |------|-----|-----|----|----|
/// | CROD | EID | PID | G1 | G2 |
///
/// EID > 0. PID: PROD id, blank = EID. G1 != G2.
#include <cstdint>
#include <vector>

#include "formats/card.hpp"
#include "formats/field_reader.hpp"

namespace ssid::formats {

struct Crod {
  std::int64_t eid = 0;
  std::int64_t pid = 0;
  std::int64_t g1 = 0, g2 = 0;
  bool pid_blank = false;
  std::size_t card = 0;
};

Crod parse_crod(const FieldReader& r);
std::vector<FieldValue> write_crod(const Crod& c);

}  // namespace ssid::formats
