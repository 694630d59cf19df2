#include "formats/field_reader.hpp"

#include "formats/nastran_number.hpp"

namespace ssid::formats {

std::string FieldReader::label() const {
  std::string_view id = m_card.field(1);
  return id.empty() ? m_card.name : m_card.name + " " + std::string(id);
}

void FieldReader::fail(std::size_t i, const char* name, const std::string& expected) const {
  // Field number as NASTRAN counts it: 2-9 within each (8-field) row.
  std::size_t row = i == 0 ? 0 : (i - 1) / 8;
  std::size_t nfield = i == 0 ? 1 : (i - 1) % 8 + 2;
  std::string where = label() + (row > 0 ? " continuation " + std::to_string(row) : "") + " field " +
                      std::to_string(nfield) + " (" + name + ")";
  std::string got(m_card.field(i));
  throw ParseError(m_deck.location(m_card, i),
                   where + ": expected " + expected + ", got " + (got.empty() ? "blank" : "\"" + got + "\""));
}

void FieldReader::fail_card(const std::string& message, std::size_t i) const {
  throw ParseError(m_deck.location(m_card, i), label() + ": " + message);
}

std::int64_t FieldReader::integer(std::size_t i, const char* name) const {
  auto v = parse_integer(m_card.field(i));
  if (!v) fail(i, name, "integer");
  return *v;
}

std::int64_t FieldReader::integer_or(std::size_t i, const char* name, std::int64_t d) const {
  return blank(i) ? d : integer(i, name);
}

std::optional<std::int64_t> FieldReader::integer_or_blank(std::size_t i, const char* name) const {
  if (blank(i)) return std::nullopt;
  return integer(i, name);
}

std::int64_t FieldReader::id(std::size_t i, const char* name) const {
  auto v = parse_integer(m_card.field(i));
  if (!v) fail(i, name, "integer");
  if (*v <= 0) fail(i, name, "positive integer (an id)");
  return *v;
}

std::int64_t FieldReader::id_or(std::size_t i, const char* name, std::int64_t d) const {
  return blank(i) ? d : id(i, name);
}

double FieldReader::real(std::size_t i, const char* name) const {
  auto v = parse_real(m_card.field(i));
  if (!v) fail(i, name, "real");
  return *v;
}

double FieldReader::real_or(std::size_t i, const char* name, double d) const {
  return blank(i) ? d : real(i, name);
}

std::optional<double> FieldReader::real_or_blank(std::size_t i, const char* name) const {
  if (blank(i)) return std::nullopt;
  return real(i, name);
}

std::string FieldReader::text(std::size_t i, const char* name) const {
  if (blank(i)) fail(i, name, "a name");
  return std::string(m_card.field(i));
}

std::string FieldReader::text_or(std::size_t i, const char* name, const std::string& d) const {
  return blank(i) ? d : std::string(m_card.field(i));
}

std::string FieldReader::components(std::size_t i, const char* name, bool allow_blank) const {
  std::string s(m_card.field(i));
  if (s.empty()) {
    if (allow_blank) return s;
    fail(i, name, "components (digits 1-6)");
  }
  if (s == "0") return s;
  bool seen[7] = {};
  for (char c : s) {
    if (c < '1' || c > '6' || seen[c - '0']) fail(i, name, "components (digits 1-6, each at most once)");
    seen[c - '0'] = true;
  }
  return s;
}

std::string FieldReader::choice(std::size_t i, const char* name, std::initializer_list<const char*> allowed,
                                const char* dflt) const {
  if (blank(i)) {
    if (dflt) return dflt;
  } else {
    for (const char* a : allowed)
      if (m_card.field(i) == a) return a;
  }
  std::string list;
  for (const char* a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
  fail(i, name, "one of " + list);
}

void FieldReader::at_most(std::size_t n) const {
  if (m_card.size() > n)
    fail_card("too many fields (" + m_card.name + " has " + std::to_string(n - 1) + " data fields)", n);
}

bool FieldReader::is_real(std::size_t i) const {
  return !blank(i) && !is_integer(i) && parse_real(m_card.field(i)).has_value();
}

bool FieldReader::is_integer(std::size_t i) const { return parse_integer(m_card.field(i)).has_value(); }

}  // namespace ssid::formats
