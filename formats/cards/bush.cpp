#include "formats/cards/bush.hpp"

#include "formats/cards/card_values.hpp"
#include "formats/cards/orientation.hpp"

namespace ssid::formats {

Cbush parse_cbush(const FieldReader& r) {
  Cbush c;
  c.eid = r.id(1, "EID");
  c.pid_blank = r.blank(2);
  c.pid = r.id_or(2, "PID", c.eid);
  c.ga = r.id(3, "GA");
  c.gb = r.id_or(4, "GB", 0);
  c.orientation_blank = !read_orientation(r, 5, c.g0, c.x);
  if (c.g0 != 0 && (c.g0 == c.ga || c.g0 == c.gb)) r.fail(5, "G0", "a grid other than GA and GB");
  c.cid = r.integer_or(8, "CID", -1);
  if (!r.blank(8) && c.cid < 0) r.fail(8, "CID", "integer >= 0");
  c.s = r.real_or(9, "S", 0.5);
  if (c.s < 0.0 || c.s > 1.0) r.fail(9, "S", "real in [0.0, 1.0]");
  c.ocid = r.integer_or(10, "OCID", -1);
  if (c.ocid < -1) r.fail(10, "OCID", "integer >= -1");
  c.si = {r.real_or(11, "S1", 0.0), r.real_or(12, "S2", 0.0), r.real_or(13, "S3", 0.0)};
  r.at_most(14);
  return c;
}

std::vector<FieldValue> write_cbush(const Cbush& c) {
  std::vector<FieldValue> v = {std::string("CBUSH"), c.eid, blank_if(c.pid, c.eid, c.pid_blank), c.ga,
                               or_default(c.gb, std::int64_t{0})};
  write_orientation(v, 5, c.g0, c.x, c.orientation_blank);
  put(v, 8, or_default(c.cid, std::int64_t{-1}));
  put(v, 9, or_default(c.s, 0.5));
  put(v, 10, or_default(c.ocid, std::int64_t{-1}));
  for (int k = 0; k < 3; ++k) put(v, 11 + k, or_default(c.si[k], 0.0));
  trim_blanks(v);
  return v;
}

Pbush parse_pbush(const FieldReader& r) {
  Pbush p;
  p.pid = r.id(1, "PID");
  // Row r covers fields 1+8r .. 8+8r: field 1+8r is PID (row 0) or blank, the flag follows.
  for (std::size_t base = 1; base < r.size() || base == 1; base += 8) {
    if (base > 1 && !r.blank(base)) r.fail(base, "(blank)", "blank (the flag goes in field 3)");
    bool empty_row = base > 1;
    for (std::size_t i = base + 1; i < base + 8; ++i) empty_row = empty_row && r.blank(i);
    if (empty_row) continue;
    std::string flag = r.choice(base + 1, "flag", {"K", "B", "GE", "RCV"}, nullptr);
    auto row6 = [&](std::array<double, 6>& a, bool& has, const char* n) {
      if (has) r.fail(base + 1, "flag", std::string("each flag once (") + n + " repeated)");
      has = true;
      for (int k = 0; k < 6; ++k) {
        std::string name = n + std::to_string(k + 1);
        a[k] = r.real_or(base + 2 + k, name.c_str(), 0.0);
      }
    };
    if (flag == "K") row6(p.k, p.has_k, "K");
    if (flag == "B") row6(p.b, p.has_b, "B");
    if (flag == "GE") row6(p.ge, p.has_ge, "GE");
    if (flag == "RCV") {
      if (p.has_rcv) r.fail(base + 1, "flag", "each flag once (RCV repeated)");
      p.has_rcv = true;
      p.sa = r.real_or(base + 2, "SA", 1.0);
      p.st = r.real_or(base + 3, "ST", 1.0);
      p.ea = r.real_or(base + 4, "EA", 1.0);
      p.et = r.real_or(base + 5, "ET", 1.0);
      for (std::size_t i = base + 6; i < base + 8; ++i)
        if (!r.blank(i)) r.fail(i, "(blank)", "blank");
    }
  }
  return p;
}

std::vector<FieldValue> write_pbush(const Pbush& p) {
  std::vector<FieldValue> v = {std::string("PBUSH"), p.pid};
  auto row = [&](const char* flag, std::initializer_list<FieldValue> values) {
    if (v.size() > 2) v.emplace_back();  // field 2 of a continuation is blank
    v.emplace_back(std::string(flag));
    for (const auto& x : values) v.push_back(x);
    while ((v.size() - 1) % 8 != 0) v.emplace_back();
  };
  auto z = [](double x) { return or_default(x, 0.0); };
  auto six = [&](const char* flag, const std::array<double, 6>& a) {
    row(flag, {z(a[0]), z(a[1]), z(a[2]), z(a[3]), z(a[4]), z(a[5])});
  };
  auto any = [](const std::array<double, 6>& a) {
    for (double x : a)
      if (x != 0.0) return true;
    return false;
  };
  if (p.has_k || any(p.k)) six("K", p.k);
  if (p.has_b || any(p.b)) six("B", p.b);
  if (p.has_ge || any(p.ge)) six("GE", p.ge);
  if (p.has_rcv || p.sa != 1.0 || p.st != 1.0 || p.ea != 1.0 || p.et != 1.0)
    row("RCV", {or_default(p.sa, 1.0), or_default(p.st, 1.0), or_default(p.ea, 1.0), or_default(p.et, 1.0)});
  trim_blanks(v);
  return v;
}

}  // namespace ssid::formats
