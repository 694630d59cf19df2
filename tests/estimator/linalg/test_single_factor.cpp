// The supernodal factorisation in single precision: its solves are backward
// stable in single precision (residual ~1e-7 of ‖A‖‖x‖) and agree with CHOLMOD's
// double factor and solve to what the condition number allows, for row-major
// blocks of any width, in place too; a non-positive pivot is named.
#include "estimator/linalg/single_factor.hpp"

#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <algorithm>
#include <limits>
#include <numeric>
#include <thread>
#include <vector>

#include "estimator/linalg/cholmod_factor.hpp"
#include "estimator/linalg/dense_blas.hpp"
#include "tests/estimator/eigen/eigen_test_models.hpp"

using namespace ssid::estimator;
using namespace ssid::test;
using RowMajorF = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

namespace {

/// Supernodes with rows below their own columns (whose updates and off-diagonal
/// solves the checks exercise).
long supernodes_with_rows_below(const SingleSupernodalFactor& s) {
  long count = 0;
  for (size_t k = 0; k + 1 < s.super.size(); ++k)
    count += (s.pi[k + 1] - s.pi[k]) > (s.super[k + 1] - s.super[k]);
  return count;
}

void check_single_solves(const SpMat& A, long min_updating_supernodes) {
  CholmodFactor f(FactorKind::Supernodal);  // the reference: CHOLMOD in double
  REQUIRE(f.factorize(A).ok());
  SingleSupernodalFactor s;
  CholmodFactor g(FactorKind::Supernodal);
  const FactorStatus st = g.factorize_single(A, s);
  REQUIRE(st.ok());
  CHECK(st.rcond > 0.0);
  CHECK_FALSE(g.factorized());  // no double factor: solve() is not available
  CHECK_THROWS_AS(g.solve(Eigen::MatrixXd::Ones(A.rows(), 1)), std::logic_error);
  CHECK(supernodes_with_rows_below(s) >= min_updating_supernodes);
  REQUIRE(s.n == A.rows());
  // κ(A) by power iterations (A for λ_max, CHOLMOD's double solves for λ_min):
  // estimates from inside, so the forward-error bound below errs on the strict side.
  const double cond = [&] {
    // Random starts: the constant vector is a rigid translation of the lattice, an
    // eigenvector of A itself (the lowest), from which power iterations would not move.
    Eigen::VectorXd u = Eigen::VectorXd::Random(A.rows()), v = Eigen::VectorXd::Random(A.rows());
    double lmax = 0.0, inv_lmin = 0.0;
    for (int it = 0; it < 60; ++it) {
      u = A * u.normalized();
      lmax = u.norm();
      v = f.solve(Eigen::MatrixXd(v.normalized())).col(0);
      inv_lmin = v.norm();
    }
    return lmax * inv_lmin;
  }();
  const double anorm = Eigen::MatrixXd(A).norm();
  SingleSupernodalFactor::Work work;
  // Block widths from one column to more than the multilevel method's 45.
  for (long nrhs : {1L, 3L, 17L, 45L, 64L, 80L, 100L}) {
    CAPTURE(nrhs);
    const Eigen::MatrixXd B = Eigen::MatrixXd::Random(A.rows(), nrhs);
    const Eigen::MatrixXd Xd = f.solve(B);
    RowMajorF Bf = B.cast<float>(), Xf(A.rows(), nrhs);
    s.solve(Bf.data(), Xf.data(), nrhs, work);
    const Eigen::MatrixXd X = Xf.cast<double>();
    // Backward error of a single-precision solve, and the forward error it implies.
    const double backward = (A * X - Bf.cast<double>()).norm() / (anorm * X.norm());
    CHECK(backward <= 1e-6);
    CHECK((X - Xd).norm() <= 1e-6 * cond * Xd.norm());
    // Column ranges solved apart, on two threads at once with the BLAS held to one
    // thread (the multilevel cycle's split): the same solution, to rounding (the
    // BLAS may block a thinner product differently), and the columns outside a
    // range neither read nor written.
    if (nrhs >= 3) {
      const long mid = nrhs / 3;
      RowMajorF Xp = RowMajorF::Constant(A.rows(), nrhs, std::numeric_limits<float>::quiet_NaN());
      RowMajorF Bp = Bf;
      Bp.col(nrhs - 1).setConstant(std::numeric_limits<float>::quiet_NaN());  // outside both ranges
      {
        const detail::BlasThreadLimit one_thread;
        SingleSupernodalFactor::Work w1, w2;
        std::thread t([&] { s.solve_columns(Bp.data(), Xp.data(), nrhs, 0, mid, w1); });
        s.solve_columns(Bp.data(), Xp.data(), nrhs, mid, nrhs - 1, w2);
        t.join();
      }
      CHECK(Xp.col(nrhs - 1).array().isNaN().all());
      const Eigen::MatrixXd Xs = Xp.leftCols(nrhs - 1).cast<double>();
      CHECK(Xs.allFinite());
      CHECK((Xs - X.leftCols(nrhs - 1)).norm() <= 1e-5 * X.leftCols(nrhs - 1).norm());
      CHECK_THROWS_AS(s.solve_columns(Bp.data(), Xp.data(), nrhs, 1, nrhs + 1, work), std::invalid_argument);
      CHECK_THROWS_AS(s.solve_columns(Bp.data(), Xp.data(), nrhs, 2, 1, work), std::invalid_argument);
    }
    s.solve(Bf.data(), Bf.data(), nrhs, work);  // in place
    CHECK((Bf - Xf).norm() == 0.0f);
  }
}

}  // namespace

TEST_CASE("Single-precision supernodal solves: backward stable, any block width, in place", "[cholmod][slow]") {
  for (int n : {40, 200}) {
    const auto [K, M] = random_pencil(n, 3u + static_cast<unsigned>(n));
    check_single_solves(K, 0);  // dense: one or a few supernodes
  }
  // A lattice truss: many supernodes with rows below them (the scatter and gather
  // of the off-diagonal rows, the updates between supernodes), in a reversed numbering.
  const int nn = 6 * 6 * 6;
  std::vector<int> perm(3 * nn);
  std::iota(perm.begin(), perm.end(), 0);
  std::reverse(perm.begin(), perm.end());
  const auto [K0, M] = free_lattice_truss(6, perm);
  check_single_solves(K0 + SpMat(M * 0.5), 20);
  // A larger lattice: supernodes with hundreds of rows below them.
  const auto [K1, M1] = free_lattice_truss(9);
  check_single_solves(K1 + SpMat(M1 * 0.5), 50);
}

TEST_CASE("Single-precision factorisation names a non-positive pivot", "[cholmod]") {
  const auto [K0, M] = free_lattice_truss(4);
  CholmodFactor f(FactorKind::Supernodal);
  SingleSupernodalFactor s;
  const SpMat indefinite = K0 - SpMat(M * 1e6);  // far below the lowest eigenvalue
  const FactorStatus st = f.factorize_single(indefinite, s);
  CHECK(st.code == FactorStatus::Code::NotPositiveDefinite);
  CHECK(s.empty());
  CholmodFactor d(FactorKind::Supernodal);  // the same ordering, in double: the same first bad pivot
  const FactorStatus sd = d.factorize(indefinite);
  REQUIRE(sd.code == FactorStatus::Code::NotPositiveDefinite);
  CHECK(st.column == sd.column);
  CholmodFactor simplicial(FactorKind::Simplicial);
  CHECK(simplicial.factorize_single(K0 + SpMat(M), s).code == FactorStatus::Code::Failed);
}

TEST_CASE("factorize_single leaves no double factor behind", "[cholmod]") {
  const auto [K0, M] = free_lattice_truss(4);
  const SpMat A = K0 + SpMat(M), B = K0 + SpMat(M * 2.0);  // the same pattern
  CholmodFactor f(FactorKind::Supernodal);
  REQUIRE(f.factorize(A).ok());
  REQUIRE(f.factorized());
  SingleSupernodalFactor s;
  REQUIRE(f.factorize_single(B, s).ok());
  CHECK_FALSE(f.factorized());  // A's double values must not answer for B
  CHECK_THROWS_AS(f.solve(Eigen::MatrixXd::Ones(A.rows(), 1)), std::logic_error);
  REQUIRE(f.factorize(B).ok());
  CHECK(f.factorized());
}

TEST_CASE("An empty single-precision factor refuses to solve", "[cholmod]") {
  SingleSupernodalFactor empty;
  SingleSupernodalFactor::Work w;
  float b = 1.0f, x = 0.0f;
  CHECK_THROWS_AS(empty.solve(&b, &x, 1, w), std::logic_error);
}
