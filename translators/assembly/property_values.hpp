#pragma once
/// \file property_values.hpp
/// Property, material and element values by their NASTRAN field names (the
/// PNAME/MPNAME of DVPREL1/DVMREL1): setting them in a model copy (assembly at
/// new parameter values) and holding their rates of change (the direction of
/// a derivative). Names follow the QRG: PROD A J NSM; PBAR A I1 I2 I12 J NSM
/// K1 K2; PBARL/PBEAML DIM1… NSM; PBEAM A I1 I2 I12 J NSM K1 K2 (constant
/// section: every station); PELAS K; PMASS M; PBUSH K1…K6; CONM2 M X1 X2 X3
/// I11 I21 I22 I31 I32 I33; CELAS2 K; CMASS2 M; CONROD A J NSM;
/// MAT1 E G NU RHO.
#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "formats/bulk_model.hpp"

namespace ssid::translators {

/// Where a named value lives: a property (by PID), a material (by MID) or an
/// element (CONM2, CELAS2, CMASS2, CONROD, by EID).
enum class ValueOwner { Property, Material, Element };

struct ValueKey {
  ValueOwner owner = ValueOwner::Property;
  std::int64_t id = 0;
  std::string name;  ///< upper case, e.g. "A", "DIM2", "E"
  bool operator<(const ValueKey& o) const {
    if (owner != o.owner) return owner < o.owner;
    if (id != o.id) return id < o.id;
    return name < o.name;
  }
};

/// Rates of change of named values (a direction in property space).
class ValueDelta {
 public:
  void add(const ValueKey& key, double rate) { m_rates[key] += rate; }
  double get(ValueOwner owner, std::int64_t id, const std::string& name) const {
    auto it = m_rates.find({owner, id, name});
    return it == m_rates.end() ? 0.0 : it->second;
  }
  bool touches(ValueOwner owner, std::int64_t id) const;
  bool empty() const { return m_rates.empty(); }
  const std::map<ValueKey, double>& rates() const { return m_rates; }

 private:
  std::map<ValueKey, double> m_rates;
};

/// The card type that owns a property id ("PROD", "PBAR", …), or "" if none.
std::string property_type(const formats::BulkModel& model, std::int64_t pid);

/// Reads a named value; throws std::invalid_argument naming the card type and
/// field when the name is not one of that card's fields or the id is absent.
double get_value(const formats::BulkModel& model, const ValueKey& key);
/// Sets a named value (MAT1: the derived members of E, G, NU follow, as NASTRAN
/// re-derives them); same errors as get_value.
void set_value(formats::BulkModel& model, const ValueKey& key, double value);

/// MAT1 derivation rule applied to rates: the rates of the derived members of
/// E, G, NU from the rates of the given ones, at the material's current values.
/// Returns (dE, dG, dNU).
std::array<double, 3> mat1_rates(const formats::Mat1& m, double de, double dg, double dnu);

}  // namespace ssid::translators
