#include "translators/dof_map.hpp"

namespace ssid::translators {

std::size_t DofMap::add(Dof d) {
  auto [it, fresh] = m_index.emplace(key(d), m_dofs.size());
  if (fresh) m_dofs.push_back(d);
  return it->second;
}

std::optional<std::size_t> DofMap::find(Dof d) const {
  auto it = m_index.find(key(d));
  if (it == m_index.end()) return std::nullopt;
  return it->second;
}

}  // namespace ssid::translators
