#include "formats/cards/grid.hpp"

#include "formats/cards/card_values.hpp"

namespace ssid::formats {

Grid parse_grid(const FieldReader& r) {
  Grid g;
  g.id = r.id(1, "ID");
  g.cp_blank = r.blank(2);
  g.cp = r.integer_or(2, "CP", 0);
  g.x[0] = r.real_or(3, "X1", 0.0);
  g.x[1] = r.real_or(4, "X2", 0.0);
  g.x[2] = r.real_or(5, "X3", 0.0);
  g.cd_blank = r.blank(6);
  g.cd = r.integer_or(6, "CD", 0);
  g.ps_blank = r.blank(7);
  g.ps = r.components(7, "PS", true);
  g.seid_blank = r.blank(8);
  g.seid = r.integer_or(8, "SEID", 0);
  if (r.size() > 9) r.fail_card("too many fields (GRID has 8 data fields)", 9);
  return g;
}

std::vector<FieldValue> write_grid(const Grid& g) {
  return {std::string("GRID"), g.id, blank_if(g.cp, 0, g.cp_blank), g.x[0], g.x[1], g.x[2],
          blank_if(g.cd, 0, g.cd_blank), text_or_blank(g.ps), blank_if(g.seid, 0, g.seid_blank)};
}

}  // namespace ssid::formats
