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
/// usage: bench_eigen N [--nd ND] [--block B] [--ncv NCV] [--tol TOL] [--sturm] [--method auto|spectra|block]
///                      [--dof-ordering] [--export DIR] [--export-only]
///                      [--method multilevel [--radius R] [--psteps S] [--degree D] [--guard G] [--ml-tol T] [--no-deflate]] [--compare]
///                      [--factor-only] [--analyze-only]
///   N = 12 → 10 368 DOF, 25 → 93 750 DOF, 55 → 998 250 DOF.
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
#include <cstring>
#include <stdexcept>
#include <utility>
#include <fstream>
#include <string>
#include <vector>

#include "estimator/eigen_solver.hpp"

namespace {

using SpMat = Eigen::SparseMatrix<double>;
using Mat12 = Eigen::Matrix<double, 12, 12>;

double cpu_s() {
  struct rusage ru {};
  getrusage(RUSAGE_SELF, &ru);
  return static_cast<double>(ru.ru_utime.tv_sec + ru.ru_stime.tv_sec) +
         1e-6 * static_cast<double>(ru.ru_utime.tv_usec + ru.ru_stime.tv_usec);
}

long peak_rss_mib() {
  struct rusage ru {};
  getrusage(RUSAGE_SELF, &ru);
  return ru.ru_maxrss / 1024;
}

double now_s() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

struct Section {
  double E = 2.1e11, G = 8.1e10, rho = 7850.0;
  double A = 1.0e-3, Iy = 1.0e-6, Iz = 1.0e-6, J = 2.0e-6;
};

/// Euler–Bernoulli 3D frame element stiffness in global axes, DOFs
/// (u, v, w, θx, θy, θz) at end a then end b. Local x runs a → b; local y is
/// the component of `ref` normal to x. K = Tᵀ K_local T, T = diag(R, R, R, R).
/// A private copy for the benchmark (the element library lives in translators/).
Mat12 frame_stiffness(const Eigen::Vector3d& xa, const Eigen::Vector3d& xb, const Eigen::Vector3d& ref,
                      const Section& s) {
  const Eigen::Vector3d d = xb - xa;
  const double L = d.norm(), L2 = L * L, L3 = L2 * L;
  const Eigen::Vector3d ex = d / L;
  const Eigen::Vector3d ey = (ref - ref.dot(ex) * ex).normalized();
  const Eigen::Vector3d ez = ex.cross(ey);
  Mat12 k = Mat12::Zero();
  const double ea = s.E * s.A / L, gj = s.G * s.J / L;
  k(0, 0) = k(6, 6) = ea;
  k(0, 6) = -ea;
  k(3, 3) = k(9, 9) = gj;
  k(3, 9) = -gj;
  // Bending in the local x-y plane (v, θz), inertia Iz.
  const double z = s.E * s.Iz;
  k(1, 1) = k(7, 7) = 12 * z / L3;
  k(1, 7) = -12 * z / L3;
  k(1, 5) = k(1, 11) = 6 * z / L2;
  k(5, 7) = k(7, 11) = -6 * z / L2;
  k(5, 5) = k(11, 11) = 4 * z / L;
  k(5, 11) = 2 * z / L;
  // Bending in the local x-z plane (w, θy), inertia Iy (signs: θy = −dw/dx).
  const double y = s.E * s.Iy;
  k(2, 2) = k(8, 8) = 12 * y / L3;
  k(2, 8) = -12 * y / L3;
  k(2, 4) = k(2, 10) = -6 * y / L2;
  k(4, 8) = k(8, 10) = 6 * y / L2;
  k(4, 4) = k(10, 10) = 4 * y / L;
  k(4, 10) = 2 * y / L;
  k = k.selfadjointView<Eigen::Upper>();
  Eigen::Matrix3d R;
  R.row(0) = ex;
  R.row(1) = ey;
  R.row(2) = ez;
  Mat12 T = Mat12::Zero();
  for (int b = 0; b < 4; ++b) T.block<3, 3>(3 * b, 3 * b) = R;
  return T.transpose() * k * T;
}

struct Model {
  SpMat K, M;
  long nodes = 0, elements = 0;
  int n = 0;  // nodes per edge
};

/// The six rigid-body modes of the lattice (translations, then rotations about
/// the origin: u = e × x, θ = e), its near-null space for the multilevel method.
Eigen::MatrixXd rigid_body_modes(const Model& m) {
  Eigen::MatrixXd B = Eigen::MatrixXd::Zero(6 * m.nodes, 6);
  const int n = m.n;
  for (long a = 0; a < m.nodes; ++a) {
    const Eigen::Vector3d x(static_cast<double>(a % n), static_cast<double>((a / n) % n), static_cast<double>(a / n / n));
    for (int c = 0; c < 3; ++c) {
      B(6 * a + c, c) = 1.0;
      const Eigen::Vector3d u = Eigen::Vector3d::Unit(c).cross(x);
      for (int d = 0; d < 3; ++d) B(6 * a + d, 3 + c) = u(d);
      B(6 * a + 3 + c, 3 + c) = 1.0;
    }
  }
  return B;
}

Model lattice(int n, const Section& s) {
  Model m;
  m.n = n;
  auto id = [n](int i, int j, int k) { return (static_cast<long>(k) * n + j) * n + i; };
  m.nodes = static_cast<long>(n) * n * n;
  const long ndof = 6 * m.nodes;
  std::vector<Eigen::Triplet<double>> tk, tm;
  tk.reserve(static_cast<size_t>(3 * m.nodes) * 64);
  std::vector<double> mass(static_cast<size_t>(m.nodes), 0.0);
  // Elements along x, y, z from every node.
  const Eigen::Vector3d ref_for_x(0, 1, 0), ref_for_yz(1, 0, 0);
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        for (int dir = 0; dir < 3; ++dir) {
          const int i2 = i + (dir == 0), j2 = j + (dir == 1), k2 = k + (dir == 2);
          if (i2 >= n || j2 >= n || k2 >= n) continue;
          const long a = id(i, j, k), b = id(i2, j2, k2);
          const Eigen::Vector3d xa(i, j, k), xb(i2, j2, k2);
          const Mat12 ke = frame_stiffness(xa, xb, dir == 0 ? ref_for_x : ref_for_yz, s);
          const long dofs[2] = {6 * a, 6 * b};
          for (int r = 0; r < 12; ++r)
            for (int c = 0; c < 12; ++c)
              if (ke(r, c) != 0.0)
                tk.emplace_back(static_cast<int>(dofs[r / 6] + r % 6), static_cast<int>(dofs[c / 6] + c % 6), ke(r, c));
          const double half = 0.5 * s.rho * s.A * (xb - xa).norm();
          mass[static_cast<size_t>(a)] += half;
          mass[static_cast<size_t>(b)] += half;
          ++m.elements;
        }
  m.K.resize(ndof, ndof);
  m.K.setFromTriplets(tk.begin(), tk.end());
  m.K.makeCompressed();
  std::vector<Eigen::Triplet<double>>().swap(tk);
  tm.reserve(static_cast<size_t>(ndof));
  for (long a = 0; a < m.nodes; ++a)
    for (int c = 0; c < 6; ++c) tm.emplace_back(static_cast<int>(6 * a + c), static_cast<int>(6 * a + c),
                                                 c < 3 ? mass[static_cast<size_t>(a)] : 0.0);
  m.M.resize(ndof, ndof);
  m.M.setFromTriplets(tm.begin(), tm.end());
  m.M.makeCompressed();
  return m;
}

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

/// Wall and CPU seconds of one call.
template <class F>
std::pair<double, double> timed(F&& f) {
  const double w = now_s(), c = cpu_s();
  f();
  return {now_s() - w, cpu_s() - c};
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
  if (argc < 2) {
    std::fprintf(stderr,
                 "usage: bench_eigen N [--nd ND] [--block B] [--ncv NCV] [--tol TOL] [--sturm] [--dof-ordering]\n"
                 "                   [--export DIR] [--export-only] [--factor-only] [--analyze-only]\n");
    return 2;
  }
  const int n = std::stoi(argv[1]);
  int nd = 41, ncv = 0, block = EigenOptions{}.block;
  EigenMethod method = EigenMethod::Auto;
  double tol = 1e-10;
  ssid::estimator::multilevel::MultilevelOptions ml;
  bool compare = false, no_deflate = false;
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
    }
    else if (!std::strcmp(argv[i], "--radius") && i + 1 < argc) ml.amg.aggregate_radius = std::stoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--degree") && i + 1 < argc) ml.amg.smoother_degree = std::stoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--psteps") && i + 1 < argc) ml.amg.prolongator_steps = std::stoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--ml-tol") && i + 1 < argc) ml.tol = std::stod(argv[++i]);
    else if (!std::strcmp(argv[i], "--guard") && i + 1 < argc) ml.guard = std::stoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--compare")) compare = true;
    else if (!std::strcmp(argv[i], "--no-deflate")) no_deflate = true;
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
  if (method == EigenMethod::Multilevel || method == EigenMethod::Auto) o.near_null_space = rigid_body_modes(m);
  if (method == EigenMethod::Multilevel) {
    const double t_start = now_s();
    o.progress = [t_start](const std::string& msg, double) {
      std::fprintf(stderr, "  %7.1f s  %s\n", now_s() - t_start, msg.c_str());
    };
    EigenResult r;
    const auto tsolve = timed([&] { r = EigenSolver(o).solve(m.K, m.M); });
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
  EigenSolver solver(o);
  EigenResult r;
  const auto tsolve = timed([&] { r = solver.solve(m.K, m.M); });
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
