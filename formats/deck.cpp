#include "formats/deck.hpp"

#include "formats/nastran_number.hpp"

namespace ssid::formats {

namespace {
std::string value_text(const FieldValue& v) {
  if (auto* i = std::get_if<std::int64_t>(&v)) return std::to_string(*i);
  if (auto* d = std::get_if<double>(&v)) return *format_real_exact(*d, 64);
  if (auto* s = std::get_if<std::string>(&v)) return *s;
  return {};
}
}  // namespace

void Deck::set_values(std::size_t card_index, std::vector<FieldValue> values) {
  Card& c = cards.at(card_index);
  if (!c.modified) c.original_fields.assign(c.fields().begin(), c.fields().end());
  auto* f = arena->make_array<std::string_view>(values.size());
  for (std::size_t i = 1; i < values.size(); ++i) f[i] = arena->copy(value_text(values[i]));
  if (!values.empty()) {
    values[0] = c.name;
    f[0] = arena->copy(c.name);
  }
  c.m_fields = f;
  c.m_nfields = static_cast<std::uint32_t>(values.size());
  c.values = std::move(values);
  c.modified = true;
}

std::size_t Deck::append_card(std::size_t file, const std::string& name, std::vector<FieldValue> values,
                              FieldFormat format) {
  Card c;
  c.name = name;
  c.format = format;
  c.file = static_cast<std::uint32_t>(file);
  std::size_t index = cards.size();
  cards.push_back(std::move(c));
  if (values.empty()) values.emplace_back(name);
  set_values(index, std::move(values));
  files.at(file).chunks.push_back({Chunk::Kind::Card, 0, 0, static_cast<std::uint32_t>(index)});
  return index;
}

void Deck::append_text(std::size_t file, const std::string& text) {
  SourceFile& f = files.at(file);
  auto b = static_cast<std::uint32_t>(f.text.size());
  f.text += text;
  f.chunks.push_back({Chunk::Kind::Verbatim, b, static_cast<std::uint32_t>(f.text.size()), 0});
}

Deck new_deck(const std::string& path) {
  Deck d;
  d.files.emplace_back();
  d.files[0].path = path;
  return d;
}

}  // namespace ssid::formats
