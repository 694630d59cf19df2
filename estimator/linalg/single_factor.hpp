#pragma once
/// \file single_factor.hpp
/// A supernodal Cholesky factor in single precision (factorize_supernodal_single,
/// on CHOLMOD's supernodal analysis), and its solves on row-major blocks: the
/// multilevel preconditioner's coarse factor and solve.
///
/// Why: the coarse factor of the 1M-DOF lattice takes 1.6·10¹² flops and its solve
/// reads 2.7·10⁸ entries for every preconditioner application (in double: 27 s, and
/// about 1 s with 45 right-hand sides, over half of the cycle). A preconditioner
/// needs a few digits, the rest of its cycle already runs in single precision, and
/// single-precision BLAS does twice the flops per instruction on half the bytes.
/// CHOLMOD 3 (SuiteSparse 5) has no single precision, hence the factorisation here.
/// Cholesky is backward stable: the factor and each solve solve (A + E) x = b with
/// ‖E‖ ≈ 10⁻⁷ ‖A‖ up to a modest factor, so the answer loses about κ(A)·10⁻⁷; a
/// matrix too ill-conditioned for that fails with a non-positive pivot or a small
/// rcond, and the caller falls back to double (AggregationAmg does).
///
/// Layout (CHOLMOD's supernodal L of P A Pᵀ = L Lᵀ): supernode s holds the columns
/// [super[s], super[s+1]) of L; its rows are rows[pi[s] .. pi[s+1]) (the first
/// nscol of them the supernode's own columns) and its values, column-major
/// nsrow x nscol, start at values[px[s]].
#include <vector>

namespace ssid::estimator {

struct SingleSupernodalFactor {
  long n = 0;
  std::vector<long> perm;  ///< row k of L is row perm[k] of A
  std::vector<long> super, pi, px, rows;
  std::vector<float> values;

  bool empty() const { return n == 0; }
  /// CHOLMOD's reciprocal condition estimate of the factored matrix,
  /// (min diag L / max diag L)²; 0 when empty.
  double rcond_estimate() const;

  /// Workspace of solve (kept by the caller between solves: no allocation per call).
  struct Work {
    std::vector<float> y, t;
  };
  /// X = A⁻¹ B for n x nrhs row-major blocks (the nrhs values of one row side by
  /// side); b and x may be the same. Throws std::logic_error when empty.
  void solve(const float* b, float* x, long nrhs, Work& work) const { solve_columns(b, x, nrhs, 0, nrhs, work); }
  /// The same for columns [c0, c1) only of n x ld row-major blocks: the other
  /// columns are neither read nor written, so callers on different threads, each
  /// with its own Work, may solve disjoint column ranges of one block at once (the
  /// BLAS held to one thread: see detail::BlasThreadLimit). Why: OpenBLAS's own
  /// threads, on the small supernodes of a coarse model, cost more in hand-overs
  /// and in spinning while idle than they gained
  /// (AggregationAmg::solve_coarse_single). Throws std::invalid_argument for a
  /// range outside [0, ld].
  void solve_columns(const float* b, float* x, long ld, long c0, long c1, Work& work) const;
};

/// Numeric Cholesky factorisation in single precision on a supernodal symbolic
/// structure: f holds n, perm, super, pi, px and rows (values are allocated here);
/// C = P A Pᵀ is given by its lower triangle in L's numbering, column by column
/// (CSC: column j's rows Ci[Cp[j] .. Cp[j+1]), each ≥ j, any order). Left-looking:
/// each supernode gathers its columns of C, subtracts the updates of the
/// supernodes below it in the elimination tree that reach it (ssyrk and sgemm on
/// their rows, then a scatter), and factors itself (spotrf on the diagonal block,
/// strsm below it); CHOLMOD's own supernodal algorithm, in single precision, which
/// CHOLMOD 3 does not offer. Returns −1, or the column of L whose pivot was not
/// positive (the factor is then unusable). Throws std::logic_error if LAPACK
/// reports an illegal argument (a bad structure).
long factorize_supernodal_single(const std::vector<long>& Cp, const std::vector<long>& Ci,
                                 const std::vector<double>& Cx, SingleSupernodalFactor& f);

}  // namespace ssid::estimator
