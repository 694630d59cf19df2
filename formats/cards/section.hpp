#pragma once
/// \file section.hpp
/// PBARL and PBEAML — bar and beam properties given by cross-section dimensions.
///
/// | 1     | 2    | 3    | 4     | 5    | 6 | 7 | 8 | 9 |
/// |-------|------|------|-------|------|---|---|---|---|
/// | PBARL | PID  | MID  | GROUP | TYPE |   |   |   |   |
/// |       | DIM1 | DIM2 | ...   | DIMn | NSM |  |   |   |
///
/// PID, MID > 0. GROUP: blank = "MSCBML0". TYPE: the section shape; the number
/// of dimensions n follows from it (pbarl_dim_count). DIMi required; NSM
/// (non-structural mass per length) follows the last dimension, blank = 0.0.
/// A TYPE ssid does not know keeps every value of the continuations in `dims`
/// (NSM cannot be told apart) and `known_type` is false.
///
/// | 1      | 2       | 3       | 4     | 5       | 6      | 7      | 8 | 9 |
/// |--------|---------|---------|-------|---------|--------|--------|---|---|
/// | PBEAML | PID     | MID     | GROUP | TYPE    |        |        |   |   |
/// |        | DIM1(A) | ...     | DIMn(A) | NSM(A) | SO(1) | X(1)/XB | DIM1(1) | ... |
/// |        | ...     | NSM(m)  | SO(B) | X(B)/XB | DIM1(B) | ...  | DIMn(B) | NSM(B) |
///
/// The values after field 5 run on continuously: end A's n dimensions and NSM,
/// then for each further station SO (YES/NO, blank = YES), X/XB (blank = 1.0),
/// n dimensions (blank = end A's) and NSM (blank = 0.0). A constant section has
/// only end A.
#include <cstdint>
#include <string>
#include <vector>

#include "formats/card.hpp"
#include "formats/field_reader.hpp"

namespace ssid::formats {

/// Number of dimensions of a PBARL/PBEAML section type (MSC list); 0 when unknown.
int pbarl_dim_count(const std::string& type);
/// Types whose section properties ssid computes: every type of the MSC list
/// (translators/elements/section.hpp), i.e. pbarl_dim_count(type) > 0.
bool pbarl_type_sectioned(const std::string& type);

struct Pbarl {
  std::int64_t pid = 0, mid = 0;
  std::string group = "MSCBML0";
  std::string type;
  std::vector<double> dims;
  double nsm = 0.0;
  bool known_type = true;
  bool group_blank = true;
  std::size_t card = 0;
};

struct PbeamlStation {
  std::string so = "YES";
  double xxb = 0.0;  ///< 0.0 for end A, 1.0 for end B
  std::vector<double> dims;
  double nsm = 0.0;
};

struct Pbeaml {
  std::int64_t pid = 0, mid = 0;
  std::string group = "MSCBML0";
  std::string type;
  /// stations[0] is end A; further stations in the order given (the last is end B).
  std::vector<PbeamlStation> stations;
  bool known_type = true;
  bool group_blank = true;
  std::size_t card = 0;
  /// End A's dimensions and NSM (the constant section).
  const std::vector<double>& dims() const { return stations.front().dims; }
  double nsm() const { return stations.front().nsm; }
};

Pbarl parse_pbarl(const FieldReader& r);
std::vector<FieldValue> write_pbarl(const Pbarl& p);
Pbeaml parse_pbeaml(const FieldReader& r);
std::vector<FieldValue> write_pbeaml(const Pbeaml& p);

}  // namespace ssid::formats
