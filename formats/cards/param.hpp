#pragma once
/// \file param.hpp
/// PARAM — a named parameter (WTMASS, AUTOSPC, GRDPNT, COUPMASS, ...).
///
/// | 1     | 2 | 3  | 4  |
/// |-------|---|----|----|
/// | PARAM | N | V1 | V2 |
///
/// N: the name. V1 (and V2 for complex values): integer, real or text, typed
/// as written. What a parameter means, and its default when absent, is for the
/// code that uses it (e.g. WTMASS 1.0, AUTOSPC YES in SOL 103).
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "formats/card.hpp"
#include "formats/field_reader.hpp"

namespace ssid::formats {

struct Param {
  std::string name;
  std::vector<FieldValue> values;  ///< V1 (, V2): integer, real, text or blank
  std::size_t card = 0;

  /// V1 as an integer; nullopt when it is not one.
  std::optional<std::int64_t> integer() const;
  /// V1 as a real (an integer is accepted, as NASTRAN does); nullopt otherwise.
  std::optional<double> real() const;
  /// V1 as text (YES, NO, ...); nullopt when it is a number or blank.
  std::optional<std::string> text() const;
};

Param parse_param(const FieldReader& r);
std::vector<FieldValue> write_param(const Param& p);

}  // namespace ssid::formats
