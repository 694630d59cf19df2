#include "translators/weight.hpp"

#include <Eigen/Dense>

#include "translators/constraints.hpp"

namespace ssid::translators {

Eigen::MatrixXd rigid_body_modes(const DofMap& dofs, const std::unordered_map<std::int64_t, Eigen::Vector3d>& positions,
                                 const Eigen::Vector3d& reference) {
  Eigen::MatrixXd D = Eigen::MatrixXd::Zero(static_cast<int>(dofs.size()), 6);
  for (std::size_t i = 0; i < dofs.size(); ++i) {
    const Dof& d = dofs.at(i);
    if (d.component == 0) continue;
    auto it = positions.find(d.point);
    if (it == positions.end()) continue;
    D.row(static_cast<int>(i)) = rigid_body_rows(it->second, reference).row(d.component - 1);
  }
  return D;
}

WeightSummary grid_point_weight(const Eigen::SparseMatrix<double>& Mgg, const DofMap& dofs,
                                const std::unordered_map<std::int64_t, Eigen::Vector3d>& positions,
                                const Eigen::Vector3d& reference) {
  const Eigen::MatrixXd D = rigid_body_modes(dofs, positions, reference);
  WeightSummary w;
  w.M0 = D.transpose() * (Mgg * D);
  const auto& M0 = w.M0;
  w.mass = M0.diagonal().head<3>();
  // CG offsets from the translation–rotation coupling (NASTRAN's MO partition):
  // for mass in x: y = −M0(0,5)/mx, z = M0(0,4)/mx; etc.
  w.cg.setZero();
  if (w.mass(0) != 0) w.cg.row(0) << 0.0, -M0(0, 5) / w.mass(0), M0(0, 4) / w.mass(0);
  if (w.mass(1) != 0) w.cg.row(1) << M0(1, 5) / w.mass(1), 0.0, -M0(1, 3) / w.mass(1);
  if (w.mass(2) != 0) w.cg.row(2) << -M0(2, 4) / w.mass(2), M0(2, 3) / w.mass(2), 0.0;
  // The x coordinate is seen by the y and z masses, etc.
  w.center = reference;
  w.center += Eigen::Vector3d(0.5 * (w.cg(1, 0) + w.cg(2, 0)), 0.5 * (w.cg(0, 1) + w.cg(2, 1)), 0.5 * (w.cg(0, 2) + w.cg(1, 2)));
  // Inertia about the reference, then shifted to the CG (parallel axis, per-direction masses).
  Eigen::Matrix3d I0 = M0.block<3, 3>(3, 3);
  Eigen::Matrix3d shift;
  const Eigen::Vector3d m = w.mass;
  const Eigen::Matrix3d& c = w.cg;
  shift(0, 0) = m(1) * c(1, 2) * c(1, 2) + m(2) * c(2, 1) * c(2, 1);
  shift(1, 1) = m(0) * c(0, 2) * c(0, 2) + m(2) * c(2, 0) * c(2, 0);
  shift(2, 2) = m(0) * c(0, 1) * c(0, 1) + m(1) * c(1, 0) * c(1, 0);
  shift(0, 1) = shift(1, 0) = -m(2) * c(2, 0) * c(2, 1);
  shift(0, 2) = shift(2, 0) = -m(1) * c(1, 0) * c(1, 2);
  shift(1, 2) = shift(2, 1) = -m(0) * c(0, 1) * c(0, 2);
  w.inertia_cg = I0 - shift;
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(w.inertia_cg);
  w.principal = es.eigenvalues();
  return w;
}

}  // namespace ssid::translators
