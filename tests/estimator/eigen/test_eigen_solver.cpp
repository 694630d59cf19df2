#include "estimator/eigen/eigen_solver.hpp"
#include "formats/parse_error.hpp"

#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "tests/estimator/eigen/eigen_test_models.hpp"

using namespace ssid::estimator;
using namespace ssid::test;

namespace {

const double kPi = 3.14159265358979323846;

/// Checks every solve independently of the solver's own figures: residual
/// ‖Kφ − λMφ‖/‖Kφ‖ for elastic modes, backward error for all (rigid included),
/// M-orthonormality, and that the solver's reported checks agree.
void check_modes(const SpMat& K, const SpMat& M, const EigenResult& r, double zero_below = 0.0) {
  REQUIRE(r.ok());
  REQUIRE(r.modes.cols() == r.eigenvalues.size());
  const Eigen::MatrixXd KP = K * r.modes, MP = M * r.modes;
  const double kn = Eigen::MatrixXd(K).cwiseAbs().colwise().sum().maxCoeff();
  for (int j = 0; j < r.size(); ++j) {
    const double lam = r.eigenvalues(j);
    const double res = (KP.col(j) - lam * MP.col(j)).norm();
    if (lam > zero_below) CHECK(res <= 1e-9 * KP.col(j).norm());
    CHECK(res <= 1e-11 * kn * r.modes.col(j).norm());
    CHECK(r.residuals(j) == Approx(res / KP.col(j).norm()).epsilon(1e-6).margin(1e-300));
  }
  const Eigen::MatrixXd G = r.modes.transpose() * MP;
  CHECK((G - Eigen::MatrixXd::Identity(r.size(), r.size())).cwiseAbs().maxCoeff() <= 1e-10);
  CHECK(r.orthogonality <= 1e-10);
  CHECK((r.generalized_mass.array() - 1.0).abs().maxCoeff() <= 1e-10);
  for (int j = 0; j < r.size(); ++j)
    CHECK(r.generalized_stiffness(j) == Approx(r.eigenvalues(j)).margin(1e-9 * std::abs(r.eigenvalues.maxCoeff())));
  for (int j = 1; j < r.size(); ++j) CHECK(r.eigenvalues(j) >= r.eigenvalues(j - 1));
}

EigenOptions lowest(int nd, EigenMethod method = EigenMethod::Auto) {
  EigenOptions o;
  o.nd = nd;
  o.method = method;
  return o;
}

// Every numerical test runs with both Krylov iterations.
#define BOTH_METHODS() \
  const EigenMethod method = GENERATE(EigenMethod::Spectra, EigenMethod::BlockLanczos); \
  CAPTURE(method == EigenMethod::Spectra ? "Spectra" : "BlockLanczos")

}  // namespace

TEST_CASE("Eigen-solver matches the dense generalised solver on random SPD pencils", "[eigen][slow]") {
  BOTH_METHODS();
  for (int n : {30, 80, 150}) {
    for (unsigned seed : {11u, 12u}) {
      const auto [K, M] = random_pencil(n, seed + static_cast<unsigned>(n));
      const Eigen::VectorXd dense = Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd>(
                                        Eigen::MatrixXd(K), Eigen::MatrixXd(M))
                                        .eigenvalues();
      const int nd = std::min(12, n / 3);
      const EigenResult r = solve_modes(K, M, lowest(nd, method));
      check_modes(K, M, r);
      REQUIRE(r.size() == nd);
      for (int j = 0; j < nd; ++j) CHECK(r.eigenvalues(j) == Approx(dense(j)).epsilon(1e-10));
    }
  }
}

TEST_CASE("Fixed-fixed spring-mass chain: closed-form eigenvalues", "[eigen]") {
  BOTH_METHODS();
  const int n = 200;
  const double k = 1000.0, m = 2.0;
  const SpMat K = chain_stiffness(n, k, true);
  const SpMat M = diagonal(Eigen::VectorXd::Constant(n, m));
  const EigenResult r = solve_modes(K, M, lowest(10, method));
  check_modes(K, M, r);
  REQUIRE(r.size() == 10);
  for (int j = 1; j <= 10; ++j) {
    const double s = std::sin(j * kPi / (2.0 * (n + 1)));
    CHECK(r.eigenvalues(j - 1) == Approx(4.0 * k / m * s * s).epsilon(1e-10));
  }
}

TEST_CASE("Free-free chain: exactly one zero mode, then the closed form", "[eigen]") {
  BOTH_METHODS();
  const int n = 150;
  const double k = 50.0, m = 0.5;
  const SpMat K = chain_stiffness(n, k, false);
  const SpMat M = diagonal(Eigen::VectorXd::Constant(n, m));
  const EigenResult r = solve_modes(K, M, lowest(8, method));
  check_modes(K, M, r, 1e-8);
  REQUIRE(r.size() == 8);
  CHECK(r.shift < 0.0);
  CHECK(std::abs(r.eigenvalues(0)) < 1e-10 * r.eigenvalues(1) / 1e-3);  // rigid: zero to round-off
  CHECK(r.eigenvalues(1) > 1e-3);
  for (int j = 0; j < 8; ++j) {
    const double s = std::sin(j * kPi / (2.0 * n));
    CHECK(r.eigenvalues(j) == Approx(4.0 * k / m * s * s).margin(1e-10 * k / m));
  }
  // The rigid mode is a uniform translation.
  CHECK((r.modes.col(0).array() - r.modes(0, 0)).abs().maxCoeff() <= 1e-8 * std::abs(r.modes(0, 0)));
}

TEST_CASE("Free 3D truss: exactly six rigid-body modes", "[eigen]") {
  BOTH_METHODS();
  const auto [K, M] = free_box_truss();
  const Eigen::VectorXd dense = Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd>(
                                    Eigen::MatrixXd(K), Eigen::MatrixXd(M))
                                    .eigenvalues();
  const EigenResult r = solve_modes(K, M, lowest(10, method));
  check_modes(K, M, r, 1e-6);
  REQUIRE(r.size() == 10);
  int zeros = 0;
  for (int j = 0; j < 10; ++j)
    if (std::abs(r.eigenvalues(j)) < 1e-8 * dense(23)) ++zeros;
  CHECK(zeros == 6);
  for (int j = 6; j < 10; ++j) CHECK(r.eigenvalues(j) == Approx(dense(j)).epsilon(1e-10));
}

TEST_CASE("Lumped mass with massless DOFs: a massless midpoint halves the spring", "[eigen]") {
  BOTH_METHODS();
  // 2n+1 DOFs: masses at even indices, massless nodes at odd ones between two
  // springs k. Condensing the massless nodes gives a chain of springs k/2.
  const int n = 60;
  const double k = 400.0, m = 1.5;
  Triplets t;
  for (int i = 0; i + 1 < 2 * n - 1; ++i) add_spring(t, i, i + 1, k);
  add_spring(t, 0, -1, k / 2);
  add_spring(t, 2 * n - 2, -1, k / 2);
  const SpMat K = from_triplets(2 * n - 1, t);
  Eigen::VectorXd md = Eigen::VectorXd::Zero(2 * n - 1);
  for (int i = 0; i < 2 * n - 1; i += 2) md(i) = m;
  const SpMat M = diagonal(md);
  const EigenResult r = solve_modes(K, M, lowest(12, method));
  check_modes(K, M, r);
  for (int j = 1; j <= 12; ++j) {
    const double s = std::sin(j * kPi / (2.0 * (n + 1)));
    CHECK(r.eigenvalues(j - 1) == Approx(4.0 * (k / 2) / m * s * s).epsilon(1e-10));
  }
  // The massless DOFs sit exactly midway (they carry no inertia): purified modes.
  for (int j = 0; j < 12; ++j)
    for (int i = 1; i < 2 * n - 2; i += 2)
      CHECK(r.modes(i, j) == Approx(0.5 * (r.modes(i - 1, j) + r.modes(i + 1, j))).margin(1e-10));
}

TEST_CASE("Half the DOFs massless and a small model: the Krylov basis stays inside the range of M", "[eigen]") {
  BOTH_METHODS();
  // 10 masses, 10 massless nodes between them, grounded at both ends: only 10
  // finite eigenvalues. A Lanczos basis wider than 10 would run out of the
  // mass-carrying subspace and return spurious pairs (seen once with ncv = 20).
  const int n = 20;
  const double k = 1000.0, m = 2.0;
  Triplets t;
  for (int i = 0; i + 1 < n; ++i) add_spring(t, i, i + 1, k);
  add_spring(t, 0, -1, k);
  add_spring(t, n - 1, -1, k);
  const SpMat K = from_triplets(n, t);
  Eigen::VectorXd md = Eigen::VectorXd::Zero(n);
  for (int i = 0; i < n; i += 2) md(i) = m;
  const SpMat M = diagonal(md);
  // Independent reference: condense the massless DOFs (static), dense solve.
  const Eigen::MatrixXd Kd(K);
  std::vector<int> mass_idx, zero_idx;
  for (int i = 0; i < n; ++i) (md(i) > 0 ? mass_idx : zero_idx).push_back(i);
  const int a = static_cast<int>(mass_idx.size()), b = static_cast<int>(zero_idx.size());
  Eigen::MatrixXd Kaa(a, a), Kab(a, b), Kbb(b, b);
  for (int i = 0; i < a; ++i)
    for (int j = 0; j < a; ++j) Kaa(i, j) = Kd(mass_idx[i], mass_idx[j]);
  for (int i = 0; i < a; ++i)
    for (int j = 0; j < b; ++j) Kab(i, j) = Kd(mass_idx[i], zero_idx[j]);
  for (int i = 0; i < b; ++i)
    for (int j = 0; j < b; ++j) Kbb(i, j) = Kd(zero_idx[i], zero_idx[j]);
  const Eigen::MatrixXd Kc = Kaa - Kab * Kbb.ldlt().solve(Kab.transpose());
  const Eigen::VectorXd dense = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(Kc / m).eigenvalues();
  for (int nd : {4, 6, 9}) {
    CAPTURE(nd);
    const EigenResult r = solve_modes(K, M, lowest(nd, method));
    check_modes(K, M, r);
    REQUIRE(r.size() == nd);
    for (int j = 0; j < nd; ++j) CHECK(r.eigenvalues(j) == Approx(dense(j)).epsilon(1e-10));
  }
}

TEST_CASE("Value-only changes reuse the symbolic analysis", "[eigen]") {
  BOTH_METHODS();
  const auto [K, M] = random_pencil(120, 99u);
  EigenSolver solver(lowest(6, method));
  const EigenResult r1 = solver.solve(K, M);
  check_modes(K, M, r1);
  CHECK(r1.analyses == 1);
  for (double scale : {2.0, 0.5}) {
    const SpMat K2 = scale * K;
    const EigenResult r2 = solver.solve(K2, M);
    check_modes(K2, M, r2);
    CHECK(r2.analyses == 0);  // pattern unchanged: refactor only
    for (int j = 0; j < 6; ++j) CHECK(r2.eigenvalues(j) == Approx(scale * r1.eigenvalues(j)).epsilon(1e-10));
  }
  CHECK(solver.factor().analysis_count() == 1);
  CHECK(solver.factor().factorization_count() == 3);
}

TEST_CASE("Band requests find every mode in [V1, V2], multiple ones included", "[eigen]") {
  BOTH_METHODS();
  // Two identical free-free chains side by side: every eigenvalue is double, the
  // zero one too; a band with 2 x 17 modes, more than the first Lanczos run asks.
  const int n = 100;
  const double k = 100.0, m = 1.0;
  Triplets t;
  for (int c = 0; c < 2; ++c)
    for (int i = 0; i + 1 < n; ++i) add_spring(t, c * n + i, c * n + i + 1, k);
  const SpMat K = from_triplets(2 * n, t);
  const SpMat M = diagonal(Eigen::VectorXd::Constant(2 * n, m));
  auto lam = [&](int j) {
    const double s = std::sin(j * kPi / (2.0 * n));
    return 4.0 * k / m * s * s;
  };
  // Band from between modes 3 and 4 to between modes 20 and 21 (j = 4..20 inside).
  const double f1 = eigenvalue_to_hz(0.5 * (lam(3) + lam(4)));
  const double f2 = eigenvalue_to_hz(0.5 * (lam(20) + lam(21)));
  for (bool sturm : {true, false}) {
    EigenOptions o = eigrl_options(f1, f2, 0);
    o.method = method;
    o.sturm_check = sturm;
    const EigenResult r = solve_modes(K, M, o);
    check_modes(K, M, r);
    REQUIRE(r.size() == 34);
    for (int j = 0; j < 34; ++j) CHECK(r.eigenvalues(j) == Approx(lam(4 + j / 2)).epsilon(1e-9));
    if (sturm) CHECK(r.sturm_count == 42);  // j = 0..20, twice
    CHECK(r.lanczos_runs >= (sturm ? 1 : 2));
    CHECK(r.warnings.empty());
  }
  // EIGRL with ND: the lowest ND inside the band.
  EigenOptions o5 = eigrl_options(f1, f2, 5);
  o5.method = method;
  const EigenResult r5 = solve_modes(K, M, o5);
  check_modes(K, M, r5);
  REQUIRE(r5.size() == 5);
  CHECK(r5.eigenvalues(0) == Approx(lam(4)).epsilon(1e-9));
  CHECK(r5.eigenvalues(4) == Approx(lam(6)).epsilon(1e-9));
  // EIGR F1, F2 with NE: all roots in the band as well.
  EigenOptions oe = eigr_options(f1, f2, 30, 0);
  oe.method = method;
  const EigenResult re = solve_modes(K, M, oe);
  check_modes(K, M, re);
  CHECK(re.size() == 34);
}

TEST_CASE("NORM=MAX scales the largest component to one", "[eigen]") {
  BOTH_METHODS();
  const SpMat K = chain_stiffness(50, 10.0, true);
  const SpMat M = diagonal(Eigen::VectorXd::Constant(50, 1.0));
  EigenOptions o = lowest(4, method);
  o.norm = ModeNormalization::Max;
  const EigenResult r = solve_modes(K, M, o);
  REQUIRE(r.ok());
  for (int j = 0; j < 4; ++j) {
    CHECK(r.modes.col(j).cwiseAbs().maxCoeff() == Approx(1.0).epsilon(1e-14));
    CHECK(r.generalized_stiffness(j) == Approx(r.eigenvalues(j) * r.generalized_mass(j)).epsilon(1e-9));
  }
}

TEST_CASE("A mechanism is reported with its DOF index", "[eigen]") {
  BOTH_METHODS();
  // DOF 5 of a chain is massless and attached to nothing: K − σM is singular there.
  const int n = 20;
  Triplets t;
  for (int i = 0; i + 1 < n; ++i)
    if (i != 5 && i + 1 != 5) add_spring(t, i, i + 1, 10.0);
  add_spring(t, 4, 6, 10.0);
  t.emplace_back(5, 5, 0.0);
  const SpMat K = from_triplets(n, t);
  Eigen::VectorXd md = Eigen::VectorXd::Ones(n);
  md(5) = 0.0;
  const EigenResult r = solve_modes(K, diagonal(md), lowest(3, method));
  CHECK(r.status == EigenResult::Status::NotPositiveDefinite);
  CHECK(r.failed_dof == 5);
  CHECK(r.message.find("DOF index 5") != std::string::npos);
  CHECK(r.message.find("mechanism") != std::string::npos);
}

TEST_CASE("A near-mechanism is reported as near-singular", "[eigen]") {
  BOTH_METHODS();
  const int n = 20;
  SpMat K = chain_stiffness(n, 10.0, true);
  Eigen::VectorXd md = Eigen::VectorXd::Ones(n);
  md(n - 1) = 0.0;  // massless end DOF held by a spring 1e-20 of the others
  for (int j : {n - 2}) {
    K.coeffRef(n - 1, j) = 0.0;
    K.coeffRef(j, n - 1) = 0.0;
  }
  K.coeffRef(n - 2, n - 2) = 10.0;
  K.coeffRef(n - 1, n - 1) = 1e-19;
  const EigenResult r = solve_modes(K, diagonal(md), lowest(3, method));
  CHECK(r.status == EigenResult::Status::NearSingular);
  CHECK(r.message.find("nearly singular") != std::string::npos);
}

TEST_CASE("Bad requests throw", "[eigen]") {
  BOTH_METHODS();
  const SpMat K = chain_stiffness(10, 1.0, true);
  const SpMat M = diagonal(Eigen::VectorXd::Ones(10));
  // A request the input can fix (EIGRL): bad input; sizes that disagree: a bug.
  CHECK_THROWS_AS(solve_modes(K, M, EigenOptions{}), ssid::formats::InputError);  // nothing requested
  CHECK_THROWS_AS(solve_modes(K, diagonal(Eigen::VectorXd::Ones(9)), lowest(2, method)), std::invalid_argument);
  CHECK_THROWS_AS(solve_modes(K, M, eigrl_options(5.0, 1.0, 0)), ssid::formats::InputError);
}

TEST_CASE("Progress is reported", "[eigen]") {
  BOTH_METHODS();
  const SpMat K = chain_stiffness(400, 1.0, true);
  const SpMat M = diagonal(Eigen::VectorXd::Ones(400));
  EigenOptions o = lowest(20, method);
  int calls = 0;
  double last = -1.0;
  o.progress = [&](const ProgressEvent& e) {
    ++calls;
    if (e.fraction >= 0) last = e.fraction;
  };
  const EigenResult r = solve_modes(K, M, o);
  check_modes(K, M, r);
  CHECK(calls >= 4);
  CHECK(last == 1.0);
}

TEST_CASE("DOF groups (grid points) give the same modes as the DOF-graph ordering", "[eigen]") {
  BOTH_METHODS();
  // Lattice truss of 5^3 nodes, 375 DOF, six rigid-body modes; rows numbered
  // node by node (groups = row / 3) and in a scrambled order.
  const int nn = 125;
  for (bool scrambled : {false, true}) {
    CAPTURE(scrambled);
    std::vector<int> perm;
    if (scrambled) {
      perm.resize(3 * nn);
      for (int i = 0; i < 3 * nn; ++i) perm[static_cast<size_t>(i)] = i;
      std::mt19937 rng(17u);
      std::shuffle(perm.begin(), perm.end(), rng);
    }
    const auto [K, M] = free_lattice_truss(5, perm);
    std::vector<long> groups(3 * nn);
    for (int a = 0; a < nn; ++a)
      for (int c = 0; c < 3; ++c) groups[static_cast<size_t>(scrambled ? perm[static_cast<size_t>(3 * a + c)] : 3 * a + c)] = a;
    const EigenResult plain = solve_modes(K, M, lowest(20, method));
    EigenOptions og = lowest(20, method);
    og.dof_groups = groups;
    EigenSolver solver(og);
    const EigenResult grouped = solver.solve(K, M);
    check_modes(K, M, plain, 1e-6);
    check_modes(K, M, grouped, 1e-6);
    REQUIRE(grouped.size() == 20);
    CHECK(grouped.ordering.find("on 125 groups") != std::string::npos);
    const double top = plain.eigenvalues(19);
    int zeros = 0;
    for (int j = 0; j < 20; ++j) {
      if (std::abs(grouped.eigenvalues(j)) < 1e-8 * top) ++zeros;
      CHECK(grouped.eigenvalues(j) == Approx(plain.eigenvalues(j)).epsilon(1e-10).margin(1e-10 * top));
    }
    CHECK(zeros == 6);
    // Values change only: the grouped analysis is reused.
    const SpMat K2 = 3.0 * K;
    const EigenResult again = solver.solve(K2, M);
    check_modes(K2, M, again, 1e-6);
    CHECK(again.analyses == 0);
    CHECK(solver.factor().analysis_count() == 1);
    for (int j = 6; j < 20; ++j) CHECK(again.eigenvalues(j) == Approx(3.0 * grouped.eigenvalues(j)).epsilon(1e-10));
  }
}

TEST_CASE("DOF groups of the wrong size throw", "[eigen]") {
  const SpMat K = chain_stiffness(10, 1.0, true);
  const SpMat M = diagonal(Eigen::VectorXd::Ones(10));
  EigenOptions o = lowest(2);
  o.dof_groups = {0, 0, 1};
  CHECK_THROWS_AS(solve_modes(K, M, o), std::invalid_argument);
}

TEST_CASE("A factor larger than max_factor_bytes is refused with its size", "[eigen]") {
  const auto [K, M] = free_lattice_truss(4);
  EigenOptions o = lowest(8);
  o.max_factor_bytes = 1000.0;
  const EigenResult r = solve_modes(K, M, o);
  CHECK(r.status == EigenResult::Status::FactorFailed);
  CHECK(r.message.find("GiB") != std::string::npos);
  CHECK(r.message.find("max_factor_bytes") != std::string::npos);
  CHECK(r.factor_bytes > 1000.0);
  o.max_factor_bytes = -1.0;  // no limit
  check_modes(K, M, solve_modes(K, M, o), 1e-6);
}
