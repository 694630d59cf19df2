#pragma once
/// \file parameter_units.hpp
/// What a DESVAR is, and its unit, for the reports: NASTRAN has no unit system,
/// so a deck states its own. ssid reads it from a comment line
///   $ units: SI (m, kg, N, Pa, s)
/// (as `ssid truss` writes it); a deck without one is in "deck units".
///
/// A parameter x enters the fields it designs as value = C0 + Σ COEF·x
/// (DVPREL1/DVMREL1). Its unit is that of the fields (COEF taken as a pure
/// number, e.g. a share of a series-equivalent area), unless XINIT is 1 and no
/// coefficient is 1: x is then a dimensionless scale factor of the fields
/// (COEF carries the nominal value, e.g. CONM2 M = 0.6 kg · x).
#include <string>

#include "formats/deck.hpp"
#include "translators/assembly/fe_model.hpp"

namespace ssid::translators {

/// The unit system a deck states.
struct DeckUnits {
  bool si = false;     ///< the deck states SI units (m, kg, s, N, Pa)
  std::string source;  ///< where: "file:line" of the "$ units:" comment; empty: the deck states none
  std::string text;    ///< the comment's text after "units:", trimmed
};

/// The first "$ units:" comment of the deck's files (case-insensitive).
DeckUnits deck_units(const formats::Deck& deck);

/// A parameter's meaning and unit.
struct ParameterUnit {
  std::string designs;  ///< what it designs: "PROD A (31 cards)", "CONM2 M (80), PELAS K (3)"
  std::string unit;     ///< "m^2", "N/m", "scale factor", "deck units (area)", "" when it designs nothing
};

/// The SI unit of a designed field ("m^2" for PROD A), or "" when ssid does not know the field.
std::string si_unit(const std::string& type, const std::string& field);
/// The physical quantity of a designed field ("area" for PROD A), or "" when unknown.
std::string quantity(const std::string& type, const std::string& field);

/// What `p` designs and its unit in `units` (see the file comment). `bulk` tells
/// a spring's components (PELAS through its CELAS1s, CELAS2 itself): N/m on
/// translations, N m/rad on rotations.
ParameterUnit parameter_unit(const DesignParameter& p, const DeckUnits& units, const formats::BulkModel& bulk);

}  // namespace ssid::translators
