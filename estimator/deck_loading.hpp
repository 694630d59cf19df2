#pragma once
/// \file deck_loading.hpp
/// A deck's bulk data as the estimator takes it: typed, resolved, and refused
/// with its first errors when reading the deck or its cards found any. Why one
/// function: `ssid estimate` had checked only the cards' problems, so a deck with
/// a reading error (an orphan continuation line, an unterminated continuation:
/// data that reached no card) was estimated from without a word, while `ssid modes`
/// and the diagnosis refused it, each with its own copy of the check.
#include <string>
#include <vector>

#include "formats/bulk_model.hpp"
#include "formats/deck.hpp"

namespace ssid::estimator {

/// parse_bulk and resolve. Throws std::invalid_argument when the deck's reading or
/// its cards have errors: "<who>: N error(s) in the deck; nothing assembled:" and
/// the first twenty (each with its file:line and card), "<who>: " left out when who
/// is empty. Warnings pass, appended to `warnings` when given (as Problem::str()).
formats::BulkModel resolved_bulk(const formats::Deck& deck, const std::string& who = "",
                                 std::vector<std::string>* warnings = nullptr);

}  // namespace ssid::estimator
