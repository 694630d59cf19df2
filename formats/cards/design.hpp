#pragma once
/// \file design.hpp
/// The design model: DESVAR (a parameter), DVPREL1 (a property as a linear
/// function of parameters) and DVMREL1 (a material value likewise). ssid's
/// updating parameters are these cards, so decks stay valid for other codes.
///
/// | 1      | 2  | 3     | 4     | 5   | 6   | 7     | 8     | 9 |
/// |--------|----|-------|-------|-----|-----|-------|-------|---|
/// | DESVAR | ID | LABEL | XINIT | XLB | XUB | DELXV | DDVAL |   |
///
/// ID > 0. LABEL: a name (up to 8 characters). XINIT: initial value,
/// XLB <= XINIT <= XUB. XLB: blank = -1.0E20; XUB: blank = 1.0E20. DELXV:
/// move limit, blank = the optimizer's default. DDVAL: DDVAL set of discrete values, blank = none.
///
/// | 1       | 2     | 3     | 4     | 5          | 6     | 7     | 8  | 9 |
/// |---------|-------|-------|-------|------------|-------|-------|----|---|
/// | DVPREL1 | ID    | TYPE  | PID   | PNAME/FID  | PMIN  | PMAX  | C0 |   |
/// |         | DVID1 | COEF1 | DVID2 | COEF2      | DVID3 | COEF3 | ...|   |
///
/// P = C0 + sum(COEFi * X(DVIDi)). TYPE: the property card (PBAR, PROD, ...);
/// PNAME: the field's name (A, I1, ...) or FID: its field number (integer).
/// PMIN: blank = NASTRAN's type-dependent default (kept blank); PMAX: blank =
/// 1.0E20; C0: blank = 0.0. DVID/COEF pairs run on from field 2 of the first
/// continuation (four per row); at least one.
///
/// | 1       | 2     | 3     | 4     | 5      | 6     | 7     | 8  | 9 |
/// |---------|-------|-------|-------|--------|-------|-------|----|---|
/// | DVMREL1 | ID    | TYPE  | MID   | MPNAME | MPMIN | MPMAX | C0 |   |
/// |         | DVID1 | COEF1 | DVID2 | COEF2  | ...   |       |    |   |
///
/// As DVPREL1 for a material (TYPE MAT1, ...; MPNAME E, G, NU, RHO, ...).
/// MPMIN: blank = NASTRAN's default (kept blank); MPMAX: blank = 1.0E20.
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "formats/card.hpp"
#include "formats/field_reader.hpp"

namespace ssid::formats {

struct Desvar {
  std::int64_t id = 0;
  std::string label;
  double xinit = 0.0, xlb = -1.0e20, xub = 1.0e20;
  std::optional<double> delxv;
  std::optional<std::int64_t> ddval;
  std::size_t card = 0;
};

struct Dvprel1 {
  std::int64_t id = 0;
  std::string type;
  std::int64_t pid = 0;
  std::string pname;    ///< "" when the field is given by number
  std::int64_t fid = 0; ///< field number when PNAME is an integer, else 0
  std::optional<double> pmin;
  double pmax = 1.0e20, c0 = 0.0;
  std::vector<std::pair<std::int64_t, double>> terms;  ///< (DVID, COEF)
  std::size_t card = 0;
};

struct Dvmrel1 {
  std::int64_t id = 0;
  std::string type;
  std::int64_t mid = 0;
  std::string mpname;
  std::optional<double> mpmin;
  double mpmax = 1.0e20, c0 = 0.0;
  std::vector<std::pair<std::int64_t, double>> terms;
  std::size_t card = 0;
};

Desvar parse_desvar(const FieldReader& r);
std::vector<FieldValue> write_desvar(const Desvar& d);
Dvprel1 parse_dvprel1(const FieldReader& r);
std::vector<FieldValue> write_dvprel1(const Dvprel1& d);
Dvmrel1 parse_dvmrel1(const FieldReader& r);
std::vector<FieldValue> write_dvmrel1(const Dvmrel1& d);

}  // namespace ssid::formats
