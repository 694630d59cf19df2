// NelsonSolver (one analysis of K − λM for all modes, LDLᵀ with a residual
// check) against the one-shot LU form and central finite differences.
#include <Eigen/Dense>
#include <catch2/catch.hpp>
#include <random>

#include "estimator/updating/sensitivity.hpp"

using namespace ssid::estimator;

namespace {

/// A grounded spring chain with cross springs (a banded, indefinite K − λM for
/// λ inside the spectrum); K = Σ r_j K_j, M = M0 + r_2 M_2.
struct Chain {
  int n = 60;
  std::vector<SparseMatrix> Kj, Mj;
  SparseMatrix M0;
  Chain() {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(0.5, 1.5);
    std::vector<Eigen::Triplet<double>> a, b, m0, m2;
    auto spring = [&](std::vector<Eigen::Triplet<double>>& t, int i, int j, double k) {
      t.emplace_back(i, i, k);
      if (j >= 0) {
        t.emplace_back(j, j, k);
        t.emplace_back(i, j, -k);
        t.emplace_back(j, i, -k);
      }
    };
    for (int i = 0; i < n; ++i) {
      spring(i < n / 2 ? a : b, i, i - 1, 1000 * u(rng));
      if (i >= 2) spring(i % 3 ? a : b, i, i - 2, 300 * u(rng));
      (i % 2 ? m2 : m0).emplace_back(i, i, u(rng));
    }
    auto make = [&](const std::vector<Eigen::Triplet<double>>& t) {
      SparseMatrix s(n, n);
      s.setFromTriplets(t.begin(), t.end());
      return s;
    };
    Kj = {make(a), make(b), SparseMatrix(n, n)};
    M0 = make(m0);
    Mj = {SparseMatrix(n, n), SparseMatrix(n, n), make(m2)};
  }
  std::pair<SparseMatrix, SparseMatrix> at(const Eigen::Vector3d& r) const {
    SparseMatrix K = r(0) * Kj[0] + r(1) * Kj[1];
    SparseMatrix M = M0 + r(2) * Mj[2];
    return {K, M};
  }
};

std::pair<Eigen::VectorXd, Eigen::MatrixXd> modes(const SparseMatrix& K, const SparseMatrix& M) {
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es{Eigen::MatrixXd(K), Eigen::MatrixXd(M)};
  return {es.eigenvalues(), es.eigenvectors()};
}

}  // namespace

TEST_CASE("NelsonSolver: the same eigenvector derivatives as the LU form and as finite differences", "[estimator][sensitivity]") {
  const Chain c;
  const Eigen::Vector3d r(1.0, 1.2, 0.9);
  const auto [K, M] = c.at(r);
  const auto [lambda, Phi] = modes(K, M);
  NelsonSolver solver(K, M);
  for (int i : {0, 1, 5, 17, 30, 59}) {
    INFO("mode " << i);
    const Eigen::VectorXd phi = Phi.col(i);
    const Eigen::MatrixXd fast = solver.derivatives(lambda(i), phi, c.Kj, c.Mj);
    const Eigen::MatrixXd lu = nelson_derivatives(K, M, lambda(i), phi, c.Kj, c.Mj);
    CHECK((fast - lu).norm() <= 1e-9 * lu.norm());
    // Central differences of the mass-normalised mode (sign fixed to φ).
    for (int j = 0; j < 3; ++j) {
      const double h = 1e-6;
      Eigen::Vector3d rp = r, rm = r;
      rp(j) += h;
      rm(j) -= h;
      auto [Kp, Mp] = c.at(rp);
      auto [Km, Mm] = c.at(rm);
      Eigen::VectorXd pp = modes(Kp, Mp).second.col(i), pm = modes(Km, Mm).second.col(i);
      if (pp.dot(phi) < 0) pp = -pp;
      if (pm.dot(phi) < 0) pm = -pm;
      const Eigen::VectorXd fd = (pp - pm) / (2 * h);
      CHECK((fast.col(j) - fd).norm() <= 1e-5 * std::max(1.0, fd.norm()));
    }
  }
  CHECK(solver.lu_fallbacks() == 0);
}
