#include "formats/cards/orientation.hpp"

#include "formats/cards/card_values.hpp"

namespace ssid::formats {

bool read_orientation(const FieldReader& r, std::size_t i, std::int64_t& g0, std::array<double, 3>& x) {
  if (r.blank(i) && r.blank(i + 1) && r.blank(i + 2)) return false;
  if (r.is_integer(i)) {
    g0 = r.id(i, "G0");
    x = {0.0, 0.0, 0.0};
    if (!r.blank(i + 1)) r.fail(i + 1, "X2", "blank (field 6 holds G0)");
    if (!r.blank(i + 2)) r.fail(i + 2, "X3", "blank (field 6 holds G0)");
    return true;
  }
  g0 = 0;
  x = {r.real_or(i, "X1", 0.0), r.real_or(i + 1, "X2", 0.0), r.real_or(i + 2, "X3", 0.0)};
  if (x[0] == 0.0 && x[1] == 0.0 && x[2] == 0.0)
    r.fail_card("orientation vector X1-X3 is zero (give X1-X3 or G0)", i);
  return true;
}

void write_orientation(std::vector<FieldValue>& v, std::size_t i, std::int64_t g0, const std::array<double, 3>& x,
                       bool blank) {
  if (blank) {
    put(v, i + 2, std::monostate{});
    return;
  }
  if (g0 > 0) {
    put(v, i, g0);
    put(v, i + 2, std::monostate{});
    return;
  }
  put(v, i, x[0]);
  put(v, i + 1, x[1]);
  put(v, i + 2, x[2]);
}

}  // namespace ssid::formats
