#pragma once
/// \file deck_writer.hpp
/// Writes decks back: unchanged cards byte for byte, changed cards formatted
/// anew in their original field format, generated cards in clean small field.
#include <string>
#include <vector>

#include "formats/deck.hpp"

namespace ssid::formats {

/// Formats a card from values (`values[0]` is the name; its value is ignored).
/// Small and free-field cards are promoted to large field when a value cannot be
/// written exactly in 8 characters; in large field, reals are exact when 16
/// characters can hold them and otherwise rounded to the most digits that fit.
/// Reals always carry a decimal point. When `original` is given, a field whose
/// value did not change keeps its original text.
std::string format_card(const std::string& name, const std::vector<FieldValue>& values, FieldFormat format,
                        const std::string& newline = "\n", const Card* original = nullptr);

/// The text of one file of the deck (its INCLUDE statements unchanged).
std::string render_file(const Deck& deck, std::size_t file);

/// Writes the main file to `path` and each included file beside it, at its
/// INCLUDE name relative to the output of the file that includes it, so the
/// written set is self-consistent. Included files given by absolute path are
/// left in place when unchanged (an error when they hold changed cards). Never
/// overwrites an input file. Returns the paths written. Throws std::runtime_error.
std::vector<std::string> write_deck(const Deck& deck, const std::string& path);

}  // namespace ssid::formats
