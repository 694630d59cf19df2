#include "formats/cards/spc.hpp"

#include "formats/cards/card_values.hpp"

namespace ssid::formats {

Spc parse_spc(const FieldReader& r) {
  Spc s;
  s.sid = r.id(1, "SID");
  const char* names[2][3] = {{"G1", "C1", "D1"}, {"G2", "C2", "D2"}};
  for (int k = 0; k < 2; ++k) {
    std::size_t i = 2 + 3 * k;
    if (k > 0 && r.blank(i) && r.blank(i + 1) && r.blank(i + 2)) break;
    SpcEntry e;
    e.g = r.id(i, names[k][0]);
    e.c = r.components(i + 1, names[k][1], true);
    if (e.c == "0") e.c.clear();
    e.d = r.real_or(i + 2, names[k][2], 0.0);
    s.entries.push_back(e);
  }
  r.at_most(8);
  return s;
}

std::vector<FieldValue> write_spc(const Spc& s) {
  std::vector<FieldValue> v = {std::string("SPC"), s.sid};
  for (const SpcEntry& e : s.entries) {
    v.emplace_back(e.g);
    v.push_back(text_or_blank(e.c));
    v.push_back(or_default(e.d, 0.0));
  }
  trim_blanks(v);
  return v;
}

Spc1 parse_spc1(const FieldReader& r) {
  Spc1 s;
  s.sid = r.id(1, "SID");
  s.c = r.components(2, "C", true);
  if (s.c == "0") s.c.clear();
  if (r.card().field(4) == "THRU") {
    std::int64_t a = r.id(3, "G1"), b = r.id(5, "G2");
    if (b < a) r.fail(5, "G2", "an id >= G1");
    if (b - a > 10000000) r.fail(5, "G2", "a range of at most 10 million grids");
    for (std::int64_t k = a; k <= b; ++k) s.grids.push_back(k);
    s.thru = true;
    r.at_most(6);
    return s;
  }
  for (std::size_t i = 3; i < r.size(); ++i)
    if (!r.blank(i)) s.grids.push_back(r.id(i, "Gi"));
  if (s.grids.empty()) r.fail(3, "G1", "a grid");
  return s;
}

std::vector<FieldValue> write_spc1(const Spc1& s) {
  std::vector<FieldValue> v = {std::string("SPC1"), s.sid, text_or_blank(s.c)};
  bool consecutive = s.grids.size() >= 2;
  for (std::size_t k = 1; k < s.grids.size(); ++k) consecutive = consecutive && s.grids[k] == s.grids[k - 1] + 1;
  if (s.thru && consecutive) {
    v.insert(v.end(), {s.grids.front(), std::string("THRU"), s.grids.back()});
    return v;
  }
  for (std::int64_t g : s.grids) v.emplace_back(g);
  return v;
}

Spcadd parse_spcadd(const FieldReader& r) {
  Spcadd s;
  s.sid = r.id(1, "SID");
  for (std::size_t i = 2; i < r.size(); ++i)
    if (!r.blank(i)) s.sets.push_back(r.id(i, "Si"));
  if (s.sets.empty()) r.fail(2, "S1", "an SPC set id");
  return s;
}

std::vector<FieldValue> write_spcadd(const Spcadd& s) {
  std::vector<FieldValue> v = {std::string("SPCADD"), s.sid};
  for (std::int64_t k : s.sets) v.emplace_back(k);
  return v;
}

Mpc parse_mpc(const FieldReader& r) {
  Mpc m;
  m.sid = r.id(1, "SID");
  // Row k holds fields 1+8k .. 8+8k: (row 0: SID, row > 0: blank), two terms, blank.
  for (std::size_t base = 1; base < r.size(); base += 8) {
    if (base > 1 && !r.blank(base)) r.fail(base, "(blank)", "blank (terms start in field 3)");
    if (!r.blank(base + 7)) r.fail(base + 7, "(blank)", "blank");
    for (std::size_t i : {base + 1, base + 4}) {
      if (r.blank(i) && r.blank(i + 1) && r.blank(i + 2)) continue;
      MpcTerm t;
      t.g = r.id(i, "Gj");
      t.c = r.integer_or(i + 1, "Cj", 0);
      if (t.c < 0 || t.c > 6) r.fail(i + 1, "Cj", "a component 0-6 (0 or blank for a scalar point)");
      t.a = r.real(i + 2, "Aj");
      if (m.terms.empty() && t.a == 0.0) r.fail(i + 2, "A1", "a nonzero coefficient for the dependent DOF");
      m.terms.push_back(t);
    }
  }
  if (m.terms.empty()) r.fail(2, "G1", "a term");
  return m;
}

std::vector<FieldValue> write_mpc(const Mpc& m) {
  std::vector<FieldValue> v = {std::string("MPC"), m.sid};
  for (std::size_t k = 0; k < m.terms.size(); ++k) {
    if (k > 0 && k % 2 == 0) v.emplace_back(), v.emplace_back();  // field 9, then field 2 of the next row
    const MpcTerm& t = m.terms[k];
    v.emplace_back(t.g);
    v.push_back(or_default(t.c, std::int64_t{0}));
    v.emplace_back(t.a);
  }
  return v;
}

}  // namespace ssid::formats
