// The single-precision copy of a supernodal factor: its solves are backward
// stable in single precision (residual ~1e-7 of ‖A‖‖x‖) and agree with CHOLMOD's
// double solve to what the condition number allows, for row-major blocks of any
// width, in place too.
#include "estimator/single_factor.hpp"

#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <numeric>
#include <vector>

#include "estimator/cholmod_factor.hpp"
#include "eigen_test_models.hpp"

using namespace ssid::estimator;
using namespace ssid::test;
using RowMajorF = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

namespace {

void check_single_solves(const SpMat& A) {
  CholmodFactor f(FactorKind::Supernodal);
  REQUIRE(f.factorize(A).ok());
  const SingleSupernodalFactor s = f.single_precision_copy();
  REQUIRE(s.n == A.rows());
  REQUIRE(s.super.size() >= 2);
  const Eigen::MatrixXd Ad = Eigen::MatrixXd(A);
  const double cond = [&] {
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(Ad);
    return es.eigenvalues().maxCoeff() / es.eigenvalues().minCoeff();
  }();
  SingleSupernodalFactor::Work work;
  for (long nrhs : {1L, 3L, 17L}) {
    CAPTURE(nrhs);
    const Eigen::MatrixXd B = Eigen::MatrixXd::Random(A.rows(), nrhs);
    const Eigen::MatrixXd Xd = f.solve(B);
    RowMajorF Bf = B.cast<float>(), Xf(A.rows(), nrhs);
    s.solve(Bf.data(), Xf.data(), nrhs, work);
    const Eigen::MatrixXd X = Xf.cast<double>();
    // Backward error of a single-precision solve, and the forward error it implies.
    const double backward = (Ad * X - Bf.cast<double>()).norm() / (Ad.norm() * X.norm());
    CHECK(backward <= 1e-6);
    CHECK((X - Xd).norm() <= 1e-6 * cond * Xd.norm());
    s.solve(Bf.data(), Bf.data(), nrhs, work);  // in place
    CHECK((Bf - Xf).norm() == 0.0f);
  }
}

}  // namespace

TEST_CASE("Single-precision supernodal solves: backward stable, any block width, in place", "[cholmod]") {
  for (int n : {40, 200}) {
    const auto [K, M] = random_pencil(n, 3u + static_cast<unsigned>(n));
    check_single_solves(K);
  }
  // A lattice truss: many supernodes with rows below them (the scatter and gather
  // of the off-diagonal rows), in a scrambled numbering (the permutation).
  const int nn = 6 * 6 * 6;
  std::vector<int> perm(3 * nn);
  std::iota(perm.begin(), perm.end(), 0);
  std::reverse(perm.begin(), perm.end());
  const auto [K0, M] = free_lattice_truss(6, perm);
  check_single_solves(K0 + SpMat(M * 0.5));
}

TEST_CASE("Single-precision copy needs a supernodal factor", "[cholmod]") {
  const auto [K, M] = random_pencil(30, 5u);
  CholmodFactor simplicial(FactorKind::Simplicial), none;
  REQUIRE(simplicial.factorize(K).ok());
  CHECK_THROWS_AS(simplicial.single_precision_copy(), std::logic_error);
  CHECK_THROWS_AS(none.single_precision_copy(), std::logic_error);
  SingleSupernodalFactor empty;
  SingleSupernodalFactor::Work w;
  float b = 1.0f, x = 0.0f;
  CHECK_THROWS_AS(empty.solve(&b, &x, 1, w), std::logic_error);
}
