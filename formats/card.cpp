#include "formats/card.hpp"

namespace ssid::formats {

std::uint32_t Card::line_of(std::size_t i) const {
  std::uint32_t l = line;
  for (std::uint32_t r = 0; r < m_nrows; ++r) {
    if (m_rows[r].second > i) break;
    l = m_rows[r].first;
  }
  return l;
}

}  // namespace ssid::formats
