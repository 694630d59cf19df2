#pragma once
/// \file modal_indicators.hpp
/// Properties of one complex mode shape, used by every identification method:
/// modal phase collinearity (MPC), mean phase deviation (MPD), complex-to-real
/// conversion, the complex MAC, and scaling to unit modal mass from a driving point.
#include <Eigen/Core>
#include <complex>

namespace ssid::estimator::identification {

/// Modal phase collinearity (Pappa et al.): with S = [Re φ, Im φ]ᵀ[Re φ, Im φ] and its
/// eigenvalues λ₁ ≥ λ₂, MPC = ((λ₁ − λ₂)/(λ₁ + λ₂))², computed as |φᵀφ|² / (φᴴφ)².
/// 1 for a real (mono-phase) shape, 0 for a circular one; 0 for the zero vector.
/// (Not centred on the mean of the components: a shape's mean carries meaning here.)
double modal_phase_collinearity(const Eigen::Ref<const Eigen::VectorXcd>& phi);

/// The angle θ₀ (rad) of the best real line through the components of φ in the complex
/// plane, θ₀ = ½ arg(φᵀφ): e^{−iθ₀}φ has the largest Σ (Re)² of all rotations.
double principal_phase(const Eigen::Ref<const Eigen::VectorXcd>& phi);

/// Mean phase deviation, degrees: the magnitude-weighted mean angle between each
/// component and the line at θ₀ (principal_phase),
///   MPD = Σ_j |φ_j| δ_j / Σ_j |φ_j|,  δ_j = min over the line's two directions ∈ [0°, 90°].
/// 0 for a real shape.
double mean_phase_deviation(const Eigen::Ref<const Eigen::VectorXcd>& phi);

/// Complex MAC, |aᴴb|² / ((aᴴa)(bᴴb)); 0 when either is zero.
double complex_mac(const Eigen::Ref<const Eigen::VectorXcd>& a, const Eigen::Ref<const Eigen::VectorXcd>& b);

/// Real normal mode of a complex shape: Re(e^{−iθ₀}φ) (θ₀ = principal_phase), signed so
/// that its largest-magnitude component is positive. Its complexity is 1 − MPC(φ).
Eigen::VectorXd real_mode(const Eigen::Ref<const Eigen::VectorXcd>& phi);

/// A shape rotated by e^{−iθ₀} and signed as real_mode (the complex form of it).
Eigen::VectorXcd rotate_to_real(const Eigen::Ref<const Eigen::VectorXcd>& phi);

/// Scaling to unit modal mass from a driving point. For one mode with continuous pole
/// λ = −ζω + iω_d, the residue column of reference q, r = R(:, q) (H(s) ≈ R/(s − λ) + …),
/// and p the response at the same DOF and direction as reference q (the driving point),
/// a real normal mode φ of unit modal mass (φᵀMφ = 1) satisfies R = φφᵀ/(2iω_d), hence
///   φ_p = √(2iω_d r_p),  φ = 2iω_d r / φ_p   (complex; real for proportional damping).
/// Returns φ at every response (unit: √(unit of r · s⁻¹) … e.g. residues of
/// displacement/force give φ in 1/√kg). The sign is that of real_mode.
Eigen::VectorXcd unit_modal_mass_shape(const Eigen::Ref<const Eigen::VectorXcd>& residue_column,
                                       std::complex<double> pole, Eigen::Index driving_point);

}  // namespace ssid::estimator::identification
