#include "formats/cards/design.hpp"

#include "formats/cards/card_values.hpp"

namespace ssid::formats {

namespace {

/// DVIDi COEFi pairs from field 9 (continuation 1) on; blank pairs are skipped.
std::vector<std::pair<std::int64_t, double>> read_terms(const FieldReader& r) {
  std::vector<std::pair<std::int64_t, double>> terms;
  for (std::size_t i = 9; i < r.size(); i += 2) {
    if (r.blank(i) && r.blank(i + 1)) continue;
    terms.emplace_back(r.id(i, "DVIDi"), r.real(i + 1, "COEFi"));
  }
  if (terms.empty()) r.fail(9, "DVID1", "at least one DVID/COEF pair on the continuation");
  return terms;
}

void write_terms(std::vector<FieldValue>& v, const std::vector<std::pair<std::int64_t, double>>& terms) {
  put(v, 8, FieldValue());
  for (const auto& [id, coef] : terms) {
    v.emplace_back(id);
    v.emplace_back(coef);
  }
}

}  // namespace

Desvar parse_desvar(const FieldReader& r) {
  Desvar d;
  d.id = r.id(1, "ID");
  d.label = r.text(2, "LABEL");
  d.xinit = r.real(3, "XINIT");
  d.xlb = r.real_or(4, "XLB", -1.0e20);
  d.xub = r.real_or(5, "XUB", 1.0e20);
  if (d.xlb > d.xub) r.fail(5, "XUB", "a bound >= XLB");
  if (d.xinit < d.xlb || d.xinit > d.xub) r.fail(3, "XINIT", "a value within [XLB, XUB]");
  d.delxv = r.real_or_blank(6, "DELXV");
  if (d.delxv && *d.delxv <= 0.0) r.fail(6, "DELXV", "real > 0.0");
  d.ddval = r.integer_or_blank(7, "DDVAL");
  if (d.ddval && *d.ddval <= 0) r.fail(7, "DDVAL", "positive integer (a DDVAL id)");
  r.at_most(8);
  return d;
}

std::vector<FieldValue> write_desvar(const Desvar& d) {
  std::vector<FieldValue> v = {std::string("DESVAR"), d.id, d.label, d.xinit, or_default(d.xlb, -1.0e20),
                               or_default(d.xub, 1.0e20), optional_value(d.delxv), optional_value(d.ddval)};
  trim_blanks(v);
  return v;
}

Dvprel1 parse_dvprel1(const FieldReader& r) {
  Dvprel1 d;
  d.id = r.id(1, "ID");
  d.type = r.text(2, "TYPE");
  d.pid = r.id(3, "PID");
  if (r.is_integer(4)) {
    d.fid = r.integer(4, "FID");
    if (d.fid == 0) r.fail(4, "FID", "a nonzero field number or a property name");
  } else {
    d.pname = r.text(4, "PNAME");
    if (r.is_real(4)) r.fail(4, "PNAME", "a property name or field number");
  }
  d.pmin = r.real_or_blank(5, "PMIN");
  d.pmax = r.real_or(6, "PMAX", 1.0e20);
  if (d.pmin && *d.pmin > d.pmax) r.fail(6, "PMAX", "a bound >= PMIN");
  d.c0 = r.real_or(7, "C0", 0.0);
  if (!r.blank(8)) r.fail(8, "(blank)", "blank");
  d.terms = read_terms(r);
  return d;
}

std::vector<FieldValue> write_dvprel1(const Dvprel1& d) {
  std::vector<FieldValue> v = {std::string("DVPREL1"), d.id, d.type, d.pid,
                               d.pname.empty() ? FieldValue(d.fid) : FieldValue(d.pname),
                               optional_value(d.pmin), or_default(d.pmax, 1.0e20), or_default(d.c0, 0.0)};
  write_terms(v, d.terms);
  return v;
}

Dvmrel1 parse_dvmrel1(const FieldReader& r) {
  Dvmrel1 d;
  d.id = r.id(1, "ID");
  d.type = r.text(2, "TYPE");
  d.mid = r.id(3, "MID");
  d.mpname = r.text(4, "MPNAME");
  if (r.is_integer(4) || r.is_real(4)) r.fail(4, "MPNAME", "a material property name (E, G, NU, RHO, ...)");
  d.mpmin = r.real_or_blank(5, "MPMIN");
  d.mpmax = r.real_or(6, "MPMAX", 1.0e20);
  if (d.mpmin && *d.mpmin > d.mpmax) r.fail(6, "MPMAX", "a bound >= MPMIN");
  d.c0 = r.real_or(7, "C0", 0.0);
  if (!r.blank(8)) r.fail(8, "(blank)", "blank");
  d.terms = read_terms(r);
  return d;
}

std::vector<FieldValue> write_dvmrel1(const Dvmrel1& d) {
  std::vector<FieldValue> v = {std::string("DVMREL1"), d.id, d.type, d.mid, d.mpname,
                               optional_value(d.mpmin), or_default(d.mpmax, 1.0e20), or_default(d.c0, 0.0)};
  write_terms(v, d.terms);
  return v;
}

}  // namespace ssid::formats
