#include "estimator/updating/bayes.hpp"

#include <Eigen/Dense>
#include <cmath>

namespace ssid::estimator {

BayesStep bayes_step(const Eigen::Ref<const Eigen::VectorXd>& r_i, const Eigen::Ref<const Eigen::VectorXd>& r0,
                     const Eigen::Ref<const Eigen::MatrixXd>& prior_cov, const Eigen::Ref<const Eigen::VectorXd>& z,
                     const Eigen::Ref<const Eigen::VectorXd>& u, const Eigen::Ref<const Eigen::MatrixXd>& T,
                     const Eigen::Ref<const Eigen::VectorXd>& sigma_e, const Eigen::Ref<const Eigen::VectorXd>& lower,
                     const Eigen::Ref<const Eigen::VectorXd>& upper, double damping) {
  const Eigen::VectorXd w = sigma_e.array().square().inverse().matrix();  // S_ee^-1 diagonal
  Eigen::LLT<Eigen::MatrixXd> prior(prior_cov);
  const Eigen::MatrixXd Srr_inv = prior.solve(Eigen::MatrixXd::Identity(prior_cov.rows(), prior_cov.cols()));
  const Eigen::MatrixXd H = Srr_inv + T.transpose() * w.asDiagonal() * T;
  const Eigen::VectorXd e = z - u;
  const Eigen::VectorXd g = Srr_inv * (r0 - r_i) + T.transpose() * (w.asDiagonal() * e);
  Eigen::LLT<Eigen::MatrixXd> hl(H);
  BayesStep s;
  if (damping > 0) {
    Eigen::MatrixXd Hd = H;
    Hd.diagonal() *= 1.0 + damping;
    s.r_next = r_i + Eigen::LLT<Eigen::MatrixXd>(Hd).solve(g);
  } else {
    s.r_next = r_i + hl.solve(g);
  }
  s.posterior_cov = hl.solve(Eigen::MatrixXd::Identity(H.rows(), H.cols()));
  s.misfit = e.dot(w.asDiagonal() * e);
  const Eigen::VectorXd dr = r0 - r_i;
  s.objective = s.misfit + dr.dot(Srr_inv * dr);
  for (int k = 0; k < s.r_next.size(); ++k) {
    if (s.r_next(k) < lower(k)) { s.r_next(k) = lower(k); s.clipped = true; }
    if (s.r_next(k) > upper(k)) { s.r_next(k) = upper(k); s.clipped = true; }
  }
  return s;
}

double laplace_log_evidence(double objective_at_mode, const Eigen::Ref<const Eigen::VectorXd>& sigma_e,
                            const Eigen::Ref<const Eigen::MatrixXd>& prior_cov,
                            const Eigen::Ref<const Eigen::MatrixXd>& posterior_cov) {
  const double m = static_cast<double>(sigma_e.size());
  const double logdet_ee = 2.0 * sigma_e.array().log().sum();
  auto logdet = [](const Eigen::MatrixXd& A) {
    Eigen::LLT<Eigen::MatrixXd> l(A);
    return 2.0 * l.matrixLLT().diagonal().array().log().sum();
  };
  return -0.5 * objective_at_mode - 0.5 * logdet_ee - 0.5 * m * std::log(2.0 * M_PI) +
         0.5 * logdet(posterior_cov) - 0.5 * logdet(prior_cov);
}

Identifiability identifiability(const Eigen::Ref<const Eigen::MatrixXd>& T, const Eigen::Ref<const Eigen::VectorXd>& sigma_e,
                                const Eigen::Ref<const Eigen::MatrixXd>& prior_cov,
                                const Eigen::Ref<const Eigen::MatrixXd>& posterior_cov, double tol) {
  Identifiability id;
  Eigen::LLT<Eigen::MatrixXd> pl(prior_cov);
  const Eigen::MatrixXd W = sigma_e.array().inverse().matrix().asDiagonal() * T * Eigen::MatrixXd(pl.matrixL());
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(W);
  id.singular_values = svd.singularValues();
  const double smax = id.singular_values.size() ? id.singular_values(0) : 0.0;
  for (int i = 0; i < id.singular_values.size(); ++i)
    if (id.singular_values(i) > tol * smax) ++id.rank;
  const double smin = id.singular_values.size() ? id.singular_values(id.singular_values.size() - 1) : 0.0;
  id.condition = smin > 0 ? smax / smin : INFINITY;
  id.std_ratio = (posterior_cov.diagonal().array().sqrt() / prior_cov.diagonal().array().sqrt()).matrix();
  const Eigen::VectorXd s = posterior_cov.diagonal().array().sqrt();
  id.correlation = s.asDiagonal().inverse() * posterior_cov * s.asDiagonal().inverse();
  return id;
}

}  // namespace ssid::estimator
