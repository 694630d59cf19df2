#pragma once
/// \file constraints.hpp
/// Multipoint and single-point constraints, and the reduction from the g-set
/// (all grid and scalar DOFs) to the analysis set.
///
/// Every multipoint constraint (MPC cards, RBAR, RBE2, RBE3) is an equation
///   u_d = \sum_j c_j u_j
/// that makes DOF d dependent (NASTRAN's m-set). Single-point constraints
/// (SPC, SPC1, GRID PS, AUTOSPC) fix DOFs to zero (s-set). The remaining DOFs
/// form the analysis set a, and
///   u_g = T u_a,   K_a = T^T K_g T,   M_a = T^T M_g T
/// with T built by substituting dependent DOFs recursively (a dependent may be
/// written in terms of another dependent, as chained rigid elements are).
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <array>
#include <string>
#include <vector>

#include "translators/dof_map.hpp"

namespace ssid::translators {

using SparseMatrix = Eigen::SparseMatrix<double>;

/// u_dependent = sum(coefficient * u_independent).
struct MpcEquation {
  std::size_t dependent = 0;                           ///< g-set index
  std::vector<std::pair<std::size_t, double>> terms;   ///< (g-set index, coefficient)
  std::string source;                                  ///< e.g. "RBE2 100", for messages
};

/// Result of the reduction: the a-set and the transformation u_g = T u_a.
struct Reduction {
  SparseMatrix T;                      ///< g x a
  std::vector<std::size_t> a_to_g;     ///< a-set index -> g-set index
  std::vector<long> g_to_a;            ///< g-set index -> a-set index, or -1 (dependent/constrained)
  std::vector<std::size_t> dependent;  ///< m-set, g indices
  std::vector<std::size_t> constrained;///< s-set, g indices
};

/// Builds T from the MPC equations and the SPC set. Throws std::invalid_argument
/// (with the sources named) when a DOF is made dependent twice, when an SPC
/// constrains a dependent DOF, or when dependencies form a cycle.
Reduction build_reduction(std::size_t g_size, const std::vector<MpcEquation>& mpcs,
                          const std::vector<std::size_t>& spc);

/// T^T A T for a symmetric A (g x g).
SparseMatrix reduce(const SparseMatrix& A, const Reduction& r);

/// Rigid-body relations of a set of grids: the 6 DOFs of grid p in terms of
/// the 6 rigid-body parameters (translation u0 and rotation θ0 at point x0):
///   u_p = u0 + θ0 × (x_p − x0),  θ_p = θ0.
/// Rows are (tx ty tz rx ry rz) of p; 6 x 6.
Eigen::Matrix<double, 6, 6> rigid_body_rows(const Eigen::Vector3d& xp, const Eigen::Vector3d& x0);

/// Equations of a rigid element given as independent and dependent DOF lists:
/// all listed DOFs move as one rigid body; the independent ones (exactly 6
/// linearly independent rigid-body DOFs) determine it. `dofs` holds, per grid,
/// its position, its 6 g-set indices and the components (1-6) that are
/// independent and dependent. Used for RBAR (CNA/CNB, CMA/CMB) and RBE2 (GN, CM).
struct RigidGrid {
  Eigen::Vector3d x;
  std::array<std::size_t, 6> g;     ///< g-set index of components 1..6
  std::string independent;          ///< component digits
  std::string dependent;            ///< component digits
  /// Displacement frame (GRID CD) in basic: the components above are along its
  /// columns, u_basic = frame · u_cd.
  Eigen::Matrix3d frame = Eigen::Matrix3d::Identity();
};
std::vector<MpcEquation> rigid_equations(const std::vector<RigidGrid>& grids, const std::string& source);

/// RBE3: the dependent components `refc` of the reference grid follow a
/// weighted least-squares rigid fit of the independent grids' motions (MSC
/// Nastran's interpolation element): with S_i = rigid_body_rows(x_i, x_ref)
/// restricted to the weighted components C_i and weights W (translations w_i,
/// rotations w_i·Lc² with Lc the mean distance of the independent grids from
/// the reference), u_ref = (S^T W S)^{-1} S^T W u_ind.
struct Rbe3Group {
  double weight = 1.0;
  std::string components;
  std::vector<std::pair<Eigen::Vector3d, std::array<std::size_t, 6>>> grids;
  /// Displacement frames of `grids` (same order); empty: all basic.
  std::vector<Eigen::Matrix3d> frames;
};
std::vector<MpcEquation> rbe3_equations(const Eigen::Vector3d& xref, const std::array<std::size_t, 6>& gref,
                                        const std::string& refc, const std::vector<Rbe3Group>& groups,
                                        const std::string& source,
                                        const Eigen::Matrix3d& ref_frame = Eigen::Matrix3d::Identity());

/// AUTOSPC: DOFs that have no stiffness. For each grid, the 3x3 translational and
/// rotational blocks of K_n (the stiffness after MPC elimination) are examined;
/// a direction whose stiffness is below `eps` times the largest diagonal term of K
/// is singular, and the component most aligned with it is constrained (NASTRAN's
/// grid point singularity processing; EPZERO default 1e-8). Scalar points with a
/// zero diagonal are constrained too. Returns g-set indices.
std::vector<std::size_t> find_singular_dofs(const SparseMatrix& Kg, const Reduction& mpc_only,
                                            const DofMap& dofs, double eps = 1e-8);

}  // namespace ssid::translators
