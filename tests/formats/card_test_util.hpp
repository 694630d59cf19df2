#pragma once
// Helpers shared by the typed-card tests: parse one card from text, catch its
// error message, write -> reparse round trips, and golden-file decks.
#include <catch2/catch.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "formats/bulk_model.hpp"
#include "formats/deck.hpp"
#include "formats/deck_writer.hpp"

namespace card_test {

using namespace ssid::formats;

template <typename F>
auto parse_text(const std::string& text, F parse) {
  Deck d = read_deck_text(text, "t.bdf");
  REQUIRE(d.cards.size() == 1);
  return parse(FieldReader(d, d.cards[0]));
}

/// The full message ("t.bdf:1: ...") the parser throws, or "(no error)".
template <typename F>
std::string error_of(const std::string& text, F parse) {
  try {
    parse_text(text, parse);
  } catch (const ParseError& e) {
    return e.what();
  }
  return "(no error)";
}

/// write -> clean small-field text -> parse -> write gives the same values.
template <typename T, typename P, typename W>
void check_roundtrip(const T& x, P parse, W write) {
  std::vector<FieldValue> v1 = write(x);
  std::string text = format_card(std::get<std::string>(v1[0]), v1, FieldFormat::Small);
  INFO(text);
  auto y = parse_text(text, parse);
  CHECK(write(y) == v1);
}

inline std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

/// Golden deck tests/data/cards/<family>.bdf:
///  - read and rendered unchanged, it comes back byte for byte;
///  - parse + resolve give exactly `expected` problems (messages contain them, in order);
///  - every typed card written from scratch (clean small field) matches <family>.out.bdf
///    byte for byte (set SSID_UPDATE_GOLDEN=1 to regenerate, then review the diff);
///  - the deck with every card re-rendered through its writer parses to the same values.
inline void check_golden(const std::string& family, const std::vector<std::string>& expected) {
  namespace fs = std::filesystem;
  const fs::path src = fs::path(SSID_TEST_DATA) / "cards" / (family + ".bdf");
  const fs::path gold = fs::path(SSID_TEST_DATA) / "cards" / (family + ".out.bdf");
  Deck d = read_deck(src.string());
  CHECK(render_file(d, 0) == slurp(src));
  BulkModel m = parse_bulk(d);
  resolve(d, m);
  std::string all;
  for (const auto& p : m.problems) all += p.str() + "\n";
  INFO(all);
  REQUIRE(m.problems.size() == expected.size());
  for (std::size_t k = 0; k < expected.size(); ++k) CHECK_THAT(m.problems[k].message, Catch::Contains(expected[k]));
  CHECK(m.unsupported.empty());

  const auto written = write_bulk(m);
  std::size_t typed = 0;
  for (const auto& [name, n] : m.supported) typed += n;
  CHECK(written.size() == typed);
  std::string fresh;
  for (const auto& [i, v] : written) fresh += format_card(d.cards[i].name, v, FieldFormat::Small);
  if (std::getenv("SSID_UPDATE_GOLDEN")) std::ofstream(gold, std::ios::binary) << fresh;
  CHECK(fresh == slurp(gold));

  for (const auto& [i, v] : written) d.set_values(i, v);
  Deck back = read_deck_text(render_file(d, 0), "back.bdf");
  BulkModel m2 = parse_bulk(back);
  CHECK(write_bulk(m2) == written);
  Deck again = read_deck_text(fresh, "fresh.bdf");
  CHECK(write_bulk(parse_bulk(again)) == written);
}

}  // namespace card_test
