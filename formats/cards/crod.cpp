#include "formats/cards/crod.hpp"

#include "formats/cards/card_values.hpp"

namespace ssid::formats {

Crod parse_crod(const FieldReader& r) {
  Crod c;
  c.eid = r.id(1, "EID");
  c.pid_blank = r.blank(2);
  c.pid = r.id_or(2, "PID", c.eid);
  c.g1 = r.id(3, "G1");
  c.g2 = r.id(4, "G2");
  if (c.g1 == c.g2) r.fail_card("G1 and G2 must differ (both " + std::to_string(c.g1) + ")", 4);
  if (r.size() > 5) r.fail_card("too many fields (CROD has 4 data fields)", 5);
  return c;
}

std::vector<FieldValue> write_crod(const Crod& c) {
  return {std::string("CROD"), c.eid, blank_if(c.pid, c.eid, c.pid_blank), c.g1, c.g2};
}

}  // namespace ssid::formats
