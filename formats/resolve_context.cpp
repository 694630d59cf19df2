#include "formats/resolve_context.hpp"

#include <algorithm>
#include <array>

namespace ssid::formats::detail {

Problem error_at(const Deck& deck, const Card& card, std::size_t field, const std::string& msg) {
  return {Problem::Severity::Error, deck.location(card, field), msg};
}
Problem warning_at(const Deck& deck, const Card& card, std::size_t field, const std::string& msg) {
  return {Problem::Severity::Warning, deck.location(card, field), msg};
}

std::string label(const Deck& deck, std::size_t card) {
  const Card& c = deck.cards[card];
  std::string_view id = c.field(1);
  return id.empty() ? c.name : c.name + " " + std::string(id);
}

void IdRegistry::define(std::int64_t id, std::size_t card, bool repeatable, std::size_t field) {
  const Card& c = m_deck.cards[card];
  std::string family = id_family(m_space, c.name);
  auto it = m_defs.find(id);
  if (it == m_defs.end()) {
    m_defs.emplace(id, Def{card, &c.name, repeatable, std::move(family)});
    return;
  }
  if (it->second.family == family) return clash(it->second, id, card, repeatable, field, std::move(family));
  auto [b, e] = m_more.equal_range(id);
  for (auto m = b; m != e; ++m)
    if (m->second.family == family) return clash(m->second, id, card, repeatable, field, std::move(family));
  m_more.emplace(id, Def{card, &c.name, repeatable, std::move(family)});
}

void IdRegistry::clash(Def& first_def, std::int64_t id, std::size_t card, bool repeatable, std::size_t field,
                       std::string family) {
  if (repeatable && first_def.repeatable) return;
  // Card types are defined in turn, not in deck order: the earlier card is the first definition.
  std::size_t later = card;
  if (card < first_def.card) {
    later = first_def.card;
    first_def = Def{card, &m_deck.cards[card].name, repeatable, std::move(family)};
  }
  const Card& first = m_deck.cards[first_def.card];
  const Card& dup = m_deck.cards[later];
  m_problems.push_back(error_at(m_deck, dup, field,
                                "duplicate " + m_noun + " " + std::to_string(id) + " (" + dup.name +
                                    "; first defined by " + first.name + " at " + m_deck.location(first).str() + ")"));
}

void IdRegistry::need(std::int64_t id, const std::vector<std::string>& types, std::size_t by, std::size_t field,
                      const char* field_name) const {
  std::string expect;
  for (const auto& t : types) expect += (expect.empty() ? "" : "/") + t;
  const Card& c = m_deck.cards[by];
  const Def* d = find(id);
  if (!d) {
    m_problems.push_back(error_at(m_deck, c, field,
                                  (expect.empty() ? m_noun : expect) + " " + std::to_string(id) + " required by " +
                                      label(m_deck, by) + " does not exist"));
    return;
  }
  if (types.empty()) return;
  auto accepted = [&](const Def& def) { return std::find(types.begin(), types.end(), *def.type) != types.end(); };
  if (accepted(*d)) return;
  auto [b, e] = m_more.equal_range(id);
  for (auto m = b; m != e; ++m)
    if (accepted(m->second)) return;
  const std::string msg = label(m_deck, by) + " refers to " + field_name + " " + std::to_string(id) + ", which is a " +
                          *d->type + ", expected " + expect;
  // A material of another type is a warning: NASTRAN checks a material against its use
  // only for the elements of the solution run (MSC Nastran ran pyNastran's bwb_saero_trim
  // with an unused PBEAML on a MAT8, and heat-transfer decks give PROD a MAT4). The
  // assembly refuses an element whose material it cannot use.
  if (m_space == IdSpace::Material)
    m_problems.push_back(warning_at(m_deck, c, field, msg + "; an element using it cannot be assembled"));
  else
    m_problems.push_back(error_at(m_deck, c, field, msg));
}

ResolveContext::ResolveContext(const Deck& deck, std::vector<Problem>& problems) : m_deck(deck), m_problems(problems) {
  m_spaces.reserve(kIdSpaceCount);
  for (std::size_t s = 0; s < kIdSpaceCount; ++s) m_spaces.emplace_back(deck, problems, static_cast<IdSpace>(s));
}
void ResolveContext::need(const Reference& ref, std::int64_t id, std::size_t card) const {
  if (ref.zero_means_none && id <= 0) return;
  ids(ref.space).need(id, ref.expected, card, ref.field, ref.field_name);
}

void ResolveContext::error(std::size_t card, std::size_t field, const std::string& msg) {
  m_problems.push_back(error_at(m_deck, m_deck.cards[card], field, msg));
}

void ResolveContext::warning(std::size_t card, std::size_t field, const std::string& msg) {
  m_problems.push_back(warning_at(m_deck, m_deck.cards[card], field, msg));
}

void ResolveContext::scalar_end(std::int64_t g, std::int64_t c, std::size_t card, std::size_t field,
                                const char* gname) {
  if (g == 0) return;
  IdRegistry& grids = ids(IdSpace::GridPoint);
  grids.need(g, {}, card, field, gname);
  const IdRegistry::Def* d = grids.find(g);
  if (!d) return;
  bool is_spoint = *d->type != "GRID";
  if (is_spoint && c > 0)
    error(card, field + 1,
          label(card) + ": " + gname + " " + std::to_string(g) + " is a scalar point (" + *d->type +
              "), its component must be 0 or blank, got " + std::to_string(c));
  if (!is_spoint && c == 0)
    error(card, field + 1,
          label(card) + ": " + gname + " " + std::to_string(g) + " is a GRID, its component must be 1-6, got blank or 0");
}

void ResolveContext::scalar_point(std::int64_t s, std::size_t card, std::size_t field, const char* sname) {
  if (s == 0) return;
  IdRegistry& grids = ids(IdSpace::GridPoint);
  grids.need(s, {}, card, field, sname);
  const IdRegistry::Def* d = grids.find(s);
  if (d && *d->type == "GRID")
    error(card, field,
          label(card) + ": " + sname + " " + std::to_string(s) + " is a GRID; " + m_deck.cards[card].name +
              " connects scalar points only");
}

}  // namespace ssid::formats::detail
