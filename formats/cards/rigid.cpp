#include "formats/cards/rigid.hpp"

#include "formats/cards/card_values.hpp"

namespace ssid::formats {

namespace {
std::size_t ndigits(const std::string& c) { return c == "0" ? 0 : c.size(); }

/// Pads `v` with blanks so the next value starts a continuation row (field 2).
void to_row_start(std::vector<FieldValue>& v) {
  while ((v.size() - 1) % 8 != 0) v.emplace_back();
}
}  // namespace

Rbar parse_rbar(const FieldReader& r) {
  Rbar e;
  e.eid = r.id(1, "EID");
  e.ga = r.id(2, "GA");
  e.gb = r.id(3, "GB");
  if (e.ga == e.gb) r.fail_card("GA and GB must differ (both " + std::to_string(e.ga) + ")", 3);
  e.cna = r.components(4, "CNA", true);
  e.cnb = r.components(5, "CNB", true);
  e.cma = r.components(6, "CMA", true);
  e.cmb = r.components(7, "CMB", true);
  e.alpha = r.real_or(8, "ALPHA", 0.0);
  r.at_most(9);
  if (ndigits(e.cna) + ndigits(e.cnb) != 6)
    r.fail_card("CNA and CNB must list six independent components together (got \"" + e.cna + "\" and \"" + e.cnb +
                    "\")",
                4);
  return e;
}

std::vector<FieldValue> write_rbar(const Rbar& e) {
  std::vector<FieldValue> v = {std::string("RBAR"), e.eid, e.ga, e.gb, text_or_blank(e.cna), text_or_blank(e.cnb),
                               text_or_blank(e.cma), text_or_blank(e.cmb), or_default(e.alpha, 0.0)};
  trim_blanks(v);
  return v;
}

Rbe2 parse_rbe2(const FieldReader& r) {
  Rbe2 e;
  e.eid = r.id(1, "EID");
  e.gn = r.id(2, "GN");
  e.cm = r.components(3, "CM");
  std::size_t last = r.size() - 1;
  if (last >= 4 && r.is_real(last)) {
    e.alpha = r.real(last, "ALPHA");
    --last;
  }
  for (std::size_t i = 4; i <= last && i < r.size(); ++i)
    if (!r.blank(i)) e.gm.push_back(r.id(i, "GMi"));
  if (e.gm.empty()) r.fail(4, "GM1", "a dependent grid");
  for (std::int64_t g : e.gm)
    if (g == e.gn) r.fail_card("GN " + std::to_string(g) + " is also listed as a dependent grid", 4);
  return e;
}

std::vector<FieldValue> write_rbe2(const Rbe2& e) {
  std::vector<FieldValue> v = {std::string("RBE2"), e.eid, e.gn, e.cm};
  for (std::int64_t g : e.gm) v.emplace_back(g);
  if (e.alpha != 0.0) v.emplace_back(e.alpha);
  return v;
}

Rbe3 parse_rbe3(const FieldReader& r) {
  Rbe3 e;
  e.eid = r.id(1, "EID");
  if (!r.blank(2)) r.fail(2, "(blank)", "blank");
  e.refgrid = r.id(3, "REFGRID");
  e.refc = r.components(4, "REFC");
  enum class Mode { Groups, Um, Alpha, Done } mode = Mode::Groups;
  // In a group: 0 = expect weight, 1 = expect components, 2 = grids.
  int state = 0;
  for (std::size_t i = 5; i < r.size(); ++i) {
    if (r.blank(i)) continue;
    std::string_view f = r.card().field(i);
    if (f == "UM") {
      if (mode != Mode::Groups) r.fail(i, "UM", "UM once, before ALPHA");
      mode = Mode::Um;
      continue;
    }
    if (f == "ALPHA") {
      if (mode == Mode::Alpha || e.has_alpha) r.fail(i, "ALPHA", "ALPHA once");
      mode = Mode::Alpha;
      continue;
    }
    if (mode == Mode::Groups) {
      if (state != 1 && r.is_real(i)) {
        if (state == 0 || !e.groups.back().grids.empty()) {
          e.groups.push_back({r.real(i, "WTi"), "", {}});
          state = 1;
          continue;
        }
      }
      if (state == 0) r.fail(i, "WT1", "real (a weight)");
      if (state == 1) {
        e.groups.back().components = r.components(i, "Ci");
        state = 2;
        continue;
      }
      e.groups.back().grids.push_back(r.id(i, "Gi,j"));
    } else if (mode == Mode::Um) {
      std::int64_t g = r.id(i, "GMi");
      std::size_t j = i + 1;
      while (j < r.size() && r.blank(j)) ++j;
      e.um.emplace_back(g, r.components(j, "CMi"));
      i = j;
    } else if (mode == Mode::Alpha) {
      e.alpha = r.real(i, "ALPHA");
      e.has_alpha = true;
      mode = Mode::Done;
    } else {
      r.fail(i, "(blank)", "nothing after ALPHA");
    }
  }
  if (e.groups.empty()) r.fail(5, "WT1", "at least one weight, component and grid group");
  if (e.groups.back().grids.empty()) r.fail_card("the last weight group has no grids", r.size() - 1);
  if (mode == Mode::Alpha) r.fail(r.size(), "ALPHA", "real after \"ALPHA\"");
  return e;
}

std::vector<FieldValue> write_rbe3(const Rbe3& e) {
  std::vector<FieldValue> v = {std::string("RBE3"), e.eid, FieldValue(), e.refgrid, e.refc};
  for (const Rbe3Group& g : e.groups) {
    v.emplace_back(g.weight);
    v.emplace_back(g.components);
    for (std::int64_t id : g.grids) v.emplace_back(id);
  }
  if (!e.um.empty()) {
    to_row_start(v);
    v.emplace_back(std::string("UM"));
    for (const auto& [g, c] : e.um) {
      // Pairs do not straddle a row: field 2 of a continuation stays blank.
      if ((v.size() - 1) % 8 == 0) v.emplace_back();
      if ((v.size() - 1) % 8 == 7) v.emplace_back(), v.emplace_back();
      v.emplace_back(g);
      v.emplace_back(c);
    }
  }
  if (e.has_alpha || e.alpha != 0.0) {
    to_row_start(v);
    v.emplace_back(std::string("ALPHA"));
    v.emplace_back(e.alpha);
  }
  return v;
}

}  // namespace ssid::formats
