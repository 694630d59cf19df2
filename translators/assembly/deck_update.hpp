#pragma once
/// \file deck_update.hpp
/// The SD2NAS analogue of the seed report: new parameter values written back
/// into a deck. Each changed DESVAR gets the new XINIT, and every property,
/// material or element field designed by it through DVPREL1/DVMREL1 gets the
/// value the assembly uses,
///   value = C0 + Σᵢ COEFᵢ · xᵢ,  clipped to [PMIN, PMAX],
/// so that assembling the written deck reproduces the operators (and modes) of
/// the estimator's final parameters. Nothing else changes: cards without a
/// changed value, comments and control statements are written back byte for
/// byte, and a changed card keeps the original text of its unchanged fields
/// (formats/deck_writer.hpp; a value that does not fit 8 columns exactly
/// promotes its card to large field).
#include <map>
#include <string>
#include <vector>

#include "formats/deck.hpp"

namespace ssid::translators {

/// What an update changed, for the user.
struct DeckUpdateReport {
  std::vector<std::string> parameters;  ///< "STRUTA (DESVAR 1): 0.0002015 -> 0.00021"
  std::vector<std::string> fields;      ///< "PROD 101 A: 0.000205 -> 0.000211 (file.bdf:100)"
  std::size_t cards_changed = 0;
};

/// Sets the DESVARs named in `values` (by DESVAR label, case-insensitive) and
/// every value designed by them. Throws std::invalid_argument for a label that
/// is no DESVAR of the deck (the labels are listed), a value outside the
/// DESVAR's [XLB, XUB] or not finite, and ModelError/ParseError when the deck
/// itself cannot be assembled (the relations are resolved by the assembly).
DeckUpdateReport update_deck(formats::Deck& deck, const std::map<std::string, double>& values);

/// The `parameters[].name` / `parameters[].estimate` pairs of an estimation
/// result (or a hand-written what-if file) in JSON text; everything else in the
/// file is ignored. Throws std::invalid_argument naming `source` and the entry.
std::map<std::string, double> parameter_values_from_json(const std::string& text, const std::string& source);

}  // namespace ssid::translators
