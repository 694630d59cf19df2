#include "formats/cards/rod.hpp"

#include "formats/cards/card_values.hpp"

namespace ssid::formats {

Prod parse_prod(const FieldReader& r) {
  Prod p;
  p.pid = r.id(1, "PID");
  p.mid = r.id(2, "MID");
  p.a = r.real(3, "A");
  p.j = r.real_or(4, "J", 0.0);
  p.c = r.real_or(5, "C", 0.0);
  p.nsm = r.real_or(6, "NSM", 0.0);
  r.at_most(7);
  return p;
}

std::vector<FieldValue> write_prod(const Prod& p) {
  std::vector<FieldValue> v = {std::string("PROD"), p.pid, p.mid, p.a,
                               or_default(p.j, 0.0), or_default(p.c, 0.0), or_default(p.nsm, 0.0)};
  trim_blanks(v);
  return v;
}

Conrod parse_conrod(const FieldReader& r) {
  Conrod c;
  c.eid = r.id(1, "EID");
  c.g1 = r.id(2, "G1");
  c.g2 = r.id(3, "G2");
  if (c.g1 == c.g2) r.fail_card("G1 and G2 must differ (both " + std::to_string(c.g1) + ")", 3);
  c.mid = r.id(4, "MID");
  c.a = r.real(5, "A");
  c.j = r.real_or(6, "J", 0.0);
  c.c = r.real_or(7, "C", 0.0);
  c.nsm = r.real_or(8, "NSM", 0.0);
  r.at_most(9);
  return c;
}

std::vector<FieldValue> write_conrod(const Conrod& c) {
  std::vector<FieldValue> v = {std::string("CONROD"), c.eid, c.g1, c.g2, c.mid, c.a,
                               or_default(c.j, 0.0), or_default(c.c, 0.0), or_default(c.nsm, 0.0)};
  trim_blanks(v);
  return v;
}

}  // namespace ssid::formats
