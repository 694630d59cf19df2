/// \file bench_kernels.cpp
/// The multilevel eigen-solver's kernels, one by one, on the benchmark lattice
/// (bench/lattice.hpp) ordered as the solver orders it (DOFs with mass first), with
/// blocks of the width LOBPCG uses at the start (45 columns: 35 wanted + 10 guard):
/// the sparse block products in double (LOBPCG's A X) and single precision (the
/// smoother's), the prolongation and restriction, one preconditioner application
/// and its coarse solve, and the dense Gram and update products of the
/// Rayleigh–Ritz step. Each is run `reps` times; the best and median wall times are
/// printed with the bytes each pass must move at least (matrix once, blocks read and
/// written once), so the figure says how far a kernel is from the memory bandwidth.
///
/// usage: bench_kernels N [--cols B] [--reps R] [--isa]
///   N = 25 → 93 750 DOF, 55 → 998 250 DOF (docs/performance.md).
///   --isa: only the kernels that have a version per instruction set (KernelIsa,
///   block_ops.hpp), each version this CPU supports timed in turn, repetition by
///   repetition (so a drift of the machine's speed hits them alike), and the
///   dense products against the same product by the system BLAS (cblas_dgemm on
///   the blocks seen column-major, the call a BLAS user would make): a version
///   slower than BLAS, or than the narrower version, shows up on any machine.
///   SSID_KERNEL_ISA=generic|avx2|avx512 picks the version of a plain run.
#include <algorithm>
#include <cstdio>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

#include "bench/lattice.hpp"
#include "estimator/linalg/allocation_policy.hpp"
#include "estimator/eigen/eigen_solver.hpp"
#include "estimator/eigen/multilevel/aggregation_amg.hpp"
#include "estimator/eigen/multilevel/block_ops.hpp"
#include "estimator/linalg/dense_blas.hpp"

namespace {

using namespace bench;
namespace ml = ssid::estimator::multilevel;

void report(const char* name, int reps, double bytes, double flops, const std::function<void()>& f) {
  std::vector<double> t;
  for (int r = 0; r < reps; ++r) t.push_back(timed(f).first);
  std::sort(t.begin(), t.end());
  const double best = t.front(), median = t[t.size() / 2];
  std::printf("%-34s best %8.4f s  median %8.4f s  %6.1f GB/s  %6.1f GFlop/s\n", name, best, median,
              bytes / best * 1e-9, flops / best * 1e-9);
}

template <class T>
ml::RowBlockOf<T> random_block(long n, long b) {
  return Eigen::Matrix<T, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>::Random(n, b);
}

/// One contender of a comparison: a kernel version (isa set) or the BLAS (none).
struct Contender {
  std::string label;
  std::function<void()> run;
  bool blas = false;
  ml::KernelIsa isa = ml::KernelIsa::Generic;
};

/// Times every contender `reps` times, round-robin, and prints a row each: best and
/// median wall time, best CPU time (all threads: on a loaded machine the steadier
/// figure, and it counts BLAS threads that spin), GB/s and GFlop/s at the best wall
/// time, and its speed against the BLAS row (when there is one), by wall and by CPU.
void compare(const char* name, int reps, double bytes, double flops, const std::vector<Contender>& cs) {
  std::vector<std::vector<double>> wall(cs.size()), cpu(cs.size());
  for (int r = 0; r < reps; ++r)
    for (size_t c = 0; c < cs.size(); ++c) {
      if (!cs[c].blas) ml::set_kernel_isa(cs[c].isa);
      const auto t = timed(cs[c].run);
      wall[c].push_back(t.first), cpu[c].push_back(t.second);
    }
  double blas_wall = 0.0, blas_cpu = 0.0;
  for (size_t c = 0; c < cs.size(); ++c) {
    std::sort(wall[c].begin(), wall[c].end());
    std::sort(cpu[c].begin(), cpu[c].end());
    if (cs[c].blas) blas_wall = wall[c].front(), blas_cpu = cpu[c].front();
  }
  for (size_t c = 0; c < cs.size(); ++c) {
    const double best = wall[c].front(), median = wall[c][wall[c].size() / 2];
    std::printf("%-30s %-7s best %7.4f s median %7.4f s CPU %7.4f s %6.1f GB/s %6.1f GFlop/s", name,
                cs[c].label.c_str(), best, median, cpu[c].front(), bytes / best * 1e-9, flops / best * 1e-9);
    if (blas_wall > 0.0 && !cs[c].blas)
      std::printf("  x BLAS %5.2f wall %5.2f CPU", blas_wall / best, blas_cpu / std::max(cpu[c].front(), 1e-6));
    std::printf("\n");
  }
}

/// A row-major n x b block seen as the column-major b x n matrix it also is.
Eigen::Map<const Eigen::MatrixXd> column_major(const ml::RowBlock& X) {
  return Eigen::Map<const Eigen::MatrixXd>(X.data(), X.cols(), X.rows());
}
Eigen::Map<Eigen::MatrixXd> column_major(ml::RowBlock& X) {
  return Eigen::Map<Eigen::MatrixXd>(X.data(), X.cols(), X.rows());
}

/// --isa: each kernel version this CPU supports, and the BLAS for the dense products.
void compare_versions(const ml::SparseMatrix& A, long ndof, long b, int reps) {
  namespace detail = ssid::estimator::detail;
  const ml::KernelIsa chosen = ml::kernel_isa();
  std::string names;
  for (const ml::KernelIsa isa : ml::supported_kernel_isas()) names += std::string(" ") + ml::kernel_isa_name(isa);
  std::printf("kernel versions this CPU supports:%s (a plain run uses %s)\n", names.c_str(), ml::kernel_isa_name(chosen));
  // The kernel versions, plus the BLAS when `blas` is given.
  const auto contenders = [&](const std::function<void()>& kernel, const std::function<void()>& blas) {
    std::vector<Contender> cs;
    for (const ml::KernelIsa isa : ml::supported_kernel_isas()) cs.push_back({ml::kernel_isa_name(isa), kernel, false, isa});
    if (blas) cs.push_back({"BLAS", blas, true});
    return cs;
  };
  const double nnzA = static_cast<double>(A.nonZeros()), nb = static_cast<double>(ndof) * static_cast<double>(b);
  const ml::RowBlock X = random_block<double>(ndof, b), Y = random_block<double>(ndof, b);
  ml::RowBlock Z;
  compare("sym_times double", reps, nnzA * 12 + nb * 16, 2 * nnzA * b, contenders([&] { ml::sym_times(A, X, Z); }, {}));
  const Eigen::SparseMatrix<float> Af = A.cast<float>();
  ml::RowBlockOf<float> Xf, Zf;
  ml::convert(X, Xf);
  compare("sym_times float", reps, nnzA * 8 + nb * 8, 2 * nnzA * b, contenders([&] { ml::sym_times(Af, Xf, Zf); }, {}));
  Eigen::MatrixXd G(b, b);
  compare("gram X^T Y", reps, nb * 16, 2 * nb * b,
          contenders([&] { G = ml::gram(X, Y); },
                     [&] { detail::gemm(false, true, 1.0, column_major(X), column_major(Y), 0.0, G); }));
  compare("gram X^T Y, symmetric", reps, nb * 16, nb * b,
          contenders([&] { G = ml::gram_symmetric(X, Y); },
                     [&] { detail::gemm(false, true, 1.0, column_major(X), column_major(Y), 0.0, G); }));
  const Eigen::VectorXd w = Eigen::VectorXd::Random(ndof);
  compare("gram X^T diag(w) Y", reps, nb * 16 + static_cast<double>(ndof) * 8, 2 * nb * b,
          contenders([&] { G = ml::gram_weighted(X, w, Y); }, {}));
  const Eigen::MatrixXd C = Eigen::MatrixXd::Random(b, b);
  Z.resize(ndof, b);
  compare("update X C", reps, nb * 16, 2 * nb * b,
          contenders([&] { ml::times_dense_into(X, C, 0.0, Z); },
                     [&] { detail::gemm(true, false, 1.0, C, column_major(X), 0.0, column_major(Z)); }));
  const ml::RowBlock XWP = random_block<double>(ndof, 3 * b);
  const Eigen::MatrixXd C3 = Eigen::MatrixXd::Random(3 * b, b);
  compare("update [X W P] C (one block)", reps, nb * 32, 2 * nb * 3 * b,
          contenders([&] { ml::times_dense_into(XWP, C3, 0.0, Z); },
                     [&] { detail::gemm(true, false, 1.0, C3, column_major(XWP), 0.0, column_major(Z)); }));
  ml::set_kernel_isa(chosen);
}

}  // namespace

int main(int argc, char** argv) {
  ssid::estimator::restart_with_huge_page_heap(argv);  // as ssid does (allocation_policy.hpp)
  ssid::estimator::keep_freed_memory();
  if (argc < 2) {
    std::fprintf(stderr, "usage: bench_kernels N [--cols B] [--reps R] [--isa]\n");
    return 2;
  }
  try {
    ml::apply_kernel_isa_environment();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_kernels: SSID_KERNEL_ISA: %s\n", e.what());
    return 2;
  }
  const int n = std::stoi(argv[1]);
  long b = 45;
  int reps = 5;
  bool versions = false;
  for (int i = 2; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--cols") && i + 1 < argc) b = std::stol(argv[++i]);
    else if (!std::strcmp(argv[i], "--reps") && i + 1 < argc) reps = std::stoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--isa")) versions = true;
    else {
      std::fprintf(stderr, "bench_kernels: unknown or incomplete option %s\n", argv[i]);
      return 2;
    }
  }
  const Model m = lattice(n, Section{});
  const long ndof = m.K.rows();
  // The solver's ordering: translations (mass) first, rotations after.
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> perm(ndof);
  const long half = ndof / 2;
  for (long i = 0; i < ndof; ++i) perm.indices()(i) = static_cast<int>(i % 6 < 3 ? (i / 6) * 3 + i % 6 : half + (i / 6) * 3 + i % 6 - 3);
  const double sigma = ssid::estimator::automatic_shift(m.K, m.M);
  const ml::SparseMatrix A0 = m.K - sigma * m.M;
  ml::SparseMatrix A = perm * A0 * perm.transpose();
  A.makeCompressed();
  std::vector<long> groups(static_cast<size_t>(ndof));
  Eigen::MatrixXd B0 = rigid_body_modes(m), B(ndof, 6);
  for (long i = 0; i < ndof; ++i) {
    groups[static_cast<size_t>(perm.indices()(i))] = i / 6;
    B.row(perm.indices()(i)) = B0.row(i);
  }
  if (versions) {
    std::printf("lattice %d^3: %ld DOF, nnz(A) %ld; %ld columns, %d threads\n", n, ndof,
                static_cast<long>(A.nonZeros()), b, static_cast<int>(ml::worker_threads()));
    compare_versions(A, ndof, b, reps);
    std::printf("peak RSS %ld MiB\n", peak_rss_mib());
    return 0;
  }
  double t0 = now_s();
  const ml::AggregationAmg amg(A, groups, B);
  const auto& at = amg.times();
  std::printf("lattice %d^3: %ld DOF, nnz(A) %ld, nnz(P) %ld, coarse %ld DOF; preconditioner %.1f s (coarse factor "
              "%.1f s, %s); %ld columns, %d threads\n",
              n, ndof, static_cast<long>(A.nonZeros()), static_cast<long>(amg.prolongator().nonZeros()),
              amg.coarse_size(), now_s() - t0, at.coarse_factor, amg.coarse_factor_single() ? "single" : "double", b,
              static_cast<int>(ml::worker_threads()));

  const double nnzA = static_cast<double>(A.nonZeros()), nnzP = static_cast<double>(amg.prolongator().nonZeros());
  const double nb = static_cast<double>(ndof) * static_cast<double>(b), nc = static_cast<double>(amg.coarse_size());
  {
    const ml::RowBlock X = random_block<double>(ndof, b);
    ml::RowBlock Y;
    report("sym_times double", reps, nnzA * 12 + nb * 16, 2 * nnzA * b, [&] { ml::sym_times(A, X, Y); });
    const Eigen::SparseMatrix<float> Af = A.cast<float>();
    ml::RowBlockOf<float> Xf;
    ml::convert(X, Xf);
    ml::RowBlockOf<float> Yf, Ef;
    report("sym_times float", reps, nnzA * 8 + nb * 8, 2 * nnzA * b, [&] { ml::sym_times(Af, Xf, Yf); });
    report("sym_residual float", reps, nnzA * 8 + nb * 12, 2 * nnzA * b, [&] { ml::sym_residual(Af, Xf, Xf, Yf); });
    const Eigen::SparseMatrix<float, Eigen::RowMajor> Prowf = amg.prolongator_rows().cast<float>();
    report("restriction P^T E float", reps, nnzP * 8 + nb * 4 + nc * b * 4, 2 * nnzP * b,
           [&] { ml::transpose_times(Prowf, Xf, Ef); });
    Yf = Xf;
    report("prolongation X += P Y float", reps, nnzP * 8 + nb * 8 + nc * b * 4, 2 * nnzP * b,
           [&] { ml::times_add(Prowf, Ef, Yf); });
    const Eigen::MatrixXd Rc = Eigen::MatrixXd::Random(amg.coarse_size(), b);
    if (const auto* single = amg.coarse_factor_single()) {
      ssid::estimator::SingleSupernodalFactor::Work work;
      ml::RowBlockOf<float> Rcf = Rc.cast<float>(), Xcf(amg.coarse_size(), b);
      report("coarse solve, single precision", reps, amg.coarse_factor().factor_bytes(),
             4 * amg.coarse_factor().factor_nnz() * b, [&] { single->solve(Rcf.data(), Xcf.data(), b, work); });
    }
    if (amg.coarse_factor().factorized())
      report("coarse solve, double", reps, 2 * amg.coarse_factor().factor_bytes(),
             4 * amg.coarse_factor().factor_nnz() * b, [&] { const Eigen::MatrixXd Xc = amg.coarse_factor().solve(Rc); });
    report("preconditioner (one cycle)", reps, 0, 0, [&] { amg.apply(X, Y); });
  }
  {
    const ml::RowBlock X = random_block<double>(ndof, b), Y = random_block<double>(ndof, b);
    report("gram X^T Y", reps, nb * 16, 2 * nb * b, [&] { const Eigen::MatrixXd G = ml::gram(X, Y); });
    report("gram X^T Y, symmetric", reps, nb * 16, nb * b, [&] { const Eigen::MatrixXd G = ml::gram_symmetric(X, Y); });
    const Eigen::MatrixXd Cb = Eigen::MatrixXd::Random(b, b);
    ml::RowBlock Z;
    report("update X C", reps, nb * 16, 2 * nb * b, [&] { ml::times_dense_into(X, Cb, 0.0, Z); });
    const ml::RowBlock W = random_block<double>(ndof, b), P = random_block<double>(ndof, b);
    const Eigen::MatrixXd C = Eigen::MatrixXd::Random(3 * b, b);
    report("update [X W P] C (three blocks)", reps, nb * 32, 2 * nb * 3 * b,
           [&] { ml::times_dense_sum({&X, &W, &P}, C, 0.0, Z); });
    const ml::RowBlock XWP = random_block<double>(ndof, 3 * b);
    report("update [X W P] C (one block)", reps, nb * 32, 2 * nb * 3 * b, [&] { ml::times_dense_into(XWP, C, 0.0, Z); });
  }
  std::printf("peak RSS %ld MiB\n", peak_rss_mib());
  return 0;
}
