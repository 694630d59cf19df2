#include "formats/bulk_model.hpp"

#include <functional>
#include <unordered_map>

namespace ssid::formats {

namespace {

using ParseFn = void (*)(const FieldReader&, std::size_t card, BulkModel&);

template <typename T, T (*Parse)(const FieldReader&), std::vector<T> BulkModel::*Member>
void add(const FieldReader& r, std::size_t card, BulkModel& m) {
  T v = Parse(r);
  v.card = card;
  (m.*Member).push_back(std::move(v));
}

const std::unordered_map<std::string, ParseFn>& parsers() {
  static const std::unordered_map<std::string, ParseFn> table = {
      {"GRID", add<Grid, parse_grid, &BulkModel::grids>},
      {"CROD", add<Crod, parse_crod, &BulkModel::crods>},
  };
  return table;
}

Problem error_at(const Deck& deck, const Card& card, std::size_t field, const std::string& msg) {
  return {Problem::Severity::Error, deck.location(card, field), msg};
}

}  // namespace

bool is_supported_card(const std::string& name) { return parsers().count(name) > 0; }

BulkModel parse_bulk(const Deck& deck) {
  BulkModel m;
  const auto& table = parsers();
  // Decks come in runs of one card type: remember the last lookup.
  const std::string* last_name = nullptr;
  ParseFn fn = nullptr;
  std::size_t* counter = nullptr;
  for (std::size_t i = 0; i < deck.cards.size(); ++i) {
    const Card& c = deck.cards[i];
    if (!last_name || *last_name != c.name) {
      auto it = table.find(c.name);
      fn = it == table.end() ? nullptr : it->second;
      counter = fn ? &m.supported[c.name] : &m.unsupported[c.name];
      last_name = &c.name;
    }
    ++*counter;
    if (!fn) continue;
    try {
      fn(FieldReader(deck, c), i, m);
    } catch (const ParseError& e) {
      m.problems.push_back({Problem::Severity::Error, e.where(), e.detail()});
    }
  }
  return m;
}

void resolve(const Deck& deck, BulkModel& m) {
  std::unordered_map<std::int64_t, std::size_t> grid_index;
  for (const Grid& g : m.grids) {
    auto [it, fresh] = grid_index.emplace(g.id, g.card);
    if (!fresh)
      m.problems.push_back(error_at(deck, deck.cards[g.card], 1,
                                    "duplicate GRID " + std::to_string(g.id) + " (first defined at " +
                                        deck.location(deck.cards[it->second]).str() + ")"));
  }
  auto need_grid = [&](std::int64_t gid, const Card& by, std::size_t field, const std::string& by_label) {
    if (!grid_index.count(gid))
      m.problems.push_back(error_at(deck, by, field, "GRID " + std::to_string(gid) + " required by " + by_label + " does not exist"));
  };
  for (const Crod& c : m.crods) {
    const Card& card = deck.cards[c.card];
    std::string lbl = "CROD " + std::to_string(c.eid);
    need_grid(c.g1, card, 3, lbl);
    need_grid(c.g2, card, 4, lbl);
  }
}

}  // namespace ssid::formats
