#pragma once
/// \file card.hpp
/// A bulk data card as read: its name, its fields as text, where it came from,
/// and the span of original text it occupies so it can be written back byte for byte.
#include <cstdint>
#include <string>
#include <variant>
#include <vector>

namespace ssid::formats {

/// The field format of a card's first line; a changed card is rewritten in it.
enum class FieldFormat : std::uint8_t { Small, Large, Free };

/// One value to write into a field: blank, integer, real or text.
using FieldValue = std::variant<std::monostate, std::int64_t, double, std::string>;

/// A bulk data entry with its continuations folded in.
///
/// Fields are numbered as in pyNastran and in error messages: `fields[0]` is the
/// card name (NASTRAN field 1 of the first line); `fields[1..8]` are NASTRAN fields
/// 2-9 of the first line; `fields[9..16]` fields 2-9 of the first continuation, and
/// so on. Continuation markers (field 10 and field 1 of continuations) are dropped.
/// Texts are trimmed and upper-cased; trailing blank fields are removed.
struct Card {
  std::string name;                 ///< upper case, without the large-field '*'
  std::vector<std::string> fields;  ///< fields[0] == name
  FieldFormat format = FieldFormat::Small;
  std::uint32_t file = 0;    ///< index into Deck::files
  std::uint32_t line = 0;    ///< 1-based line of the first physical line
  std::uint32_t begin = 0;   ///< byte span [begin, end) of the original text in its file
  std::uint32_t end = 0;
  /// Physical lines of the card: (1-based line, index of its first field in `fields`).
  std::vector<std::pair<std::uint32_t, std::uint32_t>> rows;
  /// Set when the card's values were replaced; then `values` holds them and the
  /// writer formats the card anew instead of copying the original text.
  bool modified = false;
  std::vector<FieldValue> values;

  /// Number of fields including the name.
  std::size_t size() const { return fields.size(); }
  /// Field text, "" beyond the last field.
  const std::string& field(std::size_t i) const;
  /// 1-based source line holding field i.
  std::uint32_t line_of(std::size_t i) const;
};

}  // namespace ssid::formats
