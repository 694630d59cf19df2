#pragma once
/// \file eigen_solver.hpp
/// Lowest modes of the generalised symmetric eigenproblem
///   K φ = λ M φ,   λ = ω² (rad/s)²,
/// with K symmetric positive (semi-)definite and M symmetric positive semi-definite
/// (lumped diagonal with massless DOFs allowed), both sparse in full symmetric storage.
///
/// Method: Lanczos in shift-invert mode on
///   (K − σM)⁻¹ M x = ν x,   ν = 1/(λ − σ),
/// with the M inner product: block Lanczos (block_lanczos.hpp, 16 right-hand
/// sides per solve) from 50 000 DOF or a dense factor (nnz(L)/n ≥ 100),
/// Spectra's SymGEigsShiftSolver otherwise. Models whose factor would not fit in
/// memory go to EigenMethod::Multilevel (multilevel/multilevel_eigen.hpp: LOBPCG
/// with an aggregation multigrid preconditioner, no factor of the full model).
/// (K − σM)⁻¹ is a CHOLMOD supernodal Cholesky factor (CholmodFactor), analysed
/// once per sparsity pattern and refactored when only values change; with
/// `dof_groups` the fill-reducing ordering is computed on the grid-point graph. σ lies below the lowest eigenvalue (σ < 0 by default), so
/// K − σM is positive definite even for free-free structures, whose rigid-body
/// modes come out with λ ≈ 0.
///
/// Massless DOFs: M is singular there and so is the M "inner product". The start
/// vector is (K − σM)⁻¹ M r, inside the range of the operator, so every Lanczos
/// vector and every Ritz vector is too; the final Rayleigh–Ritz step on one more
/// block solve (K − σM)⁻¹ M Φ purifies and sharpens the modes. This is the
/// standard cure for the spurious infinite-eigenvalue directions.
///
/// Range requests (EIGRL V1/V2, EIGR F1/F2) find ALL modes in the band: nev grows
/// until the largest converged eigenvalue lies above the band's top; then, when
/// `sturm_check` is on, the number of eigenvalues below the top is counted
/// independently by the inertia of K − λ_top M (Sylvester; simplicial LDLᵀ) and
/// nev grows again if Lanczos missed one. See docs/eigen_solver.md.
#include "estimator/linalg/cholmod_factor.hpp"
#include "estimator/eigen/multilevel/multilevel_eigen.hpp"
#include "estimator/reporting/progress.hpp"

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <limits>
#include <string>
#include <vector>

namespace ssid::estimator {

/// How modes are scaled (EIGRL/EIGR NORM).
enum class ModeNormalization {
  Mass,  ///< φᵀMφ = 1 (NASTRAN's default, NORM=MASS)
  Max    ///< largest |component| = 1 (NORM=MAX)
};

/// Which Krylov iteration on (K − σM)⁻¹M EigenMethod::Auto takes. From this
/// size, block Lanczos: a block solve reads the factor once for 16 right-hand
/// sides, which pays when the factor is large; on smaller models the
/// single-vector iteration (Spectra) needs far fewer solves. The measurements
/// behind both thresholds are in docs/performance.md ("Eigen-solver").
inline constexpr long kAutoBlockLanczosDof = 50000;
/// Below that size Auto still takes block Lanczos when the factor is dense for its
/// size, nnz(L)/n at least this: reading L then dominates each solve and the block
/// amortises it.
inline constexpr double kAutoBlockLanczosFill = 100.0;

enum class EigenMethod {
  Auto,          ///< BlockLanczos for n ≥ 50 000 or nnz(L)/n ≥ 100, Spectra otherwise
  Spectra,       ///< Spectra's SymGEigsShiftSolver (implicitly restarted Lanczos, one vector)
  BlockLanczos,  ///< block Lanczos (block_lanczos.hpp): b solves per factor pass
  /// LOBPCG with a smoothed-aggregation preconditioner (multilevel/multilevel_eigen.hpp):
  /// no factor of the full model; needs dof_groups and near_null_space, lowest ND only.
  /// Auto takes it, when both are given, where the factor would exceed
  /// max_factor_bytes or the method is predicted faster (method_choice.hpp).
  Multilevel
};

/// What to extract. Bounds are frequencies in Hz (as EIGRL V1, V2 and EIGR F1, F2
/// give them); a NaN bound is absent. Field meanings follow NASTRAN:
/// - lowest `nd` modes when only nd is given;
/// - all modes with f in [f_low, f_high] when the band is given and nd is 0;
/// - the lowest nd modes in the band when both are given.
struct EigenOptions {
  double f_low = std::numeric_limits<double>::quiet_NaN();   ///< Hz (V1 / F1); NaN: no lower bound
  double f_high = std::numeric_limits<double>::quiet_NaN();  ///< Hz (V2 / F2); NaN: no upper bound
  int nd = 0;                                                ///< number of modes desired (ND)
  int ne = 0;  ///< EIGR NE: estimated number of roots in the band; only sizes the first Lanczos run
  ModeNormalization norm = ModeNormalization::Mass;

  /// Shift σ in eigenvalue units (rad/s)²; NaN: automatic, −1e-5 × the mean
  /// diagonal ratio K_ii/M_ii over DOFs with mass (below zero, far below the
  /// node-level frequencies, so rigid-body modes converge first and elastic ones
  /// at the speed of a zero shift). K − σM must be positive definite.
  double shift = std::numeric_limits<double>::quiet_NaN();
  EigenMethod method = EigenMethod::Auto;
  int block = 16;         ///< block size for BlockLanczos: one solve with 16 columns costs about one with 8 (L is read once); ≥ the largest multiplicity helps
  int ncv = 0;            ///< Spectra: Lanczos basis size; 0: automatic (2 nev + 1 or nev + 20, ≤ n)
  double tol = 1e-10;     ///< Spectra's relative tolerance on the Ritz values ν
  int maxit = 1000;       ///< Spectra's restart limit
  bool sturm_check = true;  ///< verify band completeness by an inertia count
  bool refine = true;       ///< one block solve + Rayleigh–Ritz after Lanczos
  FactorKind factor_kind = FactorKind::Supernodal;
  /// Grid point of every DOF (row of K), for the fill-reducing ordering: when
  /// given, the ordering is computed on the grid-point graph and expanded, the
  /// DOFs of a grid point eliminated together (CholmodFactor::set_dof_groups).
  /// Any ids ≥ 0 (grid ids will do); empty: CHOLMOD orders the DOF graph.
  /// Callers that know the grids (the assembler's DofMap) should fill it: it
  /// cuts the factorisation's time and memory (docs/eigen_solver.md).
  std::vector<long> dof_groups;
  /// Largest Cholesky factor to attempt, bytes, judged from the symbolic
  /// analysis before any numeric work (a larger one gives FactorFailed with the
  /// size in the message). 0: automatic, 80 % of the machine's physical memory;
  /// negative: no limit.
  double max_factor_bytes = 0.0;
  /// Rigid-body modes of the model (n x 6, or any near-null space of K), for
  /// EigenMethod::Multilevel's coarse space; empty: that method is not available.
  Eigen::MatrixXd near_null_space;
  /// The constant-strain displacement fields (n x 6, translators::a_set_strain_fields),
  /// added to EigenMethod::Multilevel's coarse space; empty: rigid-body modes only.
  /// Why: a coarse space linear in each aggregate rather than piecewise rigid (94k
  /// lattice: 17-18 LOBPCG iterations against 25; docs/performance.md).
  Eigen::MatrixXd strain_fields;
  multilevel::MultilevelOptions multilevel;  ///< EigenMethod::Multilevel's settings
  /// K − σM with a reciprocal condition estimate below this is reported near-singular.
  double near_singular_rcond = 1e-15;
  unsigned seed = 12345;  ///< start vector seed (results are deterministic)
  Progress progress;      ///< phases and solve counts on long runs
};

/// EIGRL (V1, V2, ND, NORM) as NASTRAN defines it: V1, V2 in Hz, blank = NaN.
EigenOptions eigrl_options(double v1, double v2, int nd, ModeNormalization norm = ModeNormalization::Mass);
/// EIGR (F1, F2, NE, ND, NORM): NE (estimated count) only sizes the first Lanczos run.
EigenOptions eigr_options(double f1, double f2, int ne, int nd, ModeNormalization norm = ModeNormalization::Mass);

struct EigenResult {
  enum class Status {
    Ok,
    NotPositiveDefinite,  ///< K − σM has a non-positive pivot: mechanism or shift above an eigenvalue
    NearSingular,         ///< K − σM numerically singular
    NotConverged,         ///< Lanczos stopped before the requested modes converged
    FactorFailed          ///< CHOLMOD failure (e.g. out of memory)
  };
  Status status = Status::Ok;
  std::string message;    ///< what went wrong, with the DOF index where there is one
  long failed_dof = -1;   ///< index into K's rows for NotPositiveDefinite
  std::vector<std::string> warnings;
  /// The Sturm count of the band disagrees with the eigenvalues found in it (a
  /// warning says by how much): modes may be missing, the result is not trustworthy.
  bool sturm_mismatch = false;

  Eigen::VectorXd eigenvalues;            ///< λ ascending, (rad/s)²
  Eigen::MatrixXd modes;                  ///< n x m, normalised per EigenOptions::norm
  Eigen::VectorXd generalized_mass;       ///< φᵀMφ
  Eigen::VectorXd generalized_stiffness;  ///< φᵀKφ
  /// ‖Kφ − λMφ‖₂ / ‖Kφ‖₂ (meaningful for elastic modes; a rigid-body mode's Kφ is round-off).
  Eigen::VectorXd residuals;
  /// Backward error ‖Kφ − λMφ‖₂ / ((‖K‖₁ + |λ| ‖M‖₁) ‖φ‖₂): small for every mode, rigid ones included.
  Eigen::VectorXd backward_errors;
  /// max over i, j of |φᵢᵀMφⱼ / √(mᵢ mⱼ) − δᵢⱼ|.
  double orthogonality = 0.0;

  // How the solve went.
  double shift = 0.0;
  int nev = 0, ncv = 0, lanczos_runs = 0;
  std::string method;    ///< "Spectra", "BlockLanczos" or "Multilevel"
  /// Why that method: EigenMethod::Auto's choice by predicted cost and the figures
  /// it was made by (method_choice.hpp), "requested" when the options named the
  /// method, or "direct: no multilevel method without ..." when Auto had no choice.
  std::string method_reason;
  long iterations = 0;   ///< Spectra restarts, block Lanczos block solves or LOBPCG iterations, summed over runs
  long coarse_size = 0;  ///< Multilevel: DOFs of the coarse model
  int deflated = 0;      ///< Multilevel: exact zero-energy modes taken from near_null_space first
  long solves = 0;       ///< right-hand-side columns solved with the factor
  long sturm_count = -1; ///< eigenvalues below the band top by inertia; −1 when not counted
  int analyses = 0;      ///< symbolic analyses done by this solve (0 when reused)
  double analyze_seconds = 0, factor_seconds = 0 /* analysis included */, lanczos_seconds = 0, total_seconds = 0;
  double factor_nnz = 0, factor_flops = 0;
  double factor_bytes = 0;  ///< memory of L and the factorisation workspace, from the symbolic analysis
  std::string ordering;

  bool ok() const { return status == Status::Ok; }
  int size() const { return static_cast<int>(eigenvalues.size()); }
  double radians(int i) const;
  double cycles(int i) const;
};

/// Holds the CHOLMOD analysis between solves: construct once, call solve() for
/// each parameter update of a model whose sparsity does not change.
class EigenSolver {
 public:
  using SparseMatrix = Eigen::SparseMatrix<double>;
  explicit EigenSolver(EigenOptions options = {});

  /// Throws std::invalid_argument on inconsistent sizes or options (nothing
  /// requested, f_low > f_high); numerical outcomes come back in the status.
  EigenResult solve(const SparseMatrix& K, const SparseMatrix& M);

  const CholmodFactor& factor() const { return m_factor; }
  EigenOptions& options() { return m_options; }
  const EigenOptions& options() const { return m_options; }

 private:
  EigenOptions m_options;
  CholmodFactor m_factor;
};

/// One-shot convenience: EigenSolver(options).solve(K, M).
EigenResult solve_modes(const Eigen::SparseMatrix<double>& K, const Eigen::SparseMatrix<double>& M,
                        const EigenOptions& options = {});

/// Throws the failure kind of a solve that did not succeed (`!r.ok()`), with
/// `message` as its text: formats::InputError for NotPositiveDefinite (the model
/// has a mechanism or negative stiffness: the input must change), and
/// formats::NumericalError for the outcomes of the computation itself (near
/// singular, not converged, factorisation failed).
[[noreturn]] void throw_solve_failure(const EigenResult& r, const std::string& message);

/// The automatic shift (EigenOptions::shift NaN): −1e-5 × Σ|K_ii| / Σ M_ii over
/// the DOFs with mass; −1 when there is no mass or no stiffness there.
double automatic_shift(const Eigen::SparseMatrix<double>& K, const Eigen::SparseMatrix<double>& M);

/// λ ↔ Hz: λ = (2πf)². The one conversion in ssid. A negative eigenvalue (a
/// rigid-body mode's round-off, or an unstable model) reads as f = √|λ| / 2π,
/// NASTRAN's convention in the CYCLES column of its eigenvalue table; the
/// eigen-solver warns about eigenvalues that are negative beyond round-off.
double hz_to_eigenvalue(double f);
double eigenvalue_to_hz(double lambda);

/// Fills eigenvalue-derived checks (generalised mass/stiffness, residuals,
/// backward errors, orthogonality) of `r` from its eigenvalues and modes.
void compute_checks(const Eigen::SparseMatrix<double>& K, const Eigen::SparseMatrix<double>& M, EigenResult& r);

}  // namespace ssid::estimator
