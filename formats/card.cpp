#include "formats/card.hpp"

namespace ssid::formats {

const std::string& Card::field(std::size_t i) const {
  static const std::string empty;
  return i < fields.size() ? fields[i] : empty;
}

std::uint32_t Card::line_of(std::size_t i) const {
  std::uint32_t l = line;
  for (const auto& [row_line, first] : rows) {
    if (first > i) break;
    l = row_line;
  }
  return l;
}

}  // namespace ssid::formats
