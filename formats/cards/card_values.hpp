#pragma once
/// \file card_values.hpp
/// Helpers for the card writers: leave a field blank when it holds its default.
#include <string>

#include "formats/card.hpp"

namespace ssid::formats {

/// Blank when `v == dflt` and the field was blank when read (or the writer prefers blank).
inline FieldValue blank_if(std::int64_t v, std::int64_t dflt, bool prefer_blank) {
  if (prefer_blank && v == dflt) return std::monostate{};
  return v;
}
inline FieldValue blank_if(double v, double dflt, bool prefer_blank) {
  if (prefer_blank && v == dflt) return std::monostate{};
  return v;
}
inline FieldValue text_or_blank(const std::string& s) {
  if (s.empty()) return std::monostate{};
  return s;
}

}  // namespace ssid::formats
