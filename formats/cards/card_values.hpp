#pragma once
/// \file card_values.hpp
/// Helpers for the card writers: leave a field blank when it holds its default.
#include <optional>
#include <string>
#include <vector>

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
/// Blank when the value is its documented default (a blank field reads back as it).
inline FieldValue or_default(double v, double dflt) { return blank_if(v, dflt, true); }
inline FieldValue or_default(std::int64_t v, std::int64_t dflt) { return blank_if(v, dflt, true); }
inline FieldValue or_default(const std::string& v, const std::string& dflt) {
  if (v == dflt) return std::monostate{};
  return v;
}
inline FieldValue optional_value(const std::optional<double>& v) {
  if (!v) return std::monostate{};
  return *v;
}
inline FieldValue optional_value(const std::optional<std::int64_t>& v) {
  if (!v) return std::monostate{};
  return *v;
}

/// Sets values[i], growing the list with blanks as needed.
inline void put(std::vector<FieldValue>& values, std::size_t i, FieldValue v) {
  if (values.size() <= i) values.resize(i + 1);
  values[i] = std::move(v);
}

/// Drops trailing blank values (a card ends at its last non-blank field).
inline void trim_blanks(std::vector<FieldValue>& values) {
  while (values.size() > 1 && std::holds_alternative<std::monostate>(values.back())) values.pop_back();
}

}  // namespace ssid::formats
