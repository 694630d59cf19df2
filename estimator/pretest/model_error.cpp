#include "estimator/pretest/model_error.hpp"

#include <algorithm>
#include <fmt/format.h>
#include <map>
#include <random>
#include <vector>

#include "formats/bulk_model.hpp"
#include "formats/card_traits.hpp"
#include "formats/parse_error.hpp"

namespace ssid::estimator::pretest {

AreaPerturbation perturb_strut_areas(formats::Deck& deck, std::uint64_t seed, double change) {
  if (!(change > 0 && change < 1))
    throw formats::InputError(fmt::format("area perturbation: change {} (expected in (0, 1))", change));
  const formats::BulkModel bulk = formats::resolved_bulk(deck, "area perturbation");
  std::map<std::int64_t, const formats::Prod*> prods;
  std::map<std::int64_t, const formats::Pbar*> pbars;
  for (const auto& p : bulk.prods) prods[p.pid] = &p;
  for (const auto& p : bulk.pbars) pbars[p.pid] = &p;
  // The largest property id, over the card traits' property space (as the deck
  // editor finds its fresh ids), so a new property card never reuses an id.
  std::int64_t max_pid = 0;
  for (const formats::CardTraits& t : formats::card_traits())
    if (t.each_id && t.space == formats::IdSpace::Property)
      t.each_id(bulk, [&max_pid](std::int64_t id, std::size_t) { max_pid = std::max(max_pid, id); });

  enum class Kind { Crod, Conrod, Cbar };
  std::vector<std::pair<Kind, std::size_t>> struts;
  for (std::size_t i = 0; i < bulk.crods.size(); ++i) struts.emplace_back(Kind::Crod, i);
  for (std::size_t i = 0; i < bulk.conrods.size(); ++i) struts.emplace_back(Kind::Conrod, i);
  for (std::size_t i = 0; i < bulk.cbars.size(); ++i) struts.emplace_back(Kind::Cbar, i);
  if (struts.empty()) throw formats::InputError("area perturbation: the deck has no CROD, CONROD or CBAR");

  // Fisher–Yates with our own index mapping (std::uniform_int_distribution differs between libraries).
  std::mt19937_64 rng(seed);
  for (std::size_t i = struts.size() - 1; i > 0; --i) std::swap(struts[i], struts[rng() % (i + 1)]);

  AreaPerturbation out;
  out.struts = static_cast<std::int64_t>(struts.size());
  const std::size_t third = struts.size() / 3;
  std::int64_t next_pid = max_pid + 1;
  // The element gets a copy of its property of its own, with A scaled.
  auto own_property = [&](auto element, const auto& properties, const char* element_name, const char* property_name,
                          auto write_property, auto write_element, double factor) {
    const auto it = properties.find(element.pid);
    if (it == properties.end())
      throw formats::InputError(fmt::format("area perturbation: {} {} refers to {} {}, which is missing", element_name,
                                            element.eid, property_name, element.pid));
    auto p = *it->second;
    p.pid = next_pid++;
    p.a *= factor;
    deck.append_card(0, property_name, write_property(p));
    element.pid = p.pid;
    element.pid_blank = false;
    deck.set_values(element.card, write_element(element));
  };
  for (std::size_t s = 0; s < 2 * third; ++s) {
    const double factor = s < third ? 1 - change : 1 + change;
    ++(s < third ? out.decreased : out.increased);
    const auto [kind, i] = struts[s];
    if (kind == Kind::Crod) {
      own_property(bulk.crods[i], prods, "CROD", "PROD", formats::write_prod, formats::write_crod, factor);
    } else if (kind == Kind::Conrod) {
      formats::Conrod c = bulk.conrods[i];
      c.a *= factor;
      deck.set_values(c.card, formats::write_conrod(c));
    } else {
      own_property(bulk.cbars[i], pbars, "CBAR", "PBAR", formats::write_pbar, formats::write_cbar, factor);
    }
  }
  return out;
}

}  // namespace ssid::estimator::pretest
