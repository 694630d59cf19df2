#pragma once
/// \file bulk_model.hpp
/// The typed view of a deck's bulk data: one vector per supported card type,
/// the count of cards kept verbatim, and every problem found, all at once.
#include <map>
#include <string>
#include <vector>

#include "formats/cards/crod.hpp"
#include "formats/cards/grid.hpp"
#include "formats/deck.hpp"

namespace ssid::formats {

struct BulkModel {
  std::vector<Grid> grids;
  std::vector<Crod> crods;

  /// Cards with no typed parser, by name: kept verbatim in the deck, written back unchanged.
  std::map<std::string, std::size_t> unsupported;
  /// Typed cards, by name.
  std::map<std::string, std::size_t> supported;
  /// Field errors and cross-reference problems (resolve), in deck order.
  std::vector<Problem> problems;
};

/// Parses every card with a typed parser; field errors are collected, not thrown.
BulkModel parse_bulk(const Deck& deck);

/// Checks the model as a whole — duplicate ids, dangling references ("GRID 12
/// required by CROD 10"), properties of the wrong type — and appends every
/// problem found to model.problems.
void resolve(const Deck& deck, BulkModel& model);

/// True when a card of this name has a typed parser.
bool is_supported_card(const std::string& name);

}  // namespace ssid::formats
