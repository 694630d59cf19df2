#include "estimator/eigen/multilevel/aggregation_amg.hpp"

#include "estimator/linalg/dense_blas.hpp"
#include "formats/parse_error.hpp"

#include <Eigen/Cholesky>
#include <Eigen/QR>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>
#include <random>
#include <stdexcept>
#include <string>
#include <unordered_map>

namespace ssid::estimator::multilevel {

namespace {

/// Groups renumbered 0..ng−1 in order of first appearance, and the DOFs of each.
struct GroupIndex {
  std::vector<long> of_dof;       // group of each DOF, 0-based
  std::vector<long> start, dofs;  // CSR: the DOFs of each group
  long count() const { return static_cast<long>(start.size()) - 1; }
};

GroupIndex index_groups(const std::vector<long>& groups) {
  GroupIndex g;
  std::unordered_map<long, long> id;
  g.of_dof.resize(groups.size());
  for (size_t i = 0; i < groups.size(); ++i) {
    if (groups[i] < 0) throw std::invalid_argument("AggregationAmg: negative group id");
    auto [it, fresh] = id.emplace(groups[i], static_cast<long>(id.size()));
    g.of_dof[i] = it->second;
  }
  const long ng = static_cast<long>(id.size());
  g.start.assign(static_cast<size_t>(ng) + 1, 0);
  for (long x : g.of_dof) ++g.start[static_cast<size_t>(x) + 1];
  std::partial_sum(g.start.begin(), g.start.end(), g.start.begin());
  g.dofs.resize(groups.size());
  std::vector<long> fill(g.start.begin(), g.start.end() - 1);
  for (size_t i = 0; i < groups.size(); ++i) g.dofs[static_cast<size_t>(fill[static_cast<size_t>(g.of_dof[i])]++)] = static_cast<long>(i);
  return g;
}

/// Grid-point graph of A (CSR without self-loops): an edge where any DOF of one
/// group couples to any DOF of the other.
void group_graph(const SparseMatrix& A, const GroupIndex& g, std::vector<long>& start, std::vector<long>& adj) {
  const long ng = g.count();
  std::vector<long> mark(static_cast<size_t>(ng), -1);
  start.assign(static_cast<size_t>(ng) + 1, 0);
  adj.clear();
  for (long a = 0; a < ng; ++a) {
    mark[static_cast<size_t>(a)] = a;
    for (long p = g.start[static_cast<size_t>(a)]; p < g.start[static_cast<size_t>(a) + 1]; ++p)
      for (SparseMatrix::InnerIterator it(A, g.dofs[static_cast<size_t>(p)]); it; ++it) {
        const long b = g.of_dof[static_cast<size_t>(it.row())];
        if (mark[static_cast<size_t>(b)] != a) mark[static_cast<size_t>(b)] = a, adj.push_back(b);
      }
    start[static_cast<size_t>(a) + 1] = static_cast<long>(adj.size());
  }
}

/// Aggregate of every group (see the header): roots with free neighbourhoods take
/// the free groups within `radius` steps; leftovers join an aggregated neighbour.
std::vector<long> aggregate(const std::vector<long>& start, const std::vector<long>& adj, int radius, long& count) {
  const long ng = static_cast<long>(start.size()) - 1;
  std::vector<long> agg(static_cast<size_t>(ng), -1);
  count = 0;
  std::vector<long> frontier, next;
  for (long r = 0; r < ng; ++r) {
    if (agg[static_cast<size_t>(r)] >= 0) continue;
    bool free = true;
    for (long p = start[static_cast<size_t>(r)]; p < start[static_cast<size_t>(r) + 1] && free; ++p)
      free = agg[static_cast<size_t>(adj[static_cast<size_t>(p)])] < 0;
    if (!free) continue;
    agg[static_cast<size_t>(r)] = count;
    frontier.assign(1, r);
    for (int step = 0; step < radius; ++step) {
      next.clear();
      for (long a : frontier)
        for (long p = start[static_cast<size_t>(a)]; p < start[static_cast<size_t>(a) + 1]; ++p) {
          const long b = adj[static_cast<size_t>(p)];
          if (agg[static_cast<size_t>(b)] < 0) agg[static_cast<size_t>(b)] = count, next.push_back(b);
        }
      frontier.swap(next);
    }
    ++count;
  }
  // Leftovers: join the neighbouring aggregate with the most links, in passes
  // (a leftover next only to leftovers waits for the next pass).
  for (bool changed = true; changed;) {
    changed = false;
    std::vector<long> snapshot = agg;
    for (long a = 0; a < ng; ++a) {
      if (agg[static_cast<size_t>(a)] >= 0) continue;
      long best = -1, best_links = 0;
      for (long p = start[static_cast<size_t>(a)]; p < start[static_cast<size_t>(a) + 1]; ++p) {
        const long t = snapshot[static_cast<size_t>(adj[static_cast<size_t>(p)])];
        if (t < 0) continue;
        long links = 0;
        for (long q = start[static_cast<size_t>(a)]; q < start[static_cast<size_t>(a) + 1]; ++q)
          links += snapshot[static_cast<size_t>(adj[static_cast<size_t>(q)])] == t;
        if (links > best_links) best = t, best_links = links;
      }
      if (best >= 0) agg[static_cast<size_t>(a)] = best, changed = true;
    }
  }
  for (long a = 0; a < ng; ++a)
    if (agg[static_cast<size_t>(a)] < 0) agg[static_cast<size_t>(a)] = count++;  // isolated grid points
  return agg;
}

}  // namespace

AmgOptions AggregationAmg::resolved(const AmgOptions& options, long grid_points, bool strain_fields) {
  AmgOptions o = options;
  if (o.aggregate_radius == 0) o.aggregate_radius = strain_fields && grid_points > AmgOptions::kLargeModelGrids ? 3 : 2;
  if (o.prolongator_steps < 0) o.prolongator_steps = strain_fields ? 1 : 2;
  return o;
}

AggregationAmg::AggregationAmg(const SparseMatrix& A, const std::vector<long>& groups, const Eigen::MatrixXd& B,
                               const AmgOptions& options, const Eigen::MatrixXd& F)
    : m_A(A), m_options(options) {
  const long n = A.rows();
  if (A.cols() != n || !A.isCompressed()) throw std::invalid_argument("AggregationAmg: A must be square and compressed");
  if (static_cast<long>(groups.size()) != n || B.rows() != n || B.cols() == 0)
    throw std::invalid_argument("AggregationAmg: " + std::to_string(groups.size()) + " groups and a " +
                                std::to_string(B.rows()) + " x " + std::to_string(B.cols()) +
                                " near-null space for " + std::to_string(n) + " DOFs");
  if (F.size() > 0 && F.rows() != n)
    throw std::invalid_argument("AggregationAmg: the strain fields have " + std::to_string(F.rows()) + " rows for " +
                                std::to_string(n) + " DOFs");
  if (options.aggregate_radius < 0 || options.prolongator_steps < -1 || options.smoother_degree < 1 ||
      !(options.smoother_ratio > 1.0))
    throw std::invalid_argument(
        "AggregationAmg: the radius must be >= 0 (0: automatic), the smoother degree >= 1, the prolongator steps "
        ">= -1 (-1: automatic) and the ratio > 1");
  const bool fields = F.size() > 0 && F.cwiseAbs().maxCoeff() > 0.0;  // all-zero fields add nothing
  using Clock = std::chrono::steady_clock;
  auto since = [](Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); };
  auto t = Clock::now();
  const GroupIndex g = index_groups(groups);
  const long ng = g.count();
  m_options = resolved(options, ng, fields);
  m_start = g.start;
  m_dofs = g.dofs;

  // Block Jacobi: the inverse of each grid point's diagonal block of A.
  m_dinv_start.assign(static_cast<size_t>(ng) + 1, 0);
  for (long a = 0; a < ng; ++a) {
    const long k = m_start[static_cast<size_t>(a) + 1] - m_start[static_cast<size_t>(a)];
    m_dinv_start[static_cast<size_t>(a) + 1] = m_dinv_start[static_cast<size_t>(a)] + k * k;
  }
  m_dinv.resize(static_cast<size_t>(m_dinv_start.back()));
  std::vector<long> local(static_cast<size_t>(n), -1);
  for (long a = 0; a < ng; ++a) {
    const long s = m_start[static_cast<size_t>(a)], k = m_start[static_cast<size_t>(a) + 1] - s;
    Eigen::MatrixXd D = Eigen::MatrixXd::Zero(k, k);
    for (long i = 0; i < k; ++i) local[static_cast<size_t>(m_dofs[static_cast<size_t>(s + i)])] = i;
    for (long j = 0; j < k; ++j)
      for (SparseMatrix::InnerIterator it(A, m_dofs[static_cast<size_t>(s + j)]); it; ++it)
        if (g.of_dof[static_cast<size_t>(it.row())] == a) D(local[static_cast<size_t>(it.row())], j) = it.value();
    Eigen::LLT<Eigen::MatrixXd> llt(D);
    if (llt.info() != Eigen::Success) {
      // The first DOF of the block with no positive pivot left: its diagonal.
      long bad = m_dofs[static_cast<size_t>(s)];
      for (long q = 0; q < k; ++q)
        if (!(D(q, q) > 0.0)) { bad = m_dofs[static_cast<size_t>(s + q)]; break; }
      throw NotPositiveDefiniteBlock("the grid point of DOF index " + std::to_string(bad) +
                                         " has a singular block of K - sigma*M: a DOF with neither stiffness nor mass",
                                     bad);
    }
    const Eigen::MatrixXd Di = llt.solve(Eigen::MatrixXd::Identity(k, k));
    Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
        m_dinv.data() + m_dinv_start[static_cast<size_t>(a)], k, k) = Di;
  }

  // Single precision holds magnitudes up to 3.4e38 only: a model whose A or D⁻¹
  // has entries beyond kSingleRange (a margin of 1e8 for the vectors they multiply,
  // and for the coarse matrix PᵀAP) runs its cycle, and its coarse factor, in
  // double instead of overflowing to infinities (single_precision() says which).
  if (m_options.single_precision) {
    constexpr double kSingleRange = 1e30;
    double largest = 0.0;
    for (long k = 0; k < A.nonZeros(); ++k) largest = std::max(largest, std::abs(A.valuePtr()[k]));
    for (const double v : m_dinv) largest = std::max(largest, std::abs(v));
    if (!(largest <= kSingleRange)) m_options.single_precision = false, m_options.coarse_single_precision = false;
  }

  // ρ(D⁻¹A) by power iteration (D⁻¹A is similar to the symmetric D^{-½}AD^{-½}:
  // its eigenvalues are real and positive; 30 steps from a random start come within
  // a few per cent from below, hence the 10 % margin).
  m_double.A = &m_A, m_double.dinv = m_dinv.data();
  {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    RowBlock v(n, 1), w, z, unused;
    for (long i = 0; i < n; ++i) v(i, 0) = u(rng);
    double est = 0.0;
    for (int it = 0; it < 30; ++it) {
      sym_times(A, v, w);
      jacobi_step(m_double, w, 0.0, 1.0, z, unused, true);  // z = D⁻¹ w
      est = z.norm() / v.norm();
      v = z / z.norm();
    }
    m_rho = 1.1 * est;
  }

  // Aggregates and the tentative prolongator.
  std::vector<long> gstart, gadj;
  group_graph(A, g, gstart, gadj);
  const std::vector<long> agg = aggregate(gstart, gadj, m_options.aggregate_radius, m_aggregates);
  std::vector<long> agg_start(static_cast<size_t>(m_aggregates) + 1, 0), agg_groups(static_cast<size_t>(ng));
  for (long a : agg) ++agg_start[static_cast<size_t>(a) + 1];
  std::partial_sum(agg_start.begin(), agg_start.end(), agg_start.begin());
  {
    std::vector<long> fill(agg_start.begin(), agg_start.end() - 1);
    for (long a = 0; a < ng; ++a) agg_groups[static_cast<size_t>(fill[static_cast<size_t>(agg[static_cast<size_t>(a)])]++)] = a;
  }
  std::vector<Eigen::Triplet<double>> tp;
  tp.reserve(static_cast<size_t>(n) * static_cast<size_t>(B.cols() + (fields ? F.cols() : 0)));
  std::vector<long> coarse_group;  // aggregate of each coarse DOF (its ordering group)
  long nc = 0;
  std::vector<long> rows;
  for (long c = 0; c < m_aggregates; ++c) {
    rows.clear();
    for (long p = agg_start[static_cast<size_t>(c)]; p < agg_start[static_cast<size_t>(c) + 1]; ++p) {
      const long a = agg_groups[static_cast<size_t>(p)];
      for (long q = m_start[static_cast<size_t>(a)]; q < m_start[static_cast<size_t>(a) + 1]; ++q) rows.push_back(m_dofs[static_cast<size_t>(q)]);
    }
    const Eigen::Index nr = static_cast<Eigen::Index>(rows.size());
    auto aggregate_rows = [&](const Eigen::MatrixXd& X) {  // X's rows of this aggregate
      Eigen::MatrixXd Xl(nr, X.cols());
      for (Eigen::Index i = 0; i < nr; ++i) Xl.row(i) = X.row(rows[static_cast<size_t>(i)]);
      return Xl;
    };
    Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(aggregate_rows(B));
    qr.setThreshold(1e-10);
    Eigen::MatrixXd Q = qr.householderQ() * Eigen::MatrixXd::Identity(nr, qr.rank());
    if (fields) {
      // The strain fields' part outside span B (projected twice: one pass leaves
      // rounding of the part removed, which is most of a field far from the model's
      // centre). A direction is kept only above kFieldThreshold of the largest
      // (and above 1e-10 of the fields' own size): an aggregate that cannot tell a
      // field from a rigid motion (a straight chain of grids, a flat patch) leaves
      // a remainder of coordinate rounding, which normalised would be a rough,
      // high-energy coarse shape.
      Eigen::MatrixXd Fl = aggregate_rows(F);
      const double size = Fl.colwise().norm().maxCoeff();
      Fl -= Q * (Q.transpose() * Fl);
      Fl -= Q * (Q.transpose() * Fl);
      Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qf(Fl);
      qf.setThreshold(kFieldThreshold);
      const Eigen::Index rf = qf.maxPivot() > 1e-10 * size ? qf.rank() : 0;
      if (rf > 0) {
        const Eigen::MatrixXd QF = qf.householderQ() * Eigen::MatrixXd::Identity(nr, rf);
        Eigen::MatrixXd QB(nr, Q.cols() + rf);
        QB << Q, QF;
        Q.swap(QB);
      }
    }
    const long rank = Q.cols();
    for (long j = 0; j < rank; ++j) {
      for (size_t i = 0; i < rows.size(); ++i)
        if (Q(static_cast<Eigen::Index>(i), j) != 0.0) tp.emplace_back(rows[i], nc, Q(static_cast<Eigen::Index>(i), j));
      coarse_group.push_back(c);
      ++nc;
    }
  }
  SparseMatrix P0(n, nc);
  P0.setFromTriplets(tp.begin(), tp.end());
  std::vector<Eigen::Triplet<double>>().swap(tp);
  m_times.aggregation = since(t);
  t = Clock::now();

  if (m_options.prolongator_steps > 0) {
    // D⁻¹ as a sparse block-diagonal matrix, then P ← P − ω (D⁻¹A) P, s times.
    std::vector<Eigen::Triplet<double>> td;
    td.reserve(m_dinv.size());
    for (long a = 0; a < ng; ++a) {
      const long s = m_start[static_cast<size_t>(a)], k = m_start[static_cast<size_t>(a) + 1] - s;
      const double* d = m_dinv.data() + m_dinv_start[static_cast<size_t>(a)];
      for (long i = 0; i < k; ++i)
        for (long j = 0; j < k; ++j) td.emplace_back(m_dofs[static_cast<size_t>(s + i)], m_dofs[static_cast<size_t>(s + j)], d[i * k + j]);
    }
    SparseMatrix Dinv(n, n);
    Dinv.setFromTriplets(td.begin(), td.end());
    const double omega = 4.0 / (3.0 * m_rho);
    // D⁻¹A formed once (A's pattern: its rows come whole by grid point), then
    // (D⁻¹A) P per step: D⁻¹ (A P) multiplied the grown A P instead, 2.4 s of the
    // 1M lattice's second step against about 1 s for (D⁻¹A) P.
    const SparseMatrix DinvA = parallel_product(Dinv, A);
    m_P = P0;
    for (int step = 0; step < m_options.prolongator_steps; ++step) m_P = m_P - omega * parallel_product(DinvA, m_P);
  } else {
    m_P = P0;
  }
  m_P.prune(0.0);
  m_P.makeCompressed();
  m_Prow = m_P;
  m_Prow.makeCompressed();

  m_times.smoothing = since(t);

  // Coarse matrix and its factor.
  t = Clock::now();
  // Coarse columns come aggregate by aggregate (consecutive): the blocks of the product.
  m_coarse_blocks.assign(1, 0);
  for (long c = 1; c <= nc; ++c)
    if (c == nc || coarse_group[static_cast<size_t>(c)] != coarse_group[static_cast<size_t>(c) - 1])
      m_coarse_blocks.push_back(c);
  const SparseMatrix Ac = galerkin_lower(A, m_P, m_Prow, m_coarse_blocks);  // lower triangle
  m_times.coarse_matrix = since(t);
  m_coarse.set_dof_groups(coarse_group);
  t = Clock::now();
  // Single precision: factorised in single precision only (the cycle's coarse solve
  // is all that uses it); otherwise CHOLMOD's double factor.
  const bool single_coarse = m_options.single_precision && m_options.coarse_single_precision;
  FactorStatus fs;
  if (single_coarse) {
    fs = m_coarse.factorize_single(Ac, m_coarse_single);
    if (!fs.ok() || !(fs.rcond >= m_options.single_min_rcond)) {
      // Too ill-conditioned for single precision: CHOLMOD's double factor instead.
      m_coarse_single = SingleSupernodalFactor{};
      fs = m_coarse.factorize(Ac);
    }
  } else {
    fs = m_coarse.factorize(Ac);
  }
  m_times.coarse_factor = since(t);
  m_times.coarse_analysis = m_coarse.last_analyze_seconds();
  if (!fs.ok() && fs.code != FactorStatus::Code::NearSingular)
    throw formats::NumericalError("AggregationAmg: the coarse matrix (" + std::to_string(nc) +
                             " DOFs) cannot be factorised: " + fs.message);
  m_double.Prow = &m_Prow;
  if (m_options.single_precision) {
    m_Af = A.cast<float>();
    m_Prowf = m_Prow.cast<float>();
    m_Af.makeCompressed(), m_Prowf.makeCompressed();
    m_dinvf.assign(m_dinv.begin(), m_dinv.end());
    m_single.A = &m_Af, m_single.Prow = &m_Prowf, m_single.dinv = m_dinvf.data();
  }
}

template <class T>
void AggregationAmg::jacobi_step(const Level<T>& L, const RowBlockOf<T>& res, double alpha, double beta,
                                 RowBlockOf<T>& d, RowBlockOf<T>& X, bool set_x) const {
  block_jacobi_pass(GridBlocks<T>{&m_start, &m_dofs, &m_dinv_start, L.dinv}, res, alpha, beta, d, X, set_x);
}

// Chebyshev iteration on A X = R preconditioned by D (Saad, Iterative Methods,
// Alg. 12.1), `degree` steps over the interval [ρ/ratio, ρ] of D⁻¹A. Each step is
// two fused passes: res −= A d (sym_subtract), then z = D⁻¹ res, d = α d + β z and
// X += d grid point by grid point (jacobi_step); the vector updates written as
// separate block expressions ran on one thread and cost as much as the products.
template <class T>
void AggregationAmg::chebyshev(const Level<T>& L, const RowBlockOf<T>& R, RowBlockOf<T>& X, bool zero_start) const {
  const int degree = m_options.smoother_degree;  // >= 1 (the constructor checks)
  const double lmax = m_rho, lmin = m_rho / m_options.smoother_ratio;
  const double theta = 0.5 * (lmax + lmin), delta = 0.5 * (lmax - lmin), sigma = theta / delta;
  double rho = 1.0 / sigma;
  RowBlockOf<T> &res = L.res, &d = L.d;
  if (zero_start) {
    jacobi_step(L, R, 0.0, 1.0 / theta, d, X, true);  // X = d = D⁻¹ R / θ; the residual R − A X comes below
  } else {
    sym_residual(*L.A, X, R, res);
    jacobi_step(L, res, 0.0, 1.0 / theta, d, X, false);
  }
  for (int k = 1; k < degree; ++k) {
    if (zero_start && k == 1) sym_residual(*L.A, d, R, res);  // X = d so far
    else sym_subtract(*L.A, d, res);
    const double rho_next = 1.0 / (2.0 * sigma - rho);
    jacobi_step(L, res, rho_next * rho, 2.0 * rho_next / delta, d, X, false);
    rho = rho_next;
  }
}

template <class T>
void AggregationAmg::cycle(const Level<T>& L, const RowBlockOf<T>& R, RowBlockOf<T>& X) const {
  chebyshev(L, R, X, true);
  // The residual restricted is kept in the smoother's res (the second smoothing
  // recomputes its own): a block less of fresh memory.
  RowBlockOf<T> &E = L.res, &Ec = L.Ec, &Y = L.Y;
  sym_residual(*L.A, X, R, E);
  transpose_times(*L.Prow, E, Ec);  // Pᵀ E, coarse x b
  coarse_solve(Ec, Y);
  times_add(*L.Prow, Y, X);  // X += P Y
  chebyshev(L, R, X, false);
}

// Why split by columns rather than leave the threads to OpenBLAS: a coarse
// model's supernodes are small (the 94k lattice: 13 188 DOFs), and OpenBLAS's threads
// took their work by hand-overs on every call and spun, yielding, between calls,
// competing with the cycle's own threads for the cores (94k: 2 s of 12.5 s of CPU).
// Each part reads all of L: with 45 columns, 22 flops or more per value read.
void AggregationAmg::solve_coarse_single(const float* b, float* y, long nrhs) const {
  // Narrower parts gain nothing: the 1M start's 16-column block solves cost the same
  // split in two or on OpenBLAS's threads (15 solves: 7.1 s against 7.3 s, means of
  // 5 and 7 runs; each part reads all of L, hundreds of megabytes there), so they
  // stay whole; LOBPCG's 45 columns split.
  constexpr long kMinColumnsPerPart = 16;
  const long parts = std::min(worker_threads(), std::max<long>(1, nrhs / kMinColumnsPerPart));
  if (m_coarse_work.size() < static_cast<size_t>(worker_threads()))
    m_coarse_work.resize(static_cast<size_t>(worker_threads()));
  if (parts <= 1) {
    m_coarse_single.solve_columns(b, y, nrhs, 0, nrhs, m_coarse_work[0]);
    return;
  }
  // `parts` pieces of at least kMinColumnsPerPart columns (parallel_parts would cut
  // nrhs into one piece per hardware thread, however thin), one per thread.
  const detail::BlasThreadLimit one_thread;
  parallel_parts(
      parts,
      [&](long, long first, long last) {
        for (long t = first; t < last; ++t)
          m_coarse_single.solve_columns(b, y, nrhs, t * nrhs / parts, (t + 1) * nrhs / parts,
                                        m_coarse_work[static_cast<size_t>(t)]);
      },
      2);
}

Eigen::MatrixXd AggregationAmg::solve_coarse(const Eigen::MatrixXd& X) const {
  if (m_coarse_single.empty()) return m_coarse.solve(X);
  RowBlockOf<float> Xf = X.cast<float>(), Yf(X.rows(), X.cols());
  solve_coarse_single(Xf.data(), Yf.data(), X.cols());
  return Yf.cast<double>();
}

template <>
void AggregationAmg::coarse_solve(const RowBlockOf<float>& Ec, RowBlockOf<float>& Y) const {
  if (!m_coarse_single.empty()) {  // the cycle's row-major floats are the solve's own layout: no copy
    Y.resize(Ec.rows(), Ec.cols());
    solve_coarse_single(Ec.data(), Y.data(), Ec.cols());
    return;
  }
  // The double factor solves column-major double blocks: the coarse block (small) is copied.
  Y = solve_coarse(Eigen::MatrixXd(Ec.cast<double>())).cast<float>();
}

template <>
void AggregationAmg::coarse_solve(const RowBlockOf<double>& Ec, RowBlockOf<double>& Y) const {
  Y = solve_coarse(Eigen::MatrixXd(Ec));
}

void AggregationAmg::prolong(const RowBlock& Y, RowBlock& X) const { multilevel::times(prolongator_rows(), Y, X); }

const SparseMatrix& AggregationAmg::prolongator() const {
  if (m_released) throw std::logic_error("AggregationAmg: the double-precision prolongator was released");
  return m_P;
}

const SparseRowMatrix& AggregationAmg::prolongator_rows() const {
  if (m_released) throw std::logic_error("AggregationAmg: the double-precision prolongator was released");
  return m_Prow;
}

void AggregationAmg::release_double_prolongator() {
  if (!m_options.single_precision || m_released) return;  // the double cycle runs on m_Prow
  SparseMatrix().swap(m_P);  // assigning an empty matrix would keep the storage
  SparseRowMatrix().swap(m_Prow);
  m_double.Prow = nullptr;
  m_released = true;
}

void AggregationAmg::apply(const RowBlock& R, RowBlock& X) const {
  if (!m_options.single_precision) {
    cycle(m_double, R, X);
    return;
  }
  convert(R, m_single.R);
  cycle(m_single, m_single.R, m_single.X);
  convert(m_single.X, X);
}

}  // namespace ssid::estimator::multilevel
