#include "estimator/pretest/tam.hpp"

#include <Eigen/Dense>
#include <cmath>

#include "estimator/pretest/targets.hpp"

namespace ssid::estimator::pretest {

std::string tam_name(TamKind k) {
  switch (k) {
    case TamKind::Guyan: return "guyan";
    case TamKind::Serep: return "serep";
    case TamKind::Irs: return "irs";
  }
  return "?";
}

TamCheck tam_check(TamKind kind, const Eigen::SparseMatrix<double>& K, const Eigen::SparseMatrix<double>& M,
                   const Eigen::Ref<const Eigen::MatrixXd>& Phi, const Eigen::Ref<const Eigen::VectorXd>& hz,
                   const std::vector<Eigen::Index>& sensors, const XorAcceptance& acceptance) {
  TamCheck c;
  c.kind = kind;
  const ReducedModel r = kind == TamKind::Guyan ? guyan_reduce(K, M, sensors)
                         : kind == TamKind::Irs ? irs_reduce(K, M, sensors)
                                                : serep_reduce(K, M, Phi, sensors);
  c.status = r.status;
  c.message = r.message;
  if (r.status != ReductionStatus::Ok) return c;
  const Eigen::MatrixXd Phi_a = take_rows(Phi, sensors);
  // Not normalised: the FE modes are mass-normalised, so the diagonal measures how
  // much of each mode's mass the TAM keeps (a normalised diagonal is 1 by construction).
  c.xor_matrix = cross_orthogonality(Phi_a, r.M, Phi_a, false);
  const Eigen::Index m = Phi.cols();
  const Eigen::MatrixXd A = c.xor_matrix.cwiseAbs();
  c.min_diagonal = m ? A.diagonal().minCoeff() : 0.0;
  c.max_offdiagonal = 0;
  for (Eigen::Index i = 0; i < m; ++i)
    for (Eigen::Index j = 0; j < m; ++j)
      if (i != j) c.max_offdiagonal = std::max(c.max_offdiagonal, A(i, j));
  // The TAM's own frequencies, on the range of M_TAM: a SEREP TAM on more sensors
  // than modes has a singular mass (rank m), whose null space holds no mode.
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> em(r.M);
  const Eigen::VectorXd d = em.eigenvalues();
  const double tol = 1e-10 * d.cwiseAbs().maxCoeff();
  Eigen::MatrixXd Q(r.M.rows(), r.M.rows());
  Eigen::Index used = 0;
  for (Eigen::Index i = 0; i < d.size(); ++i)
    if (d(i) > tol) Q.col(used++) = em.eigenvectors().col(i) / std::sqrt(d(i));
  Q.conservativeResize(Eigen::NoChange, used);
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> ek(Q.transpose() * r.K * Q, Eigen::EigenvaluesOnly);
  std::vector<double> f;
  for (Eigen::Index i = 0; i < ek.eigenvalues().size(); ++i)
    f.push_back(std::sqrt(std::max(ek.eigenvalues()(i), 0.0)) / (2 * M_PI));
  // Each target against the nearest TAM frequency: the TAM also holds the
  // rigid-body modes and those below the band, which pairing by order would miscount.
  c.tam_hz.resize(m);
  for (Eigen::Index j = 0; j < m; ++j) {
    double best = f.empty() ? 0.0 : f[0];
    for (double x : f)
      if (std::abs(x - hz(j)) < std::abs(best - hz(j))) best = x;
    c.tam_hz(j) = best;
    if (hz(j) > 0) c.max_frequency_error_pct = std::max(c.max_frequency_error_pct, 100 * std::abs(best - hz(j)) / hz(j));
  }
  c.accepted = c.min_diagonal > acceptance.min_diagonal && c.max_offdiagonal < acceptance.max_offdiagonal;
  c.accepted_primary = c.accepted && c.max_offdiagonal < acceptance.max_offdiagonal_primary;
  return c;
}

}  // namespace ssid::estimator::pretest
