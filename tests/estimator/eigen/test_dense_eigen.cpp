// Dense fallback: closed-form chains, massless DOFs, free-free rigid-body
// modes, agreement with the Lanczos solver, residuals and orthogonality.
#include <catch2/catch.hpp>
#include <cmath>

#include "tests/estimator/eigen/eigen_test_models.hpp"
#include "estimator/eigen/dense_eigen.hpp"

using namespace ssid::estimator;
using namespace ssid::test;

TEST_CASE("dense: every mode of a fixed-fixed chain, closed form", "[dense_eigen]") {
  const int n = 30;
  const double k = 1000.0, m = 2.0;
  const SpMat K = chain_stiffness(n, k, true);
  const SpMat M = diagonal(Eigen::VectorXd::Constant(n, m));
  const EigenResult r = solve_modes_dense(K, M);
  REQUIRE(r.ok());
  REQUIRE(r.size() == n);
  for (int j = 1; j <= n; ++j) {
    const double s = std::sin(j * M_PI / (2.0 * (n + 1)));
    CHECK(r.eigenvalues(j - 1) == Approx(4 * k / m * s * s).epsilon(1e-11));
  }
  CHECK(r.generalized_mass.isApproxToConstant(1.0, 1e-12));
  CHECK(r.orthogonality < 1e-12);
  CHECK(r.residuals.maxCoeff() < 1e-11);
}

TEST_CASE("dense: massless DOFs give no mode; band and count select", "[dense_eigen]") {
  const int n = 20;
  const SpMat K = chain_stiffness(n, 500.0, true);
  Eigen::VectorXd d = Eigen::VectorXd::Ones(n);
  for (int i = 0; i < n; i += 2) d(i) = 0.0;  // every other DOF massless
  const SpMat M = diagonal(d);
  EigenResult all = solve_modes_dense(K, M);
  REQUIRE(all.ok());
  CHECK(all.size() == n / 2);
  CHECK(all.backward_errors.maxCoeff() < 1e-13);
  CHECK(all.orthogonality < 1e-11);
  // The same as the block Lanczos solver's lowest four. (The single-vector Spectra
  // path returns wrong λ₃, λ₄ here with status Ok — reported, not ours to fix.)
  EigenOptions o;
  o.nd = 4;
  o.method = EigenMethod::BlockLanczos;
  const EigenResult lan = solve_modes(K, M, o);
  const EigenResult four = solve_modes_dense(K, M, o);
  REQUIRE(lan.ok());
  REQUIRE(four.size() == 4);
  for (int i = 0; i < 4; ++i) CHECK(four.eigenvalues(i) == Approx(lan.eigenvalues(i)).epsilon(1e-10));
  // Band [f(2), f(5)] inclusive of its ends (slightly widened).
  EigenOptions b;
  b.f_low = eigenvalue_to_hz(all.eigenvalues(1)) * (1 - 1e-9);
  b.f_high = eigenvalue_to_hz(all.eigenvalues(4)) * (1 + 1e-9);
  const EigenResult band = solve_modes_dense(K, M, b);
  REQUIRE(band.size() == 4);
  CHECK(band.eigenvalues(0) == Approx(all.eigenvalues(1)));
  // Asking for more than exist is a warning, not a failure.
  EigenOptions many;
  many.nd = n;
  const EigenResult w = solve_modes_dense(K, M, many);
  CHECK(w.size() == n / 2);
  CHECK(w.warnings.size() == 1);
}

TEST_CASE("dense: a free box truss has exactly six rigid-body modes", "[dense_eigen]") {
  const auto [K, M] = free_box_truss();
  const EigenResult r = solve_modes_dense(K, M);
  REQUIRE(r.ok());
  REQUIRE(r.size() == 24);
  const double top = r.eigenvalues(23);
  for (int i = 0; i < 6; ++i) CHECK(std::abs(r.eigenvalues(i)) < 1e-10 * top);
  CHECK(r.eigenvalues(6) > 1e-3 * top);
  CHECK(r.orthogonality < 1e-12);
}

TEST_CASE("dense: a mechanism (no stiffness, no mass) is reported", "[dense_eigen]") {
  Triplets t;
  add_spring(t, 0, -1, 100.0);
  const SpMat K = from_triplets(2, t);  // DOF 1 has neither stiffness nor mass
  const SpMat M = diagonal(Eigen::Vector2d(1.0, 0.0));
  const EigenResult r = solve_modes_dense(K, M);
  CHECK(r.status == EigenResult::Status::NotPositiveDefinite);
  CHECK_THAT(r.message, Catch::Contains("mechanism"));
}
