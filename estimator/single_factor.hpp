#pragma once
/// \file single_factor.hpp
/// A supernodal Cholesky factor copied to single precision, and its solves on
/// row-major blocks: the multilevel preconditioner's coarse solve.
///
/// Why: the coarse solve of the 1M-DOF lattice reads a factor of 2.7·10⁸ entries
/// for every preconditioner application (about 1 s in double with 45 right-hand
/// sides, over half of the cycle). A preconditioner needs a few digits, the rest of
/// its cycle already runs in single precision, and single-precision BLAS does twice
/// the flops per instruction on half the bytes. The factor is computed in double
/// by CHOLMOD (single-precision factorisation is not in SuiteSparse 5) and rounded:
/// each solve is then backward stable in single precision, i.e. it solves
/// (A + E) x = b with ‖E‖ ≈ 10⁻⁷ ‖A‖ up to a modest factor.
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

  /// Workspace of solve (kept by the caller between solves: no allocation per call).
  struct Work {
    std::vector<float> y, t;
  };
  /// X = A⁻¹ B for n x nrhs row-major blocks (the nrhs values of one row side by
  /// side); b and x may be the same. Throws std::logic_error when empty.
  void solve(const float* b, float* x, long nrhs, Work& work) const;
};

}  // namespace ssid::estimator
