#pragma once
/// \file rigid.hpp
/// Rigid elements: RBAR, RBE2, RBE3.
///
/// | 1    | 2   | 3  | 4  | 5   | 6   | 7   | 8   | 9     |
/// |------|-----|----|----|-----|-----|-----|-----|-------|
/// | RBAR | EID | GA | GB | CNA | CNB | CMA | CMB | ALPHA |
///
/// EID > 0; GA != GB. CNA, CNB: independent components at each end (together
/// exactly six); CMA, CMB: dependent components; when both are blank, every
/// component not independent is dependent (NASTRAN's default; the struct
/// keeps the fields as given). ALPHA (thermal expansion): blank = 0.0.
///
/// | 1    | 2   | 3   | 4   | 5   | 6   | 7   | 8   | 9   |
/// |------|-----|-----|-----|-----|-----|-----|-----|-----|
/// | RBE2 | EID | GN  | CM  | GM1 | GM2 | GM3 | GM4 | GM5 |
/// |      | GM6 | ... | GMn | ALPHA |   |     |     |     |
///
/// GN: independent grid; CM: its dependent components at every GMi; blank
/// fields between grids are skipped. A real after the last grid is ALPHA.
///
/// | 1    | 2    | 3       | 4    | 5    | 6    | 7     | 8     | 9    |
/// |------|------|---------|------|------|------|-------|-------|------|
/// | RBE3 | EID  |         | REFGRID | REFC | WT1 | C1  | G1,1  | G1,2 |
/// |      | G1,3 | WT2     | C2   | G2,1 | ...  |       |       |      |
/// |      | "UM" | GM1     | CM1  | GM2  | CM2  | ...   |       |      |
/// |      | "ALPHA" | ALPHA |    |      |      |       |       |      |
///
/// REFGRID: the dependent reference grid, REFC its components. Each group is a
/// weight (real), its components and its grids (integers) up to the next
/// weight. "UM" starts pairs of grids and components that are dependent
/// instead of REFC; "ALPHA" is followed by the thermal expansion (blank = 0.0).
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "formats/card.hpp"
#include "formats/field_reader.hpp"

namespace ssid::formats {

struct Rbar {
  std::int64_t eid = 0, ga = 0, gb = 0;
  std::string cna, cnb, cma, cmb;  ///< component digits, "" = blank
  double alpha = 0.0;
  std::size_t card = 0;
};

struct Rbe2 {
  std::int64_t eid = 0, gn = 0;
  std::string cm;
  std::vector<std::int64_t> gm;
  double alpha = 0.0;
  std::size_t card = 0;
};

struct Rbe3Group {
  double weight = 1.0;
  std::string components;
  std::vector<std::int64_t> grids;
};

struct Rbe3 {
  std::int64_t eid = 0, refgrid = 0;
  std::string refc;
  std::vector<Rbe3Group> groups;
  std::vector<std::pair<std::int64_t, std::string>> um;  ///< (GMi, CMi)
  double alpha = 0.0;
  bool has_alpha = false;
  std::size_t card = 0;
};

Rbar parse_rbar(const FieldReader& r);
std::vector<FieldValue> write_rbar(const Rbar& e);
Rbe2 parse_rbe2(const FieldReader& r);
std::vector<FieldValue> write_rbe2(const Rbe2& e);
Rbe3 parse_rbe3(const FieldReader& r);
std::vector<FieldValue> write_rbe3(const Rbe3& e);

}  // namespace ssid::formats
