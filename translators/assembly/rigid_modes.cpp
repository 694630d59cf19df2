#include "translators/assembly/rigid_modes.hpp"

#include <unordered_map>

#include "translators/constraints.hpp"

namespace ssid::translators {

Eigen::MatrixXd a_set_rigid_body_modes(const FeModel& model) {
  const auto& a_to_g = model.reduction().a_to_g;
  const ModelGeometry& geo = model.geometry();
  std::unordered_map<std::int64_t, const GridPoint*> grid;
  for (const auto& p : geo.grids()) grid[p.id] = &p;
  Eigen::MatrixXd B = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(a_to_g.size()), 6);
  for (std::size_t i = 0; i < a_to_g.size(); ++i) {
    const Dof& d = geo.gset().at(a_to_g[i]);
    if (d.component < 1 || d.component > 6) continue;
    const auto it = grid.find(d.point);
    if (it == grid.end()) continue;
    const GridPoint& p = *it->second;
    // Rows in basic axes, then into the displacement frame: u_cd = frameᵀ u_basic.
    const Eigen::Matrix<double, 6, 6> basic = rigid_body_rows(p.x, Eigen::Vector3d::Zero());
    const int c = d.component - 1, block = c < 3 ? 0 : 3;
    B.row(static_cast<Eigen::Index>(i)) = p.frame.col(c - block).transpose() * basic.middleRows<3>(block);
  }
  return B;
}

}  // namespace ssid::translators
