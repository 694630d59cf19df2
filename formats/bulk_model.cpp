#include "formats/bulk_model.hpp"

#include "formats/bulk_catalogue.hpp"
#include "formats/card_traits.hpp"
#include "formats/resolve_context.hpp"
#include "formats/nastran_number.hpp"

#include <algorithm>
#include <array>
#include <map>
#include <unordered_map>

namespace ssid::formats {

using detail::error_at;
using detail::label;

namespace {

/// The typed cards' entries by name (DMIG included: counted, read elsewhere).
const std::unordered_map<std::string, const CardTraits*>& parsers() {
  static const std::unordered_map<std::string, const CardTraits*> table = [] {
    std::unordered_map<std::string, const CardTraits*> m;
    for (const CardTraits& t : card_traits())
      if (t.typed())
        for (const std::string& name : t.names) m.emplace(name, &t);
    return m;
  }();
  return table;
}

/// Only one BAROR/BEAMOR (GRDSET) is allowed; returns the first, reports the others.
template <typename T>
const T* single(const Deck& deck, const std::vector<T>& v, const char* name, std::vector<Problem>& problems) {
  for (std::size_t k = 1; k < v.size(); ++k)
    problems.push_back(error_at(deck, deck.cards[v[k].card], 0,
                                std::string("more than one ") + name + " (first at " +
                                    deck.location(deck.cards[v[0].card]).str() + ")"));
  return v.empty() ? nullptr : &v[0];
}

void apply_defaults(const Deck& deck, BulkModel& m) {
  if (const Grdset* grdset = single(deck, m.grdsets, "GRDSET", m.problems))
    for (Grid& g : m.grids) apply_grdset(g, *grdset);
  const Baror* baror = single(deck, m.barors, "BAROR", m.problems);
  for (Cbar& c : m.cbars)
    if (!apply_baror(c, baror))
      m.problems.push_back(error_at(deck, deck.cards[c.card], 5,
                                    label(deck, c.card) + ": orientation (fields 6-8) blank and no BAROR gives one"));
  const Beamor* beamor = single(deck, m.beamors, "BEAMOR", m.problems);
  for (Cbeam& c : m.cbeams)
    if (!apply_beamor(c, beamor))
      m.problems.push_back(error_at(deck, deck.cards[c.card], 5,
                                    label(deck, c.card) + ": orientation (fields 6-8) blank and no BEAMOR gives one"));
}

}  // namespace

bool is_supported_card(const std::string& name) { return parsers().count(name) > 0; }

std::vector<std::string> supported_card_names() {
  std::vector<std::string> names;
  for (const auto& [name, traits] : parsers()) names.push_back(name);
  std::sort(names.begin(), names.end());
  return names;
}

namespace {
/// "unknown card name CRDO — did you mean CROD?" (NASTRAN: USER FATAL MESSAGE 307).
/// The text is made once per name (`made`): a garbage file can hold a million cards.
Problem unknown_card(const Deck& deck, const Card& c, std::unordered_map<std::string, std::string>& made) {
  auto [it, fresh] = made.try_emplace(c.name);
  if (fresh) {
    it->second = "unknown card name " + c.name;
    if (auto near = nearest_bulk_entry_name(c.name)) it->second += " — did you mean " + *near + "?";
    else it->second += " (not a NASTRAN bulk data entry)";
  }
  return error_at(deck, c, 0, it->second);
}
}  // namespace

BulkModel parse_bulk(const Deck& deck) {
  BulkModel m;
  const auto& table = parsers();
  // Decks come in runs of one card type: remember the last lookup.
  const std::string* last_name = nullptr;
  const CardTraits* traits = nullptr;
  bool known = false;  ///< the name is a bulk data entry (typed or kept verbatim)
  std::unordered_map<std::string, std::string> unknown_messages;
  std::size_t* counter = nullptr;
  for (std::size_t i = 0; i < deck.cards.size(); ++i) {
    const Card& c = deck.cards[i];
    if (!last_name || *last_name != c.name) {
      auto it = table.find(c.name);
      traits = it == table.end() ? nullptr : it->second;
      counter = traits ? &m.supported[c.name] : &m.unsupported[c.name];
      known = traits || is_bulk_entry_name(c.name);
      last_name = &c.name;
    }
    ++*counter;
    if (!traits) {
      if (!known) m.problems.push_back(unknown_card(deck, c, unknown_messages));
      continue;
    }
    try {
      traits->parse(FieldReader(deck, c), i, m);
    } catch (const ParseError& e) {
      m.problems.push_back({Problem::Severity::Error, e.where(), e.detail()});
    }
  }
  apply_defaults(deck, m);
  return m;
}

std::map<std::size_t, std::vector<FieldValue>> write_bulk(const BulkModel& m) {
  std::map<std::size_t, std::vector<FieldValue>> out;
  for (const CardTraits& t : card_traits())
    if (t.write) t.write(m, out);
  return out;
}

namespace {

using detail::IdRegistry;
using detail::ResolveContext;

/// Defines every id of `space`: the typed cards in table order, then the cards
/// kept verbatim (their field 2), in deck order.
void fill_space(const Deck& deck, const BulkModel& m, IdSpace space, ResolveContext& ctx) {
  IdRegistry& ids = ctx.ids(space);
  std::unordered_map<std::string, bool> verbatim;  // name -> repeats allowed
  for (const CardTraits& t : card_traits()) {
    if (t.space != space) continue;
    if (!t.typed()) {
      for (const std::string& n : t.names) verbatim.emplace(n, t.repeats_allowed);
      continue;
    }
    if (t.each_id) t.each_id(m, [&](std::int64_t id, std::size_t card) { ids.define(id, card, t.repeats_allowed); });
  }
  if (verbatim.empty()) return;
  for (std::size_t i = 0; i < deck.cards.size(); ++i) {
    const Card& c = deck.cards[i];
    auto it = verbatim.find(c.name);
    if (it == verbatim.end()) continue;
    if (auto id = parse_integer(c.field(1))) ids.define(*id, i, it->second);
  }
}

/// The scalar points scalar elements define by naming them (SPOINT remark 2):
/// an end with component 0 or blank that no GRID, SPOINT or EPOINT defines.
/// Typed cards give their G, C pairs (CELAS1-4, CMASS1-4; the scalar-point forms
/// with C = 0); cards kept verbatim (CDAMPi) are read by their ScalarConnection
/// (G1 C1 G2 C2 in fields 4-7, or S1 S2 in fields 4-5). Each becomes a scalar
/// point of the model (BulkModel::implied_spoints).
void define_implied_spoints(const Deck& deck, BulkModel& m, IdRegistry& grids) {
  std::map<std::int64_t, std::size_t> implied;  // id -> the first card naming it
  auto end = [&](std::int64_t g, std::int64_t c, std::size_t card) {
    if (g > 0 && c == 0 && !grids.find(g)) {
      auto [it, fresh] = implied.emplace(g, card);
      if (!fresh && card < it->second) it->second = card;
    }
  };
  std::unordered_map<std::string, ScalarConnection> verbatim;
  for (const CardTraits& t : card_traits()) {
    if (t.each_scalar_end) t.each_scalar_end(m, end);
    if (!t.typed() && t.scalar_connection != ScalarConnection::None)
      for (const std::string& n : t.names) verbatim.emplace(n, t.scalar_connection);
  }
  auto field_id = [&](const Card& c, std::size_t i) -> std::int64_t {
    auto v = parse_integer(c.field(i));
    return v ? *v : 0;
  };
  for (std::size_t i = 0; i < deck.cards.size(); ++i) {
    const Card& c = deck.cards[i];
    auto it = verbatim.find(c.name);
    if (it == verbatim.end()) continue;
    if (it->second == ScalarConnection::GridComponentPairs) {
      end(field_id(c, 3), field_id(c, 4), i);
      end(field_id(c, 5), field_id(c, 6), i);
    } else {
      end(field_id(c, 3), 0, i);
      end(field_id(c, 4), 0, i);
    }
  }
  m.implied_spoints.clear();
  for (const auto& [id, card] : implied) {
    m.implied_spoints.push_back(id);
    grids.define(id, card);
  }
}

}  // namespace

void resolve(const Deck& deck, BulkModel& m) {
  ResolveContext ctx(deck, m.problems);

  // The model's id spaces first (grids, the element families, properties,
  // materials, coordinate systems): every reference may point into them.
  for (std::size_t s = 0; s < kIdSpaceCount; ++s) {
    const auto space = static_cast<IdSpace>(s);
    if (!is_model_space(space)) continue;
    fill_space(deck, m, space, ctx);
    if (space == IdSpace::GridPoint) define_implied_spoints(deck, m, ctx.ids(space));
  }

  // References to coordinate systems (and CORD2 RID chains), then every other
  // reference and check, card type by card type in table order. A set space
  // (SPC, SPCADD, methods, design model) is filled at the first type of its own.
  for (const CardTraits& t : card_traits())
    if (t.resolve) t.resolve(m, ctx, true);
  std::array<bool, kIdSpaceCount> filled{};
  for (const CardTraits& t : card_traits()) {
    const auto s = static_cast<std::size_t>(t.space);
    if (t.space != IdSpace::None && !is_model_space(t.space) && !filled[s]) {
      fill_space(deck, m, t.space, ctx);
      filled[s] = true;
    }
    if (t.resolve) t.resolve(m, ctx, false);
  }
}

BulkModel resolved_bulk(const Deck& deck, const std::string& who, std::vector<std::string>* warnings) {
  BulkModel model = parse_bulk(deck);
  resolve(deck, model);
  constexpr std::size_t kShown = 20;
  std::string errors;
  std::size_t count = 0;
  const std::vector<Problem>* lists[] = {&deck.problems, &model.problems};
  for (const auto* list : lists)
    for (const auto& p : *list) {
      if (p.severity != Problem::Severity::Error) {
        if (warnings) warnings->push_back(p.str());
      } else if (++count <= kShown) {
        errors += "\n  " + p.str();
      }
    }
  if (count)
    throw InputError((who.empty() ? "" : who + ": ") + std::to_string(count) + " error(s) in the deck; nothing assembled:" +
                     errors + (count > kShown ? "\n  ... and " + std::to_string(count - kShown) + " more" : ""));
  return model;
}

}  // namespace ssid::formats
