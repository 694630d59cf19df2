#include "formats/cards/beam.hpp"

#include "formats/cards/bar.hpp"
#include "formats/cards/card_values.hpp"
#include "formats/cards/orientation.hpp"

namespace ssid::formats {

namespace {

/// Field 9 of CBEAM/BEAMOR: OFFT (text) or BIT (real).
void read_offt_bit(const FieldReader& r, std::string& offt, std::optional<double>& bit) {
  if (r.blank(8)) return;
  if (r.is_real(8) || r.is_integer(8)) {
    bit = r.real(8, "BIT");
    return;
  }
  offt = r.choice(8, "OFFT/BIT", k_offt_words, nullptr);
}

FieldValue offt_bit_value(const std::string& offt, const std::optional<double>& bit) {
  if (bit) return *bit;
  return text_or_blank(offt);
}

}  // namespace

Cbeam parse_cbeam(const FieldReader& r) {
  Cbeam c;
  c.eid = r.id(1, "EID");
  c.pid_blank = r.blank(2);
  c.pid = r.id_or(2, "PID", c.eid);
  c.ga = r.id(3, "GA");
  c.gb = r.id(4, "GB");
  if (c.ga == c.gb) r.fail_card("GA and GB must differ (both " + std::to_string(c.ga) + ")", 4);
  c.orientation_blank = !read_orientation(r, 5, c.g0, c.x);
  if (c.g0 == c.ga || c.g0 == c.gb) r.fail(5, "G0", "a grid other than GA and GB");
  c.offt_blank = r.blank(8);
  read_offt_bit(r, c.offt, c.bit);
  c.pa = r.components(9, "PA", true);
  c.pb = r.components(10, "PB", true);
  const char* w[] = {"W1A", "W2A", "W3A", "W1B", "W2B", "W3B"};
  for (int k = 0; k < 3; ++k) c.wa[k] = r.real_or(11 + k, w[k], 0.0);
  for (int k = 0; k < 3; ++k) c.wb[k] = r.real_or(14 + k, w[3 + k], 0.0);
  c.sa = r.id_or(17, "SA", 0);
  c.sb = r.id_or(18, "SB", 0);
  r.at_most(19);
  return c;
}

std::vector<FieldValue> write_cbeam(const Cbeam& c) {
  std::vector<FieldValue> v = {std::string("CBEAM"), c.eid, c.pid_blank ? FieldValue() : FieldValue(c.pid), c.ga,
                               c.gb};
  write_orientation(v, 5, c.g0, c.x, c.orientation_blank);
  put(v, 8, c.offt_blank ? FieldValue() : offt_bit_value(c.offt, c.bit));
  put(v, 9, text_or_blank(c.pa));
  put(v, 10, text_or_blank(c.pb));
  for (int k = 0; k < 3; ++k) put(v, 11 + k, or_default(c.wa[k], 0.0));
  for (int k = 0; k < 3; ++k) put(v, 14 + k, or_default(c.wb[k], 0.0));
  put(v, 17, or_default(c.sa, std::int64_t{0}));
  put(v, 18, or_default(c.sb, std::int64_t{0}));
  trim_blanks(v);
  return v;
}

bool apply_beamor(Cbeam& c, const Beamor* b) {
  if (c.pid_blank) c.pid = b && b->pid ? *b->pid : c.eid;
  if (c.offt_blank && b) {
    if (b->bit) c.bit = b->bit;
    if (!b->offt.empty()) c.offt = b->offt;
  }
  if (c.orientation_blank) {
    if (!b || !b->has_orientation) return false;
    c.g0 = b->g0;
    c.x = b->x;
  }
  return true;
}

Beamor parse_beamor(const FieldReader& r) {
  Beamor b;
  if (!r.blank(1)) r.fail(1, "(blank)", "blank");
  if (!r.blank(2)) b.pid = r.id(2, "PID");
  if (!r.blank(3)) r.fail(3, "(blank)", "blank");
  if (!r.blank(4)) r.fail(4, "(blank)", "blank");
  b.has_orientation = read_orientation(r, 5, b.g0, b.x);
  read_offt_bit(r, b.offt, b.bit);
  r.at_most(9);
  return b;
}

std::vector<FieldValue> write_beamor(const Beamor& b) {
  std::vector<FieldValue> v = {std::string("BEAMOR"), FieldValue(), optional_value(b.pid), FieldValue(),
                               FieldValue()};
  write_orientation(v, 5, b.g0, b.x, !b.has_orientation);
  put(v, 8, offt_bit_value(b.offt, b.bit));
  trim_blanks(v);
  return v;
}

namespace {

bool is_so(const FieldReader& r, std::size_t i) {
  auto f = r.card().field(i);
  return f == "YES" || f == "YESA" || f == "NO";
}

}  // namespace

Pbeam parse_pbeam(const FieldReader& r) {
  Pbeam p;
  p.pid = r.id(1, "PID");
  p.mid = r.id(2, "MID");
  p.a = r.real(3, "A(A)");
  p.i1 = r.real_or(4, "I1(A)", 0.0);
  p.i2 = r.real_or(5, "I2(A)", 0.0);
  p.i12 = r.real_or(6, "I12(A)", 0.0);
  p.j = r.real_or(7, "J(A)", 0.0);
  p.nsm = r.real_or(8, "NSM(A)", 0.0);
  if (p.i1 < 0.0) r.fail(4, "I1(A)", "real >= 0.0");
  if (p.i2 < 0.0) r.fail(5, "I2(A)", "real >= 0.0");
  {
    double* cdef[] = {&p.c1, &p.c2, &p.d1, &p.d2, &p.e1, &p.e2, &p.f1, &p.f2};
    const char* names[] = {"C1(A)", "C2(A)", "D1(A)", "D2(A)", "E1(A)", "E2(A)", "F1(A)", "F2(A)"};
    for (int k = 0; k < 8; ++k) *cdef[k] = r.real_or(9 + k, names[k], 0.0);
  }
  std::size_t i = 17;
  while (i < r.size() && is_so(r, i)) {
    PbeamStation s;
    s.so = std::string(r.card().field(i));
    s.xxb = r.real(i + 1, "X/XB");
    if (s.xxb < 0.0 || s.xxb > 1.0) r.fail(i + 1, "X/XB", "real in [0.0, 1.0]");
    s.a = r.real_or(i + 2, "A", p.a);
    s.i1 = r.real_or(i + 3, "I1", p.i1);
    s.i2 = r.real_or(i + 4, "I2", p.i2);
    s.i12 = r.real_or(i + 5, "I12", p.i12);
    s.j = r.real_or(i + 6, "J", p.j);
    s.nsm = r.real_or(i + 7, "NSM", p.nsm);
    i += 8;
    if (s.so == "YESA") {
      s.c1 = p.c1, s.c2 = p.c2, s.d1 = p.d1, s.d2 = p.d2, s.e1 = p.e1, s.e2 = p.e2, s.f1 = p.f1, s.f2 = p.f2;
    } else if (s.so == "YES") {
      double* cdef[] = {&s.c1, &s.c2, &s.d1, &s.d2, &s.e1, &s.e2, &s.f1, &s.f2};
      const char* names[] = {"C1", "C2", "D1", "D2", "E1", "E2", "F1", "F2"};
      for (int k = 0; k < 8; ++k) *cdef[k] = r.real_or(i + k, names[k], 0.0);
      i += 8;
    }
    p.stations.push_back(s);
  }
  if (!p.stations.empty() && p.stations.back().xxb != 1.0)
    r.fail_card("the last PBEAM station must be end B (X/XB = 1.0)", i - 1);
  // Tail: K1 K2 S1 S2 NSI(A) NSI(B) CW(A) CW(B) / M1(A) M2(A) M1(B) M2(B) N1(A) N2(A) N1(B) N2(B).
  p.k1 = r.real_or(i, "K1", 1.0);
  p.k2 = r.real_or(i + 1, "K2", 1.0);
  p.s1 = r.real_or(i + 2, "S1", 0.0);
  p.s2 = r.real_or(i + 3, "S2", 0.0);
  p.nsia = r.real_or(i + 4, "NSI(A)", 0.0);
  p.nsib_blank = r.blank(i + 5);
  p.nsib = r.real_or(i + 5, "NSI(B)", p.nsia);
  p.cwa = r.real_or(i + 6, "CW(A)", 0.0);
  p.cwb_blank = r.blank(i + 7);
  p.cwb = r.real_or(i + 7, "CW(B)", p.cwa);
  p.m1a = r.real_or(i + 8, "M1(A)", 0.0);
  p.m2a = r.real_or(i + 9, "M2(A)", 0.0);
  p.m1b_blank = r.blank(i + 10);
  p.m1b = r.real_or(i + 10, "M1(B)", p.m1a);
  p.m2b_blank = r.blank(i + 11);
  p.m2b = r.real_or(i + 11, "M2(B)", p.m2a);
  p.n1a = r.real_or(i + 12, "N1(A)", 0.0);
  p.n2a = r.real_or(i + 13, "N2(A)", 0.0);
  p.n1b_blank = r.blank(i + 14);
  p.n1b = r.real_or(i + 14, "N1(B)", p.n1a);
  p.n2b_blank = r.blank(i + 15);
  p.n2b = r.real_or(i + 15, "N2(B)", p.n2a);
  r.at_most(i + 16);
  return p;
}

std::vector<FieldValue> write_pbeam(const Pbeam& p) {
  std::vector<FieldValue> v = {std::string("PBEAM"),  p.pid, p.mid, p.a, or_default(p.i1, 0.0),
                               or_default(p.i2, 0.0), or_default(p.i12, 0.0), or_default(p.j, 0.0),
                               or_default(p.nsm, 0.0)};
  // Appends one continuation's eight fields. Each field is moved in as it comes: a
  // std::initializer_list<FieldValue> (a const array of variants, copied element by
  // element) made GCC 12 warn -Wmaybe-uninitialized about the std::string alternative.
  auto row8 = [&v](auto&&... row) {
    static_assert(sizeof...(row) == 8, "a PBEAM continuation has eight fields");
    (v.emplace_back(std::forward<decltype(row)>(row)), ...);
  };
  auto z = [](double x) { return or_default(x, 0.0); };
  row8(z(p.c1), z(p.c2), z(p.d1), z(p.d2), z(p.e1), z(p.e2), z(p.f1), z(p.f2));
  for (const PbeamStation& s : p.stations) {
    row8(s.so, s.xxb, s.a, s.i1, s.i2, s.i12, s.j, s.nsm);
    if (s.so == "YES") row8(z(s.c1), z(s.c2), z(s.d1), z(s.d2), z(s.e1), z(s.e2), z(s.f1), z(s.f2));
  }
  auto b = [](double x, double a, bool blank) { return blank && x == a ? FieldValue() : FieldValue(x); };
  row8(or_default(p.k1, 1.0), or_default(p.k2, 1.0), z(p.s1), z(p.s2), z(p.nsia), b(p.nsib, p.nsia, p.nsib_blank),
       z(p.cwa), b(p.cwb, p.cwa, p.cwb_blank));
  row8(z(p.m1a), z(p.m2a), b(p.m1b, p.m1a, p.m1b_blank), b(p.m2b, p.m2a, p.m2b_blank), z(p.n1a), z(p.n2a),
       b(p.n1b, p.n1a, p.n1b_blank), b(p.n2b, p.n2a, p.n2b_blank));
  trim_blanks(v);
  return v;
}

}  // namespace ssid::formats
