#pragma once
/// \file point.hpp
/// Concentrated and scalar elements: CONM2, CMASS1/2 and CELAS1/2 (scalar,
/// grounded or between two DOFs), CBUSH (element-axis springs K1..K6).
#include <Eigen/Core>

#include "translators/elements/element_types.hpp"

namespace ssid::translators::elements {

// ---------------------------------------------------------------- CONM2
/// CONM2 values, resolved by the caller to basic:
///  - `offset`: vector from the grid to the centre of gravity in basic
///    (CID ≥ 0: the card's X rotated from CID's frame at the grid; CID = −1:
///    X minus the grid position),
///  - `inertia_frame`: columns are the axes (in basic) in which I11..I33 are
///    given (the CID frame; identity for CID = −1 or 0),
///  - `t`: the grid's displacement frame (GRID CD).
/// Inertia about the CG, as the QRG writes it:
///   I = [I11 −I21 −I31; −I21 I22 −I32; −I31 −I32 I33],
///   I11 = ∫(x2² + x3²) dm, I21 = ∫ x1 x2 dm, …
struct Conm2 {
  double mass = 0;
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();
  double i11 = 0, i21 = 0, i22 = 0, i31 = 0, i32 = 0, i33 = 0;
  Eigen::Matrix3d inertia_frame = Eigen::Matrix3d::Identity();
  Eigen::Matrix3d t = Eigen::Matrix3d::Identity();
};

enum class Conm2Param { Mass, I11, I21, I22, I31, I32, I33 };

/// 6 x 6 mass at the grid in its displacement frame:
///   M_cg = diag(m I3, R I Rᵀ),  S = [I −[r]×; 0 I]  (u_cg = u + θ × r),
///   M = T6ᵀ Sᵀ M_cg S T6,  T6 = blockdiag(t, t).
Matrix6d conm2_matrix(const Conm2& c);
/// ∂M/∂p: M is linear in m and each Iij, so this is M with that value 1 and
/// the others 0.
Matrix6d conm2_derivative(const Conm2& c, Conm2Param which);

// ---------------------------------------------------------------- scalars
/// CELAS1/2 stiffness or CMASS1/2 mass `value` between two DOFs: the 2 x 2
/// [v −v; −v v] on (DOF1, DOF2); when one terminal is grounded (blank grid or
/// component 0), the 1 x 1 [v] on the other. Its derivative with respect to
/// the value is the same matrix with v = 1.
Eigen::MatrixXd scalar_element_matrix(double value, bool grounded);

// ---------------------------------------------------------------- CBUSH
/// CBUSH geometry in basic. `axes`: rows are the element x, y, z in basic —
/// from bar_element_axes-like rules with v (bush_axes_from_vector) or the CID
/// system's axes (the caller evaluates them at GA for a curvilinear CID).
/// `s`: spring location along GA–GB (S field, default 0.5). Grounded
/// (GB blank): the spring acts at GA.
struct BushGeometry {
  GridPair grids;
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();
  double s = 0.5;
  bool grounded = false;
};

/// CBAR-like frame: x from GA to GB, v in the x–y plane. Throws
/// std::invalid_argument for coincident grids (use CID) or v parallel to x.
Eigen::Matrix3d bush_axes_from_vector(const Eigen::Vector3d& xa, const Eigen::Vector3d& xb,
                                      const Eigen::Vector3d& v);

/// Stiffness from k = (K1..K6) in the element frame, acting on the relative
/// motion at the spring point p = xa + s (xb − xa), each grid carried there
/// rigidly:  Δ = E (S_b u_b − S_a u_a),  K = [−S_a S_b]ᵀ Eᵀ diag(k) E [−S_a S_b]
/// with E = blockdiag(axes, axes), S = [I −[p − x]×; 0 I] blockdiag(t, t).
/// Returns 12 x 12 (GA then GB), or 6 x 6 on GA when grounded. Rigid-body
/// motion of the two grids is strain-free whatever their distance.
Eigen::MatrixXd bush_stiffness(const BushGeometry& g, const Eigen::Matrix<double, 6, 1>& k);
/// ∂K/∂Ki (i = 1..6): linear, the stiffness with k = e_i.
Eigen::MatrixXd bush_derivative(const BushGeometry& g, int i);

}  // namespace ssid::translators::elements
