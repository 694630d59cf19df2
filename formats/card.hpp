#pragma once
/// \file card.hpp
/// A bulk data card as read: its name, its fields as text, where it came from,
/// and the span of original text it occupies so it can be written back byte for byte.
#include <cstdint>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace ssid::formats {

/// The field format of a card's first line; a changed card is rewritten in it.
enum class FieldFormat : std::uint8_t { Small, Large, Free };

/// One value to write into a field: blank, integer, real or text.
using FieldValue = std::variant<std::monostate, std::int64_t, double, std::string>;

/// A read-only list of field texts (views into the deck's arena).
class FieldList {
public:
  FieldList(const std::string_view* p, std::size_t n) : m_p(p), m_n(n) {}
  std::size_t size() const { return m_n; }
  bool empty() const { return m_n == 0; }
  std::string_view operator[](std::size_t i) const { return m_p[i]; }
  const std::string_view* begin() const { return m_p; }
  const std::string_view* end() const { return m_p + m_n; }

private:
  const std::string_view* m_p;
  std::size_t m_n;
};

/// A bulk data entry with its continuations folded in.
///
/// Fields are numbered as in pyNastran and in error messages: field(0) is the
/// card name (NASTRAN field 1 of the first line); field(1..8) are NASTRAN fields
/// 2-9 of the first line; field(9..16) fields 2-9 of the first continuation, and
/// so on. Continuation markers (field 10 and field 1 of continuations) are dropped.
/// Texts are trimmed and upper-cased; trailing blank fields are removed. The texts
/// live in the owning Deck's arena: a Card is valid as long as its Deck.
struct Card {
  std::string name;  ///< upper case, without the large-field '*'
  FieldFormat format = FieldFormat::Small;
  /// Set when the card's values were replaced; then `values` holds them and the
  /// writer formats the card anew instead of copying the original text.
  bool modified = false;
  std::uint32_t file = 0;   ///< index into Deck::files
  std::uint32_t line = 0;   ///< 1-based line of the first physical line
  std::uint32_t begin = 0;  ///< byte span [begin, end) of the original text in its file
  std::uint32_t end = 0;
  std::vector<FieldValue> values;  ///< when modified: values[0] is the name
  /// The fields as read, kept when the card is modified so unchanged values keep their text.
  std::vector<std::string_view> original_fields;
  /// Free-field replication (a "=" or "=(n)" line, deck_reader.cpp): the index of the
  /// card the chain of replicated cards starts from, set on that card and on every
  /// card generated from it; -1 otherwise. Each generated card is derived from the one
  /// before it, so the writer rewrites the whole chain when one of its cards changes.
  std::int32_t replication_root = -1;

  /// Number of fields including the name.
  std::size_t size() const { return m_nfields; }
  /// Field text, "" beyond the last field.
  std::string_view field(std::size_t i) const { return i < m_nfields ? m_fields[i] : std::string_view(); }
  FieldList fields() const { return {m_fields, m_nfields}; }
  /// 1-based source line holding field i.
  std::uint32_t line_of(std::size_t i) const;

  // Set by the reader and Deck (arena storage).
  const std::string_view* m_fields = nullptr;
  std::uint32_t m_nfields = 0;
  std::uint32_t m_nrows = 0;
  /// Physical lines: (1-based line, index of its first field).
  const std::pair<std::uint32_t, std::uint32_t>* m_rows = nullptr;
};

}  // namespace ssid::formats
