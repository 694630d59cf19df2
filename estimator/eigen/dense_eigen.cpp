#include "estimator/eigen/dense_eigen.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "formats/parse_error.hpp"

namespace ssid::estimator {

EigenResult solve_modes_dense(const Eigen::SparseMatrix<double>& K, const Eigen::SparseMatrix<double>& M,
                              const EigenOptions& o) {
  if (K.rows() != K.cols() || M.rows() != M.cols() || K.rows() != M.rows())
    throw std::invalid_argument("solve_modes_dense: K is " + std::to_string(K.rows()) + " x " +
                                std::to_string(K.cols()) + " and M is " + std::to_string(M.rows()) + " x " +
                                std::to_string(M.cols()) + ", expected two square matrices of one size");
  const bool has_high = !std::isnan(o.f_high);
  const bool has_low = !std::isnan(o.f_low) && o.f_low > 0.0;
  if (has_high && has_low && o.f_low > o.f_high)
    throw formats::InputError("solve_modes_dense: lower frequency " + std::to_string(o.f_low) + " Hz above upper " +
                                std::to_string(o.f_high) + " Hz");
  EigenResult res;
  res.method = "dense";
  const Eigen::Index n = K.rows();
  const Eigen::MatrixXd Kd(K), Md(M);

  double sigma = o.shift;
  if (std::isnan(sigma)) {
    double sk = 0.0, sm = 0.0;
    for (Eigen::Index i = 0; i < n; ++i)
      if (Md(i, i) > 0.0) sk += std::abs(Kd(i, i)), sm += Md(i, i);
    // A direct solve needs no shift near the lowest eigenvalue for convergence; a
    // shift of the order of the eigenvalue scale keeps K − σM well conditioned
    // (a rigid-body cluster's M-orthogonality follows K − σM's).
    sigma = (sm > 0.0 && sk > 0.0) ? -1e-2 * sk / sm : -1.0;
  }
  res.shift = sigma;
  const Eigen::MatrixXd A = Kd - sigma * Md;
  Eigen::LLT<Eigen::MatrixXd> llt(A);
  if (llt.info() != Eigen::Success) {
    res.status = EigenResult::Status::NotPositiveDefinite;
    res.message = "K - sigma*M (sigma = " + std::to_string(sigma) +
                  ") is not positive definite: a mechanism (a DOF with neither stiffness nor mass, or an "
                  "unrestrained joint) or an indefinite K";
    return res;
  }
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(Md, A, Eigen::ComputeEigenvectors | Eigen::Ax_lBx);
  if (es.info() != Eigen::Success) {
    res.status = EigenResult::Status::NotConverged;
    res.message = "dense symmetric eigen-solver did not converge";
    return res;
  }
  const Eigen::VectorXd mu = es.eigenvalues();
  const double mu_max = n ? mu.cwiseAbs().maxCoeff() : 0.0;
  struct Root {
    double lambda;
    Eigen::Index col;
  };
  std::vector<Root> roots;
  for (Eigen::Index i = 0; i < n; ++i)
    if (mu(i) > 1e-12 * mu_max) roots.push_back({sigma + 1.0 / mu(i), i});
  std::sort(roots.begin(), roots.end(), [](const Root& a, const Root& b) { return a.lambda < b.lambda; });
  const double lam_lo = has_low ? hz_to_eigenvalue(o.f_low) : -std::numeric_limits<double>::infinity();
  const double lam_hi = has_high ? hz_to_eigenvalue(o.f_high) : std::numeric_limits<double>::infinity();
  std::vector<Root> keep;
  for (const auto& r : roots) {
    // Rigid-body roots (λ ≈ 0, possibly −ε) belong to a band that starts at 0.
    if (has_low && r.lambda < lam_lo) continue;
    if (r.lambda > lam_hi) continue;
    keep.push_back(r);
    if (o.nd > 0 && static_cast<int>(keep.size()) == o.nd) break;
  }
  const auto m = static_cast<Eigen::Index>(keep.size());
  res.eigenvalues.resize(m);
  res.modes.resize(n, m);
  for (Eigen::Index j = 0; j < m; ++j) {
    res.eigenvalues(j) = keep[static_cast<std::size_t>(j)].lambda;
    Eigen::VectorXd phi = es.eigenvectors().col(keep[static_cast<std::size_t>(j)].col);
    if (o.norm == ModeNormalization::Mass) {
      const double gm = phi.dot(Md * phi);
      phi /= std::sqrt(gm);
    } else {
      Eigen::Index imax = 0;
      phi.cwiseAbs().maxCoeff(&imax);
      phi /= phi(imax);
    }
    res.modes.col(j) = phi;
  }
  res.nev = static_cast<int>(m);
  compute_checks(K, M, res);
  if (o.nd > 0 && m < o.nd && !has_high)
    res.warnings.push_back(std::to_string(o.nd) + " modes asked; the model has " + std::to_string(roots.size()) +
                           " (" + std::to_string(n) + " analysis-set DOFs, " +
                           std::to_string(n - static_cast<Eigen::Index>(roots.size())) + " of them massless directions)");
  return res;
}

}  // namespace ssid::estimator
