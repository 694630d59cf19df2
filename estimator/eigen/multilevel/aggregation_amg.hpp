#pragma once
/// \file aggregation_amg.hpp
/// Two-level smoothed-aggregation preconditioner for a symmetric positive
/// definite structural matrix A = K − σM: X ≈ A⁻¹ R for a block of residuals.
///
/// Why: a direct factor of a large 3D model grows like n^{4/3} in memory and n² in
/// flops (the 1M-DOF lattice needs a 22 GiB factor and 2.7·10¹³ flops); the
/// multilevel eigen-solver (multilevel_eigen.hpp) needs only an approximate
/// inverse, applied in O(n) per vector. Method (Vaněk, Mandel & Brezina 1996):
/// - grid points (`groups`, the DOFs of one grid) are aggregated: a root whose
///   neighbours are all free takes every free grid point within
///   `aggregate_radius` graph steps; leftovers join a neighbouring aggregate;
/// - the tentative prolongator P₀ restricts the near-null space B (the rigid-body
///   modes, n x 6), and the further low-energy fields F when given (the
///   constant-strain fields), to each aggregate and orthonormalises them (QR), so
///   the coarse space reproduces rigid motions (and uniform strains) exactly;
/// - the prolongator is smoothed, P = (I − ω D⁻¹A)^s P₀ (s = prolongator_steps), ω = 4/(3 ρ(D⁻¹A)), D the
///   grid-point blocks of A: coarse functions then bend smoothly instead of
///   jumping at aggregate borders (the energy of P's columns drops by orders);
/// - the coarse matrix Aᶜ = Pᵀ A P is factorised by CHOLMOD (it is small);
/// - one application: Chebyshev smoothing (degree `smoother_degree`, block
///   Jacobi D) on A X = R, the coarse correction X += P Aᶜ⁻¹ Pᵀ (R − A X), and the
///   same smoothing again: a symmetric positive definite operator, as the
///   eigen-solver's theory asks.
#include "estimator/linalg/cholmod_factor.hpp"
#include "estimator/eigen/multilevel/block_ops.hpp"

#include <Eigen/Core>
#include <stdexcept>
#include <string>
#include <vector>

namespace ssid::estimator::multilevel {

/// A grid point's diagonal block of A is not positive definite: a DOF with
/// neither stiffness nor mass (a mechanism). `dof` is a row of A in that block.
struct NotPositiveDefiniteBlock : std::runtime_error {
  NotPositiveDefiniteBlock(const std::string& what, long dof_) : std::runtime_error(what), dof(dof_) {}
  long dof;
};

struct AmgOptions {
  /// Graph distance from an aggregate's root to its members; 0: automatic.
  /// Automatic with strain fields F: 2 up to kLargeModelGrids grid points, 3 beyond.
  /// The coarse model holds about a seventh of the DOFs with radius 2 and a
  /// fifteenth with radius 3, and its factor grows faster than the model, so the
  /// larger radius pays on large models although LOBPCG then needs more iterations.
  /// Automatic without F: 2 at every size (with radius 1 the coarse model of a large
  /// model is too big for its factor to pay). The lattice measurements behind these
  /// choices: docs/performance.md ("The multilevel method", passes 1-7).
  int aggregate_radius = 0;
  /// The automatic radius with strain fields is 3 above this many grid points
  /// (grid points rather than DOFs: the coarse model grows with the aggregates).
  static constexpr long kLargeModelGrids = 20000;
  int smoother_degree = 4;       ///< Chebyshev degree before and after the coarse correction
  double smoother_ratio = 30.0;  ///< the Chebyshev interval is [ρ/ratio, ρ] of D⁻¹A
  /// Jacobi smoothing steps of the prolongator, P = (I − ω D⁻¹A)^s P₀ (0: the
  /// tentative P₀; −1: automatic, 1 with strain fields F, 2 without).
  /// Without F, two rather than the classical one: a beam model's piecewise-rigid
  /// aggregates bend too stiffly, and the second step lowers the coarse model's
  /// first eigenvalue error and the eigen-solver's iterations by about a third for a
  /// coarse factor about twice as dense. With F the coarse space bends by itself,
  /// and one step keeps the coarse matrix's stencil, and so its factor, small
  /// (figures: docs/performance.md).
  int prolongator_steps = -1;
  /// The cycle (smoothing, restriction, prolongation) in single precision; the
  /// coarse factor and solve too unless coarse_single_precision is off. Why: a preconditioner needs a few digits, and its
  /// sparse block products are bound by memory traffic, which floats halve (same
  /// iterations; docs/performance.md). The cycle is then symmetric to about
  /// 1e-8 rather than 1e-15 (relative; the test frame), which LOBPCG, converging
  /// to 1e-6, does not see. Off by itself for a model with entries of A or D⁻¹
  /// beyond 1e30 (AggregationAmg::single_precision()).
  bool single_precision = true;
  /// With single_precision: the coarse matrix is factorised in single precision
  /// too (CholmodFactor::factorize_single), and CHOLMOD's double factor is not
  /// computed. Why: at 1M DOFs the coarse factor (1.6·10¹² flops) was 27 s of the
  /// setup and its solve over half of the cycle (docs/performance.md); the coarse
  /// matrix of a shifted structural model is well conditioned (about 10⁴ for the
  /// benchmark lattice), far from what single precision cannot factor.
  bool coarse_single_precision = true;
  /// The single-precision coarse factor is kept only when it succeeds with CHOLMOD's
  /// reciprocal condition estimate (min diag L / max diag L)² at least this;
  /// otherwise the coarse matrix is factorised in double (a model whose coarse
  /// matrix single precision cannot resolve then costs time, not accuracy). The
  /// estimate is crude (94k lattice: 0.021 with the strain fields, whose κ(Aᶜ) is
  /// 2.4·10⁴ by power and inverse iterations; 0.056 and 1.2·10⁴ with the rigid-body
  /// modes alone): the check mainly catches a factorisation that breaks down or
  /// nearly does.
  double single_min_rcond = 1e-6;
};

class AggregationAmg {
 public:
  /// A: symmetric positive definite, both triangles stored, compressed. groups:
  /// grid point of each DOF (any ids ≥ 0). B: near-null space, A.rows() x k. F:
  /// further low-energy fields for the coarse space (the constant-strain fields,
  /// translators::a_set_strain_fields), A.rows() x m, or empty (all zeros: the
  /// same); in each aggregate only their directions outside B's span, above
  /// kFieldThreshold of the largest, join it.
  /// Throws std::invalid_argument on inconsistent sizes, NotPositiveDefiniteBlock
  /// for a grid point whose block of A is singular, and std::runtime_error when
  /// the coarse matrix cannot be factorised. A must outlive this object.
  AggregationAmg(const SparseMatrix& A, const std::vector<long>& groups, const Eigen::MatrixXd& B,
                 const AmgOptions& options = {}, const Eigen::MatrixXd& F = Eigen::MatrixXd());
  // The cycle's levels point into this object.
  AggregationAmg(const AggregationAmg&) = delete;
  AggregationAmg& operator=(const AggregationAmg&) = delete;

  /// X ≈ A⁻¹ R, one symmetric two-level cycle. Not thread-safe: the cycle's
  /// blocks are kept between calls (a fresh n x b block costs its page faults).
  void apply(const RowBlock& R, RowBlock& X) const;

  /// n x coarse, column-major. Throws std::logic_error once released.
  const SparseMatrix& prolongator() const;
  /// The same, row-major. Throws std::logic_error once released.
  const SparseRowMatrix& prolongator_rows() const;
  /// Frees the double-precision prolongator (prolongator(), prolongator_rows(),
  /// prolong() then throw) when the cycle runs in single precision on its own
  /// copy; nothing otherwise. Why: a caller done with the coarse model gives back
  /// two copies of P before allocating its iteration's blocks, which then reuse
  /// that memory instead of touching fresh pages (94k lattice: 86 MB, 1M: about a
  /// gigabyte; a first touch costs 0.4-2 s a gigabyte on a virtual machine).
  void release_double_prolongator();
  bool double_prolongator_released() const { return m_released; }
  /// Column blocks of P, one per aggregate: [coarse_blocks()[k], coarse_blocks()[k+1]).
  const std::vector<long>& coarse_blocks() const { return m_coarse_blocks; }
  /// X = P Y: coarse blocks interpolated to the model.
  void prolong(const RowBlock& Y, RowBlock& X) const;
  long coarse_size() const { return m_coarse_blocks.empty() ? 0 : m_coarse_blocks.back(); }  ///< also once P is released
  long aggregates() const { return m_aggregates; }
  /// The options as applied: the automatic radius and prolongator steps resolved.
  const AmgOptions& options() const { return m_options; }
  /// The automatic radius and prolongator steps resolved for a model of
  /// `grid_points` grid points, with strain fields or not.
  static AmgOptions resolved(const AmgOptions& options, long grid_points, bool strain_fields);
  /// A strain field's direction outside the rigid-body modes is kept in an
  /// aggregate's coarse space only above this fraction of the largest one.
  static constexpr double kFieldThreshold = 1e-6;
  double spectral_radius() const { return m_rho; }  ///< estimate of ρ(D⁻¹A) used by the smoothers
  /// Whether the cycle runs in single precision: AmgOptions::single_precision,
  /// unless A or D⁻¹ has entries beyond 1e30 (single precision would overflow).
  bool single_precision() const { return m_options.single_precision; }
  /// The factor of Aᶜ = Pᵀ A P (also the shift-invert operator of the coarse model
  /// when A = K − σM: Pᵀ K P − σ Pᵀ M P): its analysis always, its double
  /// factor only when the coarse factor is not in single precision.
  const CholmodFactor& coarse_factor() const { return m_coarse; }
  /// Aᶜ⁻¹ X for a column-major block, on whichever coarse factor there is (single
  /// precision when it is). Not thread-safe (the single factor's workspace is kept).
  Eigen::MatrixXd solve_coarse(const Eigen::MatrixXd& X) const;
  /// The coarse factor in single precision (AmgOptions::coarse_single_precision); null when there is none.
  const SingleSupernodalFactor* coarse_factor_single() const {
    return m_coarse_single.empty() ? nullptr : &m_coarse_single;
  }
  /// Wall seconds of the setup's parts: aggregation and the tentative prolongator,
  /// its smoothing, the coarse matrix product, the coarse factorisation.
  struct Times {
    double aggregation = 0, smoothing = 0, coarse_matrix = 0, coarse_factor = 0;
    double coarse_analysis = 0;  ///< the symbolic analysis (orderings tried), part of coarse_factor
  };
  const Times& times() const { return m_times; }

 private:
  /// The operators the cycle runs on, in precision T (double: the members below;
  /// float: copies), and the cycle's blocks, kept between calls (a fresh n x b
  /// block costs its page faults).
  template <class T>
  struct Level {
    const SparseOf<T>* A = nullptr;
    const SparseRowOf<T>* Prow = nullptr;
    const T* dinv = nullptr;
    mutable RowBlockOf<T> res, d, Ec, Y, R, X;
  };

  /// One fused smoothing pass: z = β D⁻¹ res, d = α d + z (d = z when α = 0), then
  /// X += d (X = d when set_x).
  template <class T>
  void jacobi_step(const Level<T>& L, const RowBlockOf<T>& res, double alpha, double beta, RowBlockOf<T>& d,
                   RowBlockOf<T>& X, bool set_x) const;
  template <class T>
  void chebyshev(const Level<T>& L, const RowBlockOf<T>& R, RowBlockOf<T>& X, bool zero_start) const;
  /// Y = Aᶜ⁻¹ Ec (single precision: on the single-precision factor when there is one).
  template <class T>
  void coarse_solve(const RowBlockOf<T>& Ec, RowBlockOf<T>& Y) const;
  template <class T>
  void cycle(const Level<T>& L, const RowBlockOf<T>& R, RowBlockOf<T>& X) const;

  const SparseMatrix& m_A;
  AmgOptions m_options;
  // Grid-point blocks of D⁻¹: the DOFs of group g are m_dofs[m_start[g] .. m_start[g+1]),
  // their inverse block (row-major, k x k) starts at m_dinv[m_dinv_start[g]].
  std::vector<long> m_start, m_dofs, m_dinv_start;
  std::vector<double> m_dinv;
  double m_rho = 0.0;
  bool m_released = false;
  long m_aggregates = 0;
  SparseMatrix m_P;
  SparseRowMatrix m_Prow;
  std::vector<long> m_coarse_blocks;
  CholmodFactor m_coarse;
  SingleSupernodalFactor m_coarse_single;  // empty unless the coarse factor is in single precision
  mutable std::vector<SingleSupernodalFactor::Work> m_coarse_work;  // one per part of a split solve
  /// Y = Aᶜ⁻¹ B on the single-precision factor, n x nrhs row-major: the columns split
  /// over the cores, each part on a single-threaded BLAS.
  void solve_coarse_single(const float* b, float* y, long nrhs) const;
  Times m_times;
  Level<double> m_double;
  Level<float> m_single;
  SparseOf<float> m_Af;
  SparseRowOf<float> m_Prowf;
  std::vector<float> m_dinvf;
};

}  // namespace ssid::estimator::multilevel
