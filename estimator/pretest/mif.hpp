#pragma once
/// \file mif.hpp
/// Pretest planning, step 4a: the mode indicator function of candidate
/// excitations (issue 23 item 4; pretest paper §2.4; Williams, Crowley and Vold
/// 1985 for the multivariate form).
#include <Eigen/Core>

namespace ssid::estimator::pretest {

/// Receptance FRF of a modal model at ω (rad/s), outputs x inputs:
///   H(ω) = Φ_o diag(1 / (λ_r − ω² + 2 i ζ ω_r ω)) Γ,  ω_r = sqrt(λ_r),
/// with Φ_o (o x r) the mass-normalised modes at the outputs, Γ (r x k) the
/// modal participation of each input (Γ = Φ_inᵀ b for a force pattern b),
/// λ the eigenvalues ((rad/s)²; rigid-body modes, λ = 0, give −1/ω²) and ζ the
/// modal damping ratio of every mode.
Eigen::MatrixXcd modal_frf(const Eigen::Ref<const Eigen::MatrixXd>& Phi_o, const Eigen::Ref<const Eigen::MatrixXd>& Gamma,
                           const Eigen::Ref<const Eigen::VectorXd>& eigenvalues, double zeta, double omega);

/// Multivariate mode indicator function at one frequency: the eigenvalues μ
/// (ascending, k of them for k inputs) of
///   Re(H)ᵀ Re(H) f = μ (Re(H)ᵀ Re(H) + Im(H)ᵀ Im(H)) f,
/// 0 ≤ μ ≤ 1. Away from a mode the response is nearly in phase with the force
/// and μ ≈ 1; at a real normal mode that the inputs excite it is in quadrature
/// and the smallest μ drops towards 0. For one input this is
///   MIF = Σ_i (Re H_i)² / Σ_i |H_i|²,
/// which for a single-DOF system H = 1/(k − mω² + i c ω) is (k − mω²)² / ((k − mω²)² + (cω)²).
/// Returns ones when H is zero (nothing excited: nothing indicated).
Eigen::VectorXd multivariate_mif(const Eigen::Ref<const Eigen::MatrixXcd>& H);

}  // namespace ssid::estimator::pretest
