#pragma once
/// \file dof_map.hpp
/// Degrees of freedom: (grid or scalar point id, component 1-6; 0 for a scalar
/// point) to matrix index and back.
#include <cstdint>
#include <optional>
#include <unordered_map>
#include <vector>

namespace ssid::translators {

struct Dof {
  std::int64_t point = 0;
  int component = 0;  ///< 1-6 for grids, 0 for scalar points
  bool operator==(const Dof& o) const { return point == o.point && component == o.component; }
};

/// Bidirectional map between DOFs and dense indices 0..size()-1.
class DofMap {
public:
  /// Appends a DOF; returns its index. Adding an existing DOF returns its index.
  std::size_t add(Dof d);
  std::optional<std::size_t> find(Dof d) const;
  const Dof& at(std::size_t i) const { return m_dofs.at(i); }
  std::size_t size() const { return m_dofs.size(); }
  const std::vector<Dof>& dofs() const { return m_dofs; }

private:
  static std::int64_t key(Dof d) { return d.point * 8 + d.component; }
  std::vector<Dof> m_dofs;
  std::unordered_map<std::int64_t, std::size_t> m_index;
};

}  // namespace ssid::translators
