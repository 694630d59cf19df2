#pragma once
/// \file scalar.hpp
/// Scalar elements and point masses: CONM2, CMASS1, CMASS2, PMASS, CELAS1,
/// CELAS2, PELAS, and SPOINT (scalar points they may connect).
///
/// | 1     | 2   | 3   | 4   | 5   | 6   | 7   | 8  | 9 |
/// |-------|-----|-----|-----|-----|-----|-----|----|---|
/// | CONM2 | EID | G   | CID | M   | X1  | X2  | X3 |   |
/// |       | I11 | I21 | I22 | I31 | I32 | I33 |    |   |
///
/// EID, G > 0. CID: blank = 0; -1 means X1-X3 are offsets in the basic system
/// (CID >= -1). M: mass. X1-X3: offset of the centre of gravity from G
/// (in CID), blank = 0.0. Iij: inertia about the centre of gravity, blank = 0.0.
///
/// | 1      | 2   | 3       | 4  | 5  | 6  | 7  | 8  | 9 |
/// |--------|-----|---------|----|----|----|----|----|---|
/// | CMASS1 | EID | PID     | G1 | C1 | G2 | C2 |    |   |
/// | CMASS2 | EID | M       | G1 | C1 | G2 | C2 |    |   |
/// | CELAS1 | EID | PID     | G1 | C1 | G2 | C2 |    |   |
/// | CELAS2 | EID | K       | G1 | C1 | G2 | C2 | GE | S |
///
/// PID: PMASS / PELAS id, blank = EID. Gi: grid or scalar point; blank = 0
/// (that end grounded). Ci: component 1-6 for a grid, 0 or blank for a scalar
/// point. GE (damping), S (stress coefficient): blank = 0.0.
///
/// | 1      | 2   | 3   | 4  | 5  |
/// |--------|-----|-----|----|----|
/// | CMASS3 | EID | PID | S1 | S2 |
/// | CMASS4 | EID | M   | S1 | S2 |
/// | CELAS3 | EID | PID | S1 | S2 |
/// | CELAS4 | EID | K   | S1 | S2 |
///
/// The scalar-point forms: S1, S2 scalar points (blank or 0 = grounded, not
/// both; a point on no SPOINT is one, SPOINT remark 2). They are read into the
/// structs of CMASS1, CMASS2, CELAS1, CELAS2 with components 0 and
/// `scalar_form` set, and written back in their own form; CELAS4 has no GE or S
/// (0.0).
///
/// | 1     | 2    | 3  | 4    | 5  | 6    | 7  | 8    | 9  |
/// |-------|------|----|------|----|------|----|------|----|
/// | PELAS | PID1 | K1 | GE1  | S1 | PID2 | K2 | GE2  | S2 |
/// | PMASS | PID1 | M1 | PID2 | M2 | PID3 | M3 | PID4 | M4 |
///
/// One card holds up to two PELAS or four PMASS properties (one struct each).
/// GE, S: blank = 0.0.
///
/// | 1      | 2   | 3   | 4   | ... |
/// |--------|-----|-----|-----|-----|
/// | SPOINT | ID1 | ID2 | ID3 | ... |
/// | SPOINT | ID1 | THRU| ID2 |     |
#include <array>
#include <cstdint>
#include <vector>

#include "formats/card.hpp"
#include "formats/field_reader.hpp"

namespace ssid::formats {

struct Conm2 {
  std::int64_t eid = 0, g = 0, cid = 0;
  double m = 0.0;
  std::array<double, 3> x{0.0, 0.0, 0.0};
  double i11 = 0.0, i21 = 0.0, i22 = 0.0, i31 = 0.0, i32 = 0.0, i33 = 0.0;
  std::size_t card = 0;
};

/// CMASS1 / CELAS1 (and CMASS3 / CELAS3, `scalar_form`): connection to a property.
struct Cmass1 {
  std::int64_t eid = 0, pid = 0, g1 = 0, c1 = 0, g2 = 0, c2 = 0;
  bool pid_blank = false;
  bool scalar_form = false;  ///< read from CMASS3
  std::size_t card = 0;
};
struct Celas1 {
  std::int64_t eid = 0, pid = 0, g1 = 0, c1 = 0, g2 = 0, c2 = 0;
  bool pid_blank = false;
  bool scalar_form = false;  ///< read from CELAS3
  std::size_t card = 0;
};

struct Cmass2 {
  std::int64_t eid = 0;
  double m = 0.0;
  std::int64_t g1 = 0, c1 = 0, g2 = 0, c2 = 0;
  bool scalar_form = false;  ///< read from CMASS4
  std::size_t card = 0;
};
struct Celas2 {
  std::int64_t eid = 0;
  double k = 0.0;
  std::int64_t g1 = 0, c1 = 0, g2 = 0, c2 = 0;
  double ge = 0.0, s = 0.0;
  bool scalar_form = false;  ///< read from CELAS4
  std::size_t card = 0;
};

struct Pelas {
  std::int64_t pid = 0;
  double k = 0.0, ge = 0.0, s = 0.0;
  std::size_t card = 0;
};
struct Pmass {
  std::int64_t pid = 0;
  double m = 0.0;
  std::size_t card = 0;
};

struct Spoint {
  std::vector<std::int64_t> ids;  ///< all ids (a THRU range expanded)
  bool thru = false;              ///< written as ID1 THRU ID2 (ids must then be consecutive)
  std::size_t card = 0;
};

Conm2 parse_conm2(const FieldReader& r);
std::vector<FieldValue> write_conm2(const Conm2& c);
Cmass1 parse_cmass1(const FieldReader& r);
std::vector<FieldValue> write_cmass1(const Cmass1& c);
Cmass2 parse_cmass2(const FieldReader& r);
std::vector<FieldValue> write_cmass2(const Cmass2& c);
Celas1 parse_celas1(const FieldReader& r);
std::vector<FieldValue> write_celas1(const Celas1& c);
Celas2 parse_celas2(const FieldReader& r);
std::vector<FieldValue> write_celas2(const Celas2& c);
/// The scalar-point forms; each writer above writes them back in their form.
Cmass1 parse_cmass3(const FieldReader& r);
Cmass2 parse_cmass4(const FieldReader& r);
Celas1 parse_celas3(const FieldReader& r);
Celas2 parse_celas4(const FieldReader& r);
/// Both properties of a PELAS card (one or two).
std::vector<Pelas> parse_pelas(const FieldReader& r);
/// One PELAS property as a full 4-field entry (write_bulk joins entries of one card).
std::vector<FieldValue> write_pelas(const Pelas& p);
std::vector<Pmass> parse_pmass(const FieldReader& r);
std::vector<FieldValue> write_pmass(const Pmass& p);
Spoint parse_spoint(const FieldReader& r);
std::vector<FieldValue> write_spoint(const Spoint& s);

}  // namespace ssid::formats
