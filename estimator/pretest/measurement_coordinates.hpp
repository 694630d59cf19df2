#pragma once
/// \file measurement_coordinates.hpp
/// Pretest planning, step 1b: sensors along arbitrary directions (issue 23 item 1).
///
/// A sensor mounted along a unit vector d at a grid measures y = dᵀu_g, a
/// combination of the grid's translations, not one DOF. Every step of the
/// pretest works on DOFs (EI and KE rows, the TAMs' partition into sensor and
/// omitted DOFs), so the analysis set is changed to coordinates q in which each
/// such measurement is one coordinate. At a grid with k given directions
/// d_1…d_k (in its displacement frame) and free translations F (|F| = f ≤ 3):
///
///     q_g = D_g u_F,   D_g = [d_1,F; …; d_k,F; c_1; …; c_{f−k}]   (f x f),
///
/// where d_i,F is d_i restricted to the free translations (a constrained
/// translation does not move) and c_1… complete the rows to a basis, orthogonal
/// to the given ones. Elsewhere q = u. Then u = T q with T = blockdiag(D_g⁻¹),
/// and the model in q is the congruence
///
///     K_q = Tᵀ K T,   M_q = Tᵀ M T,   Φ_q = T⁻¹ Φ = D Φ,   f_q = Tᵀ f,
///
/// which keeps the eigenvalues, the mass normalisation (Φ_qᵀ M_q Φ_q = ΦᵀMΦ)
/// and the work of a load (Φ_qᵀ f_q = Φᵀ f). Guyan and IRS in q condense onto the
/// measured coordinates; the result does not depend on the completion c (the
/// omitted coordinates at a grid span the same space whatever basis is chosen),
/// which the unit tests check against the closed form of a single grid.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <cstdint>
#include <vector>

#include "estimator/pretest/targets.hpp"
#include "translators/dof_map.hpp"

namespace ssid::estimator::pretest {

/// A sensor along a given direction at a grid.
struct SensorDirection {
  std::int64_t grid = 0;
  Eigen::Vector3d direction = Eigen::Vector3d::UnitX();  ///< in the grid's displacement frame; need not be unit
};

/// The coordinates q in which every sensor direction is one coordinate.
struct MeasurementCoordinates {
  Eigen::SparseMatrix<double> T;      ///< u = T q (n x n)
  Eigen::SparseMatrix<double> T_inv;  ///< q = T⁻¹ u
  /// The sensor candidates in q: the given candidates, except at a grid with
  /// directions, whose candidates are its directions (`directed`, in the order
  /// given, in the rows of its first k free translations).
  std::vector<CandidateDof> candidates;

  /// Tᵀ A T: a stiffness or mass matrix in q.
  Eigen::SparseMatrix<double> congruent(const Eigen::SparseMatrix<double>& A) const;
  /// T⁻¹ U: modes (displacements) in q.
  Eigen::MatrixXd displacements(const Eigen::Ref<const Eigen::MatrixXd>& U) const;
  /// Tᵀ F: loads in q.
  Eigen::MatrixXd loads(const Eigen::Ref<const Eigen::MatrixXd>& F) const;
};

/// Builds q for the analysis set `a_set`, the translational `candidates`
/// (translational_candidates) and the sensor `directions`. Without directions
/// T is the identity and the candidates come back unchanged. Throws
/// formats::InputError for a direction at a grid that is not a candidate, a
/// zero direction, one that moves only constrained translations, more
/// directions at a grid than it has free translations, or directions at a grid
/// that are (nearly) linearly dependent (smallest singular value of the unit
/// rows below 1e-3, about 0.06°), since no test can tell such sensors apart.
MeasurementCoordinates measurement_coordinates(const std::vector<translators::Dof>& a_set,
                                               const std::vector<CandidateDof>& candidates,
                                               const std::vector<SensorDirection>& directions);

}  // namespace ssid::estimator::pretest
