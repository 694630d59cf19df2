#include <catch2/catch.hpp>

#include <Eigen/Dense>

#include "estimator/updating/sensitivity.hpp"

using namespace ssid::estimator;

namespace {
/// A fixed-free spring-mass chain whose springs and masses depend on r:
/// k_i = k0_i (1 + r0 * s_i), m_i = m0_i (1 + r1 * t_i) — distinct patterns so both
/// ∂K and ∂M are non-trivial and the eigenvalues are simple.
struct Chain {
  int n = 7;
  Eigen::VectorXd k0, s, m0, t;
  Chain() : k0(n), s(n), m0(n), t(n) {
    for (int i = 0; i < n; ++i) {
      k0(i) = 1000.0 * (1.0 + 0.3 * i);
      s(i) = (i % 3 == 0) ? 1.0 : 0.2 * i;
      m0(i) = 1.0 + 0.15 * i * i;
      t(i) = (i % 2 == 0) ? 1.0 : 0.0;
    }
  }
  Eigen::MatrixXd K(const Eigen::Vector2d& r, bool derivative = false) const {
    Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n, n);
    for (int i = 0; i < n; ++i) {
      double k = derivative ? k0(i) * s(i) : k0(i) * (1.0 + r(0) * s(i));
      K(i, i) += k;
      if (i > 0) {
        K(i - 1, i - 1) += k;
        K(i - 1, i) -= k;
        K(i, i - 1) -= k;
      }
    }
    return K;
  }
  Eigen::MatrixXd M(const Eigen::Vector2d& r, bool derivative = false) const {
    Eigen::VectorXd m = derivative ? Eigen::VectorXd(m0.cwiseProduct(t)) : Eigen::VectorXd(m0.array() * (1.0 + r(1) * t.array()));
    return m.asDiagonal();
  }
};

void solve(const Eigen::MatrixXd& K, const Eigen::MatrixXd& M, Eigen::VectorXd& lam, Eigen::MatrixXd& Phi) {
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(K, M);
  lam = es.eigenvalues();
  Phi = es.eigenvectors();  // mass-normalised
}
}  // namespace

TEST_CASE("eigenvalue and Nelson eigenvector derivatives match central finite differences", "[sensitivity]") {
  Chain c;
  const Eigen::Vector2d r(0.1, 0.05);
  Eigen::VectorXd lam;
  Eigen::MatrixXd Phi;
  solve(c.K(r), c.M(r), lam, Phi);
  std::vector<SparseMatrix> dK = {c.K(r, true).sparseView(), SparseMatrix(c.n, c.n)};
  std::vector<SparseMatrix> dM = {SparseMatrix(c.n, c.n), c.M(r, true).sparseView()};
  const SparseMatrix Ks = c.K(r).sparseView(), Ms = c.M(r).sparseView();
  const double h = 1e-6;
  for (int mode = 0; mode < c.n; ++mode) {
    Eigen::MatrixXd dphi = nelson_derivatives(Ks, Ms, lam(mode), Phi.col(mode), dK, dM);
    for (int p = 0; p < 2; ++p) {
      Eigen::Vector2d rp = r, rm = r;
      rp(p) += h;
      rm(p) -= h;
      Eigen::VectorXd lp, lm;
      Eigen::MatrixXd Pp, Pm;
      solve(c.K(rp), c.M(rp), lp, Pp);
      solve(c.K(rm), c.M(rm), lm, Pm);
      // Align signs with the nominal mode.
      if (Pp.col(mode).dot(c.M(r) * Phi.col(mode)) < 0) Pp.col(mode) *= -1;
      if (Pm.col(mode).dot(c.M(r) * Phi.col(mode)) < 0) Pm.col(mode) *= -1;
      const double dl_fd = (lp(mode) - lm(mode)) / (2 * h);
      const double dl = eigenvalue_derivative(dK[p], dM[p], lam(mode), Phi.col(mode));
      INFO("mode " << mode << " parameter " << p);
      CHECK(dl == Approx(dl_fd).epsilon(1e-6).margin(1e-6 * std::abs(lam(mode))));
      const Eigen::VectorXd dphi_fd = (Pp.col(mode) - Pm.col(mode)) / (2 * h);
      CHECK((dphi.col(p) - dphi_fd).norm() <= 1e-5 * std::max(1.0, dphi_fd.norm()));
      // Modal summation over the complete basis is exact.
      Eigen::VectorXd ms = modal_sum_derivative(Phi, lam, mode, dK[p], dM[p]);
      CHECK((ms - dphi.col(p)).norm() <= 1e-9 * std::max(1.0, dphi.col(p).norm()));
    }
  }
}

TEST_CASE("modal summation with a truncated basis is only an approximation", "[sensitivity]") {
  Chain c;
  const Eigen::Vector2d r(0.0, 0.0);
  Eigen::VectorXd lam;
  Eigen::MatrixXd Phi;
  solve(c.K(r), c.M(r), lam, Phi);
  SparseMatrix dK = c.K(r, true).sparseView(), dM(c.n, c.n);
  Eigen::VectorXd exact = nelson_derivatives(c.K(r).sparseView(), c.M(r).sparseView(), lam(0), Phi.col(0), {dK}, {dM}).col(0);
  Eigen::VectorXd trunc = modal_sum_derivative(Phi.leftCols(3), lam.head(3), 0, dK, dM);
  const double err = (trunc - exact).norm() / exact.norm();
  CHECK(err > 1e-6);  // the truncation error is real…
  // …and shrinks as the basis grows toward the complete one (exact, tested above).
  Eigen::VectorXd more = modal_sum_derivative(Phi.leftCols(c.n - 1), lam.head(c.n - 1), 0, dK, dM);
  CHECK((more - exact).norm() / exact.norm() < err);
}
