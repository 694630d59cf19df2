#include "formats/cards/mat1.hpp"

#include "formats/cards/card_values.hpp"

namespace ssid::formats {

Mat1 parse_mat1(const FieldReader& r) {
  Mat1 m;
  m.mid = r.id(1, "MID");
  auto e = r.real_or_blank(2, "E");
  auto g = r.real_or_blank(3, "G");
  auto nu = r.real_or_blank(4, "NU");
  if (e && *e < 0.0) r.fail(2, "E", "real >= 0.0");
  if (g && *g < 0.0) r.fail(3, "G", "real >= 0.0");
  // NU outside (-1.0, 0.5] is an error where it derives E or G. With E and G both
  // given NASTRAN only warns (MSC's USER WARNING MESSAGE 2251, "unreasonable or
  // inconsistent values of E, G or NU": pyNastran's freedlm, NU = 16.7586, ran) and
  // uses E and G as given: check_mat1_moduli says so.
  if (nu && !mat1_nu_in_range(*nu) && !(e && g)) r.fail(4, "NU", "real in (-1.0, 0.5] (E or G is derived from it)");
  if (!e && !g) r.fail_card("E and G are both blank (give at least one)", 2);
  m.e_given = e.has_value();
  m.g_given = g.has_value();
  m.nu_given = nu.has_value();
  // NASTRAN's rule: one blank -> from E = 2(1+NU)G; two blank -> both 0.0.
  if (e && g && nu) {
    m.e = *e, m.g = *g, m.nu = *nu;
  } else if (e && g) {
    m.e = *e, m.g = *g;
    if (*g == 0.0) r.fail(3, "G", "G > 0.0 to derive NU from E and G");
    m.nu = *e / (2.0 * *g) - 1.0;
  } else if (e && nu) {
    m.e = *e, m.nu = *nu, m.g = *e / (2.0 * (1.0 + *nu));
  } else if (g && nu) {
    m.g = *g, m.nu = *nu, m.e = 2.0 * (1.0 + *nu) * *g;
  } else {
    m.e = e.value_or(0.0), m.g = g.value_or(0.0), m.nu = 0.0;
  }
  m.rho = r.real_or(5, "RHO", 0.0);
  m.a = r.real_or(6, "A", 0.0);
  m.tref = r.real_or(7, "TREF", 0.0);
  m.ge = r.real_or(8, "GE", 0.0);
  m.st = r.real_or(9, "ST", 0.0);
  m.sc = r.real_or(10, "SC", 0.0);
  m.ss = r.real_or(11, "SS", 0.0);
  m.mcsid = r.integer_or(12, "MCSID", 0);
  if (m.mcsid < 0) r.fail(12, "MCSID", "integer >= 0");
  r.at_most(13);
  return m;
}

std::vector<FieldValue> write_mat1(const Mat1& m) {
  std::vector<FieldValue> v = {std::string("MAT1"),
                               m.mid,
                               m.e_given ? FieldValue(m.e) : FieldValue(),
                               m.g_given ? FieldValue(m.g) : FieldValue(),
                               m.nu_given ? FieldValue(m.nu) : FieldValue(),
                               or_default(m.rho, 0.0),
                               or_default(m.a, 0.0),
                               or_default(m.tref, 0.0),
                               or_default(m.ge, 0.0),
                               or_default(m.st, 0.0),
                               or_default(m.sc, 0.0),
                               or_default(m.ss, 0.0),
                               or_default(m.mcsid, std::int64_t{0})};
  trim_blanks(v);
  return v;
}

}  // namespace ssid::formats
