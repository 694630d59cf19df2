#include "estimator/linalg/cholmod_factor.hpp"

#include <cholmod.h>

#include <cstdio>
#include <numeric>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <stdexcept>

#include "formats/parse_error.hpp"

namespace ssid::estimator {

namespace detail {

/// Owns one cholmod_common and everything allocated through it. Objects are
/// freed before cholmod_l_finish, in the destructor only.
struct CholmodState {
  cholmod_common cm{};
  cholmod_factor* L = nullptr;
  // Workspaces of cholmod_l_solve2, kept between solves so that a Lanczos run
  // allocates nothing per iteration.
  mutable cholmod_dense* X = nullptr;
  mutable cholmod_dense* Y = nullptr;
  mutable cholmod_dense* E = nullptr;
  mutable long solves = 0;
  // The analysed pattern in CHOLMOD's 64-bit index type; values are borrowed.
  std::vector<SuiteSparse_long> p, i;
  cholmod_sparse A{};
  long n = 0;

  CholmodState() {
    cholmod_l_start(&cm);
    cm.print = 0;  // the library never prints; failures come back as statuses
    cm.error_handler = nullptr;
  }
  ~CholmodState() {
    if (L) cholmod_l_free_factor(&L, &cm);
    if (X) cholmod_l_free_dense(&X, &cm);
    if (Y) cholmod_l_free_dense(&Y, &cm);
    if (E) cholmod_l_free_dense(&E, &cm);
    cholmod_l_finish(&cm);
  }
  CholmodState(const CholmodState&) = delete;
  CholmodState& operator=(const CholmodState&) = delete;
};

}  // namespace detail

namespace {

int cholmod_supernodal_flag(FactorKind k) {
  switch (k) {
    case FactorKind::Supernodal: return CHOLMOD_SUPERNODAL;
    case FactorKind::Simplicial: return CHOLMOD_SIMPLICIAL;
    case FactorKind::Auto: break;
  }
  return CHOLMOD_AUTO;
}

/// A header describing tril(A) for CHOLMOD: pattern from `p`, `i`, values borrowed.
cholmod_sparse sparse_header(long n, std::vector<SuiteSparse_long>& p, std::vector<SuiteSparse_long>& i,
                             const double* x) {
  cholmod_sparse A{};
  A.nrow = static_cast<size_t>(n);
  A.ncol = static_cast<size_t>(n);
  A.nzmax = i.size();
  A.p = p.data();
  A.i = i.data();
  A.nz = nullptr;
  A.x = const_cast<double*>(x);  // CHOLMOD reads A; its API is not const-correct
  A.z = nullptr;
  A.stype = -1;  // symmetric, lower triangle stored
  A.itype = CHOLMOD_LONG;
  A.xtype = CHOLMOD_REAL;
  A.dtype = CHOLMOD_DOUBLE;
  A.sorted = 1;
  A.packed = 1;
  return A;
}

void copy_pattern(const Eigen::SparseMatrix<double>& A, std::vector<SuiteSparse_long>& p,
                  std::vector<SuiteSparse_long>& i) {
  p.assign(A.outerIndexPtr(), A.outerIndexPtr() + A.cols() + 1);
  i.assign(A.innerIndexPtr(), A.innerIndexPtr() + A.nonZeros());
}

bool is_lower_compressed(const Eigen::SparseMatrix<double>& A) {
  if (!A.isCompressed()) return false;
  for (Eigen::Index c = 0; c < A.outerSize(); ++c) {
    const int b = A.outerIndexPtr()[c], e = A.outerIndexPtr()[c + 1];
    if (b < e && A.innerIndexPtr()[b] < c) return false;  // rows sorted: first one is the smallest
  }
  return true;
}

void require_square(const Eigen::SparseMatrix<double>& A, const char* who) {
  if (A.rows() != A.cols())
    throw std::invalid_argument(std::string(who) + ": matrix is " + std::to_string(A.rows()) + " x " +
                                std::to_string(A.cols()) + ", expected square");
}

}  // namespace

Eigen::SparseMatrix<double> lower_triangle(const Eigen::SparseMatrix<double>& A) {
  Eigen::SparseMatrix<double> L = A.triangularView<Eigen::Lower>();
  L.makeCompressed();
  return L;
}

CholmodFactor::CholmodFactor(FactorKind kind)
    : m_state(std::make_unique<detail::CholmodState>()), m_kind(kind) {
  m_state->cm.supernodal = cholmod_supernodal_flag(kind);
  m_state->cm.final_ll = 1;
}
CholmodFactor::~CholmodFactor() = default;
CholmodFactor::CholmodFactor(CholmodFactor&&) noexcept = default;
CholmodFactor& CholmodFactor::operator=(CholmodFactor&&) noexcept = default;

bool CholmodFactor::same_pattern(const SparseMatrix& lower) const {
  const auto& s = *m_state;
  if (!s.L || s.n != lower.rows() || s.i.size() != static_cast<size_t>(lower.nonZeros())) return false;
  return std::equal(s.p.begin(), s.p.end(), lower.outerIndexPtr()) &&
         std::equal(s.i.begin(), s.i.end(), lower.innerIndexPtr());
}

void CholmodFactor::analyze(const SparseMatrix& A) {
  require_square(A, "CholmodFactor::analyze");
  auto& s = *m_state;
  const SparseMatrix lower = is_lower_compressed(A) ? SparseMatrix() : lower_triangle(A);
  const SparseMatrix& low = lower.size() ? lower : A;
  s.n = low.rows();
  copy_pattern(low, s.p, s.i);
  s.A = sparse_header(s.n, s.p, s.i, low.valuePtr());
  if (s.L) cholmod_l_free_factor(&s.L, &s.cm);
  const auto t0 = std::chrono::steady_clock::now();
  m_ordering.clear();
  if (!m_groups.empty()) {
    analyze_grouped(s.n);
  } else {
    s.L = cholmod_l_analyze(&s.A, &s.cm);
    if (!s.L) throw formats::NumericalError("CHOLMOD analysis failed (status " + std::to_string(s.cm.status) + ")");
    m_lnz = s.cm.lnz;
    m_fl = s.cm.fl;
  }
  m_analyze_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ++m_analyses;
}

void CholmodFactor::set_dof_groups(std::vector<long> groups) {
  for (size_t i = 0; i < groups.size(); ++i)
    if (groups[i] < 0)
      throw std::invalid_argument("CholmodFactor::set_dof_groups: row " + std::to_string(i) + " has group " +
                                  std::to_string(groups[i]) + ", expected a group id >= 0");
  if (groups == m_groups) return;
  m_groups = std::move(groups);
  auto& s = *m_state;  // the analysis no longer applies: the next factorize analyses again
  if (s.L) cholmod_l_free_factor(&s.L, &s.cm);
  s.n = 0;
}

/// Ordering on the group (grid-point) graph, expanded to the rows; see the
/// header. s.A holds the pattern of tril(A) on entry; on return s.L is the
/// analysis of the candidate ordering with the fewest flops.
void CholmodFactor::analyze_grouped(long n) {
  auto& s = *m_state;
  if (static_cast<long>(m_groups.size()) != n)
    throw std::invalid_argument("CholmodFactor: " + std::to_string(m_groups.size()) +
                                " DOF groups given for a matrix of " + std::to_string(n) + " rows");
  // Compact group ids 0..ng-1 in increasing order of the given ids (which may
  // be any non-negative numbers, NASTRAN grid ids up to 10⁸ included: sorted,
  // not indexed, so memory stays O(n)).
  std::vector<long> ids(m_groups), g(static_cast<size_t>(n));
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  const long ng = static_cast<long>(ids.size());
  for (long r = 0; r < n; ++r)
    g[static_cast<size_t>(r)] = std::lower_bound(ids.begin(), ids.end(), m_groups[static_cast<size_t>(r)]) - ids.begin();
  std::vector<long>().swap(ids);
  // Rows of each group (CSR: gp, gr).
  std::vector<long> gp(static_cast<size_t>(ng + 1), 0), gr(static_cast<size_t>(n));
  for (long r = 0; r < n; ++r) ++gp[static_cast<size_t>(g[static_cast<size_t>(r)] + 1)];
  std::partial_sum(gp.begin(), gp.end(), gp.begin());
  {
    std::vector<long> next(gp.begin(), gp.end() - 1);
    for (long r = 0; r < n; ++r) gr[static_cast<size_t>(next[static_cast<size_t>(g[static_cast<size_t>(r)])]++)] = r;
  }
  // Lower triangle of the group graph: the pair {G, H} goes to column min, row
  // max. Each pair is met from G's side and from H's side at most once each
  // (a marker per group), so duplicates are removed per column afterwards.
  const auto* Ap = s.p.data();
  const auto* Ai = s.i.data();
  std::vector<SuiteSparse_long> cp(static_cast<size_t>(ng + 1), 0), ci;
  std::vector<long> mark(static_cast<size_t>(ng), -1);
  auto for_each_pair = [&](auto&& visit) {
    std::fill(mark.begin(), mark.end(), -1);
    for (long G = 0; G < ng; ++G)
      for (long k = gp[static_cast<size_t>(G)]; k < gp[static_cast<size_t>(G + 1)]; ++k) {
        const long j = gr[static_cast<size_t>(k)];
        for (SuiteSparse_long q = Ap[j]; q < Ap[j + 1]; ++q) {
          const long H = g[static_cast<size_t>(Ai[q])];
          if (H == G || mark[static_cast<size_t>(H)] == G) continue;
          mark[static_cast<size_t>(H)] = G;
          visit(std::min(G, H), std::max(G, H));
        }
      }
  };
  for_each_pair([&](long c, long) { ++cp[static_cast<size_t>(c + 1)]; });
  std::partial_sum(cp.begin(), cp.end(), cp.begin());
  ci.resize(static_cast<size_t>(cp[static_cast<size_t>(ng)]));
  {
    std::vector<SuiteSparse_long> next(cp.begin(), cp.end() - 1);
    for_each_pair([&](long c, long r) { ci[static_cast<size_t>(next[static_cast<size_t>(c)]++)] = r; });
  }
  SuiteSparse_long w = 0;  // sort and deduplicate each column in place
  for (long c = 0; c < ng; ++c) {
    const auto b = ci.begin() + cp[static_cast<size_t>(c)], e = ci.begin() + cp[static_cast<size_t>(c + 1)];
    std::sort(b, e);
    const SuiteSparse_long start = w;
    for (auto it = b; it != e; ++it)
      if (it == b || *it != *(it - 1)) ci[static_cast<size_t>(w++)] = *it;
    cp[static_cast<size_t>(c)] = start;
  }
  cp[static_cast<size_t>(ng)] = w;
  ci.resize(static_cast<size_t>(w));
  std::vector<long>().swap(mark);

  cholmod_sparse Gs{};
  Gs.nrow = Gs.ncol = static_cast<size_t>(ng);
  Gs.nzmax = std::max<size_t>(ci.size(), 1);
  if (ci.empty()) ci.push_back(0);
  Gs.p = cp.data();
  Gs.i = ci.data();
  Gs.stype = -1;
  Gs.itype = CHOLMOD_LONG;
  Gs.xtype = CHOLMOD_PATTERN;
  Gs.dtype = CHOLMOD_DOUBLE;
  Gs.sorted = 1;
  Gs.packed = 1;

  // Candidates: AMD and METIS on the group graph; analyse each expanded
  // ordering on the rows and keep the one with fewer flops.
  const int saved_nmethods = s.cm.nmethods;
  const auto saved_method0 = s.cm.method[0];
  const int saved_postorder = s.cm.postorder;
  s.cm.nmethods = 1;
  s.cm.method[0].ordering = CHOLMOD_GIVEN;
  s.cm.postorder = 1;
  std::vector<SuiteSparse_long> gperm(static_cast<size_t>(ng)), perm(static_cast<size_t>(n));
  double best_fl = 0.0;
  std::string first_failure;
  std::vector<SuiteSparse_long> cparent, cmember;
  const double anz = static_cast<double>(s.i.size());
  for (const int method : {CHOLMOD_AMD, CHOLMOD_METIS, CHOLMOD_NESDIS}) {
    // CHOLMOD's own rule: AMD's ordering is kept without trying nested
    // dissection when it is already good (fl/lnz < 500 or lnz/anz < 5).
    if (method != CHOLMOD_AMD && s.L && m_ordering.rfind("AMD", 0) == 0 && (m_fl < 500.0 * m_lnz || m_lnz < 5.0 * anz))
      break;
    int ok = 0;
    if (method == CHOLMOD_AMD) {
      ok = cholmod_l_amd(&Gs, nullptr, 0, gperm.data(), &s.cm);
    } else if (method == CHOLMOD_METIS) {
      ok = cholmod_l_metis(&Gs, nullptr, 0, 1, gperm.data(), &s.cm);
    } else {
      cparent.resize(static_cast<size_t>(ng));
      cmember.resize(static_cast<size_t>(ng));
      ok = cholmod_l_nested_dissection(&Gs, nullptr, 0, gperm.data(), cparent.data(), cmember.data(), &s.cm) >= 0;
    }
    if (!ok) {  // METIS not installed: AMD alone
      if (first_failure.empty()) first_failure = std::to_string(s.cm.status);
      continue;
    }
    long k = 0;
    for (long q = 0; q < ng; ++q) {
      const long G = gperm[static_cast<size_t>(q)];
      for (long t = gp[static_cast<size_t>(G)]; t < gp[static_cast<size_t>(G + 1)]; ++t)
        perm[static_cast<size_t>(k++)] = gr[static_cast<size_t>(t)];
    }
    cholmod_factor* L = cholmod_l_analyze_p(&s.A, perm.data(), nullptr, 0, &s.cm);
    if (!L) {
      if (first_failure.empty()) first_failure = std::to_string(s.cm.status);
      continue;
    }
    if (!s.L || s.cm.fl < best_fl) {
      if (s.L) cholmod_l_free_factor(&s.L, &s.cm);
      s.L = L;
      best_fl = s.cm.fl;
      m_fl = s.cm.fl;
      m_lnz = s.cm.lnz;
      m_ordering = std::string(method == CHOLMOD_AMD ? "AMD" : method == CHOLMOD_METIS ? "METIS" : "NESDIS") +
                   " on " + std::to_string(ng) + " groups";
    } else {
      cholmod_l_free_factor(&L, &s.cm);
    }
  }
  s.cm.nmethods = saved_nmethods;
  s.cm.method[0] = saved_method0;
  s.cm.postorder = saved_postorder;
  if (!s.L) throw formats::NumericalError("CHOLMOD analysis on DOF groups failed (status " + first_failure + ")");
}

const CholmodFactor::SparseMatrix& CholmodFactor::analysed_lower(const SparseMatrix& A, SparseMatrix& storage, const char* who) {
  require_square(A, who);
  // Borrow A's values when it is already lower triangular and compressed;
  // otherwise build tril(A) once here.
  const bool borrow = is_lower_compressed(A);
  if (!borrow) storage = lower_triangle(A);
  const SparseMatrix& low = borrow ? A : storage;
  if (!same_pattern(low)) analyze(low);
  return low;
}

FactorStatus CholmodFactor::factorize(const SparseMatrix& A, double near_singular_rcond) {
  SparseMatrix storage;
  const SparseMatrix& low = analysed_lower(A, storage, "CholmodFactor::factorize");
  auto& s = *m_state;
  s.A = sparse_header(s.n, s.p, s.i, low.valuePtr());
  FactorStatus st;
  if (m_memory_limit > 0.0 && factor_bytes() > m_memory_limit) {
    // Refused before any numeric work: on Linux an oversized factor is not a
    // failed malloc but the out-of-memory killer, which may take other processes.
    char buf[320];
    std::snprintf(buf, sizeof buf,
                  "the factor needs %.2f GiB (symbolic analysis: nnz(L) = %.4g, %.3g flops, ordering %s), "
                  "more than the limit of %.2f GiB",
                  factor_bytes() / 1073741824.0, m_lnz, m_fl, ordering().c_str(), m_memory_limit / 1073741824.0);
    st.code = FactorStatus::Code::TooLarge;
    st.message = buf;
    return st;
  }
  const auto t0 = std::chrono::steady_clock::now();
  m_single_only = false;
  const int ok = cholmod_l_factorize(&s.A, s.L, &s.cm);
  m_factorize_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ++m_factorizations;
  if (!ok || (s.cm.status != CHOLMOD_OK && s.cm.status != CHOLMOD_NOT_POSDEF)) {
    st.code = FactorStatus::Code::Failed;
    st.message = "CHOLMOD factorisation failed (status " + std::to_string(s.cm.status) +
                 (s.cm.status == CHOLMOD_OUT_OF_MEMORY ? ": out of memory)" : ")");
    return st;
  }
  if (s.cm.status == CHOLMOD_NOT_POSDEF || s.L->minor < s.L->n) {
    const auto k = static_cast<long>(s.L->minor);
    const auto* perm = static_cast<const SuiteSparse_long*>(s.L->Perm);
    st.code = FactorStatus::Code::NotPositiveDefinite;
    st.column = perm ? static_cast<long>(perm[k]) : k;
    st.message = "matrix is not positive definite: non-positive pivot at row/column " +
                 std::to_string(st.column) + " (elimination step " + std::to_string(k) + " of " +
                 std::to_string(s.n) + ")";
    return st;
  }
  st.rcond = cholmod_l_rcond(s.L, &s.cm);
  if (!(st.rcond >= near_singular_rcond)) {
    st.code = FactorStatus::Code::NearSingular;
    st.message = "matrix is nearly singular: reciprocal condition estimate " + std::to_string(st.rcond) +
                 " below " + std::to_string(near_singular_rcond);
  }
  return st;
}

void CholmodFactor::solve(const double* b, double* x, long ncols) const {
  auto& s = *m_state;
  if (!factorized()) throw std::logic_error("CholmodFactor::solve before a successful factorize");
  cholmod_dense B{};
  B.nrow = static_cast<size_t>(s.n);
  B.ncol = static_cast<size_t>(ncols);
  B.nzmax = B.nrow * B.ncol;
  B.d = B.nrow;
  B.x = const_cast<double*>(b);  // read only by cholmod_l_solve2
  B.xtype = CHOLMOD_REAL;
  B.dtype = CHOLMOD_DOUBLE;
  auto& cm = const_cast<cholmod_common&>(s.cm);
  if (!cholmod_l_solve2(CHOLMOD_A, s.L, &B, nullptr, &s.X, nullptr, &s.Y, &s.E, &cm))
    throw formats::NumericalError("CHOLMOD solve failed (status " + std::to_string(cm.status) + ")");
  std::memcpy(x, s.X->x, sizeof(double) * B.nzmax);
  s.solves += ncols;
}

Eigen::MatrixXd CholmodFactor::solve(const Eigen::Ref<const Eigen::MatrixXd>& B) const {
  if (B.rows() != rows()) throw std::invalid_argument("CholmodFactor::solve: right-hand side has wrong row count");
  const Eigen::MatrixXd Bc = B;  // contiguous, column-major
  Eigen::MatrixXd X(B.rows(), B.cols());
  if (B.cols() > 0) solve(Bc.data(), X.data(), static_cast<long>(B.cols()));
  return X;
}

FactorStatus CholmodFactor::factorize_single(const SparseMatrix& A, SingleSupernodalFactor& out) {
  SparseMatrix storage;
  const SparseMatrix& low = analysed_lower(A, storage, "CholmodFactor::factorize_single");
  auto& s = *m_state;
  m_single_only = true;
  FactorStatus st;
  if (!s.L->is_super) {
    st.code = FactorStatus::Code::Failed;
    st.message = "single-precision factorisation needs a supernodal analysis";
    return st;
  }
  if (m_memory_limit > 0.0 && 0.5 * factor_bytes() > m_memory_limit) {
    st.code = FactorStatus::Code::TooLarge;
    st.message = "the single-precision factor needs " + std::to_string(0.5 * factor_bytes() / 1073741824.0) +
                 " GiB, more than the limit of " + std::to_string(m_memory_limit / 1073741824.0) + " GiB";
    return st;
  }
  const auto t0 = std::chrono::steady_clock::now();
  const cholmod_factor* L = s.L;
  SingleSupernodalFactor f;
  f.n = s.n;
  const auto* perm = static_cast<const SuiteSparse_long*>(L->Perm);
  f.perm.resize(static_cast<size_t>(f.n));
  for (long k = 0; k < f.n; ++k) f.perm[static_cast<size_t>(k)] = perm ? static_cast<long>(perm[k]) : k;
  const size_t ns = L->nsuper + 1;
  auto copy = [](const void* p, size_t count) {
    const auto* q = static_cast<const SuiteSparse_long*>(p);
    return std::vector<long>(q, q + count);
  };
  f.super = copy(L->super, ns);
  f.pi = copy(L->pi, ns);
  f.px = copy(L->px, ns);
  f.rows = copy(L->s, static_cast<size_t>(f.pi.back()));
  // C = P A Pᵀ, lower triangle, column by column in L's numbering.
  std::vector<long> iperm(static_cast<size_t>(f.n));
  for (long k = 0; k < f.n; ++k) iperm[static_cast<size_t>(f.perm[static_cast<size_t>(k)])] = k;
  std::vector<long> Cp(static_cast<size_t>(f.n) + 1, 0), Ci(static_cast<size_t>(low.nonZeros()));
  std::vector<double> Cx(Ci.size());
  for (long j = 0; j < f.n; ++j)
    for (SparseMatrix::InnerIterator it(low, j); it; ++it)
      ++Cp[static_cast<size_t>(std::min(iperm[static_cast<size_t>(it.row())], iperm[static_cast<size_t>(j)])) + 1];
  std::partial_sum(Cp.begin(), Cp.end(), Cp.begin());
  std::vector<long> fill(Cp.begin(), Cp.end() - 1);
  for (long j = 0; j < f.n; ++j)
    for (SparseMatrix::InnerIterator it(low, j); it; ++it) {
      const long a = iperm[static_cast<size_t>(it.row())], b = iperm[static_cast<size_t>(j)];
      const long q = fill[static_cast<size_t>(std::min(a, b))]++;
      Ci[static_cast<size_t>(q)] = std::max(a, b);
      Cx[static_cast<size_t>(q)] = it.value();
    }
  const long bad = factorize_supernodal_single(Cp, Ci, Cx, f);
  m_factorize_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ++m_factorizations;
  if (bad >= 0) {
    st.code = FactorStatus::Code::NotPositiveDefinite;
    st.column = f.perm[static_cast<size_t>(bad)];
    st.message = "matrix is not positive definite in single precision: non-positive pivot at row/column " +
                 std::to_string(st.column);
    return st;
  }
  st.rcond = f.rcond_estimate();  // CHOLMOD's: (min diag L / max diag L)²
  out = std::move(f);
  return st;
}

long CholmodFactor::rows() const { return m_state->n; }
bool CholmodFactor::factorized() const {
  const auto* L = m_state->L;
  // A symbolic analysis alone is not a factor; after factorize_single, the values
  // of an earlier double factorisation would belong to another matrix.
  return !m_single_only && L && L->minor == L->n && L->xtype != CHOLMOD_PATTERN;
}
long CholmodFactor::solve_count() const { return m_state->solves; }
double CholmodFactor::factor_nnz() const { return m_lnz; }
double CholmodFactor::factor_flops() const { return m_fl; }
double CholmodFactor::factor_bytes() const {
  const cholmod_factor* L = m_state->L;
  if (!L) return 0.0;
  const double n = static_cast<double>(L->n);
  const double idx = sizeof(SuiteSparse_long);
  if (L->is_super)
    return 8.0 * (static_cast<double>(L->xsize) + static_cast<double>(L->maxcsize)) +
           idx * (static_cast<double>(L->ssize) + 3.0 * static_cast<double>(L->nsuper) + 4.0 * n);
  return (8.0 + idx) * m_lnz + idx * 6.0 * n;  // simplicial: x, i, and p, nz, next, prev, Perm, ColCount
}
bool CholmodFactor::supernodal() const { return m_state->L && m_state->L->is_super; }

std::string CholmodFactor::ordering() const {
  if (!m_state->L) return "none";
  if (!m_ordering.empty()) return m_ordering;
  switch (m_state->L->ordering) {
    case CHOLMOD_NATURAL: return "natural";
    case CHOLMOD_GIVEN: return "given";
    case CHOLMOD_AMD: return "AMD";
    case CHOLMOD_METIS: return "METIS";
    case CHOLMOD_NESDIS: return "NESDIS";
    case CHOLMOD_COLAMD: return "COLAMD";
    case CHOLMOD_POSTORDERED: return "postordered";
    default: return "unknown";
  }
}

long count_negative_pivots(const Eigen::SparseMatrix<double>& A) {
  require_square(A, "count_negative_pivots");
  detail::CholmodState s;
  s.cm.supernodal = CHOLMOD_SIMPLICIAL;  // LDLᵀ exposes D; supernodal is LLᵀ only
  s.cm.final_ll = 0;
  const Eigen::SparseMatrix<double> low = lower_triangle(A);
  s.n = low.rows();
  copy_pattern(low, s.p, s.i);
  s.A = sparse_header(s.n, s.p, s.i, low.valuePtr());
  s.L = cholmod_l_analyze(&s.A, &s.cm);
  if (!s.L) throw formats::NumericalError("CHOLMOD analysis failed (status " + std::to_string(s.cm.status) + ")");
  cholmod_l_factorize(&s.A, s.L, &s.cm);
  if (s.cm.status < CHOLMOD_OK)
    throw formats::NumericalError("CHOLMOD LDL' factorisation failed (status " + std::to_string(s.cm.status) + ")");
  if (s.L->minor < s.L->n) return -1;  // zero pivot
  const auto* p = static_cast<const SuiteSparse_long*>(s.L->p);
  const auto* x = static_cast<const double*>(s.L->x);
  long neg = 0;
  for (long j = 0; j < s.n; ++j)
    if (x[p[j]] < 0.0) ++neg;  // simplicial LDLᵀ keeps D(j,j) in L's diagonal slot
  return neg;
}

}  // namespace ssid::estimator
