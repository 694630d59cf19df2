#include "formats/cards/bar.hpp"

#include "formats/cards/card_values.hpp"
#include "formats/cards/orientation.hpp"

namespace ssid::formats {

const std::initializer_list<const char*> k_offt_words = {"GGG", "BGG", "GGO", "BGO", "GOG", "BOG", "GOO", "BOO"};

Cbar parse_cbar(const FieldReader& r) {
  Cbar c;
  c.eid = r.id(1, "EID");
  c.pid_blank = r.blank(2);
  c.pid = r.id_or(2, "PID", c.eid);
  c.ga = r.id(3, "GA");
  c.gb = r.id(4, "GB");
  if (c.ga == c.gb) r.fail_card("GA and GB must differ (both " + std::to_string(c.ga) + ")", 4);
  c.orientation_blank = !read_orientation(r, 5, c.g0, c.x);
  if (c.g0 == c.ga || c.g0 == c.gb) r.fail(5, "G0", "a grid other than GA and GB");
  c.offt_blank = r.blank(8);
  if (!c.offt_blank && r.is_integer(8)) {
    // The older form of field 9 (COSMIC NASTRAN): a flag saying which form
    // fields 6-8 take, 1 = X1-X3, 2 = G0. MSC Nastran still runs such decks; the
    // offsets are then in the displacement systems, as OFFT GGG.
    c.legacy_flag = r.integer(8, "F");
    if (c.legacy_flag != 1 && c.legacy_flag != 2) r.fail(8, "OFFT", "one of GGG, BGG, GGO, BGO, GOG, BOG, GOO, BOO, "
                                                               "or the older flag 1 (X1-X3) or 2 (G0)");
    if (!c.orientation_blank && (c.legacy_flag == 2) != (c.g0 > 0))
      r.fail(8, "F", c.legacy_flag == 2 ? "1 (fields 6-8 hold X1-X3, not G0)" : "2 (field 6 holds G0, not X1)");
    c.offt = "GGG";
  } else {
    c.offt = r.choice(8, "OFFT", k_offt_words, "GGG");
  }
  c.pa = r.components(9, "PA", true);
  c.pb = r.components(10, "PB", true);
  const char* w[] = {"W1A", "W2A", "W3A", "W1B", "W2B", "W3B"};
  for (int k = 0; k < 3; ++k) c.wa[k] = r.real_or(11 + k, w[k], 0.0);
  for (int k = 0; k < 3; ++k) c.wb[k] = r.real_or(14 + k, w[3 + k], 0.0);
  r.at_most(17);
  return c;
}

std::vector<FieldValue> write_cbar(const Cbar& c) {
  std::vector<FieldValue> v = {std::string("CBAR"), c.eid, c.pid_blank ? FieldValue() : FieldValue(c.pid), c.ga, c.gb};
  write_orientation(v, 5, c.g0, c.x, c.orientation_blank);
  put(v, 8, c.offt_blank ? FieldValue() : c.legacy_flag ? FieldValue(c.legacy_flag) : FieldValue(c.offt));
  put(v, 9, text_or_blank(c.pa));
  put(v, 10, text_or_blank(c.pb));
  for (int k = 0; k < 3; ++k) put(v, 11 + k, or_default(c.wa[k], 0.0));
  for (int k = 0; k < 3; ++k) put(v, 14 + k, or_default(c.wb[k], 0.0));
  trim_blanks(v);
  return v;
}

bool apply_baror(Cbar& c, const Baror* b) {
  if (c.pid_blank) c.pid = b && b->pid ? *b->pid : c.eid;
  if (c.offt_blank) c.offt = b && !b->offt.empty() ? b->offt : "GGG";
  if (c.orientation_blank) {
    if (!b || !b->has_orientation) return false;
    c.g0 = b->g0;
    c.x = b->x;
  }
  return true;
}

Baror parse_baror(const FieldReader& r) {
  Baror b;
  if (!r.blank(1)) r.fail(1, "(blank)", "blank");
  if (!r.blank(2)) b.pid = r.id(2, "PID");
  if (!r.blank(3)) r.fail(3, "(blank)", "blank");
  if (!r.blank(4)) r.fail(4, "(blank)", "blank");
  b.has_orientation = read_orientation(r, 5, b.g0, b.x);
  if (!r.blank(8) && r.is_integer(8)) {
    // The older flag F of CBAR field 9 (1: X1-X3, 2: G0), which MSC Nastran still runs.
    b.legacy_flag = r.integer(8, "F");
    if (b.legacy_flag != 1 && b.legacy_flag != 2)
      r.fail(8, "OFFT", "one of GGG, BGG, GGO, BGO, GOG, BOG, GOO, BOO, or the older flag 1 (X1-X3) or 2 (G0)");
    if (b.has_orientation && (b.legacy_flag == 2) != (b.g0 > 0))
      r.fail(8, "F", b.legacy_flag == 2 ? "1 (fields 6-8 hold X1-X3, not G0)" : "2 (field 6 holds G0, not X1)");
  } else if (!r.blank(8)) {
    b.offt = r.choice(8, "OFFT", k_offt_words, nullptr);
  }
  r.at_most(9);
  return b;
}

std::vector<FieldValue> write_baror(const Baror& b) {
  std::vector<FieldValue> v = {std::string("BAROR"), FieldValue(), optional_value(b.pid), FieldValue(), FieldValue()};
  write_orientation(v, 5, b.g0, b.x, !b.has_orientation);
  put(v, 8, b.legacy_flag ? FieldValue(b.legacy_flag) : text_or_blank(b.offt));
  trim_blanks(v);
  return v;
}

Pbar parse_pbar(const FieldReader& r) {
  Pbar p;
  p.pid = r.id(1, "PID");
  p.mid = r.id(2, "MID");
  p.a = r.real_or(3, "A", 0.0);
  p.i1 = r.real_or(4, "I1", 0.0);
  p.i2 = r.real_or(5, "I2", 0.0);
  if (p.i1 < 0.0) r.fail(4, "I1", "real >= 0.0");
  if (p.i2 < 0.0) r.fail(5, "I2", "real >= 0.0");
  p.j = r.real_or(6, "J", 0.0);
  p.nsm = r.real_or(7, "NSM", 0.0);
  if (!r.blank(8)) r.fail(8, "(blank)", "blank");
  double* cdef[] = {&p.c1, &p.c2, &p.d1, &p.d2, &p.e1, &p.e2, &p.f1, &p.f2};
  const char* names[] = {"C1", "C2", "D1", "D2", "E1", "E2", "F1", "F2"};
  for (int k = 0; k < 8; ++k) *cdef[k] = r.real_or(9 + k, names[k], 0.0);
  p.k1 = r.real_or(17, "K1", 0.0);
  p.k2 = r.real_or(18, "K2", 0.0);
  p.i12 = r.real_or(19, "I12", 0.0);
  if (p.i1 * p.i2 < p.i12 * p.i12) r.fail(19, "I12", "I1*I2 >= I12^2");
  r.at_most(20);
  return p;
}

std::vector<FieldValue> write_pbar(const Pbar& p) {
  std::vector<FieldValue> v = {std::string("PBAR"), p.pid, p.mid, or_default(p.a, 0.0), or_default(p.i1, 0.0),
                               or_default(p.i2, 0.0), or_default(p.j, 0.0), or_default(p.nsm, 0.0), FieldValue()};
  const double cdef[] = {p.c1, p.c2, p.d1, p.d2, p.e1, p.e2, p.f1, p.f2};
  for (int k = 0; k < 8; ++k) put(v, 9 + k, or_default(cdef[k], 0.0));
  put(v, 17, or_default(p.k1, 0.0));
  put(v, 18, or_default(p.k2, 0.0));
  put(v, 19, or_default(p.i12, 0.0));
  trim_blanks(v);
  return v;
}

}  // namespace ssid::formats
