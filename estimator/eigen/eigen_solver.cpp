#include "estimator/eigen/eigen_solver.hpp"

#include "estimator/eigen/block_lanczos.hpp"
#include "estimator/eigen/method_choice.hpp"
#include "estimator/eigen/multilevel/block_ops.hpp"
#include "estimator/reporting/progress.hpp"
#include "formats/parse_error.hpp"

#include <Eigen/Eigenvalues>
#include <Spectra/SymGEigsShiftSolver.h>
#include <unistd.h>

#include <algorithm>
#include <utility>
#include <chrono>
#include <cmath>
#include <random>
#include <sstream>
#include <stdexcept>

namespace ssid::estimator {

namespace {

using Clock = std::chrono::steady_clock;
using SparseMatrix = Eigen::SparseMatrix<double>;
constexpr double kTwoPi = 6.283185307179586476925286766559;

/// Physical memory of the machine (0 when unknown: no limit).
double physical_memory_bytes() {
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
  return pages > 0 && page > 0 ? static_cast<double>(pages) * static_cast<double>(page) : 0.0;
}

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

/// Spectra operation object y = (K − σM)⁻¹ x over an existing CHOLMOD factor of
/// K − σM. The factor is built before the solver, so set_shift only checks σ.
class ShiftInvertOp {
 public:
  using Scalar = double;
  ShiftInvertOp(const CholmodFactor& f, double sigma, const Progress& progress)
      : m_f(f), m_sigma(sigma), m_progress(progress) {}
  Eigen::Index rows() const { return m_f.rows(); }
  Eigen::Index cols() const { return m_f.rows(); }
  void set_shift(double sigma) {
    if (sigma != m_sigma) throw std::logic_error("ShiftInvertOp: factor was built for another shift");
  }
  void perform_op(const double* x, double* y) const {
    m_f.solve(x, y, 1);
    if (++m_count % 50 == 0) report(m_progress, "Lanczos solves", m_count, -1);  // the total is not known
  }
  long count() const { return m_count; }

 private:
  const CholmodFactor& m_f;
  double m_sigma;
  const Progress& m_progress;
  mutable long m_count = 0;
};

/// Spectra operation object y = M x; a diagonal (lumped) M is applied as a vector.
class MassOp {
 public:
  using Scalar = double;
  explicit MassOp(const SparseMatrix& M) : m_M(M) {
    m_diagonal = true;
    for (Eigen::Index c = 0; c < M.outerSize() && m_diagonal; ++c)
      for (SparseMatrix::InnerIterator it(M, c); it; ++it)
        if (it.row() != it.col() && it.value() != 0.0) { m_diagonal = false; break; }
    if (m_diagonal) m_d = M.diagonal();
  }
  Eigen::Index rows() const { return m_M.rows(); }
  Eigen::Index cols() const { return m_M.cols(); }
  void perform_op(const double* x, double* y) const {
    Eigen::Map<const Eigen::VectorXd> xv(x, m_M.rows());
    Eigen::Map<Eigen::VectorXd> yv(y, m_M.rows());
    if (m_diagonal)
      yv.array() = m_d.array() * xv.array();
    else
      yv.noalias() = m_M * xv;
  }
  Eigen::MatrixXd apply(const Eigen::MatrixXd& X) const {
    if (m_diagonal) return m_d.asDiagonal() * X;
    return m_M * X;
  }

 private:
  const SparseMatrix& m_M;
  Eigen::VectorXd m_d;
  bool m_diagonal = false;
};

double norm1(const SparseMatrix& A) {
  double best = 0.0;
  for (Eigen::Index c = 0; c < A.outerSize(); ++c) {
    double s = 0.0;
    for (SparseMatrix::InnerIterator it(A, c); it; ++it) s += std::abs(it.value());
    best = std::max(best, s);
  }
  return best;
}

struct LanczosRun {
  Eigen::VectorXd values;  // converged λ, ascending
  Eigen::MatrixXd vectors;
  bool converged = false;
  long iterations = 0;
};

LanczosRun run_lanczos(const CholmodFactor& factor, const MassOp& mass, double sigma, int nev, int ncv,
                       const EigenOptions& o) {
  ShiftInvertOp op(factor, sigma, o.progress);
  MassOp bop = mass;
  Spectra::SymGEigsShiftSolver<ShiftInvertOp, MassOp, Spectra::GEigsMode::ShiftInvert> eigs(op, bop, nev, ncv,
                                                                                           sigma);
  // Start inside range((K − σM)⁻¹M): no component along massless directions.
  std::mt19937 rng(o.seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::VectorXd r(factor.rows()), Mr(factor.rows()), v0(factor.rows());
  for (Eigen::Index i = 0; i < r.size(); ++i) r(i) = u(rng);
  mass.perform_op(r.data(), Mr.data());
  factor.solve(Mr.data(), v0.data(), 1);
  if (!(v0.norm() > 0.0)) throw formats::InputError("EigenSolver: M is zero: the model has no mass on its analysis DOFs");
  eigs.init(v0.data());
  try {
    eigs.compute(Spectra::SortRule::LargestMagn, o.maxit, o.tol, Spectra::SortRule::SmallestAlge);
  } catch (const Interrupted&) {  // the caller's stop (Ctrl-C), and errors of ours, pass as they are
    throw;
  } catch (const formats::InputError&) {
    throw;
  } catch (const formats::NumericalError&) {
    throw;
  } catch (const std::runtime_error& e) {  // Spectra's own failures (a NaN in the Lanczos tridiagonal, ...)
    std::ostringstream msg;
    msg << "EigenSolver: the Lanczos iteration failed (" << e.what() << ") at the shift sigma = " << sigma
        << " (rad/s)^2: the shift-invert solves gave no finite vector (K - sigma M singular or too ill-conditioned)";
    throw formats::NumericalError(msg.str());
  }
  LanczosRun run;
  run.converged = eigs.info() == Spectra::CompInfo::Successful;
  run.iterations = eigs.num_iterations();
  run.values = eigs.eigenvalues();
  run.vectors = eigs.eigenvectors();
  return run;
}

LanczosRun run_block_lanczos(const CholmodFactor& factor, const MassOp& mass, double sigma, int nev,
                             const EigenOptions& o) {
  BlockLanczosOptions bo;
  bo.nev = nev;
  bo.block = o.block;
  bo.tol = o.tol;
  bo.seed = o.seed;
  bo.progress = o.progress;
  if (o.ncv > 0) bo.max_basis = o.ncv;
  const long n = factor.rows();
  auto solve = [&factor, n](const Eigen::MatrixXd& X) {
    Eigen::MatrixXd Y(n, X.cols());
    factor.solve(X.data(), Y.data(), static_cast<long>(X.cols()));
    return Y;
  };
  auto apply_mass = [&mass](const Eigen::MatrixXd& X) { return mass.apply(X); };
  const BlockLanczosResult b = block_lanczos(solve, apply_mass, n, sigma, bo);
  LanczosRun run;
  run.converged = b.converged;
  run.iterations = b.block_solves;
  run.values = b.lambda;
  run.vectors = b.vectors;
  return run;
}

/// One step of block inverse iteration, Y = (K − σM)⁻¹ M Φ (columns rescaled by
/// λ − σ so that Y ≈ Φ), followed by Rayleigh–Ritz on span(Y). Purifies the
/// massless-DOF directions, sharpens the vectors and makes them M-orthonormal.
void rayleigh_ritz_refine(const SparseMatrix& K, const MassOp& mass, const CholmodFactor& factor, double sigma,
                          Eigen::VectorXd& lambda, Eigen::MatrixXd& Phi) {
  if (Phi.cols() == 0) return;
  Eigen::MatrixXd Y = factor.solve(mass.apply(Phi));
  for (Eigen::Index j = 0; j < Y.cols(); ++j) Y.col(j) *= (lambda(j) - sigma);
  const Eigen::MatrixXd Kr = Y.transpose() * (K * Y);
  const Eigen::MatrixXd Mr = Y.transpose() * mass.apply(Y);
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> ges(0.5 * (Kr + Kr.transpose()),
                                                                0.5 * (Mr + Mr.transpose()));
  if (ges.info() != Eigen::Success) return;  // keep the Lanczos pairs: they are already checked after
  lambda = ges.eigenvalues();
  Phi = Y * ges.eigenvectors();
}

void normalise(Eigen::MatrixXd& Phi, const MassOp& mass, ModeNormalization norm) {
  for (Eigen::Index j = 0; j < Phi.cols(); ++j) {
    auto phi = Phi.col(j);
    Eigen::Index k = 0;
    phi.cwiseAbs().maxCoeff(&k);
    if (norm == ModeNormalization::Max) {
      phi /= phi(k);
    } else {
      Eigen::VectorXd Mphi(phi.size());
      Eigen::VectorXd pc = phi;
      mass.perform_op(pc.data(), Mphi.data());
      const double gm = pc.dot(Mphi);
      // Sign convention: the largest component is positive (deterministic output).
      phi /= std::copysign(std::sqrt(gm), phi(k));
    }
  }
}

EigenResult::Status to_status(FactorStatus::Code c) {
  switch (c) {
    case FactorStatus::Code::Ok: return EigenResult::Status::Ok;
    case FactorStatus::Code::NotPositiveDefinite: return EigenResult::Status::NotPositiveDefinite;
    case FactorStatus::Code::NearSingular: return EigenResult::Status::NearSingular;
    case FactorStatus::Code::TooLarge:
    case FactorStatus::Code::Failed: break;
  }
  return EigenResult::Status::FactorFailed;
}

/// EigenMethod::Multilevel: the lowest nd modes by LOBPCG with the aggregation
/// preconditioner, normalised and checked; res already holds the shift and any
/// factor figures. t0: when the solve began.
void solve_multilevel(const SparseMatrix& K, const SparseMatrix& M, double sigma, const EigenOptions& o,
                      const MassOp& mass, long n_massive, Clock::time_point t0, EigenResult& res) {
  res.method = "Multilevel";
  // Only the DOFs with mass carry finite eigenvalues (as in the direct path).
  const int nd = static_cast<int>(std::min<long>(o.nd, std::max<long>(n_massive - 1, 1)));
  if (nd < o.nd)
    res.warnings.push_back("only " + std::to_string(nd) + " of the " + std::to_string(o.nd) +
                           " requested modes are computed (DOFs with mass: " + std::to_string(n_massive) + ")");
  multilevel::MultilevelRun run = multilevel::multilevel_lowest(
      K, M, sigma, nd, o.dof_groups, o.near_null_space, o.multilevel, o.progress, o.strain_fields);
  res.nev = nd;
  res.ncv = 0;
  res.lanczos_runs = 1;
  res.iterations = run.iterations;
  res.solves = run.preconditioned;
  res.coarse_size = run.coarse_size;
  res.deflated = run.deflated;
  res.analyze_seconds = 0.0;
  res.factor_seconds = run.setup_seconds;
  res.lanczos_seconds = run.coarse_modes_seconds + run.lobpcg_seconds;
  if (!run.converged) {
    using F = multilevel::MultilevelRun::Failure;
    res.status = run.failure == F::NotPositiveDefinite ? EigenResult::Status::NotPositiveDefinite
                 : run.failure == F::CoarseFactor      ? EigenResult::Status::FactorFailed
                                                       : EigenResult::Status::NotConverged;
    res.failed_dof = run.failed_dof;
    res.message = "multilevel eigen-solver: " + run.message;
  }
  res.eigenvalues = run.lambda;
  res.modes = std::move(run.vectors);
  if (res.modes.rows() != K.rows()) res.modes.resize(K.rows(), 0);  // stopped before any mode
  normalise(res.modes, mass, o.norm);
  compute_checks(K, M, res);
  res.total_seconds = seconds_since(t0);
  report(o.progress, "modes done", 1.0);
}

}  // namespace

double automatic_shift(const SparseMatrix& K, const SparseMatrix& M) {
  const Eigen::VectorXd kd = K.diagonal(), md = M.diagonal();
  double sk = 0.0, sm = 0.0;
  for (Eigen::Index i = 0; i < md.size(); ++i)
    if (md(i) > 0.0) sk += std::abs(kd(i)), sm += md(i);
  return (sm > 0.0 && sk > 0.0) ? -1e-5 * sk / sm : -1.0;
}

double hz_to_eigenvalue(double f) { return (kTwoPi * f) * (kTwoPi * f); }
double eigenvalue_to_hz(double lambda) { return std::sqrt(std::abs(lambda)) / kTwoPi; }
void throw_solve_failure(const EigenResult& r, const std::string& message) {
  if (r.status == EigenResult::Status::NotPositiveDefinite) throw formats::InputError(message);
  throw formats::NumericalError(message);
}

double EigenResult::radians(int i) const { return std::sqrt(std::abs(eigenvalues(i))); }
double EigenResult::cycles(int i) const { return radians(i) / kTwoPi; }

EigenOptions eigrl_options(double v1, double v2, int nd, ModeNormalization norm) {
  EigenOptions o;
  o.f_low = v1;
  o.f_high = v2;
  o.nd = nd;
  o.norm = norm;
  return o;
}

EigenOptions eigr_options(double f1, double f2, int ne, int nd, ModeNormalization norm) {
  EigenOptions o = eigrl_options(f1, f2, nd, norm);
  o.ne = ne;  // NASTRAN's estimate of the number of roots in the band: it sizes the first run
  return o;
}

void compute_checks(const SparseMatrix& K, const SparseMatrix& M, EigenResult& r) {
  const Eigen::MatrixXd& Phi = r.modes;
  const Eigen::Index m = Phi.cols();
  // K Φ and M Φ, the columns split over the cores when there is enough work (the
  // 1M lattice: 41 columns of a million rows, single-threaded about 2 s of a 3 s
  // check). Each column is Eigen's own product, so the bits do not depend on the split.
  Eigen::MatrixXd KP(K.rows(), m), MP(M.rows(), m);
  const bool split = static_cast<double>(K.nonZeros() + M.nonZeros()) * static_cast<double>(m) >= 4e6;
  multilevel::parallel_parts(
      m,
      [&](long, long begin, long end) {
        KP.middleCols(begin, end - begin) = K * Phi.middleCols(begin, end - begin);
        MP.middleCols(begin, end - begin) = M * Phi.middleCols(begin, end - begin);
      },
      split ? 2 : m + 1);
  const double k1 = norm1(K), m1 = norm1(M);
  r.generalized_mass.resize(m);
  r.generalized_stiffness.resize(m);
  r.residuals.resize(m);
  r.backward_errors.resize(m);
  for (Eigen::Index j = 0; j < m; ++j) {
    const double lam = r.eigenvalues(j);
    r.generalized_mass(j) = Phi.col(j).dot(MP.col(j));
    r.generalized_stiffness(j) = Phi.col(j).dot(KP.col(j));
    const double res = (KP.col(j) - lam * MP.col(j)).norm();
    const double kphi = KP.col(j).norm();
    r.residuals(j) = kphi > 0.0 ? res / kphi : (res == 0.0 ? 0.0 : std::numeric_limits<double>::infinity());
    const double den = (k1 + std::abs(lam) * m1) * Phi.col(j).norm();
    r.backward_errors(j) = den > 0.0 ? res / den : 0.0;
  }
  r.orthogonality = 0.0;
  if (m > 0) {
    const Eigen::MatrixXd G = Phi.transpose() * MP;
    for (Eigen::Index i = 0; i < m; ++i)
      for (Eigen::Index j = 0; j < m; ++j) {
        const double s = std::sqrt(std::abs(G(i, i) * G(j, j)));
        const double g = s > 0.0 ? G(i, j) / s : G(i, j);
        r.orthogonality = std::max(r.orthogonality, std::abs(g - (i == j ? 1.0 : 0.0)));
      }
  }
}

EigenSolver::EigenSolver(EigenOptions options) : m_options(std::move(options)), m_factor(m_options.factor_kind) {}

EigenResult solve_modes(const SparseMatrix& K, const SparseMatrix& M, const EigenOptions& options) {
  return EigenSolver(options).solve(K, M);
}

namespace {

/// The frequency band asked for, as eigenvalues (−∞/+∞ where open).
struct Band {
  bool has_low = false, has_high = false;
  double lam_lo = 0, lam_hi = 0;
};

/// Checks the request (matrices of one size, ND or a band, the multilevel
/// method's fields) and returns the band.
Band checked_request(const EigenOptions& o, const SparseMatrix& K, const SparseMatrix& M) {
  if (K.rows() != K.cols() || M.rows() != M.cols() || K.rows() != M.rows())
    throw std::invalid_argument("EigenSolver: K is " + std::to_string(K.rows()) + " x " + std::to_string(K.cols()) +
                                " and M is " + std::to_string(M.rows()) + " x " + std::to_string(M.cols()) +
                                ", expected two square matrices of one size");
  Band band;
  band.has_high = !std::isnan(o.f_high);
  band.has_low = !std::isnan(o.f_low) && o.f_low > 0.0;
  if (!band.has_high && o.nd <= 0)
    throw formats::InputError("EigenSolver: nothing requested: give ND (number of modes) or an upper frequency");
  if (band.has_high && band.has_low && o.f_low > o.f_high)
    throw formats::InputError("EigenSolver: lower frequency " + std::to_string(o.f_low) + " Hz above upper " +
                              std::to_string(o.f_high) + " Hz");
  band.lam_lo = band.has_low ? hz_to_eigenvalue(o.f_low) : -std::numeric_limits<double>::infinity();
  band.lam_hi = band.has_high ? hz_to_eigenvalue(o.f_high) : std::numeric_limits<double>::infinity();
  if (!o.dof_groups.empty() && static_cast<Eigen::Index>(o.dof_groups.size()) != K.rows())
    throw std::invalid_argument("EigenSolver: dof_groups has " + std::to_string(o.dof_groups.size()) +
                                " entries for " + std::to_string(K.rows()) + " DOFs");
  // The multilevel method's fields, when given, checked whatever the method (Auto
  // may fall back to it): one row per DOF, finite values.
  const long n = K.rows();
  for (const auto& [field, name] : {std::pair{&o.near_null_space, "near_null_space"},
                                    std::pair{&o.strain_fields, "strain_fields"}}) {
    if (field->size() == 0) continue;
    if (field->rows() != n)
      throw std::invalid_argument("EigenSolver: " + std::string(name) + " has " + std::to_string(field->rows()) +
                                  " rows for " + std::to_string(n) + " DOFs");
    if (!field->allFinite())
      throw std::invalid_argument("EigenSolver: " + std::string(name) + " has values that are not finite");
  }
  return band;
}

/// Factors K − σM (lower triangles only; the analysis is reused when the pattern
/// is) and records the factor's figures in `res`.
FactorStatus factor_shifted(CholmodFactor& factor, const SparseMatrix& K, const SparseMatrix& M, double sigma,
                            const EigenOptions& o, EigenResult& res) {
  const int analyses_before = factor.analysis_count();
  const auto tf = Clock::now();
  const SparseMatrix A = SparseMatrix(K.triangularView<Eigen::Lower>()) - sigma * SparseMatrix(M.triangularView<Eigen::Lower>());
  const FactorStatus fs = factor.factorize(A, o.near_singular_rcond);
  res.factor_seconds = seconds_since(tf);
  if (const int analyses = factor.analysis_count() - analyses_before; analyses > 0) {
    res.analyses += analyses;
    res.analyze_seconds = factor.last_analyze_seconds();
  }
  res.factor_nnz = factor.factor_nnz();
  res.factor_flops = factor.factor_flops();
  res.factor_bytes = factor.factor_bytes();
  res.ordering = factor.ordering();
  return fs;
}

/// EigenMethod::Auto with both methods possible: the symbolic analysis of K − σM
/// (kept for the factorisation that follows when the direct method wins), then
/// the choice by predicted cost (method_choice.hpp), its reason in the result.
/// True: the multilevel method.
bool choose_by_cost(CholmodFactor& factor, const SparseMatrix& K, const SparseMatrix& M, double sigma,
                    const EigenOptions& o, EigenResult& res) {
  report(o.progress, "analysing K - sigma M (method choice)", 0.0);
  const SparseMatrix A = SparseMatrix(K.triangularView<Eigen::Lower>()) - sigma * SparseMatrix(M.triangularView<Eigen::Lower>());
  factor.analyze(A);
  res.analyses = 1;
  res.analyze_seconds = factor.last_analyze_seconds();
  res.factor_nnz = factor.factor_nnz();
  res.factor_flops = factor.factor_flops();
  res.factor_bytes = factor.factor_bytes();
  res.ordering = factor.ordering();
  const MethodChoice c =
      choose_method(K.rows(), o.nd, {res.factor_flops, res.factor_nnz, res.factor_bytes}, factor.memory_limit());
  res.method_reason = c.reason;
  if (!c.factor_fits)
    res.warnings.push_back("the factor of K - sigma M would take " + std::to_string(res.factor_bytes / 1073741824.0) +
                           " GiB (limit " + std::to_string(factor.memory_limit() / 1073741824.0) +
                           " GiB): solved by the multilevel method instead");
  return c.multilevel;
}

/// A failed factorisation as the result's status and a message saying what it means.
void record_factor_failure(const FactorStatus& fs, double sigma, EigenResult& res) {
  res.status = to_status(fs.code);
  res.failed_dof = fs.column;
  if (fs.code == FactorStatus::Code::NotPositiveDefinite)
    res.message = "K - sigma*M (sigma = " + std::to_string(sigma) + ") is not positive definite at DOF index " +
                  std::to_string(fs.column) +
                  ": a mechanism (a DOF with neither stiffness nor mass, or an unrestrained joint), "
                  "an indefinite K, or a shift above the lowest eigenvalue";
  else if (fs.code == FactorStatus::Code::NearSingular)
    res.message = "K - sigma*M (sigma = " + std::to_string(sigma) + ") is nearly singular (" + fs.message +
                  "): a near-mechanism, or a massless DOF with almost no stiffness";
  else
    res.message = "K - sigma*M cannot be factorised: " + fs.message +
                  (fs.code == FactorStatus::Code::TooLarge ? " (EigenOptions::max_factor_bytes)" : "");
}

/// Sturm count of the band top: the number of eigenvalues below λ_hi.
void sturm_count(const SparseMatrix& K, const SparseMatrix& M, const Band& band, EigenResult& res) {
  double s = band.lam_hi;
  for (int attempt = 0; attempt < 3 && res.sturm_count < 0; ++attempt) {
    res.sturm_count = count_negative_pivots(K - s * M);
    s = s * (1.0 + 1e-9) + 1e-12;  // a zero pivot: s is an eigenvalue of a leading block
  }
}

/// Lanczos runs (Spectra or block) until the band is covered, the modes asked
/// for are found and the Sturm count agrees, or every finite eigenvalue is in.
LanczosRun lanczos_until_covered(const CholmodFactor& factor, const MassOp& mass, double sigma, const EigenOptions& o,
                                 const Band& band, long n, long n_massive, EigenResult& res) {
  // Size of the first run.
  const long max_nev = std::min(n - 1, std::max<long>(n_massive - 1, 1));
  long nev = o.nd > 0 ? o.nd : (o.ne > 0 ? o.ne + 1 : 10);
  if (band.has_high && res.sturm_count >= 0) nev = std::max<long>(nev, res.sturm_count + 1);
  if (band.has_high && o.nd > 0 && res.sturm_count >= 0)
    nev = std::max<long>(o.nd, std::min<long>(nev, res.sturm_count + 1));

  const bool use_block =
      o.method == EigenMethod::BlockLanczos ||
      (o.method == EigenMethod::Auto &&
       (n >= kAutoBlockLanczosDof || res.factor_nnz >= kAutoBlockLanczosFill * static_cast<double>(n)));
  res.method = use_block ? "BlockLanczos" : "Spectra";
  const auto tl = Clock::now();
  LanczosRun run;
  for (;;) {
    nev = std::min(nev, max_nev);
    // The shift-invert operator (K − σM)⁻¹M has rank n_massive: a Lanczos basis
    // wider than that runs out of the mass-carrying subspace and its extra
    // vectors, M-orthogonal to everything only through round-off, give spurious
    // Ritz pairs. So the basis never exceeds the number of DOFs with mass.
    const long ncv_cap = std::max<long>(std::min<long>(n, n_massive), nev + 1);
    const long ncv = o.ncv > 0 ? std::min<long>(ncv_cap, std::max<long>(o.ncv, nev + 1))
                               : std::min<long>(ncv_cap, std::max<long>(2 * nev + 1, nev + 20));
    res.nev = static_cast<int>(nev);
    res.ncv = static_cast<int>(ncv);
    report(o.progress, res.method + ": nev " + std::to_string(nev), 0.4);
    if (use_block)
      run = run_block_lanczos(factor, mass, sigma, static_cast<int>(nev), o);
    else
      run = run_lanczos(factor, mass, sigma, static_cast<int>(nev), static_cast<int>(ncv), o);
    ++res.lanczos_runs;
    res.iterations += run.iterations;
    if (!run.converged) break;
    if (!band.has_high) break;
    const Eigen::VectorXd& v = run.values;
    long below_hi = 0, in_band = 0;
    for (Eigen::Index i = 0; i < v.size(); ++i) {
      if (v(i) < band.lam_hi) ++below_hi;
      if (v(i) < band.lam_hi && v(i) >= band.lam_lo) ++in_band;
    }
    const bool passed_top = v.size() > 0 && v(v.size() - 1) >= band.lam_hi;
    const bool enough_nd = o.nd > 0 && in_band >= o.nd;
    const bool sturm_ok = res.sturm_count < 0 || below_hi >= res.sturm_count;
    if ((enough_nd || passed_top) && sturm_ok) break;
    if (nev >= max_nev) break;  // every finite eigenvalue computed
    // Lanczos missed modes the inertia count sees (a multiple eigenvalue): ask for
    // more, which also widens the basis; otherwise double until past the top.
    nev = res.sturm_count >= 0 && !sturm_ok ? std::max(nev + 1 + (res.sturm_count - below_hi), res.sturm_count + 1)
                                            : 2 * nev;
  }
  res.lanczos_seconds = seconds_since(tl);
  if (!run.converged) {
    res.status = EigenResult::Status::NotConverged;
    res.message = "Lanczos did not converge: " + std::to_string(run.values.size()) + " of " + std::to_string(nev) +
                  " modes after " + std::to_string(run.iterations) + " restarts (raise maxit or ncv, or move the shift)";
  }
  return run;
}

/// The band's modes, the lowest ND of them, normalised and checked; warnings
/// where the Sturm count disagrees or fewer modes exist than asked for.
void select_modes(const SparseMatrix& K, const SparseMatrix& M, const MassOp& mass, const EigenOptions& o,
                  const Band& band, long n_massive, const Eigen::VectorXd& lambda, const Eigen::MatrixXd& Phi,
                  EigenResult& res) {
  std::vector<Eigen::Index> keep;
  for (Eigen::Index i = 0; i < lambda.size(); ++i) {
    if (lambda(i) < band.lam_lo || lambda(i) > band.lam_hi) continue;
    if (o.nd > 0 && static_cast<long>(keep.size()) >= o.nd) break;
    keep.push_back(i);
  }
  res.eigenvalues.resize(static_cast<Eigen::Index>(keep.size()));
  res.modes.resize(K.rows(), static_cast<Eigen::Index>(keep.size()));
  for (size_t j = 0; j < keep.size(); ++j) {
    res.eigenvalues(static_cast<Eigen::Index>(j)) = lambda(keep[j]);
    res.modes.col(static_cast<Eigen::Index>(j)) = Phi.col(keep[j]);
  }
  normalise(res.modes, mass, o.norm);
  compute_checks(K, M, res);
  if (band.has_high && res.sturm_count >= 0 && res.ok()) {
    long below = 0;
    for (Eigen::Index i = 0; i < lambda.size(); ++i)
      if (lambda(i) < band.lam_hi) ++below;
    if (below != res.sturm_count && !(o.nd > 0 && static_cast<long>(keep.size()) >= o.nd)) {
      res.sturm_mismatch = true;
      res.warnings.push_back("Sturm count says " + std::to_string(res.sturm_count) +
                             " eigenvalues lie below the upper bound, Lanczos found " + std::to_string(below));
    }
  }
  if (o.nd > 0 && static_cast<long>(keep.size()) < o.nd && !band.has_high && res.ok())
    res.warnings.push_back("only " + std::to_string(keep.size()) + " of the " + std::to_string(o.nd) +
                           " requested modes exist (DOFs with mass: " + std::to_string(n_massive) + ")");
}

}  // namespace

EigenResult EigenSolver::solve(const SparseMatrix& K, const SparseMatrix& M) {
  const EigenOptions& o = m_options;
  const auto t0 = Clock::now();
  const Band band = checked_request(o, K, M);
  if (o.dof_groups != m_factor.dof_groups()) m_factor.set_dof_groups(o.dof_groups);
  m_factor.set_memory_limit(o.max_factor_bytes > 0.0   ? o.max_factor_bytes
                            : o.max_factor_bytes < 0.0 ? 0.0
                                                       : 0.8 * physical_memory_bytes());
  EigenResult res;
  const long n = K.rows();
  const MassOp mass(M);
  // Shift: below zero, scaled to the model (see EigenOptions::shift).
  const double sigma = std::isnan(o.shift) ? automatic_shift(K, M) : o.shift;
  res.shift = sigma;
  const Eigen::VectorXd mdiag = M.diagonal();
  const long n_massive = (mdiag.array() > 0.0).count();
  const bool multilevel_possible =
      o.near_null_space.size() > 0 && !o.dof_groups.empty() && !band.has_high && !band.has_low && o.nd > 0;
  if (o.method == EigenMethod::Multilevel) {
    if (!multilevel_possible)
      throw std::invalid_argument(
          "EigenSolver: the multilevel method needs dof_groups, near_null_space (the rigid-body modes) and ND, "
          "without a frequency band (V1/V2, F1/F2)");
    res.method_reason = "requested";
    solve_multilevel(K, M, sigma, o, mass, n_massive, t0, res);
    return res;
  }

  if (o.method != EigenMethod::Auto) res.method_reason = "requested";
  else if (!multilevel_possible)
    res.method_reason = "direct: no multilevel method without ND, dof_groups and near_null_space, or with a band";
  else if (choose_by_cost(m_factor, K, M, sigma, o, res)) {
    solve_multilevel(K, M, sigma, o, mass, n_massive, t0, res);
    return res;
  }
  report(o.progress, "factorising K - sigma M", 0.0);
  const FactorStatus fs = factor_shifted(m_factor, K, M, sigma, o, res);
  if (!fs.ok()) {
    record_factor_failure(fs, sigma, res);
    res.total_seconds = seconds_since(t0);
    return res;
  }
  report(o.progress, "factorised", 0.3);

  if (band.has_high && o.sturm_check) {
    report(o.progress, "Sturm count (LDL' inertia of K - lambda_high M)");
    sturm_count(K, M, band, res);
  }
  const long solves_before = m_factor.solve_count();
  const LanczosRun run = lanczos_until_covered(m_factor, mass, sigma, o, band, n, n_massive, res);
  Eigen::VectorXd lambda = run.values;
  Eigen::MatrixXd Phi = run.vectors;
  if (o.refine && Phi.cols() > 0) {
    report(o.progress, "Rayleigh-Ritz refinement", 0.9);
    rayleigh_ritz_refine(K, mass, m_factor, sigma, lambda, Phi);
  }
  res.solves = m_factor.solve_count() - solves_before;
  select_modes(K, M, mass, o, band, n_massive, lambda, Phi, res);
  res.total_seconds = seconds_since(t0);
  report(o.progress, "modes done", 1.0);
  return res;
}

}  // namespace ssid::estimator
