#pragma once
/// \file bulk_catalogue.hpp
/// The names of the NASTRAN bulk data entries a real deck may hold, so that a
/// card ssid only keeps verbatim (CQUAD4, PSHELL) is told apart from a misspelt
/// one (CRDO), and the misspelt one gets the nearest real name as a suggestion.
///
/// NASTRAN itself stops on a name it does not know: "USER FATAL MESSAGE 307,
/// ILLEGAL NAME FOR BULK DATA CARD" (NASTRAN-95, um/MSSG.TXT and mis/ifp.f;
/// MSC Nastran prints the same number as "ILLEGAL NAME FOR BULK DATA ENTRY").
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace ssid::formats {

/// Every name in the catalogue (bulk_catalogue.cpp), sorted, upper case.
const std::vector<std::string_view>& bulk_entry_names();

/// True when `name` (upper case, without the large-field '*') is a NASTRAN
/// bulk data entry name or ENDDATA.
bool is_bulk_entry_name(std::string_view name);

/// Edit distance between two names: insertions, deletions, substitutions and
/// transpositions of adjacent characters each count 1 (the optimal string
/// alignment distance), so CRDO is 1 from CROD and ENDDTA 1 from ENDDATA.
std::size_t edit_distance(std::string_view a, std::string_view b);

/// The catalogue name nearest to `name`, when one lies within 1 edit (names of up
/// to 4 characters) or 2 edits (longer names); nullopt otherwise. Among names at
/// the same distance, a card ssid types (is_supported_card) wins, then the
/// alphabetically first.
std::optional<std::string> nearest_bulk_entry_name(std::string_view name);

}  // namespace ssid::formats
