#pragma once
/// \file bayes.hpp
/// The Bayesian estimator of the seed report (STARS-ID paper Eqs. (6)-(8);
/// reconciliation paper Appendix A): minimise
///   J(r) = (z − u(r))ᵀ S_ee⁻¹ (z − u(r)) + (r₀ − r)ᵀ S_rr⁻¹ (r₀ − r)
/// by the iteration (Eq. 7)
///   r_{i+1} = r_i + [S_rr⁻¹ + Tᵀ S_ee⁻¹ T]⁻¹ [S_rr⁻¹ (r₀ − r_i) + Tᵀ S_ee⁻¹ (z − u(r_i))]
/// with T = ∂u/∂r at r_i; the posterior covariance is (Eq. 8)
///   S_rr* = [S_rr⁻¹ + Tᵀ S_ee⁻¹ T]⁻¹.
/// Measurement covariance S_ee is taken diagonal (independent measurement errors).
#include <Eigen/Core>
#include <vector>

namespace ssid::estimator {

struct BayesStep {
  Eigen::VectorXd r_next;        ///< updated parameters, bounds applied
  Eigen::MatrixXd posterior_cov; ///< Eq. (8) at r_i
  double objective = 0;          ///< J(r_i)
  double misfit = 0;             ///< (z − u)ᵀ S_ee⁻¹ (z − u) at r_i
  bool clipped = false;          ///< a bound was active
};

/// One step of Eq. (7). `sigma_e` holds the measurement standard deviations
/// (diagonal S_ee). `lower`/`upper` bound r (may be ±inf); a step that leaves
/// the box is clipped to it. `damping` μ ≥ 0 (Levenberg–Marquardt): the step
/// solves (H + μ diag H) Δ = g with H = S_rr⁻¹ + Tᵀ S_ee⁻¹ T — shorter and
/// turned towards the gradient as μ grows; μ = 0 is Eq. (7). The posterior
/// covariance is H⁻¹ whatever μ.
BayesStep bayes_step(const Eigen::Ref<const Eigen::VectorXd>& r_i, const Eigen::Ref<const Eigen::VectorXd>& r0,
                     const Eigen::Ref<const Eigen::MatrixXd>& prior_cov, const Eigen::Ref<const Eigen::VectorXd>& z,
                     const Eigen::Ref<const Eigen::VectorXd>& u, const Eigen::Ref<const Eigen::MatrixXd>& T,
                     const Eigen::Ref<const Eigen::VectorXd>& sigma_e, const Eigen::Ref<const Eigen::VectorXd>& lower,
                     const Eigen::Ref<const Eigen::VectorXd>& upper, double damping = 0.0);

/// Laplace approximation of the log marginal likelihood (evidence) at the
/// posterior mode r*, for Gaussian prior N(r₀, S_rr) and measurement noise
/// N(0, S_ee):
///   log p(z) ≈ −½ J(r*) − ½ log det S_ee − (m/2) log 2π + ½ log det S_rr* − ½ log det S_rr
/// (the last two terms are the Occam factor: each added parameter pays through
/// the ratio of posterior to prior volume).
double laplace_log_evidence(double objective_at_mode, const Eigen::Ref<const Eigen::VectorXd>& sigma_e,
                            const Eigen::Ref<const Eigen::MatrixXd>& prior_cov,
                            const Eigen::Ref<const Eigen::MatrixXd>& posterior_cov);

/// Identifiability of the weighted sensitivity W = S_ee^{-1/2} T S_rr^{1/2}:
/// singular values, rank at relative tolerance `tol`, condition number, and per
/// parameter the ratio posterior std / prior std (≈ 1: the data do not inform it).
struct Identifiability {
  Eigen::VectorXd singular_values;
  int rank = 0;
  double condition = 0;
  Eigen::VectorXd std_ratio;
  Eigen::MatrixXd correlation;  ///< posterior correlation matrix
};
Identifiability identifiability(const Eigen::Ref<const Eigen::MatrixXd>& T, const Eigen::Ref<const Eigen::VectorXd>& sigma_e,
                                const Eigen::Ref<const Eigen::MatrixXd>& prior_cov,
                                const Eigen::Ref<const Eigen::MatrixXd>& posterior_cov, double tol = 1e-8);

}  // namespace ssid::estimator
