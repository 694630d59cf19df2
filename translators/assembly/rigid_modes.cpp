#include "translators/assembly/rigid_modes.hpp"

#include "translators/constraints.hpp"

namespace ssid::translators {

Eigen::MatrixXd a_set_rigid_body_modes(const FeModel& model) {
  const auto& a_to_g = model.reduction().a_to_g;
  const ModelGeometry& geo = model.geometry();
  Eigen::MatrixXd B = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(a_to_g.size()), 6);
  for (std::size_t i = 0; i < a_to_g.size(); ++i) {
    const Dof& d = geo.gset().at(a_to_g[i]);
    if (d.component < 1 || d.component > 6) continue;
    if (!geo.has_grid(d.point)) continue;
    const GridPoint& p = geo.grid(d.point, "rigid-body modes");
    // Rows in basic axes, then into the displacement frame: u_cd = frameᵀ u_basic.
    const Eigen::Matrix<double, 6, 6> basic = rigid_body_rows(p.x, Eigen::Vector3d::Zero());
    const int c = d.component - 1, block = c < 3 ? 0 : 3;
    B.row(static_cast<Eigen::Index>(i)) = p.frame.col(c - block).transpose() * basic.middleRows<3>(block);
  }
  return B;
}

Eigen::MatrixXd a_set_strain_fields(const FeModel& model) {
  const auto& a_to_g = model.reduction().a_to_g;
  const ModelGeometry& geo = model.geometry();
  // Centred on the grids' mean position, so that the fields are of the model's size
  // rather than of its distance from the basic origin. (Their constant part in an
  // aggregate is a translation: the multilevel solver keeps only what lies outside
  // the rigid-body modes there, AggregationAmg.)
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (const GridPoint& p : geo.grids()) centre += p.x;
  if (!geo.grids().empty()) centre /= static_cast<double>(geo.grids().size());
  Eigen::MatrixXd F = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(a_to_g.size()), 6);
  for (std::size_t i = 0; i < a_to_g.size(); ++i) {
    const Dof& d = geo.gset().at(a_to_g[i]);
    if (d.component < 1 || d.component > 3 || !geo.has_grid(d.point)) continue;  // rotations, scalar points: 0
    const GridPoint& p = geo.grid(d.point, "strain fields");
    const Eigen::Vector3d x = p.x - centre, e = p.frame.col(d.component - 1);
    // e · (E x) for E = sym(e_a e_bᵀ): (e_a x_b + e_b x_a) / 2.
    int col = 0;
    for (int a = 0; a < 3; ++a)
      for (int b = a; b < 3; ++b, ++col) F(static_cast<Eigen::Index>(i), col) = 0.5 * (e(a) * x(b) + e(b) * x(a));
  }
  return F;
}

}  // namespace ssid::translators
