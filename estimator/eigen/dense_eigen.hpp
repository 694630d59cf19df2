#pragma once
/// \file dense_eigen.hpp
/// Every finite mode of a small generalised eigenproblem K φ = λ M φ, dense.
///
/// M may be singular (massless DOFs: lumped rod mass has no torsional inertia)
/// and K too (free-free structures), so the problem is solved in the inverted,
/// shifted form: with σ < 0 below every eigenvalue, A = K − σM is positive
/// definite and
///   M φ = μ A φ,   μ = 1 / (λ − σ)
/// is a symmetric-definite problem (Eigen's GeneralizedSelfAdjointEigenSolver,
/// Cholesky of A then a dense symmetric QR). μ ≈ 0 (below 1e-12 μ_max) are the
/// infinite eigenvalues of the massless directions and are dropped; the others
/// give λ = σ + 1/μ. The cost is O(n³): meant for a-sets up to a few hundred DOFs,
/// where it returns all modes, which the Lanczos solver cannot.
#include <Eigen/SparseCore>

#include "estimator/eigen/eigen_solver.hpp"

namespace ssid::estimator {

/// Size up to which the CLI uses the dense solver.
constexpr long kDenseEigenLimit = 200;

/// All finite modes, then selected as EigenOptions asks (band f_low..f_high and
/// the lowest nd; nd = 0 and no band: all of them), normalised per options.norm,
/// with the checks of compute_checks. options.shift sets σ (NaN: automatic,
/// −10⁻² × the mean K_ii/M_ii over DOFs with mass: well below the lowest
/// eigenvalue and large enough that K − σM is well conditioned). Status NotPositiveDefinite when K − σM is not
/// (a mechanism: a DOF with neither stiffness nor mass).
EigenResult solve_modes_dense(const Eigen::SparseMatrix<double>& K, const Eigen::SparseMatrix<double>& M,
                              const EigenOptions& options = {});

}  // namespace ssid::estimator
