#include "estimator/multilevel/multilevel_eigen.hpp"

#include "estimator/eigen_solver.hpp"
#include "estimator/multilevel/lobpcg.hpp"

#include <algorithm>
#include <chrono>
#include <stdexcept>

namespace ssid::estimator::multilevel {

namespace {
using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }
}  // namespace

MultilevelRun multilevel_lowest(const SparseMatrix& K, const SparseMatrix& M, double sigma, int nev,
                                const std::vector<long>& groups, const Eigen::MatrixXd& B,
                                const MultilevelOptions& o, const Progress& progress) {
  MultilevelRun run;
  const long n = K.rows();
  if (nev < 1) throw std::invalid_argument("multilevel eigen-solver: ND must be at least 1");
  const int guard = o.guard > 0 ? o.guard : std::max(8, nev / 4);
  const long b = std::min<long>(nev + guard, n);

  auto t = Clock::now();
  report(progress, "multilevel: building the preconditioner", 0.0);
  SparseMatrix A = K - sigma * M;
  A.makeCompressed();
  const AggregationAmg amg(A, groups, B, o.amg);
  run.coarse_size = amg.coarse_size();
  run.aggregates = amg.aggregates();
  run.setup_seconds = seconds_since(t);

  // Start block: the coarse model's lowest b modes, interpolated.
  t = Clock::now();
  report(progress, "multilevel: coarse modes (" + std::to_string(run.coarse_size) + " DOFs)", 0.1);
  const SparseMatrix& P = amg.prolongator();
  const SparseMatrix Pt = P.transpose();
  const SparseMatrix Kc = Pt * (K * P), Mc = Pt * (M * P);
  EigenOptions co;
  co.nd = static_cast<int>(std::min<long>(b, run.coarse_size - 1));
  co.shift = sigma;
  co.method = EigenMethod::Spectra;
  co.sturm_check = false;
  const EigenResult coarse = solve_modes(Kc, Mc, co);
  if (!coarse.ok() || coarse.size() < nev) {
    run.message = "the coarse model's modes could not be computed (" + std::to_string(coarse.size()) + " of " +
                  std::to_string(nev) + "): " + coarse.message;
    return run;
  }
  RowBlock Yc = coarse.modes, X0;
  times(SparseRowMatrix(P), Yc, X0);
  run.coarse_modes_seconds = seconds_since(t);

  t = Clock::now();
  LobpcgOptions lo;
  lo.nev = nev;
  lo.tol = o.tol;
  lo.maxit = o.maxit;
  lo.progress = progress;
  const LobpcgResult lr = lobpcg_largest(
      A, M, [&amg](const RowBlock& R, RowBlock& W) { amg.apply(R, W); }, X0, lo);
  run.lobpcg_seconds = seconds_since(t);
  run.iterations = lr.iterations;
  run.preconditioned = lr.preconditioned;
  run.converged = lr.converged;
  if (!lr.converged)
    run.message = "LOBPCG did not converge in " + std::to_string(lr.iterations) + " iterations (largest residual " +
                  std::to_string(lr.residuals.head(nev).maxCoeff()) + ", tolerance " + std::to_string(o.tol) + ")";
  // λ = σ + 1/μ: μ descending gives λ ascending.
  run.lambda.resize(nev);
  run.vectors.resize(n, nev);
  for (int j = 0; j < nev; ++j) {
    run.lambda(j) = sigma + 1.0 / lr.mu(j);
    run.vectors.col(j) = lr.X.col(j);
  }
  return run;
}

}  // namespace ssid::estimator::multilevel
