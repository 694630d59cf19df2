#pragma once
/// \file truss_deck.hpp
/// Writes a truss model form as a NASTRAN SOL 103 deck through the bulk-data
/// writer (formats/deck.hpp): executive and case control, PARAMs, EIGRL, MAT1,
/// grids, elements, properties, masses, springs, rigid elements and the
/// DESVAR / DVPREL1 parameter table. Also the JSON summary of the model.
#include <nlohmann/json.hpp>
#include <string>

#include "formats/deck.hpp"
#include "translators/truss/truss_cards.hpp"

namespace ssid::translators::truss {

/// The deck of `fe`; `command` is recorded in the header comment. The deck's
/// main file is named `name` (used in messages; write it with write_deck).
formats::Deck to_deck(const TrussModel& t, const TrussCards& fe, const std::string& command,
                      const std::string& name = "generated.bdf");

/// Counts, masses, centre of gravity, layout and the parameter table.
nlohmann::json summary_json(const TrussModel& t, const TrussCards& fe);

}  // namespace ssid::translators::truss
