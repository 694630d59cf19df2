#include "estimator/eigen/multilevel/multilevel_eigen.hpp"

#include "estimator/eigen/block_lanczos.hpp"
#include "estimator/eigen/eigen_solver.hpp"
#include "estimator/eigen/multilevel/lobpcg.hpp"
#include "estimator/eigen/zero_energy_modes.hpp"

#include <algorithm>
#include <chrono>
#include <memory>
#include <stdexcept>
#include <utility>

namespace ssid::estimator::multilevel {

namespace {
using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

/// X ← (I − ω D⁻¹A)^steps X, D = diag(A), ω = 4/(3ρ) with ρ = max_i Σ_j |a_ij| / a_ii
/// ≥ ρ(D⁻¹A) (Gershgorin). A is positive definite, so D⁻¹A's eigenvalues lie in
/// (0, ρ] and each eigencomponent of X is multiplied by a factor in [−1/3, 1]: the
/// components of high energy (the roughness that interpolation leaves at the scale
/// of one element) are damped, the smooth ones kept. Leaves X as it is when a
/// diagonal entry is not positive (no such bound then; the start is only a start).
void smooth_start(const SparseMatrix& A, int steps, RowBlock& X) {
  if (steps <= 0 || X.size() == 0) return;
  const long n = A.rows(), b = X.cols();
  Eigen::VectorXd row_abs = Eigen::VectorXd::Zero(n);
  for (Eigen::Index c = 0; c < A.outerSize(); ++c)
    for (SparseMatrix::InnerIterator it(A, c); it; ++it) row_abs(it.row()) += std::abs(it.value());
  const Eigen::VectorXd d = A.diagonal();
  if (!(d.minCoeff() > 0.0)) return;
  const double rho = row_abs.cwiseQuotient(d).maxCoeff();
  const Eigen::VectorXd scale = (4.0 / (3.0 * rho)) * d.cwiseInverse();
  RowBlock AX;
  for (int s = 0; s < steps; ++s) {
    sym_times(A, X, AX);
    double* x = X.data();
    const double* ax = AX.data();
    const double* w = scale.data();
    parallel_for(n, [=](long begin, long end) {
      for (long i = begin; i < end; ++i)
        for (long j = 0; j < b; ++j) x[i * b + j] -= w[i] * ax[i * b + j];
    });
  }
}
}  // namespace

MultilevelRun multilevel_lowest(const SparseMatrix& K_in, const SparseMatrix& M_in, double sigma, int nev,
                                const std::vector<long>& groups_in, const Eigen::MatrixXd& B_in,
                                const MultilevelOptions& o, const Progress& progress, const Eigen::MatrixXd& F_in) {
  MultilevelRun run;
  const long n = K_in.rows();
  if (static_cast<long>(groups_in.size()) != n || B_in.rows() != n || (F_in.size() > 0 && F_in.rows() != n))
    throw std::invalid_argument(
        "multilevel eigen-solver: groups, near-null space and strain fields must have one row per DOF");
  // DOFs with mass first: every M X is then zero below row `mass_rows`, and the
  // Gram matrices with M skip those rows (half the DOFs of a beam model are
  // massless rotations). The results are permuted back at the end.
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> perm(n);
  long mass_rows = 0;
  {
    std::vector<char> massive(static_cast<size_t>(n), 0);
    for (Eigen::Index c = 0; c < M_in.outerSize(); ++c)
      for (SparseMatrix::InnerIterator it(M_in, c); it; ++it)
        if (it.value() != 0.0) massive[static_cast<size_t>(it.row())] = 1;
    for (long i = 0; i < n; ++i)
      if (massive[static_cast<size_t>(i)]) perm.indices()(i) = static_cast<int>(mass_rows++);
    long next = mass_rows;
    for (long i = 0; i < n; ++i)
      if (!massive[static_cast<size_t>(i)]) perm.indices()(i) = static_cast<int>(next++);
  }
  SparseMatrix K = perm * K_in * perm.transpose();  // released before LOBPCG, which needs only A and M
  const SparseMatrix M = perm * M_in * perm.transpose();
  std::vector<long> groups(static_cast<size_t>(n));
  Eigen::MatrixXd B(n, B_in.cols()), F(F_in.size() > 0 ? n : 0, F_in.cols());
  for (long i = 0; i < n; ++i) {
    groups[static_cast<size_t>(perm.indices()(i))] = groups_in[static_cast<size_t>(i)];
    B.row(perm.indices()(i)) = B_in.row(i);
    if (F.size() > 0) F.row(perm.indices()(i)) = F_in.row(i);
  }

  if (nev < 1) throw std::invalid_argument("multilevel eigen-solver: ND must be at least 1");
  const int guard = o.guard > 0 ? o.guard : std::max(8, nev / 4);

  auto t = Clock::now();
  report(progress, "multilevel: building the preconditioner", 0.0);
  SparseMatrix A = K - sigma * M;
  A.makeCompressed();
  std::unique_ptr<AggregationAmg> amg_ptr;
  try {
    amg_ptr = std::make_unique<AggregationAmg>(A, groups, B, o.amg, F);
  } catch (const NotPositiveDefiniteBlock& e) {
    run.failure = MultilevelRun::Failure::NotPositiveDefinite;
    for (long i = 0; i < n; ++i)
      if (perm.indices()(i) == e.dof) run.failed_dof = i;  // back to the caller's numbering
    run.message = "K - sigma*M (sigma = " + std::to_string(sigma) + ") is not positive definite at DOF index " +
                  std::to_string(run.failed_dof) + ": a DOF with neither stiffness nor mass";
    return run;
  } catch (const std::runtime_error& e) {
    run.failure = MultilevelRun::Failure::CoarseFactor;
    run.message = e.what();
    return run;
  }
  const AggregationAmg& amg = *amg_ptr;
  run.coarse_size = amg.coarse_size();
  run.aggregates = amg.aggregates();
  run.setup_seconds = seconds_since(t);
  const auto& at = amg.times();
  report(progress, "multilevel: preconditioner in " + std::to_string(run.setup_seconds) + " s (aggregation " +
                       std::to_string(at.aggregation) + ", smoothing " + std::to_string(at.smoothing) +
                       ", coarse matrix " + std::to_string(at.coarse_matrix) + ", coarse factor " +
                       std::to_string(at.coarse_factor) + " of which analysis " +
                       std::to_string(at.coarse_analysis) + ", ordering " + amg.coarse_factor().ordering() +
                       "; aggregate radius " + std::to_string(amg.options().aggregate_radius) +
                       ", prolongator steps " + std::to_string(amg.options().prolongator_steps) +
                       ", coarse factor in " + (amg.coarse_factor_single() ? "single" : "double") + " precision)",
         0.1);

  // Exact zero-energy modes (rigid-body modes of a free structure) taken out of the
  // iteration, which then looks for the remaining nev − r modes.
  // (zero_energy_modes.hpp; the iteration is kept A-orthogonal to them, A = K − σM:
  // Z = z / √(λ − σ), since zᵀ A z = λ − σ for an M-normalised z).
  const ZeroEnergyModes zm =
      o.deflate ? zero_energy_modes(K, M, sigma, B, 1e-2 * o.tol, nev) : ZeroEnergyModes{{}, Eigen::MatrixXd(n, 0)};
  const Eigen::VectorXd& zero_lambda = zm.lambda;
  const Eigen::MatrixXd& zero_z = zm.z;
  const int r = static_cast<int>(zm.z.cols());
  run.deflated = r;
  Deflation deflation;
  if (r > 0) {
    const Eigen::VectorXd s = (zero_lambda.array() - sigma).rsqrt();
    deflation.Z = zero_z * s.asDiagonal();
    deflation.AZ = (K * zero_z - sigma * (M * zero_z)) * s.asDiagonal();
    report(progress, "multilevel: " + std::to_string(r) + " zero-energy modes of the near-null space deflated", 0.1);
  }
  const int nev_it = nev - r;
  const long b_it = std::min<long>(nev_it + guard, n - r);
  // λ ascending: the deflated modes (λ ≈ 0) merged with the iteration's, by value.
  // (Only a run that reaches the end has modes: the early returns leave them empty.)
  auto finish = [&](const Eigen::VectorXd& lam_it, const RowBlock& X_it) {
    run.lambda.resize(nev);
    run.vectors.resize(n, nev);
    std::vector<std::pair<double, int>> order;  // (λ, index: < r deflated, else r + LOBPCG column)
    for (int j = 0; j < r; ++j) order.emplace_back(zero_lambda(j), j);
    for (int j = 0; j < nev_it; ++j) order.emplace_back(lam_it(j), r + j);
    std::stable_sort(order.begin(), order.end(), [](const auto& a, const auto& c) { return a.first < c.first; });
    std::vector<int> source(static_cast<size_t>(nev));
    for (int k = 0; k < nev; ++k) {
      source[static_cast<size_t>(k)] = order[static_cast<size_t>(k)].second;
      run.lambda(k) = order[static_cast<size_t>(k)].first;
    }
    // Back to the caller's numbering, row by row (a row of X_it is contiguous; by
    // columns each value was a cache miss: seconds at a million DOFs), threaded.
    parallel_for(n, [&](long begin, long end) {
      for (long i = begin; i < end; ++i) {
        const long p = perm.indices()(i);
        for (int k = 0; k < nev; ++k) {
          const int j = source[static_cast<size_t>(k)];
          run.vectors(i, k) = j < r ? zero_z(p, j) : X_it(p, j - r);
        }
      }
    });
  };
  if (nev_it == 0) {  // every wanted mode is a zero-energy mode
    run.converged = true;
    finish(Eigen::VectorXd(), RowBlock(n, 0));
    return run;
  }

  // Start block: the coarse model's lowest b modes above its r zero-energy ones, interpolated.
  if (run.coarse_size - 1 < nev) {
    run.failure = MultilevelRun::Failure::Breakdown;
    run.message = "the coarse model has " + std::to_string(run.coarse_size) + " DOFs, too few for " +
                  std::to_string(nev) + " modes (the model is too small for this method)";
    return run;
  }
  t = Clock::now();
  report(progress, "multilevel: coarse modes (" + std::to_string(run.coarse_size) + " DOFs)", 0.1);
  // The coarse model (Pᵀ K P, Pᵀ M P) shifted by σ is the AMG's coarse matrix,
  // already factorised: its lowest b modes come from block Lanczos on that factor.
  const SparseMatrix Mc =
      galerkin_lower(M, amg.prolongator(), amg.prolongator_rows(), amg.coarse_blocks()).selfadjointView<Eigen::Lower>();
  report(progress, "multilevel: coarse mass matrix in " + std::to_string(seconds_since(t)) + " s", 0.1);
  BlockLanczosOptions bo;
  bo.nev = static_cast<int>(std::min<long>(r + b_it, run.coarse_size - 1));
  bo.tol = 1e-5;  // a start for LOBPCG, not an answer
  bo.keep_mass_basis = true;  // Mc is a consistent (dense-ish) mass matrix; the coarse basis is small
  bo.progress = [&progress](const ProgressEvent& e) { report(progress, "coarse modes: " + e.text(), 0.1); };
  BlockLanczosResult coarse;
  double solve_seconds = 0.0;
  try {
    // The preconditioner's coarse factor, in single precision when it is (the start
    // needs a few digits: LOBPCG refines it).
    coarse = block_lanczos(
        [&amg, &solve_seconds](const Eigen::MatrixXd& X) {
          const auto ts = Clock::now();
          Eigen::MatrixXd Y = amg.solve_coarse(X);
          solve_seconds += seconds_since(ts);
          return Y;
        },
                           [&Mc](const Eigen::MatrixXd& X) {  // threaded (Eigen's product runs on one)
                             RowBlock Y;
                             sym_times(Mc, RowBlock(X), Y);
                             return Eigen::MatrixXd(Y);
                           },
                           run.coarse_size,
                           sigma, bo);
  } catch (const std::exception& e) {
    run.failure = MultilevelRun::Failure::Breakdown;
    run.message = std::string("the coarse model's modes: ") + e.what();
    return run;
  }
  if (!coarse.converged || coarse.lambda.size() < nev) {
    run.message = "the coarse model's modes could not be computed (" + std::to_string(coarse.lambda.size()) +
                  " of " + std::to_string(nev) + ")";
    return run;
  }
  RowBlock X0;
  amg.prolong(coarse.vectors.rightCols(coarse.vectors.cols() - r), X0);
  smooth_start(A, o.start_smoothing, X0);
  // Done with the coarse model and with K: their memory goes back to the heap
  // before LOBPCG allocates its blocks, which reuse it rather than touch fresh
  // pages (AggregationAmg::release_double_prolongator).
  amg_ptr->release_double_prolongator();
  SparseMatrix().swap(K);  // assigning an empty matrix would keep the storage
  run.coarse_modes_seconds = seconds_since(t);

  report(progress, "multilevel: coarse modes in " + std::to_string(run.coarse_modes_seconds) + " s (" +
                       std::to_string(coarse.block_solves) + " block solves, " + std::to_string(solve_seconds) +
                       " s)", 0.15);
  t = Clock::now();
  LobpcgOptions lo;
  lo.nev = nev_it;
  lo.tol = o.tol;
  lo.maxit = o.maxit;
  lo.mass_rows = mass_rows;
  lo.derived_gram_bound = o.derived_gram_bound;
  lo.lock_cluster_gap = o.lock_cluster_gap;
  lo.progress = progress;
  LobpcgResult lr;
  try {
    lr = lobpcg_largest(A, M, [&amg](const RowBlock& R, RowBlock& W) { amg.apply(R, W); }, std::move(X0), lo,
                        deflation);
  } catch (const std::exception& e) {  // rank-deficient start, failed first Rayleigh–Ritz step
    run.failure = MultilevelRun::Failure::Breakdown;
    run.message = e.what();
    return run;
  }
  run.lobpcg_seconds = seconds_since(t);
  run.iterations = lr.iterations;
  run.preconditioned = lr.preconditioned;
  run.converged = lr.converged;
  if (!lr.converged && !lr.breakdown.empty()) {
    run.failure = MultilevelRun::Failure::Breakdown;
    run.message = "LOBPCG stopped after " + std::to_string(lr.iterations) + " iterations: " + lr.breakdown;
  } else if (!lr.converged)
    run.message = "LOBPCG did not converge in " + std::to_string(lr.iterations) + " iterations (largest residual " +
                  std::to_string(lr.residuals.head(nev_it).maxCoeff()) + ", tolerance " + std::to_string(o.tol) + ")";
  // λ = σ + 1/μ: μ descending gives λ ascending.
  Eigen::VectorXd lam_it(nev_it);
  for (int j = 0; j < nev_it; ++j) lam_it(j) = sigma + 1.0 / lr.mu(j);
  finish(lam_it, lr.X);
  return run;
}

}  // namespace ssid::estimator::multilevel
