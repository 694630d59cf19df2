#pragma once
/// \file lobpcg.hpp
/// LOBPCG (Knyazev 2001) for the largest eigenvalues μ of the pencil
///   M x = μ A x,   A = K − σM symmetric positive definite, M positive semi-definite,
/// i.e. the lowest λ = σ + 1/μ of K φ = λ M φ: the shift-inverted form, chosen
/// because A (not M, which is singular on massless rotations) defines the inner
/// product, so every Gram matrix of the iteration is positive definite.
///
/// Each iteration: residuals R = M X − A X Θ; preconditioned directions
/// W = T R (T ≈ A⁻¹, e.g. AggregationAmg) for the columns not yet converged, a
/// near-degenerate cluster left out only as a whole (soft locking); W made A-orthogonal to X and A-orthonormal (by an eigen-decomposition
/// of its Gram matrix, which drops dependent directions); Rayleigh–Ritz on
/// span[X W P]; the new X is the b best Ritz vectors, the new P their part along
/// [W P] (the "conjugate" direction). Converged when, for each wanted column,
///   ‖M x − μ A x‖ / (μ ‖A x‖) = ‖(K − λM) x‖ / ‖(K − σM) x‖ ≤ tol,
/// a residual relative to the shifted operator, defined for rigid-body modes too.
#include "estimator/eigen/multilevel/block_ops.hpp"
#include "estimator/reporting/progress.hpp"

#include <functional>
#include <string>

namespace ssid::estimator::multilevel {

struct LobpcgOptions {
  int nev = 1;        ///< wanted eigenpairs (the largest μ); the block has X0.cols() ≥ nev columns
  double tol = 1e-8;  ///< relative residual, see the file comment
  int maxit = 300;
  /// M's rows (and so every M X) are zero from this row on: its Gram matrices are
  /// taken over the rows before (a model ordered with its massless DOFs last, as
  /// the multilevel solver orders it, halves their cost). Negative: all rows.
  long mass_rows = -1;
  /// The Gram blocks XᵀAP, XᵀMP and PᵀMP are derived from the last Rayleigh–Ritz
  /// step's small matrices rather than computed from the n x b blocks while the
  /// largest column norm of its coefficients, and the largest ratio of a column's
  /// coefficients to the A-norm of the P column they make (cancellation), are at
  /// most this: their rounding then stays a few ε times it. Why: 1.75 of the 7.5
  /// Gram products' worth an iteration (docs/performance.md). 0: always computed.
  double derived_gram_bound = 10.0;
  /// A converged column leaves the preconditioned (active) set only with its whole
  /// cluster: while a column not yet converged has a Ritz value within this
  /// relative distance of its own, it stays. Why: the Rayleigh–Ritz step mixes
  /// Ritz vectors of near-equal values, and a converged one left out beside an
  /// unconverged partner takes on its error (the 1M lattice, triple eigenvalues:
  /// a converged mode went back from 1.0e-6 to 3e-6 and the run took 26
  /// iterations, or 23, as rounding fell; with clusters locked together, 23 either
  /// way). 0: every column by itself.
  double lock_cluster_gap = 1e-4;
  Progress progress;
};

struct LobpcgResult {
  Eigen::VectorXd mu;         ///< Ritz values, descending (all block columns)
  RowBlock X;                 ///< A-orthonormal Ritz vectors (n x b)
  Eigen::VectorXd residuals;  ///< relative residuals of the columns
  bool converged = false;     ///< the first nev columns reached tol
  int iterations = 0;
  long preconditioned = 0;    ///< columns passed through the preconditioner
  int derived_grams = 0;      ///< iterations whose X and P Gram blocks were derived (LobpcgOptions::derived_gram_bound)
  std::string breakdown;      ///< why the iteration stopped early, when it did
};

/// Eigenvectors known in advance (a free structure's rigid-body modes): the
/// iteration stays A-orthogonal to them. Z: n x r with Zᵀ A Z = I, AZ = A Z.
struct Deflation {
  RowBlock Z, AZ;
};

using BlockOperator = std::function<void(const RowBlock& in, RowBlock& out)>;

/// X0: start block (n x b, b ≥ nev, linearly independent), taken by value: a
/// caller done with it moves it in, and the iteration's X is that storage (an
/// n x b block less: 360 MB at a million DOFs). `precondition(R, W)`
/// returns W ≈ A⁻¹ R. With a deflation the start block and every preconditioned
/// block are made A-orthogonal to its Z, so the Ritz pairs found are the largest μ
/// of the pencil restricted to that complement.
LobpcgResult lobpcg_largest(const SparseMatrix& A, const SparseMatrix& M, const BlockOperator& precondition,
                            RowBlock X0, const LobpcgOptions& options, const Deflation& deflation = {});

}  // namespace ssid::estimator::multilevel
