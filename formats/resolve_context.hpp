#pragma once
/// \file resolve_context.hpp
/// Internals of resolve (bulk_model.cpp) shared with the cards' own checks in
/// card_traits.cpp: the id spaces being filled and the list of problems.
#include <array>
#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

#include "formats/card_traits.hpp"
#include "formats/deck.hpp"

namespace ssid::formats::detail {

Problem error_at(const Deck& deck, const Card& card, std::size_t field, const std::string& msg);
Problem warning_at(const Deck& deck, const Card& card, std::size_t field, const std::string& msg);

/// "CBAR 10": the card's name and first field, as written.
std::string label(const Deck& deck, std::size_t card);

/// The definitions of one id space (grids, elements, properties, ...), by id.
class IdRegistry {
public:
  struct Def {
    std::size_t card;         ///< index in Deck::cards
    const std::string* type;  ///< card name
    bool repeatable;          ///< defined by a card whose repeats are no duplicate (SPOINT)
    std::string family;       ///< id_family(space, type): definitions clash only within one
  };

  IdRegistry(const Deck& deck, std::vector<Problem>& problems, IdSpace space)
      : m_deck(deck), m_problems(problems), m_space(space), m_noun(id_space_noun(space)) {}

  /// Adds `id` defined by card `card` (field `field`); a second definition in the
  /// same family (id_family) is a problem, unless both cards allow repeats
  /// (`repeatable`); one in another family is kept beside the first.
  void define(std::int64_t id, std::size_t card, bool repeatable = false, std::size_t field = 1);

  /// The first definition of `id` (the only one outside the property space).
  const Def* find(std::int64_t id) const {
    auto it = m_defs.find(id);
    return it == m_defs.end() ? nullptr : &it->second;
  }

  /// Checks that `id` exists and, when `types` is not empty, that one of its
  /// definitions is one of them.
  /// Messages: "PROD 3 required by CROD 10 does not exist";
  /// "CROD 10 refers to PID 3, which is a PBAR, expected PROD".
  void need(std::int64_t id, const std::vector<std::string>& types, std::size_t by, std::size_t field,
            const char* field_name) const;

private:
  /// Card `card` defines `id` again where `first` did (same family).
  void clash(Def& first, std::int64_t id, std::size_t card, bool repeatable, std::size_t field, std::string family);

  const Deck& m_deck;
  std::vector<Problem>& m_problems;
  IdSpace m_space;
  std::string m_noun;
  std::unordered_map<std::int64_t, Def> m_defs;
  /// Definitions of an id in m_defs from other families (property space only).
  std::unordered_multimap<std::int64_t, Def> m_more;
};

/// What the cards' checks see: the deck, the id spaces, the problem list.
class ResolveContext {
public:
  ResolveContext(const Deck& deck, std::vector<Problem>& problems);

  const Deck& deck() const { return m_deck; }
  IdRegistry& ids(IdSpace space) { return m_spaces[static_cast<std::size_t>(space)]; }
  const IdRegistry& ids(IdSpace space) const { return m_spaces[static_cast<std::size_t>(space)]; }

  /// The reference `ref` from card `card` holds `id`.
  void need(const Reference& ref, std::int64_t id, std::size_t card) const;

  void error(std::size_t card, std::size_t field, const std::string& msg);
  void warning(std::size_t card, std::size_t field, const std::string& msg);
  std::string label(std::size_t card) const { return detail::label(m_deck, card); }

  /// One end of a scalar element or an MPC term: a grid (component 1-6) or a
  /// scalar point (component 0 or blank); `field` is G's, C's is the next.
  void scalar_end(std::int64_t g, std::int64_t c, std::size_t card, std::size_t field, const char* gname);
  /// S1 or S2 of CELAS3/4, CMASS3/4 at `field`: a scalar point only (0: grounded).
  void scalar_point(std::int64_t s, std::size_t card, std::size_t field, const char* sname);

private:
  const Deck& m_deck;
  std::vector<Problem>& m_problems;
  std::vector<IdRegistry> m_spaces;  ///< by IdSpace
};

}  // namespace ssid::formats::detail
