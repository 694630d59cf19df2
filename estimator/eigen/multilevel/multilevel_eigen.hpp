#pragma once
/// \file multilevel_eigen.hpp
/// Lowest modes of K φ = λ M φ without a factorisation of the full model: LOBPCG
/// (lobpcg.hpp) on M x = μ (K − σM) x preconditioned by two-level smoothed
/// aggregation (aggregation_amg.hpp), started from the modes of the coarse model
/// (Pᵀ K P, Pᵀ M P) interpolated by the prolongator P.
///
/// Why: for large 3D models the Cholesky factor of K − σM is the wall (the
/// 1M-DOF lattice: a 22 GiB factor, 2.7·10¹³ flops); this method needs memory and
/// work proportional to the model (a few blocks of n x b vectors, the coarse
/// factor) per iteration. It needs what a direct solver does not: the grid point
/// of each DOF and the rigid-body modes of the model (EigenOptions::dof_groups and
/// near_null_space), and it only finds the lowest ND modes (no band search, no
/// Sturm count). See docs/eigen_solver.md.
#include "estimator/eigen/multilevel/aggregation_amg.hpp"
#include "estimator/reporting/progress.hpp"

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <string>
#include <vector>

namespace ssid::estimator::multilevel {

struct MultilevelOptions {
  AmgOptions amg;
  double tol = 1e-6;  ///< ‖(K − λM)φ‖ / ‖(K − σM)φ‖ per mode (eigenvalues then agree with a direct solve to ~1e-12)
  int maxit = 300;    ///< LOBPCG iterations
  int guard = 0;      ///< extra block columns beyond ND; 0: max(8, ND/4)
  bool deflate = true;  ///< the exact zero-energy modes of B taken out first (zero_energy_modes.hpp)
  /// Damped-Jacobi steps on the interpolated start block (0: none): the coarse
  /// modes, interpolated, are rough at the scale of one element (1M lattice: 27 →
  /// 23 iterations with 10 steps, docs/performance.md).
  int start_smoothing = 10;
  /// LobpcgOptions::derived_gram_bound (0: every Gram block computed from the blocks).
  double derived_gram_bound = 10.0;
  /// LobpcgOptions::lock_cluster_gap (0: columns soft-locked one by one).
  double lock_cluster_gap = 1e-4;
};

struct MultilevelRun {
  Eigen::VectorXd lambda;   ///< ascending, the lowest nev
  Eigen::MatrixXd vectors;  ///< n x nev
  bool converged = false;
  std::string message;      ///< why not, when not
  /// Why it stopped early: a singular grid-point block of K − σM (a mechanism; the
  /// DOF in failed_dof, an index into K's rows), the coarse factorisation, or a
  /// Rayleigh–Ritz step that broke down.
  enum class Failure { None, NotPositiveDefinite, CoarseFactor, Breakdown };
  Failure failure = Failure::None;
  long failed_dof = -1;
  int iterations = 0;
  long preconditioned = 0;  ///< residual columns through the preconditioner
  long coarse_size = 0, aggregates = 0;
  int deflated = 0;  ///< zero-energy modes of B returned as they are
  double setup_seconds = 0, coarse_modes_seconds = 0, lobpcg_seconds = 0;
};

/// sigma < the lowest eigenvalue (K − σM positive definite). groups: grid point of
/// each DOF; B: near-null space (rigid-body modes), n x k, also searched for exact
/// zero-energy modes (MultilevelOptions::deflate); F: further fields for the coarse
/// space only (the constant-strain fields, AggregationAmg), n x m, or empty.
MultilevelRun multilevel_lowest(const Eigen::SparseMatrix<double>& K, const Eigen::SparseMatrix<double>& M,
                                double sigma, int nev, const std::vector<long>& groups, const Eigen::MatrixXd& B,
                                const MultilevelOptions& options, const Progress& progress,
                                const Eigen::MatrixXd& F = Eigen::MatrixXd());

}  // namespace ssid::estimator::multilevel
