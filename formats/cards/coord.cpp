#include "formats/cards/coord.hpp"

#include "formats/cards/card_values.hpp"

namespace ssid::formats {

const char* Cord2::name() const {
  switch (kind) {
    case CoordKind::Cylindrical: return "CORD2C";
    case CoordKind::Spherical: return "CORD2S";
    default: return "CORD2R";
  }
}

Cord2 parse_cord2(const FieldReader& r) {
  Cord2 c;
  const std::string& n = r.card().name;
  c.kind = n == "CORD2C" ? CoordKind::Cylindrical : n == "CORD2S" ? CoordKind::Spherical : CoordKind::Rectangular;
  c.cid = r.id(1, "CID");
  c.rid = r.integer_or(2, "RID", 0);
  if (c.rid < 0) r.fail(2, "RID", "integer >= 0");
  const char* names[] = {"A1", "A2", "A3", "B1", "B2", "B3", "C1", "C2", "C3"};
  std::array<double, 3>* pts[] = {&c.a, &c.b, &c.c};
  for (int k = 0; k < 9; ++k) (*pts[k / 3])[k % 3] = r.real_or(3 + k, names[k], 0.0);
  r.at_most(12);
  // The three points must define the axes: A != B, C off the line AB.
  std::array<double, 3> ab{c.b[0] - c.a[0], c.b[1] - c.a[1], c.b[2] - c.a[2]};
  std::array<double, 3> ac{c.c[0] - c.a[0], c.c[1] - c.a[1], c.c[2] - c.a[2]};
  std::array<double, 3> n3{ab[1] * ac[2] - ab[2] * ac[1], ab[2] * ac[0] - ab[0] * ac[2], ab[0] * ac[1] - ab[1] * ac[0]};
  double lab = ab[0] * ab[0] + ab[1] * ab[1] + ab[2] * ab[2];
  double lac = ac[0] * ac[0] + ac[1] * ac[1] + ac[2] * ac[2];
  double ln = n3[0] * n3[0] + n3[1] * n3[1] + n3[2] * n3[2];
  if (lab == 0.0) r.fail_card("points A and B coincide (no z axis)", 6);
  if (ln <= 1e-24 * lab * lac) r.fail_card("point C lies on the line AB (no x-z plane)", 9);
  return c;
}

std::vector<FieldValue> write_cord2(const Cord2& c) {
  std::vector<FieldValue> v = {std::string(c.name()), c.cid, or_default(c.rid, std::int64_t{0})};
  for (const auto* p : {&c.a, &c.b, &c.c})
    for (double x : *p) v.emplace_back(x);
  trim_blanks(v);
  return v;
}

Grdset parse_grdset(const FieldReader& r) {
  Grdset g;
  for (std::size_t i : {1, 3, 4, 5})
    if (!r.blank(i)) r.fail(i, "(blank)", "blank");
  if (!r.blank(2)) g.cp = r.integer(2, "CP");
  if (!r.blank(6)) g.cd = r.integer(6, "CD");
  g.ps = r.components(7, "PS", true);
  if (!r.blank(8)) g.seid = r.integer(8, "SEID");
  r.at_most(9);
  return g;
}

std::vector<FieldValue> write_grdset(const Grdset& g) {
  std::vector<FieldValue> v = {std::string("GRDSET"), FieldValue(), optional_value(g.cp), FieldValue(), FieldValue(),
                               FieldValue(), optional_value(g.cd), text_or_blank(g.ps), optional_value(g.seid)};
  trim_blanks(v);
  return v;
}

void apply_grdset(Grid& g, const Grdset& s) {
  if (g.cp_blank && s.cp) g.cp = *s.cp;
  if (g.cd_blank && s.cd) g.cd = *s.cd;
  if (g.ps_blank && !s.ps.empty()) g.ps = s.ps;
  if (g.seid_blank && s.seid) g.seid = *s.seid;
}

}  // namespace ssid::formats
