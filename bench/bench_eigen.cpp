/// \file bench_eigen.cpp
/// Lowest modes of a free-free 3D beam-frame lattice: a cubic lattice of N³ nodes
/// 1 m apart, every lattice edge a 3D Euler–Bernoulli frame element (6 DOF per
/// node), lumped mass (translational only, as NASTRAN lumps CBAR mass: the
/// rotations are massless DOFs). Solves the lowest ND modes (default 41: six
/// rigid-body modes and 35 elastic ones) with EigenSolver and reports the times,
/// the factor, the number of solves and peak memory. Optionally writes K and M
/// as MatrixMarket (lower triangle, "symmetric") and the shift, for
/// bench/eigs_scipy.py and bench/eigs_slepc.py.
///
/// usage: bench_eigen N [--nd ND] [--block B] [--ncv NCV] [--tol TOL] [--sturm] [--method auto|direct|spectra|block]
///                      [--dof-ordering] [--export DIR] [--export-only]
///                      [--method multilevel [--radius R] [--psteps S] [--degree D] [--ratio R] [--guard G] [--start-smoothing K] [--derived-gram-bound B] [--lock-cluster-gap G] [--ml-tol T] [--no-deflate] [--no-strain] [--double-coarse]] [--compare] [--system-malloc]
///                      [--factor-only] [--analyze-only]
///   N = 12 → 10 368 DOF, 25 → 93 750 DOF, 55 → 998 250 DOF.
///   --method auto (the default) gives the solver the rigid-body modes and strain
///   fields, so that EigenMethod::Auto chooses between the direct and the
///   multilevel method by predicted cost (the choice and its reason are printed);
///   --method direct: Auto without them, the direct method (block Lanczos from
///   50 000 DOF). SSID_KERNEL_ISA=generic|avx2|avx512 picks the multilevel
///   kernels' version (block_ops.hpp; the one used is printed).
///   By default the ordering is computed on the grid-point graph (EigenOptions::
///   dof_groups = node of each DOF); --dof-ordering leaves it to CHOLMOD on the
///   DOF graph. --factor-only: analyse and factor K − σM and time one block solve
///   (the cost floor); --analyze-only: symbolic analysis only, with the memory L
///   would take (how the 1M case is sized before anything is allocated);
///   --export-only: write the MatrixMarket files without solving.
///   Times are wall clock and CPU (user + system, all threads): on a shared
///   machine the CPU time is the steadier figure.
#include <sys/resource.h>

#include <Eigen/Dense>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <utility>
#include <fstream>
#include <string>
#include <vector>

#include "bench/lattice.hpp"
#include "estimator/linalg/allocation_policy.hpp"
#include "estimator/eigen/eigen_solver.hpp"
#include "estimator/eigen/multilevel/block_ops.hpp"

namespace {

using namespace bench;

/// MatrixMarket coordinate real symmetric: the lower triangle, 1-based.
void write_mtx(const std::string& path, const SpMat& A) {
  const SpMat L = A.triangularView<Eigen::Lower>();
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (!f) throw std::runtime_error("cannot write " + path);
  std::fprintf(f, "%%%%MatrixMarket matrix coordinate real symmetric\n%ld %ld %ld\n", static_cast<long>(L.rows()),
               static_cast<long>(L.cols()), static_cast<long>(L.nonZeros()));
  for (Eigen::Index c = 0; c < L.outerSize(); ++c)
    for (SpMat::InnerIterator it(L, c); it; ++it)
      std::fprintf(f, "%ld %ld %.17g\n", static_cast<long>(it.row() + 1), static_cast<long>(c + 1), it.value());
  std::fclose(f);
}

void export_mtx(const std::string& dir, const Model& m, double shift, const Eigen::VectorXd* eigenvalues) {
  std::filesystem::create_directories(dir);  // throws, with the path, when it cannot
  write_mtx(dir + "/K.mtx", m.K);
  write_mtx(dir + "/M.mtx", m.M);
  std::FILE* f = std::fopen((dir + "/shift.txt").c_str(), "w");
  if (!f) throw std::runtime_error("cannot write " + dir + "/shift.txt");
  std::fprintf(f, "%.17g\n", shift);
  std::fclose(f);
  if (eigenvalues) {
    f = std::fopen((dir + "/eigenvalues_ssid.txt").c_str(), "w");
    if (!f) throw std::runtime_error("cannot write " + dir + "/eigenvalues_ssid.txt");
    for (Eigen::Index j = 0; j < eigenvalues->size(); ++j) std::fprintf(f, "%.17g\n", (*eigenvalues)(j));
    std::fclose(f);
  }
  std::printf("exported K.mtx, M.mtx, shift.txt%s to %s\n", eigenvalues ? ", eigenvalues_ssid.txt" : "",
              dir.c_str());
}

/// Rigid-body modes among the results (|λ| below 1e-6 of the highest).
int count_rigid(const ssid::estimator::EigenResult& r) {
  int rigid = 0;
  for (int j = 0; j < r.size(); ++j)
    if (std::abs(r.eigenvalues(j)) < 1e-6 * r.eigenvalues(r.size() - 1)) ++rigid;
  return rigid;
}

/// The checks, peak memory and eigenvalues of a solve, as every method prints them.
void print_checks(const ssid::estimator::EigenResult& r, int rigid) {
  std::printf("max residual (elastic) %.2e, max backward error %.2e, M-orthogonality %.2e\n",
              r.residuals.tail(r.size() - rigid).maxCoeff(), r.backward_errors.maxCoeff(), r.orthogonality);
  std::printf("peak RSS %ld MiB\n", peak_rss_mib());
  std::printf("eigenvalues:");
  for (int j = 0; j < r.size(); ++j) std::printf(" %.10g", r.eigenvalues(j));
  std::printf("\n");
}

}  // namespace

int main(int argc, char** argv) {
  using namespace ssid::estimator;
  // As ssid does (allocation_policy.hpp), unless --system-malloc: glibc's defaults.
  bool system_malloc = false;
  for (int i = 1; i < argc; ++i) system_malloc = system_malloc || !std::strcmp(argv[i], "--system-malloc");
  if (!system_malloc) restart_with_huge_page_heap(argv);
  if (argc < 2) {
    std::fprintf(stderr,
                 "usage: bench_eigen N [--nd ND] [--block B] [--ncv NCV] [--tol TOL] [--sturm] [--dof-ordering]\n"
                 "                   [--export DIR] [--export-only] [--factor-only] [--analyze-only]\n");
    return 2;
  }
  try {
    multilevel::apply_kernel_isa_environment();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_eigen: SSID_KERNEL_ISA: %s\n", e.what());
    return 2;
  }
  const int n = std::stoi(argv[1]);
  int nd = 41, ncv = 0, block = EigenOptions{}.block;
  EigenMethod method = EigenMethod::Auto;
  double tol = 1e-10;
  ssid::estimator::multilevel::MultilevelOptions ml;
  bool direct = false;  // --method direct: Auto without the multilevel method (no rigid-body modes given)
  bool compare = false, no_deflate = false, keep_freed = true, no_strain = false;
  bool sturm = false, dof_ordering = false, export_only = false, factor_only = false, analyze_only = false;
  std::string export_dir;
  for (int i = 2; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--nd") && i + 1 < argc) nd = std::stoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--block") && i + 1 < argc) block = std::stoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--ncv") && i + 1 < argc) ncv = std::stoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--tol") && i + 1 < argc) tol = std::stod(argv[++i]);
    else if (!std::strcmp(argv[i], "--export") && i + 1 < argc) export_dir = argv[++i];
    else if (!std::strcmp(argv[i], "--sturm")) sturm = true;
    else if (!std::strcmp(argv[i], "--method") && i + 1 < argc) {
      const std::string m = argv[++i];
      method = m == "spectra"      ? EigenMethod::Spectra
               : m == "block"      ? EigenMethod::BlockLanczos
               : m == "multilevel" ? EigenMethod::Multilevel
                                   : EigenMethod::Auto;
      direct = m == "direct";
    }
    else if (!std::strcmp(argv[i], "--radius") && i + 1 < argc) ml.amg.aggregate_radius = std::stoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--system-malloc")) keep_freed = false;
    else if (!std::strcmp(argv[i], "--double-coarse")) ml.amg.coarse_single_precision = false;
    else if (!std::strcmp(argv[i], "--degree") && i + 1 < argc) ml.amg.smoother_degree = std::stoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--ratio") && i + 1 < argc) ml.amg.smoother_ratio = std::stod(argv[++i]);
    else if (!std::strcmp(argv[i], "--psteps") && i + 1 < argc) ml.amg.prolongator_steps = std::stoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--ml-tol") && i + 1 < argc) ml.tol = std::stod(argv[++i]);
    else if (!std::strcmp(argv[i], "--guard") && i + 1 < argc) ml.guard = std::stoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--start-smoothing") && i + 1 < argc) ml.start_smoothing = std::stoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--derived-gram-bound") && i + 1 < argc) ml.derived_gram_bound = std::stod(argv[++i]);
    else if (!std::strcmp(argv[i], "--lock-cluster-gap") && i + 1 < argc) ml.lock_cluster_gap = std::stod(argv[++i]);
    else if (!std::strcmp(argv[i], "--compare")) compare = true;
    else if (!std::strcmp(argv[i], "--no-deflate")) no_deflate = true;
    else if (!std::strcmp(argv[i], "--no-strain")) no_strain = true;
    else if (!std::strcmp(argv[i], "--dof-ordering")) dof_ordering = true;
    else if (!std::strcmp(argv[i], "--export-only")) export_only = true;
    else if (!std::strcmp(argv[i], "--factor-only")) factor_only = true;
    else if (!std::strcmp(argv[i], "--analyze-only")) analyze_only = true;
    else {
      std::fprintf(stderr, "bench_eigen: unknown or incomplete option %s\n", argv[i]);
      return 2;
    }
  }
  if (export_only && export_dir.empty()) {
    std::fprintf(stderr, "bench_eigen: --export-only needs --export DIR\n");
    return 2;
  }
  if (keep_freed) ssid::estimator::keep_freed_memory();
  const char* tunables = std::getenv("GLIBC_TUNABLES");
  std::printf("malloc: %s, GLIBC_TUNABLES %s\n", keep_freed ? "freed memory kept (keep_freed_memory)" : "glibc defaults",
              tunables ? tunables : "unset");
  const Section sec;
  double t = now_s();
  const Model m = lattice(n, sec);
  const double t_build = now_s() - t;
  std::printf("lattice %d^3: %ld nodes, %ld elements, %ld DOF, nnz(K) %ld, build %.2f s, RSS %ld MiB\n", n, m.nodes,
              m.elements, static_cast<long>(m.K.rows()), static_cast<long>(m.K.nonZeros()), t_build, peak_rss_mib());
  const double sigma = automatic_shift(m.K, m.M);
  if (export_only) {
    export_mtx(export_dir, m, sigma, nullptr);
    return 0;
  }

  std::vector<long> groups;
  if (!dof_ordering) {
    groups.resize(static_cast<size_t>(m.K.rows()));
    for (size_t i = 0; i < groups.size(); ++i) groups[i] = static_cast<long>(i / 6);  // node of each DOF
  }
  std::printf("ordering on the %s graph, block %d\n", dof_ordering ? "DOF" : "grid-point", block);

  if (factor_only || analyze_only) {
    CholmodFactor f;
    f.set_dof_groups(groups);
    const SpMat A = SpMat(m.K.triangularView<Eigen::Lower>()) - sigma * SpMat(m.M.triangularView<Eigen::Lower>());
    const auto ta = timed([&] { f.analyze(A); });
    std::printf("analyse: %.3f s wall, %.3f s CPU; ordering %s, nnz(L) %.4g, flops %.4g, factor memory %.2f GiB\n",
                ta.first, ta.second, f.ordering().c_str(), f.factor_nnz(), f.factor_flops(),
                f.factor_bytes() / 1073741824.0);
    std::printf("peak RSS %ld MiB\n", peak_rss_mib());
    if (analyze_only) return 0;
    FactorStatus st;
    const auto tf = timed([&] { st = f.factorize(A); });
    if (!st.ok()) {
      std::printf("factorisation failed: %s\n", st.message.c_str());
      return 1;
    }
    std::printf("factor: %.3f s wall, %.3f s CPU (%.1f GFlop/s wall)\n", tf.first, tf.second,
                f.factor_flops() / tf.first * 1e-9);
    // One solve with 1, 8, 16, 32, 64 right-hand sides: L is read once per
    // solve, so the cost per column falls with the block width.
    const Eigen::MatrixXd B = Eigen::MatrixXd::Random(m.K.rows(), 64);
    Eigen::MatrixXd X(m.K.rows(), 64);
    for (int w : {1, 8, 16, 32, 64}) {
      const auto ts = timed([&] { f.solve(B.data(), X.data(), w); });
      std::printf("one solve, %2d columns: %.4f s wall, %.4f s CPU, %.4f s wall per column\n", w, ts.first,
                  ts.second, ts.first / w);
    }
    std::printf("peak RSS %ld MiB\n", peak_rss_mib());
    return 0;
  }

  EigenOptions o;
  o.nd = nd;
  o.ncv = ncv;
  o.tol = tol;
  o.block = block;
  o.method = method;
  o.sturm_check = false;
  o.dof_groups = groups;
  o.multilevel = ml;
  o.multilevel.deflate = !no_deflate;
  if (method == EigenMethod::Multilevel || (method == EigenMethod::Auto && !direct)) {
    o.near_null_space = rigid_body_modes(m);
    if (!no_strain) o.strain_fields = strain_fields(m);
    const double t_start = now_s();
    o.progress = [t_start](const ssid::estimator::ProgressEvent& e) {
      std::fprintf(stderr, "  %7.1f s  %s\n", now_s() - t_start, e.text().c_str());
    };
  }
  std::printf("kernels: %s\n", ssid::estimator::multilevel::kernel_isa_name(ssid::estimator::multilevel::kernel_isa()));
  EigenSolver solver(o);
  EigenResult r;
  const auto tsolve = timed([&] { r = solver.solve(m.K, m.M); });
  std::printf("method choice: %s\n", r.method_reason.c_str());
  if (r.method == "Multilevel") {
    std::printf("method Multilevel: %s; coarse %ld DOF, LOBPCG iterations %ld, preconditioned columns %ld\n",
                r.ok() ? "converged" : r.message.c_str(), r.coarse_size, r.iterations, r.solves);
    std::printf("time: total %.3f s wall (%.3f s CPU) = setup %.3f + coarse modes and LOBPCG %.3f + checks %.3f\n",
                r.total_seconds, tsolve.second, r.factor_seconds, r.lanczos_seconds,
                r.total_seconds - r.factor_seconds - r.lanczos_seconds);
    const int rigid = count_rigid(r);
    std::printf("modes %d (rigid %d): f1 elastic %.6g Hz, f_last %.6g Hz\n", r.size(), rigid,
                rigid < r.size() ? r.cycles(rigid) : 0.0, r.cycles(r.size() - 1));
    print_checks(r, rigid);
    if (compare) {
      EigenOptions d = o;
      d.method = EigenMethod::Auto;
      d.near_null_space.resize(0, 0);
      d.strain_fields.resize(0, 0);
      d.progress = nullptr;
      const EigenResult ref = EigenSolver(d).solve(m.K, m.M);
      double worst = 0.0, worst_rigid = 0.0;
      const double top = ref.eigenvalues(ref.size() - 1);
      for (int j = 0; j < std::min(r.size(), ref.size()); ++j) {
        const double dl = std::abs(r.eigenvalues(j) - ref.eigenvalues(j));
        if (j < rigid) worst_rigid = std::max(worst_rigid, dl / top);
        else worst = std::max(worst, dl / std::abs(ref.eigenvalues(j)));
      }
      std::printf("against %s (%.3f s): elastic eigenvalues agree to %.2e (relative), rigid-body ones to %.2e of "
                  "the highest\n", ref.method.c_str(), ref.total_seconds, worst, worst_rigid);
    }
    return r.ok() ? 0 : 1;
  }
  if (!r.ok()) {
    std::printf("solve failed: %s\n", r.message.c_str());
    return 1;
  }
  // The floor: the factorisation plus the solves the iteration needed, each
  // solve timed alone here with a block of the size the iteration used.
  const Eigen::MatrixXd B = Eigen::MatrixXd::Random(m.K.rows(), block);
  Eigen::MatrixXd X(m.K.rows(), block);
  const int reps = 3;
  const auto tb = timed([&] {
    for (int i = 0; i < reps; ++i) solver.factor().solve(B.data(), X.data(), block);
  });
  const double t_block = tb.first / reps;
  const double floor_s = r.factor_seconds + (static_cast<double>(r.solves) / block) * t_block;
  const int rigid = count_rigid(r);
  std::printf("shift %.6g, ordering %s, nnz(L) %.4g, flops %.4g, factor memory %.2f GiB\n", r.shift,
              r.ordering.c_str(), r.factor_nnz, r.factor_flops, r.factor_bytes / 1073741824.0);
  std::printf("modes %d (rigid %d): f1 elastic %.6g Hz, f_last %.6g Hz\n", r.size(), rigid,
              rigid < r.size() ? r.cycles(rigid) : 0.0, r.cycles(r.size() - 1));
  std::printf("method %s, nev %d, block solves %ld, columns solved %ld\n", r.method.c_str(), r.nev, r.iterations,
              r.solves);
  std::printf("time: total %.3f s wall (%.3f s CPU) = analyse %.3f + factor %.3f + Lanczos, refinement and checks %.3f\n",
              r.total_seconds, tsolve.second, r.analyze_seconds, r.factor_seconds - r.analyze_seconds,
              r.total_seconds - r.factor_seconds);
  std::printf("one block solve (%d columns) %.4f s; floor = analyse + factor + %.1f block solves = %.3f s; "
              "total / floor = %.2f\n",
              block, t_block, static_cast<double>(r.solves) / block, floor_s, r.total_seconds / floor_s);
  print_checks(r, rigid);
  if (sturm) {
    // Completeness: eigenvalues below the midpoint of the last two found, by inertia.
    const double s = r.size() > 1 ? 0.5 * (r.eigenvalues(r.size() - 1) + r.eigenvalues(r.size() - 2)) : 0.0;
    t = now_s();
    const long cnt = count_negative_pivots(m.K - s * m.M);
    std::printf("Sturm count below %.6g: %ld (expected %d), %.2f s\n", s, cnt, r.size() - 1, now_s() - t);
  }
  if (!export_dir.empty()) export_mtx(export_dir, m, r.shift, &r.eigenvalues);
  return 0;
}
