#pragma once
/// \file element_types.hpp
/// Plain values the element routines take and return. No card structs: the
/// assembly resolves cards (property, material, coordinate systems, G0/offset
/// conventions) into these values, in the basic frame, before calling.
#include <Eigen/Core>

namespace ssid::translators::elements {

using Matrix12d = Eigen::Matrix<double, 12, 12>;
using Matrix6d = Eigen::Matrix<double, 6, 6>;

/// Lumped (NASTRAN's default, PARAM COUPMASS < 0) or coupled (COUPMASS > 0).
enum class MassKind { Lumped, Coupled };

/// MAT1 values. G must already be resolved (MAT1 derives it from E and NU
/// when blank). Units are the deck's; WTMASS is applied by the assembly.
struct Material {
  double e = 0, g = 0, nu = 0, rho = 0;
};

/// Stiffness and mass of a two-grid element: 12 x 12 in the displacement
/// (global) frames of its grids, DOF order (T1 T2 T3 R1 R2 R3) of GA then GB.
struct ElementMatrices {
  Matrix12d k = Matrix12d::Zero();
  Matrix12d m = Matrix12d::Zero();
};

/// The two grids of a line element. Positions in basic; `ta`, `tb` are the
/// displacement frames (GRID CD) as 3 x 3 rotations whose columns are the
/// grid's displacement directions in basic (u_basic = t * u_global).
struct GridPair {
  Eigen::Vector3d xa = Eigen::Vector3d::Zero(), xb = Eigen::Vector3d::Zero();
  Eigen::Matrix3d ta = Eigen::Matrix3d::Identity(), tb = Eigen::Matrix3d::Identity();
};

}  // namespace ssid::translators::elements
