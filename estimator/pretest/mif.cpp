#include "estimator/pretest/mif.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <complex>

namespace ssid::estimator::pretest {

Eigen::MatrixXcd modal_frf(const Eigen::Ref<const Eigen::MatrixXd>& Phi_o, const Eigen::Ref<const Eigen::MatrixXd>& Gamma,
                           const Eigen::Ref<const Eigen::VectorXd>& eigenvalues, double zeta, double omega) {
  const Eigen::Index r = eigenvalues.size();
  Eigen::VectorXcd h(r);
  for (Eigen::Index j = 0; j < r; ++j) {
    const double lam = std::max(eigenvalues(j), 0.0);
    h(j) = 1.0 / std::complex<double>(lam - omega * omega, 2.0 * zeta * std::sqrt(lam) * omega);
  }
  return Phi_o.cast<std::complex<double>>() * h.asDiagonal() * Gamma.cast<std::complex<double>>();
}

Eigen::VectorXd multivariate_mif(const Eigen::Ref<const Eigen::MatrixXcd>& H) {
  const Eigen::Index k = H.cols();
  const Eigen::MatrixXd R = H.real(), I = H.imag();
  const Eigen::MatrixXd A = R.transpose() * R;
  const Eigen::MatrixXd B = A + I.transpose() * I;
  if (k == 1) {
    Eigen::VectorXd mu(1);
    mu(0) = B(0, 0) > 0 ? A(0, 0) / B(0, 0) : 1.0;
    return mu;
  }
  if (B.norm() == 0) return Eigen::VectorXd::Ones(k);
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(A, B);
  if (es.info() != Eigen::Success) {
    // B singular (inputs that excite the outputs alike): fall back to the
    // pseudo-inverse form, μ = eig(B⁺A) restricted to the range of B.
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eb(B);
    const Eigen::VectorXd d = eb.eigenvalues();
    const double tol = 1e-12 * d.cwiseAbs().maxCoeff();
    Eigen::VectorXd mu = Eigen::VectorXd::Ones(k);
    Eigen::Index used = 0;
    Eigen::MatrixXd Q(k, k);
    for (Eigen::Index i = 0; i < k; ++i)
      if (d(i) > tol) Q.col(used++) = eb.eigenvectors().col(i) / std::sqrt(d(i));
    Q.conservativeResize(k, used);
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> ec(Q.transpose() * A * Q);
    mu.head(used) = ec.eigenvalues();
    std::sort(mu.data(), mu.data() + k);
    return mu;
  }
  return es.eigenvalues();
}

}  // namespace ssid::estimator::pretest
