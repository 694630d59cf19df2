#pragma once
/// \file plscf.hpp
/// The polyreference least-squares complex frequency-domain estimator (pLSCF, "PolyMAX";
/// Peeters, Van der Auweraer, Guillaume and Leuridan 2004, "The PolyMAX frequency-domain
/// method: a new standard for modal parameter estimation", Shock and Vibration 11) for the
/// poles and participation factors of FRFs with several references, over a range of model
/// orders for the stabilisation diagram (stabilisation.hpp), and the least-squares
/// frequency-domain estimator (LSFD) of the mode shapes with lower and upper residuals,
/// given the chosen poles. Equations: docs/identification.md, "pLSCF and LSFD".
///
/// Input: FRF lines H(f_k) (no × ni each: responses × references, e.g. m/N) at frequencies
/// f_k (Hz, any spacing). The modal model the two steps estimate is
///   H(ω) = Σ_r ψ_r l_rᵀ/(iω − λ_r) + ψ_r* l_rᴴ/(iω − λ_r*)  (− LR/ω² + UR: LSFD),
/// λ_r the continuous poles (rad/s), l_r the participation factors (ni), ψ_r the shapes (no).
#include <Eigen/Core>
#include <limits>
#include <vector>

#include "estimator/identification/era.hpp"
#include "estimator/identification/stabilisation.hpp"
#include "estimator/reporting/progress.hpp"

namespace ssid::estimator::identification {

/// The band both steps fit: the lines with hz_min ≤ f ≤ hz_max and f > 0 (the 0 Hz line
/// carries no dynamics and the lower residual −LR/ω² is infinite there).
struct PlscfOptions {
  double hz_min = 0;                                        ///< Hz
  double hz_max = std::numeric_limits<double>::infinity();  ///< Hz
};

/// pLSCF at each polynomial order p of `orders` (increasing, ≥ 1): the right matrix-fraction
/// model H(ω) = B(ω) A(ω)⁻¹ with A = Σ_{j≤p} z^j α_j (ni × ni, real, α_p = I),
/// B_o = Σ_j z^j β_oj (1 × ni, real) per response o, z = e^{iωΔt}, Δt = 1/(2 f_max of the band);
/// each response weighted by the inverse RMS of its FRFs over the band. The poles of order p
/// (p·ni of them) are the eigenvalues z of A's companion matrix, λ = ln(z)/Δt; one of each
/// conjugate pair is returned (Im λ ≥ 0, real ones included, as era()), ordered by frequency,
/// each with
/// - participation: the left null vector l of A(z) (lᵀA(z) = 0), unit norm, its largest
///   component real and positive;
/// - shape: ψ_o ∝ B_o(z) v (v the right null vector of A(z)), the residue's column at this
///   order (its scale is arbitrary; LSFD gives the shapes of the chosen modes);
/// - mpc, mpd of that shape; msv, emac and cmi are ERA's and stay 0.
/// One reduction of the normal equations serves every order (docs: Cholesky of the shared
/// block). `progress` gets one report per order. Throws formats::InputError for FRF lines of
/// unequal size or not finite, frequencies not matching the lines, an empty band, orders not
/// increasing or < 1, or a band with too few lines for the largest order (needs > p + 1).
std::vector<OrderPoles> plscf_orders(const Eigen::Ref<const Eigen::VectorXd>& frequency_hz,
                                     const std::vector<Eigen::MatrixXcd>& frf, const PlscfOptions& options,
                                     const std::vector<Eigen::Index>& orders, const Progress& progress = {});

/// The chosen modes' poles for LSFD: for each mode of `chosen` (stabilise() of `orders`), its
/// member pole of the highest order (the most complete model; the poles of the lower orders
/// of a cluster are biased by the modes those orders cannot yet represent, so the cluster's
/// mean is not the better estimate on clean data). Throws formats::InputError when a mode
/// refers to a pole that `orders` does not have (`chosen` not made from them).
std::vector<IdentifiedPole> mode_poles(const StabilisationResult& chosen, const std::vector<OrderPoles>& orders);

/// LSFD's result: the poles with their least-squares shapes, and the residuals.
struct LsfdResult {
  /// The input poles; shape = ψ_r (no) such that ψ_r l_rᵀ is the residue matrix of λ_r
  /// (unit: the FRF's times rad/s), with mpc and mpd of it.
  std::vector<IdentifiedPole> modes;
  Eigen::MatrixXd lower_residual;  ///< LR (no × ni): the term −LR/ω², unit of H times (rad/s)²
  Eigen::MatrixXd upper_residual;  ///< UR (no × ni): the constant term, unit of H
  /// ‖H − Ĥ‖_F/‖H‖_F over the band: how much of the data the modal model leaves unexplained.
  double fit_error = 0;
};

/// LSFD: with the poles λ_r (Im λ_r > 0) and participation factors l_r of `poles` fixed, the
/// shapes ψ_r and the residuals LR, UR of each response by linear least squares over the band
/// (real and imaginary parts of every line and reference; one column-scaled QR for all
/// responses). Throws formats::InputError for no pole, a pole with Im λ ≤ 0 or a participation
/// factor not of size ni, or fewer equations than unknowns (2·lines·ni < 2·modes + 2·ni), and
/// the errors of plscf_orders for the lines.
LsfdResult lsfd(const Eigen::Ref<const Eigen::VectorXd>& frequency_hz, const std::vector<Eigen::MatrixXcd>& frf,
                const std::vector<IdentifiedPole>& poles, const PlscfOptions& options);

/// The FRFs of LSFD's modal model at the frequencies f (Hz, each > 0), one no × ni matrix
/// per line:
///   Ĥ(ω) = Σ_r [ψ_r l_rᵀ/(iω − λ_r) + ψ_r* l_rᴴ/(iω − λ_r*)] − LR/ω² + UR,  ω = 2πf,
/// the model whose misfit over the band is `fit.fit_error`: what the identified modes
/// (and the residuals standing for the modes outside the band) say the FRFs are. Throws
/// formats::InputError for a frequency ≤ 0 (the lower residual is infinite at 0 Hz).
std::vector<Eigen::MatrixXcd> lsfd_synthesis(const Eigen::Ref<const Eigen::VectorXd>& frequency_hz, const LsfdResult& fit);

}  // namespace ssid::estimator::identification
