#include "estimator/eigen/zero_energy_modes.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <cmath>
#include <vector>

namespace ssid::estimator {

ZeroEnergyModes zero_energy_modes(const Eigen::SparseMatrix<double>& K, const Eigen::SparseMatrix<double>& M,
                                  double sigma, const Eigen::MatrixXd& B, double tol, int max_modes) {
  ZeroEnergyModes out;
  out.z.resize(B.rows(), 0);
  if (B.cols() == 0 || max_modes < 1 || B.rows() != K.rows()) return out;
  const Eigen::MatrixXd KB = K * B, MB = M * B;
  const Eigen::MatrixXd Gk = B.transpose() * KB, Gm = B.transpose() * MB;
  const Eigen::MatrixXd Gms = 0.5 * (Gm + Gm.transpose());
  if (Eigen::LLT<Eigen::MatrixXd>(Gms).info() != Eigen::Success) return out;  // a direction of B without mass
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(0.5 * (Gk + Gk.transpose()), Gms);
  if (es.info() != Eigen::Success) return out;
  std::vector<Eigen::Index> keep;
  for (Eigen::Index j = 0; j < es.eigenvalues().size() && static_cast<int>(keep.size()) < max_modes; ++j) {
    const double lam = es.eigenvalues()(j);
    const Eigen::VectorXd kz = KB * es.eigenvectors().col(j), mz = MB * es.eigenvectors().col(j);
    const double shifted = (kz - sigma * mz).norm();
    // An eigenvector of the model, and of zero energy: an exact eigenvector of
    // positive λ (ground springs proportional to the mass) need not be among the
    // lowest modes, so it stays in the iteration.
    if (lam - sigma > 0.0 && shifted > 0.0 && (kz - lam * mz).norm() <= tol * shifted &&
        std::abs(lam) <= tol * (lam - sigma))
      keep.push_back(j);
  }
  const auto r = static_cast<Eigen::Index>(keep.size());
  out.lambda.resize(r);
  out.z.resize(B.rows(), r);
  for (Eigen::Index k = 0; k < r; ++k) {
    out.lambda(k) = es.eigenvalues()(keep[static_cast<size_t>(k)]);
    out.z.col(k) = B * es.eigenvectors().col(keep[static_cast<size_t>(k)]);  // cᵀ Bᵀ M B c = 1
  }
  return out;
}

}  // namespace ssid::estimator
