#include "estimator/eigen/multilevel/lobpcg.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "estimator/reporting/number_text.hpp"
#include "formats/parse_error.hpp"

namespace ssid::estimator::multilevel {

namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;

MatrixXd sym(const MatrixXd& G) { return 0.5 * (G + G.transpose()); }

/// 1/√g_jj for each diagonal entry of a Gram matrix, 0 where it is not positive:
/// the scaling to unit A-norm columns.
VectorXd unit_scaling(const MatrixXd& G) {
  VectorXd d = G.diagonal();
  for (Eigen::Index i = 0; i < d.size(); ++i) d(i) = d(i) > 0.0 ? 1.0 / std::sqrt(d(i)) : 0.0;
  return d;
}

/// T with Tᵀ G T = I for the Gram matrix G = WᵀAW, through the eigen-decomposition
/// of G scaled to unit diagonal; directions with relative energy below 1e-13 are
/// dropped (T has as many columns as are kept, possibly none).
MatrixXd a_orthonormal_transform(const MatrixXd& G) {
  const VectorXd d = unit_scaling(G);
  const MatrixXd Gs = d.asDiagonal() * G * d.asDiagonal();
  Eigen::SelfAdjointEigenSolver<MatrixXd> es(Gs);
  const VectorXd& ev = es.eigenvalues();
  const double top = ev.size() ? ev(ev.size() - 1) : 0.0;
  std::vector<Eigen::Index> keep;
  for (Eigen::Index i = 0; i < ev.size(); ++i)
    if (ev(i) > 1e-13 * top && ev(i) > 0.0) keep.push_back(i);
  MatrixXd T(G.rows(), static_cast<Eigen::Index>(keep.size()));
  for (size_t j = 0; j < keep.size(); ++j)
    T.col(static_cast<Eigen::Index>(j)) = d.asDiagonal() * es.eigenvectors().col(keep[j]) / std::sqrt(ev(keep[j]));
  return T;
}

/// Makes W A-orthonormal in place (W ← W T, AW ← AW T, T from
/// a_orthonormal_transform). `scratch` is storage to reuse. Returns the number of
/// columns kept.
long a_orthonormalise(RowBlock& W, RowBlock& AW, RowBlock& scratch) {
  if (W.cols() == 0) return 0;
  const MatrixXd T = a_orthonormal_transform(gram_symmetric(W, AW));
  times_dense_into(W, T, 0.0, scratch);
  W.swap(scratch);
  times_dense_into(AW, T, 0.0, scratch);
  AW.swap(scratch);
  return static_cast<long>(T.cols());
}

/// V ← V − Z (AZ)ᵀ V: V made A-orthogonal to the deflated vectors.
void deflate(const Deflation& d, RowBlock& V) {
  if (d.Z.cols() > 0 && V.cols() > 0) times_dense_into(d.Z, -gram(d.AZ, V), 1.0, V);
}

/// M as the iteration applies it. A diagonal M (a lumped mass matrix) is kept as
/// its diagonal and M Y is never formed: the Gram matrices scale rows as they read
/// them (gram_weighted) and the residuals multiply as they go. Why: M X, M W and
/// M P were three n x b blocks of fresh memory (a gigabyte at a million DOFs) and
/// three passes an iteration. Any other M is applied and its products stored.
struct Mass {
  const SparseMatrix* M = nullptr;
  bool diagonal = false;
  VectorXd d;     // the diagonal, when diagonal
  long rows = 0;  // M's rows are zero from this one on (LobpcgOptions::mass_rows)

  Mass(const SparseMatrix& m, long mass_rows) : M(&m), rows(mass_rows) {
    diagonal = true;
    for (Eigen::Index c = 0; c < m.outerSize() && diagonal; ++c)
      for (SparseMatrix::InnerIterator it(m, c); it; ++it)
        if (it.row() != c && it.value() != 0.0) diagonal = false;
    if (diagonal) d = m.diagonal();
  }
  /// MY = M Y, or nothing (MY emptied) when M is diagonal.
  void times(const RowBlock& Y, RowBlock& MY) const {
    if (diagonal) MY.resize(Y.rows(), 0);
    else sym_times(*M, Y, MY);
  }
  /// Xᵀ M Y, MY = M Y (unused when M is diagonal).
  MatrixXd gram(const RowBlock& X, const RowBlock& Y, const RowBlock& MY) const {
    return diagonal ? gram_weighted(X, d, Y, rows) : multilevel::gram(X, MY, rows);
  }
  /// Xᵀ M X, MX = M X (unused when M is diagonal).
  MatrixXd gram_symmetric(const RowBlock& X, const RowBlock& MX) const {
    return diagonal ? gram_weighted_symmetric(X, d, rows) : multilevel::gram_symmetric(X, MX, rows);
  }
  /// Where the value (i, j) of M X comes from: MX's storage, or d_i x_ij.
  struct Values {
    const double* mx;
    const double* x;
    const double* d;
    double operator()(long i, long j, long b) const { return d ? d[i] * x[i * b + j] : mx[i * b + j]; }
  };
  Values values(const RowBlock& X, const RowBlock& MX) const {
    return diagonal ? Values{nullptr, X.data(), d.data()} : Values{MX.data(), nullptr, nullptr};
  }
};

/// The squared column norms of R = MX − AX diag(μ) and of AX, in one threaded
/// pass, R not stored (only its active columns are, by active_residuals).
void residual_norms(const Mass::Values& mx, const RowBlock& AX, const VectorXd& mu, VectorXd& r2, VectorXd& ax2) {
  const long n = AX.rows(), b = AX.cols();
  const double* ax = AX.data();
  const double* m = mu.data();
  // Partial sums by part, added in order: the same bits on every run.
  std::vector<VectorXd> r2p(static_cast<size_t>(worker_threads()), VectorXd::Zero(b)), ax2p = r2p;
  const long parts = parallel_parts(n, [&, ax, m](long t, long begin, long end) {
    VectorXd &r2t = r2p[static_cast<size_t>(t)], &ax2t = ax2p[static_cast<size_t>(t)];
    for (long i = begin; i < end; ++i)
      for (long j = 0; j < b; ++j) {
        const double a = ax[i * b + j], r = mx(i, j, b) - a * m[j];
        r2t(j) += r * r;
        ax2t(j) += a * a;
      }
  });
  r2 = VectorXd::Zero(b), ax2 = VectorXd::Zero(b);
  for (long t = 0; t < parts; ++t) r2 += r2p[static_cast<size_t>(t)], ax2 += ax2p[static_cast<size_t>(t)];
}

/// Ra = the columns `active` of MX − AX diag(μ) (the residuals to precondition),
/// written directly: the whole R block had cost an n x b block and a pass.
void active_residuals(const Mass::Values& mx, const RowBlock& AX, const VectorXd& mu,
                      const std::vector<Eigen::Index>& active, RowBlock& Ra) {
  const long n = AX.rows(), b = AX.cols(), k = static_cast<long>(active.size());
  resize_block(Ra, n, k);
  const double* ax = AX.data();
  double* ra = Ra.data();
  parallel_for(n, [=, &active, &mu](long begin, long end) {
    for (long i = begin; i < end; ++i)
      for (long c = 0; c < k; ++c) {
        const long j = active[static_cast<size_t>(c)];
        ra[i * k + c] = mx(i, j, b) - ax[i * b + j] * mu(j);
      }
  });
}

/// ‖r_j‖ / (μ_j ‖A x_j‖) from the squared norms; `undefined` where A x_j = 0 or μ_j ≤ 0.
VectorXd relative_residuals(const VectorXd& r2, const VectorXd& ax2, const VectorXd& mu, double undefined) {
  VectorXd rel(r2.size());
  for (Eigen::Index j = 0; j < rel.size(); ++j) {
    const double ax = std::sqrt(ax2(j));
    rel(j) = ax > 0.0 && mu(j) > 0.0 ? std::sqrt(r2(j)) / (mu(j) * ax) : undefined;
  }
  return rel;
}

/// out = the columns `idx` of X.
void select_columns(const RowBlock& X, const std::vector<Eigen::Index>& idx, RowBlock& out) {
  resize_block(out, X.rows(), static_cast<long>(idx.size()));
  const long k = static_cast<long>(idx.size()), b = X.cols();
  const double* x = X.data();
  double* o = out.data();
  parallel_for(X.rows(), [=, &idx](long begin, long end) {
    for (long i = begin; i < end; ++i)
      for (long j = 0; j < k; ++j) o[i * k + j] = x[i * b + idx[static_cast<size_t>(j)]];
  });
}

/// Largest `b` eigenpairs of GM c = μ GA c (GA positive definite): μ descending and
/// C with Cᵀ GA C = I. False when GA is not numerically positive definite.
bool rayleigh_ritz(const MatrixXd& GA, const MatrixXd& GM, Eigen::Index b, VectorXd& mu, MatrixXd& C) {
  Eigen::LLT<MatrixXd> llt(GA);
  if (llt.info() != Eigen::Success) return false;
  const Eigen::Index m = GA.rows();
  // H = L⁻¹ GM L⁻ᵀ
  MatrixXd H = llt.matrixL().solve(GM);
  H = llt.matrixL().solve(MatrixXd(H.transpose()));
  Eigen::SelfAdjointEigenSolver<MatrixXd> es(sym(H));
  if (es.info() != Eigen::Success) return false;
  b = std::min(b, m);
  mu.resize(b);
  MatrixXd V(m, b);
  for (Eigen::Index j = 0; j < b; ++j) {
    mu(j) = es.eigenvalues()(m - 1 - j);
    V.col(j) = es.eigenvectors().col(m - 1 - j);
  }
  C = llt.matrixU().solve(V);  // L⁻ᵀ V
  return (C.array().isFinite()).all();
}

}  // namespace

LobpcgResult lobpcg_largest(const SparseMatrix& A, const SparseMatrix& M, const BlockOperator& precondition,
                            RowBlock X0, const LobpcgOptions& o, const Deflation& deflation) {
  const long n = A.rows();
  if (X0.rows() != n || X0.cols() < o.nev || o.nev < 1)
    throw std::invalid_argument("lobpcg: the start block must have n rows and at least nev >= 1 columns");
  if (deflation.Z.cols() != deflation.AZ.cols() ||
      (deflation.Z.cols() > 0 && (deflation.Z.rows() != n || deflation.AZ.rows() != n)))
    throw std::invalid_argument("lobpcg: the deflated blocks Z and AZ must be n x r");
  const long mrows = o.mass_rows < 0 ? n : std::min<long>(o.mass_rows, n);
  // Gram matrices with M over the rows that carry mass (MY is zero below them).
  const Mass mass(M, mrows);
  LobpcgResult res;
  // Every n-row block lives for the whole iteration and is written in place. Ra,
  // the residuals to precondition, is dead once W is computed: it then takes the
  // block products before a swap (a scratch block of its own, and another for P,
  // had cost two n x b blocks of fresh memory: 700 MB at a million DOFs). Its width
  // changes with the active set (Eigen then reallocates): cheap where freed memory
  // stays in the heap (keep_freed_memory), fresh pages each time where it does not.
  RowBlock X, AX, MX, P, AP, MP, W, AW, MW, Ra;
  X.swap(X0);  // X0 is this function's own (moved in by a caller done with it: a block less)
  deflate(deflation, X);
  sym_times(A, X, AX);
  if (a_orthonormalise(X, AX, Ra) < o.nev) throw std::invalid_argument("lobpcg: the start block is rank deficient");
  mass.times(X, MX);
  const Eigen::Index b = X.cols();
  {
    MatrixXd C;
    VectorXd mu;
    if (!rayleigh_ritz(gram_symmetric(X, AX), mass.gram_symmetric(X, MX), b, mu, C))
      throw formats::NumericalError("lobpcg: the first Rayleigh-Ritz step failed");
    times_dense_into(X, C, 0.0, Ra), X.swap(Ra);
    times_dense_into(AX, C, 0.0, Ra), AX.swap(Ra);
    if (!mass.diagonal) times_dense_into(MX, C, 0.0, Ra), MX.swap(Ra);
    res.mu = mu;
  }
  // Invariants at the top of each iteration: X is A-orthonormal with XᵀMX = diag(μ)
  // (the Rayleigh–Ritz step makes it so), P is the conjugate block of the last step.
  VectorXd rel;
  // The last Rayleigh–Ritz step: its Gram matrices (GA, GM: of the basis it used),
  // the coefficients of the X it made (Cx) and of the P it made (Cp), and whether
  // the Gram matrices of the next step may be derived from them (derived_gram_bound).
  MatrixXd last_GA, last_GM, last_Cx, last_Cp;
  bool derive = false;
  // Derived blocks come from Gram matrices whose own X-P blocks may have been
  // derived: every kMaxDerivedInARow-th step computes them afresh, so that their
  // rounding cannot compound without limit.
  constexpr int kMaxDerivedInARow = 8;
  int derived_in_a_row = 0;
  for (res.iterations = 0; res.iterations < o.maxit; ++res.iterations) {
    // Residuals and the active set.
    VectorXd r2, ax2;
    residual_norms(mass.values(X, MX), AX, res.mu, r2, ax2);
    rel = relative_residuals(r2, ax2, res.mu, 0.0);
    std::vector<Eigen::Index> active;
    int wanted_done = 0;
    {
      // A NaN residual or a non-positive Ritz value is never "converged".
      std::vector<char> done(static_cast<size_t>(b));
      for (Eigen::Index j = 0; j < b; ++j) done[static_cast<size_t>(j)] = rel(j) <= o.tol && res.mu(j) > 0.0;
      for (Eigen::Index j = 0; j < b; ++j) {
        bool lock = done[static_cast<size_t>(j)];
        if (lock && j < o.nev) ++wanted_done;
        // Locked only with its whole cluster (LobpcgOptions::lock_cluster_gap).
        for (Eigen::Index i = 0; i < b && lock; ++i)
          if (!done[static_cast<size_t>(i)] && std::abs(res.mu(i) - res.mu(j)) <= o.lock_cluster_gap * std::abs(res.mu(j)))
            lock = false;
        if (!lock) active.push_back(j);
      }
    }
    report(o.progress, "LOBPCG: modes converged", wanted_done, o.nev,
           "iteration " + std::to_string(res.iterations) + ", largest residual " +
               significant(rel.head(o.nev).maxCoeff(), 3),
           static_cast<double>(wanted_done) / o.nev);
    if (wanted_done == o.nev) {
      res.converged = true;
      break;
    }
    // Preconditioned directions W for the active columns, A-orthogonal to X; the
    // basis of the Rayleigh–Ritz step is [X, W T, P D]: W T A-orthonormal and P D
    // (the conjugate block) with unit A-norm columns. T and D stay small: the Gram
    // matrices are taken with W and P as they are and transformed, and T and D go
    // into the coefficients of the update (forming W T, A W T and P D cost three
    // n x b passes an iteration, 6 % of the time at a million DOFs).
    active_residuals(mass.values(X, MX), AX, res.mu, active, Ra);
    res.preconditioned += static_cast<long>(active.size());
    precondition(Ra, W);
    deflate(deflation, W);
    times_dense_into(X, -gram(AX, W), 1.0, W);
    sym_times(A, W, AW);
    const MatrixXd T = a_orthonormal_transform(gram_symmetric(W, AW));
    if (T.cols() == 0) {  // no new direction: stagnation
      res.breakdown = "no new search direction (stagnation)";
      break;
    }
    mass.times(W, MW);
    // The Gram blocks of X and P: X = S Cx and P = S Cp in the last step's basis S
    // (of unit A-norm columns), so XᵀAP = Cxᵀ GA Cp, XᵀMP = Cxᵀ GM Cp and PᵀMP =
    // Cpᵀ GM Cp: small products instead of passes over n x b blocks (1.75 of the
    // iteration's 7.5 Gram products' worth). Their rounding is a few ε times
    // ‖Cx‖ ‖Cp_j‖ / ‖P_j‖_A: derived only while the last step's coefficients and
    // that amplification (‖Cp_j‖ over P_j's A-norm, large when P_j is a small
    // difference of large terms) stay below derived_gram_bound, computed from the
    // blocks otherwise. XᵀAX and PᵀAP are always computed: derived, XᵀAX = I let X's
    // loss of A-orthonormality accumulate (94k lattice: 1e-14 → 9e-13 over 24
    // iterations, at the eigenvalues' accuracy), and PᵀAP gives that A-norm.
    MatrixXd PAP, XAP, XMP, PMP;
    VectorXd dp;
    bool derived = false;
    if (P.cols() > 0) {
      PAP = gram_symmetric(P, AP);
      dp = unit_scaling(PAP);
      mass.times(P, MP);
      // P's columns are those of last_Cp (both the last step's active set).
      double amplification = 0.0;
      if (derive)
        for (Eigen::Index j = 0; j < P.cols(); ++j)
          amplification = std::max(amplification, last_Cp.col(j).norm() * dp(j));
      derived = derive && amplification <= o.derived_gram_bound && derived_in_a_row < kMaxDerivedInARow;
      if (derived) {
        const MatrixXd GMCp = last_GM * last_Cp;
        XAP = last_Cx.transpose() * (last_GA * last_Cp), XMP = last_Cx.transpose() * GMCp;
        PMP = sym(last_Cp.transpose() * GMCp);
      } else {
        XAP = gram(AX, P), XMP = mass.gram(X, P, MP), PMP = mass.gram_symmetric(P, MP);
      }
    }
    res.derived_grams += derived;
    derived_in_a_row = derived ? derived_in_a_row + 1 : 0;
    // Rayleigh–Ritz on [X, W T, P D]. (W T)ᵀA(W T) = I (T makes it so) and XᵀMX =
    // diag(μ) (the last Rayleigh–Ritz step) are set; XᵀAX and XᵀA(W T), which hold
    // only as well as the last step and one Gram–Schmidt pass, are computed so that
    // their errors do not accumulate. Without P when the Gram matrix is not
    // definite (P nearly inside span[X W]).
    const Eigen::Index nw = T.cols(), np = P.cols(), m = b + nw + np;
    MatrixXd GA = MatrixXd::Identity(m, m), GM = MatrixXd::Zero(m, m);
    GM.topLeftCorner(b, b) = res.mu.asDiagonal();
    auto put = [](MatrixXd& G, Eigen::Index r, Eigen::Index c, const MatrixXd& g) {
      G.block(r, c, g.rows(), g.cols()) = g;
      G.block(c, r, g.cols(), g.rows()) = g.transpose();
    };
    const MatrixXd Tt = T.transpose();
    put(GA, 0, 0, gram_symmetric(X, AX));
    put(GA, 0, b, gram(AX, W) * T);
    put(GM, 0, b, mass.gram(X, W, MW) * T);
    put(GM, b, b, sym(Tt * mass.gram_symmetric(W, MW) * T));
    if (np > 0) {
      const auto D = dp.asDiagonal();
      put(GA, 0, b + nw, XAP * D);
      put(GA, b, b + nw, Tt * gram(W, AP) * D);
      put(GA, b + nw, b + nw, D * PAP * D);
      put(GM, 0, b + nw, XMP * D);
      put(GM, b, b + nw, Tt * mass.gram(W, P, MP) * D);
      put(GM, b + nw, b + nw, D * PMP * D);
    }
    MatrixXd C;
    VectorXd mu;
    const bool with_p = np > 0 && rayleigh_ritz(GA, GM, b, mu, C);
    if (!with_p) {
      P.resize(n, 0), AP.resize(n, 0), MP.resize(n, 0);
      if (!rayleigh_ritz(GA.topLeftCorner(b + nw, b + nw), GM.topLeftCorner(b + nw, b + nw), b, mu, C)) {
        res.breakdown = "the Rayleigh-Ritz Gram matrix is not positive definite";
        break;
      }
    }
    // Q = [W P] [T C_w; D C_p], the new conjugate directions P = Q's active
    // columns, X ← X C_x + Q (Q formed once: forming P and X separately cost the
    // [W P] product twice). Q goes into Ra's storage; P, read by then, takes its
    // active columns; X's old storage becomes the next Ra. Their products with A
    // and M are recomputed rather than combined (cheaper than the dense update for
    // a sparse A, and exact for the new blocks).
    {
      // What the next step may derive its Gram blocks from: the basis used (with or
      // without P), X's coefficients, and P's, the active columns of X's without X.
      const Eigen::Index used = with_p ? m : b + nw;
      last_GA = GA.topLeftCorner(used, used), last_GM = GM.topLeftCorner(used, used);
      last_Cx = C;
      last_Cp = MatrixXd::Zero(used, static_cast<Eigen::Index>(active.size()));
      for (size_t c = 0; c < active.size(); ++c)
        last_Cp.col(static_cast<Eigen::Index>(c)).tail(used - b) = C.col(active[c]).tail(used - b);
      derive = o.derived_gram_bound > 0.0 && C.colwise().norm().maxCoeff() <= o.derived_gram_bound;
    }
    MatrixXd Cwp(W.cols() + P.cols(), b);
    Cwp.topRows(W.cols()) = T * C.middleRows(b, nw);
    if (P.cols() > 0) Cwp.bottomRows(P.cols()) = dp.asDiagonal() * C.bottomRows(P.cols());
    times_dense_sum({&W, &P}, Cwp, 0.0, Ra);
    select_columns(Ra, active, P);
    times_dense_into(X, C.topRows(b), 1.0, Ra);
    X.swap(Ra);
    sym_times(A, X, AX);
    sym_times(A, P, AP);
    mass.times(X, MX);
    res.mu = mu;
  }
  if (!res.converged && res.breakdown.empty()) {
    // Out of iterations: the residuals of the X returned, not of the one before.
    VectorXd r2, ax2;
    residual_norms(mass.values(X, MX), AX, res.mu, r2, ax2);
    rel = relative_residuals(r2, ax2, res.mu, std::numeric_limits<double>::infinity());
  }
  res.residuals = rel;
  res.X = std::move(X);
  return res;
}

}  // namespace ssid::estimator::multilevel
