// The multilevel solver's own kernels, every instruction-set version this machine
// supports (KernelIsa, block_ops.hpp), against plain reference loops: the sparse
// block products, the transposed (scattered) product, the block-Jacobi pass, the
// Gram products and the block updates, at every width that takes a different
// path through each version's register tiles (full tiles, the shorter last tile,
// the narrower vectors, single values), with row counts that leave each dense
// kernel's row remainder, several of the Gram kernel's row chunks, and the split
// over the cores.
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "estimator/eigen/multilevel/block_ops.hpp"
#include "formats/parse_error.hpp"

using namespace ssid::estimator;
using multilevel::KernelIsa;
using multilevel::RowBlock;
using multilevel::RowBlockOf;

namespace {

/// Runs the kernels in one version while it lives; the version before is restored.
class IsaScope {
 public:
  explicit IsaScope(KernelIsa isa) : m_before(multilevel::kernel_isa()) { multilevel::set_kernel_isa(isa); }
  ~IsaScope() { multilevel::set_kernel_isa(m_before); }
  IsaScope(const IsaScope&) = delete;
  IsaScope& operator=(const IsaScope&) = delete;

 private:
  KernelIsa m_before;
};

template <class T>
RowBlockOf<T> random_block(long n, long b, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  RowBlockOf<T> X(n, b);
  for (Eigen::Index i = 0; i < X.size(); ++i) X.data()[i] = static_cast<T>(u(rng));
  return X;
}

/// max |got − want| / max |want|: the error relative to the result's scale
/// (a plain loop sums in another order than the tiles, and without FMA).
template <class T>
double relative_error(const RowBlockOf<T>& got, const std::vector<double>& want) {
  REQUIRE(static_cast<size_t>(got.size()) == want.size());
  double err = 0.0, scale = 0.0;
  for (size_t k = 0; k < want.size(); ++k) {
    err = std::max(err, std::abs(static_cast<double>(got.data()[k]) - want[k]));
    scale = std::max(scale, std::abs(want[k]));
  }
  return scale > 0.0 ? err / scale : err;
}

double relative_error(const Eigen::MatrixXd& got, const std::vector<double>& want_rowmajor, long cols) {
  double err = 0.0, scale = 0.0;
  for (Eigen::Index i = 0; i < got.rows(); ++i)
    for (Eigen::Index j = 0; j < got.cols(); ++j) {
      const double w = want_rowmajor[static_cast<size_t>(i * cols + j)];
      err = std::max(err, std::abs(got(i, j) - w));
      scale = std::max(scale, std::abs(w));
    }
  return scale > 0.0 ? err / scale : err;
}

/// The sparse kernels at width b: Y = A X, B − A X, Y − A X (A symmetric, both
/// triangles stored), R X, Y + R X, Rᵀ X, and the block-Jacobi pass.
template <class T>
void check_sparse_at_width(long b, double tol, std::mt19937& rng) {
  const long n = 37, m = 11;
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Eigen::Triplet<T>> t;
  for (long i = 0; i < n; ++i)
    for (long j = 0; j <= i; ++j)
      if (i == j || u(rng) > 0.6) {
        const T v = static_cast<T>(i == j ? 4.0 : u(rng));
        t.emplace_back(i, j, v);
        if (i != j) t.emplace_back(j, i, v);
      }
  multilevel::SparseOf<T> A(n, n);
  A.setFromTriplets(t.begin(), t.end());
  A.makeCompressed();
  t.clear();
  for (long i = 0; i < n; ++i)
    for (long j = 0; j < m; ++j)
      if (u(rng) > 0.5) t.emplace_back(i, j, static_cast<T>(u(rng)));
  multilevel::SparseRowOf<T> R(n, m);  // n x m: R Xs (Xs m x b) and Rᵀ X (X n x b)
  R.setFromTriplets(t.begin(), t.end());
  R.makeCompressed();
  const RowBlockOf<T> X = random_block<T>(n, b, rng), B = random_block<T>(n, b, rng), Xs = random_block<T>(m, b, rng);

  // The references, plain loops in double.
  std::vector<double> AX(static_cast<size_t>(n * b), 0.0), RXs(static_cast<size_t>(n * b), 0.0),
      RtX(static_cast<size_t>(m * b), 0.0);
  for (long j = 0; j < n; ++j)
    for (typename multilevel::SparseOf<T>::InnerIterator it(A, j); it; ++it)
      for (long c = 0; c < b; ++c) AX[static_cast<size_t>(it.row() * b + c)] += double(it.value()) * double(X(j, c));
  for (long i = 0; i < n; ++i)
    for (typename multilevel::SparseRowOf<T>::InnerIterator it(R, i); it; ++it)
      for (long c = 0; c < b; ++c) {
        RXs[static_cast<size_t>(i * b + c)] += double(it.value()) * double(Xs(it.col(), c));
        RtX[static_cast<size_t>(it.col() * b + c)] += double(it.value()) * double(X(i, c));
      }
  std::vector<double> BmAX(AX.size()), BpRXs(RXs.size());
  for (size_t k = 0; k < AX.size(); ++k) BmAX[k] = double(B.data()[k]) - AX[k], BpRXs[k] = double(B.data()[k]) + RXs[k];

  RowBlockOf<T> Z;
  multilevel::sym_times(A, X, Z);
  CHECK(relative_error(Z, AX) <= tol);
  multilevel::sym_residual(A, X, B, Z);
  CHECK(relative_error(Z, BmAX) <= tol);
  Z = B;
  multilevel::sym_subtract(A, X, Z);
  CHECK(relative_error(Z, BmAX) <= tol);
  multilevel::times(R, Xs, Z);
  CHECK(relative_error(Z, RXs) <= tol);
  Z = B;
  multilevel::times_add(R, Xs, Z);
  CHECK(relative_error(Z, BpRXs) <= tol);
  multilevel::transpose_times(R, X, Z);
  CHECK(relative_error(Z, RtX) <= tol);

  // Block Jacobi on grid points of 3, 1, 2 and 3 DOFs (rows scattered, some left out):
  // z = β D⁻¹ B, d = α d + z, X += d.
  const std::vector<long> start = {0, 3, 4, 6, 9};
  const std::vector<long> dofs = {5, 0, 12, 7, 30, 2, 11, 19, 36};
  const std::vector<long> dinv_start = {0, 9, 10, 14, 23};
  std::vector<T> dinv(23);
  for (auto& v : dinv) v = static_cast<T>(u(rng));
  const multilevel::GridBlocks<T> blocks{&start, &dofs, &dinv_start, dinv.data()};
  RowBlockOf<T> d = B, Xj = X;
  const double alpha = 0.5, beta = 2.0;
  multilevel::block_jacobi_pass(blocks, B, alpha, beta, d, Xj, false);
  std::vector<double> dref, dgot, xref, xgot;
  for (size_t g = 0; g + 1 < start.size(); ++g) {
    const long s0 = start[g], k = start[g + 1] - s0;
    for (long i = 0; i < k; ++i) {
      const long r = dofs[static_cast<size_t>(s0 + i)];
      for (long c = 0; c < b; ++c) {
        double z = 0.0;
        for (long j = 0; j < k; ++j)
          z += beta * double(dinv[static_cast<size_t>(dinv_start[g] + i * k + j)]) *
               double(B(dofs[static_cast<size_t>(s0 + j)], c));
        const double dn = alpha * double(B(r, c)) + z;  // d started as B
        dref.push_back(dn), dgot.push_back(double(d(r, c)));
        xref.push_back(double(X(r, c)) + dn), xgot.push_back(double(Xj(r, c)));
      }
    }
  }
  double derr = 0.0, xerr = 0.0, dscale = 0.0, xscale = 0.0;
  for (size_t k = 0; k < dref.size(); ++k) {
    derr = std::max(derr, std::abs(dgot[k] - dref[k])), dscale = std::max(dscale, std::abs(dref[k]));
    xerr = std::max(xerr, std::abs(xgot[k] - xref[k])), xscale = std::max(xscale, std::abs(xref[k]));
  }
  CHECK(derr <= tol * dscale);
  CHECK(xerr <= tol * xscale);
}

}  // namespace

TEST_CASE("kernel instruction sets: names, the CPU's choice, refusals", "[multilevel][isa]") {
  const std::vector<KernelIsa> isas = multilevel::supported_kernel_isas();
  REQUIRE(!isas.empty());
  CHECK(isas.front() == KernelIsa::Generic);
  CHECK(multilevel::kernel_isa() == isas.back());  // the widest unless set otherwise
  for (const KernelIsa isa : {KernelIsa::Generic, KernelIsa::Avx2, KernelIsa::Avx512})
    CHECK(multilevel::kernel_isa_named(multilevel::kernel_isa_name(isa)) == isa);
  CHECK_THROWS_MATCHES(multilevel::kernel_isa_named("sse9"), ssid::formats::InputError,
                       Catch::Message("unknown kernel instruction set \"sse9\" (expected generic, avx2 or avx512)"));
  for (const KernelIsa isa : {KernelIsa::Avx2, KernelIsa::Avx512})
    if (!multilevel::kernel_isa_supported(isa))
      CHECK_THROWS_AS(multilevel::set_kernel_isa(isa), ssid::formats::InputError);
  // An Avx512 CPU runs the Avx2 version too (x86-64-v4 includes v3).
  if (multilevel::kernel_isa_supported(KernelIsa::Avx512)) CHECK(multilevel::kernel_isa_supported(KernelIsa::Avx2));
  INFO("versions here: " << isas.size());
}

TEST_CASE("every kernel version agrees with plain loops at every tile width (sparse products, block Jacobi)",
          "[multilevel][isa]") {
  for (const KernelIsa isa : multilevel::supported_kernel_isas()) {
    const IsaScope scope(isa);
    std::mt19937 rng(7);
    for (long b = 1; b <= 70; ++b) {  // AVX-512 tiles: 32 doubles / 64 floats; AVX2: 32 / 64; SSE2: 16 / 32
      CAPTURE(multilevel::kernel_isa_name(isa), b);
      check_sparse_at_width<double>(b, 1e-14, rng);
      check_sparse_at_width<float>(b, 1e-5, rng);
    }
  }
}

TEST_CASE("every kernel version agrees with plain loops: Gram products and block updates", "[multilevel][isa][slow]") {
  // p, q: every remainder of the row groups (4) and of the column tiles (AVX-512
  // 32 + 8; AVX2 12 + 4; SSE2 6 + 2 values) and the padding of Y to 8 values; n:
  // fewer rows than a group, several Gram chunks (up to 256 rows each), and the
  // split over the cores (8192 rows a thread).
  const long threaded = 2 * 8192 * multilevel::worker_threads() + 5;
  for (const KernelIsa isa : multilevel::supported_kernel_isas()) {
    const IsaScope scope(isa);
    std::mt19937 rng(11);
    for (const long n : {3L, 613L, threaded}) {
      for (const long p : {1L, 2L, 3L, 4L, 5L, 7L, 13L, 45L}) {
        for (const long q : {1L, 3L, 4L, 8L, 9L, 12L, 13L, 23L, 40L, 45L}) {
          if (n == threaded && q % 4 != 1) continue;  // the large case at a few widths
          CAPTURE(multilevel::kernel_isa_name(isa), n, p, q);
          const RowBlock X = random_block<double>(n, p, rng), Y = random_block<double>(n, q, rng);
          const long half = n / 2 + 1;
          Eigen::VectorXd w(n);
          for (long k = 0; k < n; ++k) w(k) = 0.5 + 0.01 * static_cast<double>(k % 97);
          std::vector<double> G(static_cast<size_t>(p * q), 0.0), Gh(G.size(), 0.0), Gw(G.size(), 0.0);
          for (long k = 0; k < n; ++k)
            for (long i = 0; i < p; ++i)
              for (long j = 0; j < q; ++j) {
                const double v = X(k, i) * Y(k, j);
                G[static_cast<size_t>(i * q + j)] += v;
                if (k < half) Gh[static_cast<size_t>(i * q + j)] += v;
                Gw[static_cast<size_t>(i * q + j)] += w(k) * v;
              }
          CHECK(relative_error(multilevel::gram(X, Y), G, q) <= 1e-13);
          CHECK(relative_error(multilevel::gram(X, Y, half), Gh, q) <= 1e-13);
          CHECK(relative_error(multilevel::gram_weighted(X, w, Y), Gw, q) <= 1e-13);
          // Y = β Y + X C, β = 0 and 2.5.
          const Eigen::MatrixXd C = Eigen::MatrixXd::Random(p, q);
          std::vector<double> XC(static_cast<size_t>(n * q), 0.0);
          for (long k = 0; k < n; ++k)
            for (long i = 0; i < p; ++i)
              for (long j = 0; j < q; ++j) XC[static_cast<size_t>(k * q + j)] += X(k, i) * C(i, j);
          RowBlock Z;
          multilevel::times_dense_into(X, C, 0.0, Z);
          CHECK(relative_error(Z, XC) <= 1e-13);
          for (double& v : XC) v *= 3.5;
          multilevel::times_dense_into(X, C, 2.5, Z);
          CHECK(relative_error(Z, XC) <= 1e-13);
        }
        // Symmetric: Xᵀ (D X), its upper triangle computed and mirrored, and Xᵀ diag(d) X.
        CAPTURE(multilevel::kernel_isa_name(isa), n, p);
        const RowBlock X = random_block<double>(n, p, rng);
        Eigen::VectorXd d(n);
        for (long k = 0; k < n; ++k) d(k) = 1.0 + 0.02 * static_cast<double>(k % 31);
        RowBlock DX = X;
        for (long k = 0; k < n; ++k) DX.row(k) *= d(k);
        std::vector<double> S(static_cast<size_t>(p * p), 0.0);
        for (long k = 0; k < n; ++k)
          for (long i = 0; i < p; ++i)
            for (long j = 0; j < p; ++j) S[static_cast<size_t>(i * p + j)] += X(k, i) * DX(k, j);
        const Eigen::MatrixXd Gs = multilevel::gram_symmetric(X, DX), Gws = multilevel::gram_weighted_symmetric(X, d);
        CHECK(relative_error(Gs, S, p) <= 1e-13);
        CHECK(relative_error(Gws, S, p) <= 1e-13);
        CHECK(Gs == Gs.transpose());
        CHECK(Gws == Gws.transpose());
      }
    }
    // [A B C D] C in one pass, β = 1: four blocks of widths 5, 0, 45, 17.
    const long n = 1003;
    CAPTURE(multilevel::kernel_isa_name(isa));
    const RowBlock A = random_block<double>(n, 5, rng), B(n, 0), C3 = random_block<double>(n, 45, rng),
                   D = random_block<double>(n, 17, rng);
    const Eigen::MatrixXd C = Eigen::MatrixXd::Random(67, 23);
    RowBlock Z = random_block<double>(n, 23, rng);
    std::vector<double> want(Z.data(), Z.data() + Z.size());
    for (long k = 0; k < n; ++k)
      for (long j = 0; j < 23; ++j) {
        double s = 0.0;
        for (long i = 0; i < 5; ++i) s += A(k, i) * C(i, j);
        for (long i = 0; i < 45; ++i) s += C3(k, i) * C(5 + i, j);
        for (long i = 0; i < 17; ++i) s += D(k, i) * C(50 + i, j);
        want[static_cast<size_t>(k * 23 + j)] += s;
      }
    multilevel::times_dense_sum({&A, &B, &C3, &D}, C, 1.0, Z);
    CHECK(relative_error(Z, want) <= 1e-13);
  }
}

TEST_CASE("every kernel version gives the same bits on every run", "[multilevel][isa]") {
  // Threaded products add their parts in a fixed order: no dependence on timing.
  const long n = 2 * 8192 * multilevel::worker_threads() + 77;
  std::mt19937 rng(3);
  const RowBlock X = random_block<double>(n, 45, rng), Y = random_block<double>(n, 45, rng);
  for (const KernelIsa isa : multilevel::supported_kernel_isas()) {
    const IsaScope scope(isa);
    CAPTURE(multilevel::kernel_isa_name(isa));
    const Eigen::MatrixXd G1 = multilevel::gram(X, Y), G2 = multilevel::gram(X, Y);
    CHECK(G1 == G2);
  }
}
