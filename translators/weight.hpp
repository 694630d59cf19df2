#pragma once
/// \file weight.hpp
/// Grid point weight generator (NASTRAN's GRDPNT output): the rigid-body mass
/// matrix of the g-set mass about a reference point, total mass, centre of
/// gravity and inertia, as NASTRAN prints them.
///
///   D   = rigid-body transformation (g x 6): u_p = u0 + θ0 × (x_p − x_ref)
///   M0  = Dᵀ M_gg D                            (6 x 6 about the reference point)
///   mass in direction i: M0(i,i);  centre of gravity from the coupling terms:
///   x_cg = M0(1,5)... (per direction, NASTRAN's three CG tables), I(S) about the CG,
///   principal inertias I(Q) = eigenvalues of I(S).
/// Units are the deck's (mass × WTMASS as assembled).
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <unordered_map>

#include "translators/dof_map.hpp"

namespace ssid::translators {

struct WeightSummary {
  Eigen::Matrix<double, 6, 6> M0;  ///< rigid-body mass matrix about the reference point
  Eigen::Vector3d mass;            ///< mass in x, y, z
  Eigen::Matrix3d cg;              ///< row i: CG offsets from the reference point seen by the mass in direction i (NASTRAN's table)
  Eigen::Vector3d center;          ///< CG in basic coordinates (each coordinate averaged over the two masses that see it)
  Eigen::Matrix3d inertia_cg;      ///< I(S): inertia about the CG (positive moments, negative products)
  Eigen::Vector3d principal;       ///< I(Q): principal inertias, ascending
};

/// `positions` gives each grid's basic coordinates; `dofs` maps the g-set.
/// Scalar points carry no rigid-body motion and are ignored.
WeightSummary grid_point_weight(const Eigen::SparseMatrix<double>& Mgg, const DofMap& dofs,
                                const std::unordered_map<std::int64_t, Eigen::Vector3d>& positions,
                                const Eigen::Vector3d& reference = Eigen::Vector3d::Zero());

/// The g x 6 rigid-body matrix D about `reference` (rows of scalar points are zero).
Eigen::MatrixXd rigid_body_modes(const DofMap& dofs, const std::unordered_map<std::int64_t, Eigen::Vector3d>& positions,
                                 const Eigen::Vector3d& reference);

}  // namespace ssid::translators
