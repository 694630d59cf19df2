#include "formats/cards/scalar.hpp"

#include "formats/cards/card_values.hpp"

namespace ssid::formats {

namespace {

/// A single component: 1-6 for a grid, 0 (or blank) for a scalar point.
std::int64_t component(const FieldReader& r, std::size_t i, const char* name) {
  std::int64_t c = r.integer_or(i, name, 0);
  if (c < 0 || c > 6) r.fail(i, name, "a component 0-6 (0 or blank for a scalar point)");
  return c;
}

/// G1 C1 G2 C2 at fields i..i+3; a blank grid is 0 (grounded).
template <typename T>
void read_ends(const FieldReader& r, std::size_t i, T& e) {
  e.g1 = r.integer_or(i, "G1", 0);
  if (e.g1 < 0) r.fail(i, "G1", "integer >= 0 (0 or blank: grounded)");
  e.c1 = component(r, i + 1, "C1");
  e.g2 = r.integer_or(i + 2, "G2", 0);
  if (e.g2 < 0) r.fail(i + 2, "G2", "integer >= 0 (0 or blank: grounded)");
  e.c2 = component(r, i + 3, "C2");
  if (e.g1 == 0 && e.g2 == 0) r.fail(i, "G1", "a grid or scalar point (G1 and G2 both blank)");
  if (e.g1 == e.g2 && e.c1 == e.c2) r.fail_card("G1/C1 and G2/C2 are the same degree of freedom", i + 2);
}

/// S1 S2 at fields i, i+1 of the scalar-point forms: components 0; blank = 0 (grounded).
template <typename T>
void read_scalar_points(const FieldReader& r, std::size_t i, T& e) {
  e.g1 = r.integer_or(i, "S1", 0);
  if (e.g1 < 0) r.fail(i, "S1", "integer >= 0 (0 or blank: grounded)");
  e.g2 = r.integer_or(i + 1, "S2", 0);
  if (e.g2 < 0) r.fail(i + 1, "S2", "integer >= 0 (0 or blank: grounded)");
  if (e.g1 == 0 && e.g2 == 0) r.fail(i, "S1", "a scalar point (S1 and S2 both blank)");
  if (e.g1 == e.g2) r.fail_card("S1 and S2 are the same scalar point", i + 1);
  e.c1 = e.c2 = 0;
  e.scalar_form = true;
}

template <typename T>
void write_ends(std::vector<FieldValue>& v, const T& e) {
  if (e.scalar_form) {
    v.push_back(or_default(e.g1, std::int64_t{0}));
    v.push_back(or_default(e.g2, std::int64_t{0}));
    return;
  }
  v.push_back(or_default(e.g1, std::int64_t{0}));
  v.push_back(or_default(e.c1, std::int64_t{0}));
  v.push_back(or_default(e.g2, std::int64_t{0}));
  v.push_back(or_default(e.c2, std::int64_t{0}));
}

template <typename T>
T parse_scalar1(const FieldReader& r, bool scalar_form) {
  T c;
  c.eid = r.id(1, "EID");
  c.pid_blank = r.blank(2);
  c.pid = r.id_or(2, "PID", c.eid);
  if (scalar_form) {
    read_scalar_points(r, 3, c);
    r.at_most(5);
  } else {
    read_ends(r, 3, c);
    r.at_most(7);
  }
  return c;
}

template <typename T>
std::vector<FieldValue> write_scalar1(const char* name, const T& c) {
  std::vector<FieldValue> v = {std::string(name), c.eid, blank_if(c.pid, c.eid, c.pid_blank)};
  write_ends(v, c);
  trim_blanks(v);
  return v;
}

}  // namespace

Conm2 parse_conm2(const FieldReader& r) {
  Conm2 c;
  c.eid = r.id(1, "EID");
  c.g = r.id(2, "G");
  c.cid = r.integer_or(3, "CID", 0);
  if (c.cid < -1) r.fail(3, "CID", "integer >= -1");
  c.m = r.real_or(4, "M", 0.0);
  c.x = {r.real_or(5, "X1", 0.0), r.real_or(6, "X2", 0.0), r.real_or(7, "X3", 0.0)};
  if (!r.blank(8)) r.fail(8, "(blank)", "blank");
  c.i11 = r.real_or(9, "I11", 0.0);
  c.i21 = r.real_or(10, "I21", 0.0);
  c.i22 = r.real_or(11, "I22", 0.0);
  c.i31 = r.real_or(12, "I31", 0.0);
  c.i32 = r.real_or(13, "I32", 0.0);
  c.i33 = r.real_or(14, "I33", 0.0);
  r.at_most(15);
  return c;
}

std::vector<FieldValue> write_conm2(const Conm2& c) {
  auto z = [](double x) { return or_default(x, 0.0); };
  std::vector<FieldValue> v = {std::string("CONM2"), c.eid, c.g, or_default(c.cid, std::int64_t{0}), z(c.m),
                               z(c.x[0]), z(c.x[1]), z(c.x[2]), FieldValue(), z(c.i11), z(c.i21), z(c.i22),
                               z(c.i31), z(c.i32), z(c.i33)};
  trim_blanks(v);
  return v;
}

Cmass1 parse_cmass1(const FieldReader& r) { return parse_scalar1<Cmass1>(r, false); }
Cmass1 parse_cmass3(const FieldReader& r) { return parse_scalar1<Cmass1>(r, true); }
std::vector<FieldValue> write_cmass1(const Cmass1& c) { return write_scalar1(c.scalar_form ? "CMASS3" : "CMASS1", c); }
Celas1 parse_celas1(const FieldReader& r) { return parse_scalar1<Celas1>(r, false); }
Celas1 parse_celas3(const FieldReader& r) { return parse_scalar1<Celas1>(r, true); }
std::vector<FieldValue> write_celas1(const Celas1& c) { return write_scalar1(c.scalar_form ? "CELAS3" : "CELAS1", c); }

Cmass2 parse_cmass2(const FieldReader& r) {
  Cmass2 c;
  c.eid = r.id(1, "EID");
  c.m = r.real_or(2, "M", 0.0);
  read_ends(r, 3, c);
  r.at_most(7);
  return c;
}

Cmass2 parse_cmass4(const FieldReader& r) {
  Cmass2 c;
  c.eid = r.id(1, "EID");
  c.m = r.real_or(2, "M", 0.0);
  read_scalar_points(r, 3, c);
  r.at_most(5);
  return c;
}

Celas2 parse_celas4(const FieldReader& r) {
  Celas2 c;
  c.eid = r.id(1, "EID");
  c.k = r.real_or(2, "K", 0.0);
  read_scalar_points(r, 3, c);
  r.at_most(5);
  return c;
}

std::vector<FieldValue> write_cmass2(const Cmass2& c) {
  std::vector<FieldValue> v = {std::string(c.scalar_form ? "CMASS4" : "CMASS2"), c.eid, or_default(c.m, 0.0)};
  write_ends(v, c);
  trim_blanks(v);
  return v;
}

Celas2 parse_celas2(const FieldReader& r) {
  Celas2 c;
  c.eid = r.id(1, "EID");
  c.k = r.real_or(2, "K", 0.0);
  read_ends(r, 3, c);
  c.ge = r.real_or(7, "GE", 0.0);
  c.s = r.real_or(8, "S", 0.0);
  r.at_most(9);
  return c;
}

std::vector<FieldValue> write_celas2(const Celas2& c) {
  std::vector<FieldValue> v = {std::string(c.scalar_form ? "CELAS4" : "CELAS2"), c.eid, or_default(c.k, 0.0)};
  write_ends(v, c);
  if (!c.scalar_form) {
    v.push_back(or_default(c.ge, 0.0));
    v.push_back(or_default(c.s, 0.0));
  }
  trim_blanks(v);
  return v;
}

std::vector<Pelas> parse_pelas(const FieldReader& r) {
  std::vector<Pelas> out;
  const char* names[2][4] = {{"PID1", "K1", "GE1", "S1"}, {"PID2", "K2", "GE2", "S2"}};
  for (int k = 0; k < 2; ++k) {
    std::size_t i = 1 + 4 * k;
    if (k > 0 && r.blank(i) && r.blank(i + 1) && r.blank(i + 2) && r.blank(i + 3)) break;
    Pelas p;
    p.pid = r.id(i, names[k][0]);
    p.k = r.real(i + 1, names[k][1]);
    p.ge = r.real_or(i + 2, names[k][2], 0.0);
    p.s = r.real_or(i + 3, names[k][3], 0.0);
    out.push_back(p);
  }
  r.at_most(9);
  return out;
}

std::vector<FieldValue> write_pelas(const Pelas& p) {
  return {std::string("PELAS"), p.pid, p.k, or_default(p.ge, 0.0), or_default(p.s, 0.0)};
}

std::vector<Pmass> parse_pmass(const FieldReader& r) {
  std::vector<Pmass> out;
  const char* pid_names[] = {"PID1", "PID2", "PID3", "PID4"};
  const char* m_names[] = {"M1", "M2", "M3", "M4"};
  for (int k = 0; k < 4; ++k) {
    std::size_t i = 1 + 2 * k;
    if (k > 0 && r.blank(i) && r.blank(i + 1)) continue;
    Pmass p;
    p.pid = r.id(i, pid_names[k]);
    p.m = r.real(i + 1, m_names[k]);
    out.push_back(p);
  }
  r.at_most(9);
  return out;
}

std::vector<FieldValue> write_pmass(const Pmass& p) { return {std::string("PMASS"), p.pid, p.m}; }

Spoint parse_spoint(const FieldReader& r) {
  Spoint s;
  if (r.card().field(2) == "THRU") {
    std::int64_t a = r.id(1, "ID1"), b = r.id(3, "ID2");
    if (b < a) r.fail(3, "ID2", "an id >= ID1");
    if (b - a > 10000000) r.fail(3, "ID2", "a range of at most 10 million points");
    for (std::int64_t k = a; k <= b; ++k) s.ids.push_back(k);
    s.thru = true;
    r.at_most(4);
    return s;
  }
  for (std::size_t i = 1; i < r.size(); ++i)
    if (!r.blank(i)) s.ids.push_back(r.id(i, "ID"));
  if (s.ids.empty()) r.fail(1, "ID1", "a scalar point id");
  return s;
}

std::vector<FieldValue> write_spoint(const Spoint& s) {
  std::vector<FieldValue> v = {std::string("SPOINT")};
  if (s.thru && !s.ids.empty()) {
    v.insert(v.end(), {s.ids.front(), std::string("THRU"), s.ids.back()});
    return v;
  }
  for (std::int64_t id : s.ids) v.emplace_back(id);
  return v;
}

}  // namespace ssid::formats
