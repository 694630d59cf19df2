#include "translators/assembly/model_geometry.hpp"

#include <algorithm>
#include <map>

namespace ssid::translators {

std::string card_label(const formats::Deck& deck, std::size_t card) {
  const auto& c = deck.cards.at(card);
  std::string id = c.size() > 1 ? std::string(c.field(1)) : std::string();
  return deck.location(c).str() + ": " + c.name + (id.empty() ? "" : " " + id);
}

namespace {

CoordType coord_type(formats::CoordKind k) {
  switch (k) {
    case formats::CoordKind::Cylindrical: return CoordType::Cylindrical;
    case formats::CoordKind::Spherical: return CoordType::Spherical;
    default: return CoordType::Rectangular;
  }
}

Eigen::Vector3d vec(const std::array<double, 3>& a) { return {a[0], a[1], a[2]}; }

}  // namespace

ModelGeometry::ModelGeometry(const formats::Deck& deck, const formats::BulkModel& model) {
  std::vector<CoordDefinition> defs;
  for (const auto& c : model.cord2s)
    defs.push_back({static_cast<long>(c.cid), static_cast<long>(c.rid), coord_type(c.kind), vec(c.a), vec(c.b), vec(c.c),
                    card_label(deck, c.card)});
  try {
    m_systems = CoordSystems(defs);
  } catch (const std::exception& e) {
    throw ModelError(e.what());
  }

  // Grids and scalar points share one id space and are sequenced by id.
  std::map<std::int64_t, const formats::Grid*> grids;
  std::map<std::int64_t, bool> points;  // id -> is grid
  for (const auto& g : model.grids) {
    grids[g.id] = &g;
    points[g.id] = true;
  }
  for (const auto& s : model.spoints)
    for (auto id : s.ids) points.emplace(id, false);
  for (auto id : model.implied_spoints) points.emplace(id, false);
  for (const auto& [id, is_grid] : points) {
    if (!is_grid) {
      m_spoint_dof[id] = m_gset.add({id, 0});
      continue;
    }
    const formats::Grid& g = *grids[id];
    GridPoint p;
    p.id = id;
    p.cp = g.cp;
    p.cd = g.cd;
    p.ps = g.ps;
    p.card = g.card;
    const std::string who = card_label(deck, g.card);
    try {
      p.x = m_systems.position_to_basic(static_cast<long>(g.cp), vec(g.x));
      p.frame = m_systems.displacement_frame(static_cast<long>(g.cd), p.x);
    } catch (const std::out_of_range& e) {
      throw ModelError(who + ": " + e.what());
    }
    for (int c = 0; c < 6; ++c) p.dofs[static_cast<std::size_t>(c)] = m_gset.add({id, c + 1});
    m_grid_index[id] = m_grids.size();
    m_grids.push_back(p);
  }
}

const GridPoint& ModelGeometry::grid(std::int64_t id, const std::string& who) const {
  auto it = m_grid_index.find(id);
  if (it == m_grid_index.end()) {
    if (is_scalar_point(id)) throw ModelError(who + ": point " + std::to_string(id) + " is a scalar point, a GRID is required");
    throw ModelError(who + ": GRID " + std::to_string(id) + " does not exist");
  }
  return m_grids[it->second];
}

std::size_t ModelGeometry::dof(std::int64_t point, int component, const std::string& who) const {
  if (auto s = m_spoint_dof.find(point); s != m_spoint_dof.end()) {
    if (component > 1) throw ModelError(who + ": scalar point " + std::to_string(point) + " has no component " + std::to_string(component));
    return s->second;
  }
  const GridPoint& g = grid(point, who);
  if (component < 1 || component > 6)
    throw ModelError(who + ": GRID " + std::to_string(point) + " component " + std::to_string(component) + " (1-6 expected)");
  return g.dofs[static_cast<std::size_t>(component - 1)];
}

}  // namespace ssid::translators
