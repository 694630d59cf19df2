#include "estimator/sensitivity.hpp"

#include <Eigen/SparseLU>
#include <stdexcept>

namespace ssid::estimator {

double eigenvalue_derivative(const SparseMatrix& dK, const SparseMatrix& dM, double lambda,
                             const Eigen::Ref<const Eigen::VectorXd>& phi) {
  return phi.dot(dK * phi) - lambda * phi.dot(dM * phi);
}

Eigen::MatrixXd nelson_derivatives(const SparseMatrix& K, const SparseMatrix& M, double lambda,
                                   const Eigen::Ref<const Eigen::VectorXd>& phi,
                                   const std::vector<SparseMatrix>& dK, const std::vector<SparseMatrix>& dM) {
  const int n = static_cast<int>(K.rows());
  int k = 0;
  phi.cwiseAbs().maxCoeff(&k);
  // A = K − λM with row and column k replaced by the identity's.
  SparseMatrix A = K - lambda * M;
  for (int c = 0; c < A.outerSize(); ++c)
    for (SparseMatrix::InnerIterator it(A, c); it; ++it)
      if (it.row() == k || it.col() == k) it.valueRef() = (it.row() == it.col()) ? 1.0 : 0.0;
  if (A.coeff(k, k) != 1.0) A.coeffRef(k, k) = 1.0;
  A.prune(0.0);
  A.makeCompressed();
  Eigen::SparseLU<SparseMatrix> lu;
  lu.analyzePattern(A);
  lu.factorize(A);
  if (lu.info() != Eigen::Success)
    throw std::runtime_error("Nelson's method: K - lambda M is singular with the pinned DOF (repeated eigenvalue?)");
  const Eigen::VectorXd Mphi = M * phi;
  Eigen::MatrixXd out(n, static_cast<int>(dK.size()));
  for (std::size_t p = 0; p < dK.size(); ++p) {
    const double dl = eigenvalue_derivative(dK[p], dM[p], lambda, phi);
    Eigen::VectorXd rhs = -(dK[p] * phi - lambda * (dM[p] * phi) - dl * Mphi);
    rhs(k) = 0.0;
    Eigen::VectorXd v = lu.solve(rhs);
    if (lu.info() != Eigen::Success) throw std::runtime_error("Nelson's method: solve failed");
    const double c = -Mphi.dot(v) - 0.5 * phi.dot(dM[p] * phi);
    out.col(static_cast<int>(p)) = v + c * phi;
  }
  return out;
}

Eigen::VectorXd modal_sum_derivative(const Eigen::Ref<const Eigen::MatrixXd>& Phi,
                                     const Eigen::Ref<const Eigen::VectorXd>& lambdas, int i,
                                     const SparseMatrix& dK, const SparseMatrix& dM) {
  const Eigen::VectorXd phi = Phi.col(i);
  const Eigen::VectorXd f = dK * phi - lambdas(i) * (dM * phi);
  Eigen::VectorXd d = -0.5 * phi.dot(dM * phi) * phi;
  for (int j = 0; j < Phi.cols(); ++j) {
    if (j == i) continue;
    const double gap = lambdas(i) - lambdas(j);
    if (gap == 0.0) continue;  // repeated eigenvalue: the term is undefined; skip
    d += Phi.col(j) * (Phi.col(j).dot(f) / gap);
  }
  return d;
}

}  // namespace ssid::estimator
