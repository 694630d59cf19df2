#include "estimator/multilevel/lobpcg.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace ssid::estimator::multilevel {

namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;

MatrixXd sym(const MatrixXd& G) { return 0.5 * (G + G.transpose()); }

/// Makes W A-orthonormal (W ← W T, AW ← AW T) through the eigen-decomposition of
/// its scaled Gram matrix; directions with relative energy below 1e-13 are dropped.
/// Returns the number of columns kept.
long a_orthonormalise(RowBlock& W, RowBlock& AW) {
  if (W.cols() == 0) return 0;
  const MatrixXd G = sym(gram(W, AW));
  VectorXd d = G.diagonal();
  for (Eigen::Index i = 0; i < d.size(); ++i) d(i) = d(i) > 0.0 ? 1.0 / std::sqrt(d(i)) : 0.0;
  const MatrixXd Gs = d.asDiagonal() * G * d.asDiagonal();
  Eigen::SelfAdjointEigenSolver<MatrixXd> es(Gs);
  const VectorXd& ev = es.eigenvalues();
  const double top = ev.size() ? ev(ev.size() - 1) : 0.0;
  std::vector<Eigen::Index> keep;
  for (Eigen::Index i = 0; i < ev.size(); ++i)
    if (ev(i) > 1e-13 * top && ev(i) > 0.0) keep.push_back(i);
  MatrixXd T(W.cols(), static_cast<Eigen::Index>(keep.size()));
  for (size_t j = 0; j < keep.size(); ++j)
    T.col(static_cast<Eigen::Index>(j)) = d.asDiagonal() * es.eigenvectors().col(keep[j]) / std::sqrt(ev(keep[j]));
  W = times_dense(W, T);
  AW = times_dense(AW, T);
  return static_cast<long>(keep.size());
}

/// Columns `idx` of X.
RowBlock columns(const RowBlock& X, const std::vector<Eigen::Index>& idx) {
  RowBlock Y(X.rows(), static_cast<Eigen::Index>(idx.size()));
  for (size_t j = 0; j < idx.size(); ++j) Y.col(static_cast<Eigen::Index>(j)) = X.col(idx[j]);
  return Y;
}

/// Σ_k Blocks[k] C_k with C split by rows along the blocks.
RowBlock combine(const std::vector<const RowBlock*>& blocks, const MatrixXd& C) {
  RowBlock Y = RowBlock::Zero(blocks.front()->rows(), C.cols());
  Eigen::Index r = 0;
  for (const RowBlock* B : blocks) {
    if (B->cols() > 0) Y += times_dense(*B, C.middleRows(r, B->cols()));
    r += B->cols();
  }
  return Y;
}

/// Largest `b` eigenpairs of GM c = μ GA c (GA positive definite): μ descending and
/// C with Cᵀ GA C = I. False when GA is not numerically positive definite.
bool rayleigh_ritz(const MatrixXd& GA, const MatrixXd& GM, Eigen::Index b, VectorXd& mu, MatrixXd& C) {
  Eigen::LLT<MatrixXd> llt(GA);
  if (llt.info() != Eigen::Success) return false;
  const MatrixXd L = llt.matrixL();
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

/// Products with M. A lumped (diagonal) M with massless DOFs is the common case:
/// its Gram matrices XᵀMY are then taken over the DOFs with mass only, from
/// compact copies scaled by √m (half the rows of a beam model).
class MassProducts {
 public:
  explicit MassProducts(const SparseMatrix& M) : m_M(M) {
    const long n = M.rows();
    m_diagonal = true;
    for (long c = 0; c < M.outerSize() && m_diagonal; ++c)
      for (SparseMatrix::InnerIterator it(M, c); it; ++it)
        if (it.row() != it.col() && it.value() != 0.0) { m_diagonal = false; break; }
    if (!m_diagonal) return;
    const VectorXd d = M.diagonal();
    for (long i = 0; i < n; ++i)
      if (d(i) != 0.0) m_rows.push_back(i), m_sqrt.push_back(std::sqrt(std::abs(d(i)))), m_sign.push_back(d(i) > 0.0 ? 1.0 : -1.0);
  }
  void times(const RowBlock& X, RowBlock& Y) const { sym_times(m_M, X, Y); }
  /// Xᵀ M Y (MY given for the general case).
  MatrixXd gram(const RowBlock& X, const RowBlock& Y, const RowBlock& MY) const {
    if (!m_diagonal) return multilevel::gram(X, MY);
    const RowBlock Xc = compact(X, true), Yc = compact(Y, false);
    return multilevel::gram(Xc, Yc);
  }

 private:
  RowBlock compact(const RowBlock& X, bool signed_rows) const {
    RowBlock C(static_cast<Eigen::Index>(m_rows.size()), X.cols());
    for (size_t k = 0; k < m_rows.size(); ++k)
      C.row(static_cast<Eigen::Index>(k)) = (signed_rows ? m_sign[k] * m_sqrt[k] : m_sqrt[k]) * X.row(m_rows[k]);
    return C;
  }
  const SparseMatrix& m_M;
  bool m_diagonal = false;
  std::vector<long> m_rows;
  std::vector<double> m_sqrt, m_sign;
};

}  // namespace

LobpcgResult lobpcg_largest(const SparseMatrix& A, const SparseMatrix& M, const BlockOperator& precondition,
                            const RowBlock& X0, const LobpcgOptions& o) {
  const long n = A.rows();
  if (X0.rows() != n || X0.cols() < o.nev || o.nev < 1)
    throw std::invalid_argument("lobpcg: the start block must have n rows and at least nev >= 1 columns");
  const MassProducts mass(M);
  LobpcgResult res;
  RowBlock X = X0, AX, MX;
  sym_times(A, X, AX);
  if (a_orthonormalise(X, AX) < o.nev) throw std::invalid_argument("lobpcg: the start block is rank deficient");
  mass.times(X, MX);
  const Eigen::Index b = X.cols();
  {
    MatrixXd C;
    VectorXd mu;
    if (!rayleigh_ritz(sym(gram(X, AX)), sym(mass.gram(X, X, MX)), b, mu, C))
      throw std::runtime_error("lobpcg: the first Rayleigh-Ritz step failed");
    X = times_dense(X, C), AX = times_dense(AX, C), MX = times_dense(MX, C);
    res.mu = mu;
  }
  // Invariants at the top of each iteration: X is A-orthonormal with XᵀMX = diag(μ)
  // (the Rayleigh–Ritz step makes it so), P is the conjugate block of the last step.
  RowBlock P, AP, MP, W, AW, MW;
  VectorXd rel(b);
  for (res.iterations = 0; res.iterations < o.maxit; ++res.iterations) {
    // Residuals and the active set.
    RowBlock R = MX - AX * res.mu.asDiagonal();
    std::vector<Eigen::Index> active;
    int wanted_done = 0;
    for (Eigen::Index j = 0; j < b; ++j) {
      const double ax = AX.col(j).norm();
      rel(j) = ax > 0.0 && res.mu(j) > 0.0 ? R.col(j).norm() / (res.mu(j) * ax) : 0.0;
      if (rel(j) > o.tol) active.push_back(j);
      else if (j < o.nev) ++wanted_done;
    }
    report(o.progress,
           "LOBPCG iteration " + std::to_string(res.iterations) + ": " + std::to_string(wanted_done) + " of " +
               std::to_string(o.nev) + " converged, largest residual " + std::to_string(rel.head(o.nev).maxCoeff()),
           static_cast<double>(wanted_done) / o.nev);
    if (wanted_done == o.nev) {
      res.converged = true;
      break;
    }
    // Preconditioned directions for the active columns, A-orthogonal to X and
    // A-orthonormal; the conjugate block A-orthonormal too.
    const RowBlock Ra = columns(R, active);
    R.resize(0, 0);
    res.preconditioned += static_cast<long>(active.size());
    precondition(Ra, W);
    W -= times_dense(X, gram(AX, W));
    sym_times(A, W, AW);
    if (a_orthonormalise(W, AW) == 0) break;  // no new direction: stagnation
    mass.times(W, MW);
    if (P.cols() > 0) {
      if (a_orthonormalise(P, AP) == 0) P.resize(n, 0), AP.resize(n, 0), MP.resize(n, 0);
      else mass.times(P, MP);
    }
    // Rayleigh–Ritz on [X W P]. Known blocks are set, not computed: XᵀAX = I,
    // XᵀAW = 0, WᵀAW = PᵀAP = I, XᵀMX = diag(μ). Without P when the Gram matrix is
    // not definite (P nearly inside span[X W]).
    const Eigen::Index nw = W.cols(), np = P.cols(), m = b + nw + np;
    MatrixXd GA = MatrixXd::Identity(m, m), GM = MatrixXd::Zero(m, m);
    GM.topLeftCorner(b, b) = res.mu.asDiagonal();
    auto put = [](MatrixXd& G, Eigen::Index r, Eigen::Index c, const MatrixXd& g) {
      G.block(r, c, g.rows(), g.cols()) = g;
      G.block(c, r, g.cols(), g.rows()) = g.transpose();
    };
    put(GM, 0, b, mass.gram(X, W, MW));
    put(GM, b, b, sym(mass.gram(W, W, MW)));
    if (np > 0) {
      put(GA, 0, b + nw, gram(AX, P));
      put(GA, b, b + nw, gram(W, AP));
      put(GM, 0, b + nw, mass.gram(X, P, MP));
      put(GM, b, b + nw, mass.gram(W, P, MP));
      put(GM, b + nw, b + nw, sym(mass.gram(P, P, MP)));
    }
    MatrixXd C;
    VectorXd mu;
    bool with_p = np > 0 && rayleigh_ritz(GA, GM, b, mu, C);
    if (!with_p) {
      P.resize(n, 0), AP.resize(n, 0), MP.resize(n, 0);
      if (!rayleigh_ritz(GA.topLeftCorner(b + nw, b + nw), GM.topLeftCorner(b + nw, b + nw), b, mu, C)) break;
    }
    // New conjugate directions (the [W P] part of the active columns), then X; their
    // products with A and M are recomputed rather than combined (cheaper than the
    // dense update for a sparse A, and exact for the new blocks).
    const MatrixXd Cwp = C(Eigen::all, active).bottomRows(C.rows() - b);
    RowBlock Pn = combine({&W, &P}, Cwp);
    X = combine({&X, &W, &P}, C);
    P.swap(Pn);
    Pn.resize(0, 0), W.resize(0, 0), AW.resize(0, 0), MW.resize(0, 0);
    sym_times(A, X, AX);
    mass.times(X, MX);
    sym_times(A, P, AP);
    res.mu = mu;
  }
  res.residuals = rel;
  res.X = std::move(X);
  return res;
}

}  // namespace ssid::estimator::multilevel
