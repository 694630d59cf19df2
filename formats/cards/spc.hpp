#pragma once
/// \file spc.hpp
/// Single- and multipoint constraints: SPC, SPC1, SPCADD, MPC.
///
/// | 1   | 2   | 3  | 4  | 5  | 6  | 7  | 8  | 9 |
/// |-----|-----|----|----|----|----|----|----|---|
/// | SPC | SID | G1 | C1 | D1 | G2 | C2 | D2 |   |
///
/// SID > 0. Gi: grid or scalar point; Ci: components (0 or blank for a scalar
/// point); Di: enforced displacement, blank = 0.0. The second triple is optional.
///
/// | 1    | 2   | 3  | 4  | 5    | 6  | 7  | 8  | 9  |
/// |------|-----|----|----|------|----|----|----|----|
/// | SPC1 | SID | C  | G1 | G2   | G3 | G4 | G5 | G6 |
/// |      | G7  | G8 | ...|      |    |    |    |    |
/// | SPC1 | SID | C  | G1 | THRU | G2 |    |    |    |
///
/// | 1      | 2   | 3  | 4  | ... |
/// |--------|-----|----|----|-----|
/// | SPCADD | SID | S1 | S2 | ... |
///
/// SPCADD: the union of SPC/SPC1 sets S1, S2, ... (blank fields skipped).
///
/// | 1   | 2   | 3  | 4  | 5  | 6  | 7  | 8  | 9 |
/// |-----|-----|----|----|----|----|----|----|---|
/// | MPC | SID | G1 | C1 | A1 | G2 | C2 | A2 |   |
/// |     |     | G3 | C3 | A3 | G4 | C4 | A4 |   |
///
/// sum(Aj u(Gj, Cj)) = 0; the first term's DOF is the dependent one (A1 != 0).
/// Cj: one component 1-6 (0 or blank for a scalar point). Each row holds two
/// terms in fields 3-5 and 6-8; field 2 of a continuation is blank.
#include <cstdint>
#include <string>
#include <vector>

#include "formats/card.hpp"
#include "formats/field_reader.hpp"

namespace ssid::formats {

struct SpcEntry {
  std::int64_t g = 0;
  std::string c;  ///< component digits ("" for a scalar point)
  double d = 0.0;
};

struct Spc {
  std::int64_t sid = 0;
  std::vector<SpcEntry> entries;  ///< one or two
  std::size_t card = 0;
};

struct Spc1 {
  std::int64_t sid = 0;
  std::string c;
  std::vector<std::int64_t> grids;  ///< a THRU range expanded
  bool thru = false;                ///< written as G1 THRU G2 (grids consecutive)
  std::size_t card = 0;
};

struct Spcadd {
  std::int64_t sid = 0;
  std::vector<std::int64_t> sets;
  std::size_t card = 0;
};

struct MpcTerm {
  std::int64_t g = 0;
  std::int64_t c = 0;  ///< component 1-6, 0 for a scalar point
  double a = 0.0;
};

struct Mpc {
  std::int64_t sid = 0;
  std::vector<MpcTerm> terms;  ///< terms[0] is the dependent DOF
  std::size_t card = 0;
};

Spc parse_spc(const FieldReader& r);
std::vector<FieldValue> write_spc(const Spc& s);
Spc1 parse_spc1(const FieldReader& r);
std::vector<FieldValue> write_spc1(const Spc1& s);
Spcadd parse_spcadd(const FieldReader& r);
std::vector<FieldValue> write_spcadd(const Spcadd& s);
Mpc parse_mpc(const FieldReader& r);
std::vector<FieldValue> write_mpc(const Mpc& m);

}  // namespace ssid::formats
