#pragma once
/// \file field_reader.hpp
/// Typed field readers: the only place field errors are raised.
///
/// Each reader takes the field index (as in Card::fields: 1 = NASTRAN field 2 of
/// the first line) and the NASTRAN field name, so every error explains itself:
/// `truss.bdf:120: CROD 10 field 4 (G1): expected integer, got "1.5"`.
#include <cstdint>
#include <initializer_list>
#include <optional>
#include <string>

#include "formats/deck.hpp"

namespace ssid::formats {

class FieldReader {
public:
  FieldReader(const Deck& deck, const Card& card) : m_deck(deck), m_card(card) {}

  const Card& card() const { return m_card; }
  std::size_t size() const { return m_card.size(); }
  bool blank(std::size_t i) const { return m_card.field(i).empty(); }

  std::int64_t integer(std::size_t i, const char* name) const;
  std::int64_t integer_or(std::size_t i, const char* name, std::int64_t default_value) const;
  std::optional<std::int64_t> integer_or_blank(std::size_t i, const char* name) const;
  /// Integer that must be > 0 (ids).
  std::int64_t id(std::size_t i, const char* name) const;
  std::int64_t id_or(std::size_t i, const char* name, std::int64_t default_value) const;

  /// A real; an integer is accepted where a real is allowed.
  double real(std::size_t i, const char* name) const;
  double real_or(std::size_t i, const char* name, double default_value) const;
  std::optional<double> real_or_blank(std::size_t i, const char* name) const;

  std::string text(std::size_t i, const char* name) const;
  std::string text_or(std::size_t i, const char* name, const std::string& default_value) const;

  /// NASTRAN component list ("123456" digits, each once, 0 allowed alone); returned as given.
  std::string components(std::size_t i, const char* name, bool allow_blank = false) const;

  /// One of the `allowed` words (upper case); `dflt` when blank (nullptr: required).
  std::string choice(std::size_t i, const char* name, std::initializer_list<const char*> allowed,
                     const char* dflt) const;

  /// Throws "too many fields" when the card has fields at index >= n.
  void at_most(std::size_t n) const;

  /// True when field i holds a real (not an integer, not text).
  bool is_real(std::size_t i) const;

  /// True when field i holds an integer (e.g. CBAR field 6: G0 rather than X1).
  bool is_integer(std::size_t i) const;

  /// Throws the standard field error: "... field N (NAME): expected WHAT, got "TEXT"".
  [[noreturn]] void fail(std::size_t i, const char* name, const std::string& expected) const;
  /// Throws a card-level error that is not about one field's syntax.
  [[noreturn]] void fail_card(const std::string& message, std::size_t i = 0) const;

  /// "CROD 10" — name and first field, for messages.
  std::string label() const;

private:
  const Deck& m_deck;
  const Card& m_card;
};

}  // namespace ssid::formats
