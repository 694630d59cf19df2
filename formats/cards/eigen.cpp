#include "formats/cards/eigen.hpp"

#include "formats/cards/card_values.hpp"

namespace ssid::formats {

Eigrl parse_eigrl(const FieldReader& r) {
  Eigrl e;
  e.sid = r.id(1, "SID");
  e.v1 = r.real_or_blank(2, "V1");
  e.v2 = r.real_or_blank(3, "V2");
  if (e.v1 && e.v2 && !(*e.v1 < *e.v2)) r.fail(3, "V2", "a frequency above V1");
  e.nd = r.integer_or_blank(4, "ND");
  if (e.nd && *e.nd <= 0) r.fail(4, "ND", "integer > 0");
  e.msglvl = r.integer_or(5, "MSGLVL", 0);
  if (e.msglvl < 0 || e.msglvl > 4) r.fail(5, "MSGLVL", "integer 0-4");
  e.maxset = r.integer_or(6, "MAXSET", 7);
  if (e.maxset <= 0) r.fail(6, "MAXSET", "integer > 0");
  e.shfscl = r.real_or_blank(7, "SHFSCL");
  e.norm = r.choice(8, "NORM", {"MASS", "MAX"}, "MASS");
  r.at_most(9);
  return e;
}

std::vector<FieldValue> write_eigrl(const Eigrl& e) {
  std::vector<FieldValue> v = {std::string("EIGRL"),
                               e.sid,
                               optional_value(e.v1),
                               optional_value(e.v2),
                               optional_value(e.nd),
                               or_default(e.msglvl, std::int64_t{0}),
                               or_default(e.maxset, std::int64_t{7}),
                               optional_value(e.shfscl),
                               or_default(e.norm, "MASS")};
  trim_blanks(v);
  return v;
}

Eigr parse_eigr(const FieldReader& r) {
  Eigr e;
  e.sid = r.id(1, "SID");
  e.method = r.choice(2, "METHOD", {"LAN", "AHOU", "HOU", "MHOU", "INV", "SINV", "GIV", "MGIV", "AGIV"}, "LAN");
  e.f1 = r.real_or_blank(3, "F1");
  e.f2 = r.real_or_blank(4, "F2");
  if (e.f1 && e.f2 && *e.f2 < *e.f1) r.fail(4, "F2", "a frequency >= F1");
  e.ne = r.integer_or_blank(5, "NE");
  e.nd = r.integer_or_blank(6, "ND");
  if (e.nd && *e.nd <= 0) r.fail(6, "ND", "integer > 0");
  if (!r.blank(7)) r.fail(7, "(blank)", "blank");
  if (!r.blank(8)) r.fail(8, "(blank)", "blank");
  e.norm = r.choice(9, "NORM", {"MASS", "MAX", "POINT"}, "MASS");
  if (e.norm == "POINT") {
    e.g = r.id(10, "G");
    e.c = r.integer(11, "C");
    if (e.c < 0 || e.c > 6) r.fail(11, "C", "a component 0-6");
  } else {
    if (!r.blank(10)) r.fail(10, "G", "blank (NORM is not POINT)");
    if (!r.blank(11)) r.fail(11, "C", "blank (NORM is not POINT)");
  }
  r.at_most(12);
  return e;
}

std::vector<FieldValue> write_eigr(const Eigr& e) {
  std::vector<FieldValue> v = {std::string("EIGR"), e.sid,  or_default(e.method, "LAN"), optional_value(e.f1),
                               optional_value(e.f2), optional_value(e.ne), optional_value(e.nd), FieldValue(),
                               FieldValue(), or_default(e.norm, "MASS")};
  if (e.norm == "POINT") {
    v.emplace_back(e.g);
    v.emplace_back(e.c);
  }
  trim_blanks(v);
  return v;
}

}  // namespace ssid::formats
