#include "estimator/eigen/block_lanczos.hpp"

#include "estimator/linalg/dense_blas.hpp"
#include "formats/parse_error.hpp"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>
#include <string>

namespace ssid::estimator {

namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;

MatrixXd random_block(long n, int b, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  MatrixXd R(n, b);
  for (long j = 0; j < b; ++j)
    for (long i = 0; i < n; ++i) R(i, j) = u(rng);
  return R;
}

}  // namespace

BlockLanczosResult block_lanczos(const std::function<MatrixXd(const MatrixXd&)>& shift_invert,
                                 const std::function<MatrixXd(const MatrixXd&)>& mass, long n, double sigma,
                                 const BlockLanczosOptions& o) {
  if (o.nev < 1 || o.block < 1) throw std::invalid_argument("block_lanczos: nev and block must be positive");
  const long b = std::min<long>(o.block, n);
  long cap = o.max_basis > 0 ? o.max_basis : std::max<long>(20L * o.nev, 200);
  cap = std::max(std::min(cap, n), b);
  BlockLanczosResult res;
  std::mt19937 rng(o.seed);
  // S X, from M X when it is known.
  auto S_of_mass = [&](const MatrixXd& MX) {
    ++res.block_solves;
    return shift_invert(MX);
  };
  auto S = [&](const MatrixXd& X) { return S_of_mass(mass(X)); };

  // The basis sized for what a run usually reaches (about 7 nev columns on the
  // lattices) and grown only beyond: growing copies it into fresh memory (the 10k
  // lattice, first sized 2 nev + 4 b: two copies, peak 88 against 83 MiB). Not the
  // cap itself: H would be cap² values, and V at 20 nev columns a large address
  // space for a large nev.
  MatrixXd V(n, std::min<long>(cap, 8L * o.nev + 4L * b));
  MatrixXd H = MatrixXd::Zero(V.cols(), V.cols());
  // M V beside V (BlockLanczosOptions::keep_mass_basis), else no columns.
  const bool keep_mv = o.keep_mass_basis;
  MatrixXd MV(n, keep_mv ? V.cols() : 0);
  long m = 0;  // columns in the basis

  // M-orthonormalises W against V[:, 0:m] (classical Gram–Schmidt twice) and
  // within itself (modified Gram–Schmidt twice), dropping columns that vanish:
  // the block shrinks (deflation) where the Krylov space stops growing, which is
  // how an exhausted space (small n, or M of low rank) ends the iteration.
  // Returns R (kept x W.cols()) with W_in = V C + W_out R; C goes into H's
  // columns [col0, col0 + W.cols()) when col0 >= 0. MW: M W_out on return.
  auto orthonormalise = [&](MatrixXd& W, MatrixXd& MW, long col0) -> MatrixXd {
    const long act = m;
    // Against the basis: first the newest two blocks, which hold the large
    // components (the block tridiagonal part of T); then one full classical
    // Gram–Schmidt pass, and a second only when that pass removed more than
    // half of a column's squared norm (the DGKS "twice is enough" test:
    // cancellation there leaves round-off along older vectors). The n x m by
    // m x b products are the iteration's dense work: system BLAS.
    // One pass against columns [lo, hi): W ← W − V C, C = Vᵀ M W; with `test`, true
    // when it removed more than half of a column's squared M-norm. Without M V
    // kept, M W is formed from the W projected. With it, C = (M V)ᵀ W needs no
    // product with M, and M W (current on entry when `test`) is carried through
    // the pass, M W − M V C: one product with M a block instead of four or five.
    auto project = [&](long lo, long hi, bool test) -> bool {
      const auto Vs = V.middleCols(lo, hi - lo);
      MatrixXd C;
      if (keep_mv) {
        C = detail::at_b(MV.middleCols(lo, hi - lo), W);
      } else {
        MW = mass(W);
        C = detail::at_b(Vs, MW);
      }
      VectorXd before;
      if (test) before = W.cwiseProduct(MW).colwise().sum().transpose();
      detail::gemm(false, false, -1.0, Vs, C, 1.0, W);
      if (keep_mv && test) detail::gemm(false, false, -1.0, MV.middleCols(lo, hi - lo), C, 1.0, MW);
      if (col0 >= 0) H.block(lo, col0, hi - lo, W.cols()) += C;
      if (test)
        for (long c = 0; c < W.cols(); ++c)  // ‖w − V c‖²_M = ‖w‖²_M − ‖c‖² (V M-orthonormal)
          if (before(c) - C.col(c).squaredNorm() < 0.5 * before(c)) return true;
      return false;
    };
    if (act > 0) {
      // A carried M W is formed afresh after the local pass, which removes the
      // recurrence's large components by design (carried through that
      // cancellation, it would keep its round-off relative to the larger W), and
      // after a full pass that cancelled (the DGKS case).
      project(std::max<long>(0, act - 2L * b), act, false);
      if (keep_mv) MW = mass(W);
      if (project(0, act, true)) {
        if (keep_mv) MW = mass(W);
        project(0, act, true);
      }
    }
    // M w is carried along (M w − M W_kept r) rather than recomputed: one product
    // with M per block, not three per column (a consistent coarse mass matrix, as
    // the multilevel solver's, made those single-column products 80 % of its start).
    MatrixXd R = MatrixXd::Zero(W.cols(), W.cols());
    if (!(keep_mv && act > 0)) MW = mass(W);
    long kept = 0;
    for (long c = 0; c < W.cols(); ++c) {
      VectorXd w = W.col(c), mw = MW.col(c);
      const double before = std::sqrt(std::max(0.0, w.dot(mw)));
      for (int pass = 0; pass < 2 && kept > 0; ++pass) {  // classical Gram–Schmidt twice, BLAS-2
        const VectorXd r = W.leftCols(kept).transpose() * mw;
        w.noalias() -= W.leftCols(kept) * r;
        mw.noalias() -= MW.leftCols(kept) * r;
        R.col(c).head(kept) += r;
      }
      double nrm = std::sqrt(std::max(0.0, w.dot(mw)));
      if (kept > 0 && nrm < 0.5 * before) {
        // Heavy cancellation: the carried M w holds the round-off of the updates
        // relative to `before`, not to what is left; a fresh product and one more
        // pass restore M-orthogonality to round-off (the DGKS criterion).
        mw = mass(MatrixXd(w)).col(0);
        const VectorXd r = W.leftCols(kept).transpose() * mw;
        w.noalias() -= W.leftCols(kept) * r;
        R.col(c).head(kept) += r;
        mw = mass(MatrixXd(w)).col(0);
        nrm = std::sqrt(std::max(0.0, w.dot(mw)));
      }
      if (nrm > 1e-8 * before && nrm > 0.0) {
        R(kept, c) = nrm;
        W.col(kept) = w / nrm;
        MW.col(kept) = mw / nrm;
        ++kept;
      }
    }
    W.conservativeResize(Eigen::NoChange, kept);
    MW.conservativeResize(Eigen::NoChange, kept);
    return R.topRows(kept);
  };

  // Start block inside range(S).
  {
    MatrixXd W = S(random_block(n, static_cast<int>(b), rng)), MW;
    orthonormalise(W, MW, -1);
    if (W.cols() == 0) throw formats::InputError("block_lanczos: M is zero");
    V.leftCols(W.cols()) = W;
    if (keep_mv) MV.leftCols(W.cols()) = MW;
    m = W.cols();
  }
  long j0 = 0, bj = m;  // the newest block: columns [j0, j0 + bj)
  for (;;) {
    MatrixXd W = keep_mv ? S_of_mass(MV.middleCols(j0, bj)) : S(V.middleCols(j0, bj)), MW;
    const MatrixXd R = orthonormalise(W, MW, j0);  // H columns of block j are now complete
    const long kept = W.cols();
    const bool room = m + kept <= cap;
    if (room && kept > 0) {
      if (m + kept > V.cols()) {  // grow the storage
        const long old = V.cols();
        const long nc = std::min(cap, std::max(old + old / 2, m + kept));
        V.conservativeResize(Eigen::NoChange, nc);
        if (keep_mv) MV.conservativeResize(Eigen::NoChange, nc);
        H.conservativeResize(nc, nc);
        H.rightCols(nc - old).setZero();
        H.bottomRows(nc - old).setZero();
      }
      V.middleCols(m, kept) = W;
      if (keep_mv) MV.middleCols(m, kept) = MW;
      H.block(m, j0, kept, bj) = R;
    }

    // Rayleigh–Ritz on the first k = m columns (T complete there); the residual
    // of a Ritz vector V y is ‖R y_j‖ with y_j its rows of block j.
    const long k = m;
    const MatrixXd T = 0.5 * (H.topLeftCorner(k, k) + H.topLeftCorner(k, k).transpose());
    // Only the wanted (largest) Ritz pairs are computed: theta ascending, the
    // last column of Yw the largest.
    const long want = std::min<long>(o.nev, k);
    VectorXd theta;
    MatrixXd Yw;
    detail::largest_eigenpairs(T, want, theta, Yw);
    long conv = 0;
    for (long c = want - 1; c >= 0; --c) {
      const double r = kept > 0 ? (R * Yw.block(j0, c, bj, 1)).norm() : 0.0;
      if (r <= o.tol * std::max(std::abs(theta(c)), 1e-300)) ++conv;
      else break;
    }
    report(o.progress, "block Lanczos: modes converged", conv, o.nev, "basis " + std::to_string(k));
    const bool exhausted = kept == 0;  // span(V) is invariant: every Ritz pair is exact
    if (conv >= want && (conv >= o.nev || exhausted)) {
      res.converged = true;
    } else if (room && !exhausted) {
      j0 = m;
      bj = kept;
      m += kept;
      continue;
    }
    const long take = conv;
    res.lambda.resize(take);
    const MatrixXd Y = Yw.rightCols(take).rowwise().reverse();
    res.vectors = detail::a_b(V.leftCols(k), Y);
    for (long i = 0; i < take; ++i) res.lambda(i) = sigma + 1.0 / theta(want - 1 - i);
    res.basis = k;
    return res;
  }
}

}  // namespace ssid::estimator
