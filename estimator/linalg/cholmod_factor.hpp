#pragma once
/// \file cholmod_factor.hpp
/// RAII wrapper of a CHOLMOD sparse Cholesky factorisation A = P Lᵀ L Pᵀ of a
/// symmetric positive definite matrix, with the symbolic analysis (fill-reducing
/// ordering, supernode structure) kept apart from the numeric factorisation.
///
/// Why: in model updating the sparsity of K(r) − σM(r) never changes while its
/// values do, so the analysis (the ordering is the expensive, sequential part for
/// large models) is done once per pattern and every parameter update only
/// refactors. `factorize` re-analyses by itself when the pattern it is given
/// differs from the analysed one; `analysis_count()` says how often that happened.
///
/// Grouped ordering: a structural model has several DOFs per grid point (six for
/// beams and shells) that are coupled to exactly the same neighbours. Given the
/// group of every row (`set_dof_groups`), the fill-reducing ordering is computed
/// on the grid-point graph (one vertex per group, an edge where any DOF of one
/// group couples to any DOF of the other), six times smaller in each dimension
/// than the DOF graph, and expanded: the DOFs of one group are eliminated
/// together. The group graph is ordered by AMD; when AMD's ordering is poor by
/// CHOLMOD's own rule (flops/nnz(L) ≥ 500 and nnz(L)/nnz(A) ≥ 5) METIS and
/// CHOLMOD's nested dissection (NESDIS) are tried too, every candidate is
/// analysed on the rows, and the one with the fewest factorisation flops is
/// kept. On 3D beam-frame lattices this cuts the analysis time 4-6x and the
/// factor's flops by 20-50 % (docs/eigen_solver.md).
///
/// The 64-bit CHOLMOD interface (cholmod_l_*) is used so that factors of
/// million-DOF models (more than 2³¹ entries in L) fit.
#include <Eigen/SparseCore>
#include "estimator/linalg/single_factor.hpp"
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

namespace ssid::estimator {

/// Outcome of a numeric factorisation: a numerical outcome the caller acts on,
/// not an exception (bad input, such as a non-square matrix, throws).
struct FactorStatus {
  /// TooLarge: refused before numeric work, the factor would exceed the memory
  /// limit (set_memory_limit); Failed: CHOLMOD failed (out of memory included).
  enum class Code { Ok, NotPositiveDefinite, NearSingular, TooLarge, Failed };
  Code code = Code::Ok;
  /// For NotPositiveDefinite: the row/column index of the input matrix (original
  /// ordering) where the factorisation met a non-positive pivot; −1 otherwise.
  /// Supernodal factorisations report the first column of the failing supernode,
  /// so the culprit is this DOF or one eliminated together with it.
  long column = -1;
  /// Reciprocal condition estimate (min/max of diag(L))², CHOLMOD's cholmod_rcond.
  double rcond = 0.0;
  std::string message;
  bool ok() const { return code == Code::Ok; }
};

/// Which factorisation CHOLMOD builds.
enum class FactorKind {
  Supernodal,  ///< supernodal LLᵀ (BLAS-3 dense kernels; what large models need)
  Auto,        ///< let CHOLMOD choose simplicial or supernodal from the flop count
  Simplicial   ///< simplicial LLᵀ
};

namespace detail {
struct CholmodState;  // cholmod_common + factor + workspaces, defined in the .cpp
}

/// Sparse Cholesky factorisation of a symmetric matrix given by its lower
/// triangle (entries above the diagonal are ignored). Non-copyable, movable.
class CholmodFactor {
 public:
  using SparseMatrix = Eigen::SparseMatrix<double>;

  explicit CholmodFactor(FactorKind kind = FactorKind::Supernodal);
  ~CholmodFactor();
  CholmodFactor(CholmodFactor&&) noexcept;
  CholmodFactor& operator=(CholmodFactor&&) noexcept;
  CholmodFactor(const CholmodFactor&) = delete;
  CholmodFactor& operator=(const CholmodFactor&) = delete;

  /// Symbolic analysis of the pattern of tril(A): ordering (CHOLMOD tries AMD
  /// and, when fill is high, METIS/nested dissection, and keeps the best) and
  /// the supernodal structure. Throws std::invalid_argument when A is not square.
  void analyze(const SparseMatrix& A);

  /// Groups of rows for the ordering (see the file comment): groups[i] ≥ 0 is
  /// the group (grid point) of row i; group ids need not be contiguous or sorted.
  /// Empty: CHOLMOD's own ordering of the DOF graph (AMD, METIS when fill is
  /// high). Takes effect at the next analysis (a change forces one); throws
  /// std::invalid_argument for a negative id. The size is checked against the
  /// matrix at analysis.
  void set_dof_groups(std::vector<long> groups);
  const std::vector<long>& dof_groups() const { return m_groups; }

  /// Largest factor (factor_bytes(), from the symbolic analysis) that factorize
  /// will attempt; a larger one is refused with status TooLarge and a message
  /// giving the size, before any numeric work. 0: no limit.
  void set_memory_limit(double bytes) { m_memory_limit = bytes; }
  double memory_limit() const { return m_memory_limit; }

  /// Numeric factorisation of A (lower triangle used). Analyses first when no
  /// pattern was analysed or A's pattern differs from it. The input values are
  /// passed to CHOLMOD without a copy when A is compressed and lower triangular.
  /// `near_singular_rcond`: below this reciprocal condition estimate the status is
  /// NearSingular (the factor is still usable).
  FactorStatus factorize(const SparseMatrix& A, double near_singular_rcond = 1e-14);

  /// Solves A X = B for `ncols` right-hand sides stored column-major with leading
  /// dimension rows(); x and b may not alias. Requires a successful factorize.
  /// Several columns at once let CHOLMOD use BLAS-3 on each supernode and read L
  /// once for all of them.
  void solve(const double* b, double* x, long ncols = 1) const;

  Eigen::MatrixXd solve(const Eigen::Ref<const Eigen::MatrixXd>& B) const;

  /// The factorisation in single precision only (factorize_supernodal_single in
  /// single_factor.hpp) on this object's supernodal analysis, done here when A's
  /// pattern differs from the last one; CHOLMOD's double factor is not computed,
  /// so solve() is not available afterwards (nor a double factor of an earlier
  /// matrix: factorized() is false until the next factorize()). Why: the multilevel preconditioner's
  /// coarse factor (1.6·10¹² flops at 1M DOFs) needs a few digits only, and single
  /// precision halves its time and memory. The status's rcond is CHOLMOD's
  /// (min diag L / max diag L)². Requires a supernodal factor kind.
  FactorStatus factorize_single(const SparseMatrix& A, SingleSupernodalFactor& out);

  long rows() const;
  bool factorized() const;
  /// Number of symbolic analyses done so far (the reuse test counts them).
  int analysis_count() const { return m_analyses; }
  /// Number of numeric factorisations done so far.
  int factorization_count() const { return m_factorizations; }
  /// Number of right-hand-side columns solved so far.
  long solve_count() const;
  /// Entries of L (including supernodal padding) and the factorisation's flop
  /// count from the last analysis, as CHOLMOD reports them.
  double factor_nnz() const;
  double factor_flops() const;
  /// Memory of the factor from the symbolic analysis, before any numeric work:
  /// the values of L (supernodal: L->xsize doubles; simplicial: nnz(L)), its
  /// integer structure, and the largest update matrix the supernodal
  /// factorisation allocates as workspace. Bytes.
  double factor_bytes() const;
  /// Wall-clock seconds of the last analysis and the last numeric factorisation.
  double last_analyze_seconds() const { return m_analyze_s; }
  double last_factorize_seconds() const { return m_factorize_s; }
  /// "AMD", "METIS", "NESDIS", ... : the ordering CHOLMOD kept; with DOF groups
  /// "<method> on <count> groups".
  std::string ordering() const;
  bool supernodal() const;

 private:
  bool same_pattern(const SparseMatrix& lower) const;
  /// tril(A) (A itself when already lower and compressed, else built in `storage`),
  /// analysed when its pattern differs from the last analysis; throws for a
  /// non-square A (message prefixed with `who`).
  const SparseMatrix& analysed_lower(const SparseMatrix& A, SparseMatrix& storage, const char* who);
  void wrap(const SparseMatrix& lower);

  void analyze_grouped(long n);

  std::unique_ptr<detail::CholmodState> m_state;
  FactorKind m_kind;
  std::vector<long> m_groups;
  std::string m_ordering;  // set by a grouped analysis; empty: L->ordering names it
  double m_lnz = 0.0, m_fl = 0.0;
  double m_memory_limit = 0.0;
  int m_analyses = 0;
  int m_factorizations = 0;
  bool m_single_only = false;  // the last factorisation was factorize_single: no double factor
  double m_analyze_s = 0.0, m_factorize_s = 0.0;
};

/// Lower triangle of A, compressed, as CHOLMOD reads it.
Eigen::SparseMatrix<double> lower_triangle(const Eigen::SparseMatrix<double>& A);

/// Inertia count by a simplicial LDLᵀ factorisation (no pivoting) of tril(A):
/// the number of negative entries of D. By Sylvester's law this equals the number
/// of negative eigenvalues of A. Used as the Sturm-sequence count: with A = K − sM
/// (M positive definite on the DOFs with mass) it is the number of eigenvalues of
/// K φ = λ M φ below s. Returns −1 when a zero pivot stops the factorisation
/// (s is an eigenvalue of a leading block: move s slightly and count again).
long count_negative_pivots(const Eigen::SparseMatrix<double>& A);

}  // namespace ssid::estimator
