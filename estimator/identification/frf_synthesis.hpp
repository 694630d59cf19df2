#pragma once
/// \file frf_synthesis.hpp
/// FRFs synthesized from modes by modal superposition (the seed report's Eq. 2, MPI
/// modal test section), and the frequency response assurance criterion that compares
/// two FRFs line by line.
#include <Eigen/Core>
#include <cstddef>
#include <optional>
#include <vector>

namespace ssid::estimator::identification {

/// What the FRF's response is: receptance (displacement per force), mobility
/// (velocity per force) or accelerance (acceleration per force).
enum class FrfQuantity { Displacement, Velocity, Acceleration };

/// "displacement", "velocity" or "acceleration".
const char* quantity_name(FrfQuantity q);
/// The FRF's unit in the units of the model: "length/force", "length/s/force", "length/s²/force".
const char* quantity_unit(FrfQuantity q);
/// UFF dataset 58's specific data type of the ordinate numerator: 8, 11 or 12.
int quantity_data_type(FrfQuantity q);
/// The quantity of a dataset 58 ordinate numerator's data type (8, 11, 12); nullopt for another.
std::optional<FrfQuantity> quantity_of_data_type(int data_type);

/// Modes as the synthesis needs them: mass-normalised shapes (φᵀMφ = 1) at the
/// response DOFs and at the drive DOF, with their eigenvalues and damping ratios.
struct ModalFrfModel {
  Eigen::VectorXd eigenvalue;  ///< ω_r², (rad/s)²; values ≤ 0 (rigid-body modes) count as 0
  Eigen::VectorXd zeta;        ///< ζ_r, modal damping ratio (viscous), dimensionless
  Eigen::MatrixXd response;    ///< no × modes: φ_kr at the response DOFs, length/√mass
  Eigen::VectorXd drive;       ///< modes: φ_dr at the drive DOF, length/√mass
};

/// The FRFs from the drive DOF to each response DOF at the frequencies f (Hz), by the
/// seed's Eq. 2 with ω = 2πf:
/// \f[ H_{kd}(\omega) = (i\omega)^p \sum_r \frac{\phi_{kr}\,\phi_{dr}}{\omega_r^2 - \omega^2 + 2i\zeta_r\omega_r\omega} \f]
/// (Eq. 2 writes the denominator ω_r²[1 − (ω/ω_r)² + 2iζ_r ω/ω_r]; p = 0, 1, 2 for
/// displacement, velocity, acceleration; time dependence e^{iωt}, so that a lightly damped
/// driving point's receptance has negative imaginary part at resonance). Equal to
/// (K − ω²M + iωC)⁻¹ when C = M Φ diag(2ζ_rω_r) Φᵀ M and every mode is included.
/// Unit: length/force (·1/s per power of iω) in the units of the model the shapes came
/// from. Returns lines × no. Throws formats::InputError when the sizes disagree, a
/// damping ratio is negative, or a line at 0 Hz meets a rigid-body mode (infinite).
Eigen::MatrixXcd synthesize_frf(const Eigen::Ref<const Eigen::VectorXd>& frequency_hz, const ModalFrfModel& modes,
                                FrfQuantity quantity = FrfQuantity::Displacement);

/// Frequency response assurance criterion of two FRFs over the same lines,
/// FRAC = |Σ a_k conj(b_k)|² / (Σ|a_k|² Σ|b_k|²), in [0, 1] (1: the same shape up to a
/// complex factor). NaN when either is all zero. Throws formats::InputError when the
/// lengths differ.
double frf_assurance(const Eigen::Ref<const Eigen::VectorXcd>& a, const Eigen::Ref<const Eigen::VectorXcd>& b);

/// Which measured mode lends each analysis mode its damping: analysis mode r (at
/// `analysis_hz`(r)) takes measured mode t (at `measured_hz`[t]) when
/// |f_r − f_t| / f_t ≤ `tolerance` (relative), nearest pairs first, each measured and
/// each analysis mode used once; nullopt where no measured mode is left near. The
/// analyst's rule of thumb for an FRF overlay: the damping of the test mode the
/// analysis mode stands for (NASTRAN's modal damping table, TABDMP1, is set the same way).
std::vector<std::optional<std::size_t>> damping_partners(const Eigen::Ref<const Eigen::VectorXd>& analysis_hz,
                                                         const std::vector<double>& measured_hz, double tolerance);

}  // namespace ssid::estimator::identification
