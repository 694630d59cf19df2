#pragma once
/// \file evaluation.hpp
/// Pretest planning, step 5: judging a sensor and exciter placement by a simulated
/// modal test, as the pretest paper does (issue 23 item 5; seed report, Appendix A §5):
/// the full FE model's impulse responses at the exciters, measured at the sensors with
/// noise, identified with ERA over model orders and the stabilisation diagram, then
/// matched to the FE target modes (frequency and MAC) and checked by cross-orthogonality
/// with the SEREP mass on the sensors. Equations: docs/pretest.md, "Evaluation by a
/// simulated test".
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <cstdint>
#include <string>
#include <vector>

#include "estimator/correlation/measures.hpp"
#include "estimator/identification/stabilisation.hpp"
#include "estimator/pretest/exciter_placement.hpp"
#include "estimator/pretest/targets.hpp"

namespace ssid::estimator::pretest {

struct SimulatedTestOptions {
  double damping = 0.01;    ///< ζ, the modal damping ratio of every mode
  double noise_pct = 2.0;   ///< σ of the added Gaussian noise, % of each channel's RMS
  std::uint64_t seed = 1;   ///< of the noise (translators::NormalDeviates)
  /// Each channel is rounded to a converter of this many bits whose full scale is the
  /// channel's peak (a 24-bit data acquisition); 0: no rounding.
  int adc_bits = 24;
  /// The anti-alias filter's band B = bandwidth_factor · f_max (f_max the highest target,
  /// Hz); modes above B are left out of the response (an ideal filter).
  double bandwidth_factor = 1.25;
  double sampling_factor = 2.56;  ///< f_s = sampling_factor · B, Δt = 1/f_s
  Eigen::Index min_samples = 2048;  ///< at least this many samples,
  double min_periods = 20;          ///< and at least this many periods of the lowest target
  /// A target is identified by the stable mode of largest MAC (real-ised shape against
  /// the FE shape at the sensors) within match_freq_tol (relative) of its frequency,
  /// when that MAC ≥ match_mac_min; each identified mode serves one target.
  double match_freq_tol = 0.02;
  double match_mac_min = 0.9;
};

/// Input patterns of exciters on the a-set (n x E): column e is exciter e's unit direction
/// on its grid's translational candidate DOFs.
Eigen::MatrixXd exciter_inputs(Eigen::Index n, const std::vector<CandidateDof>& candidates,
                               const std::vector<std::vector<Eigen::Index>>& groups, const std::vector<Exciter>& exciters);

/// Sampled acceleration impulse responses (Markov parameters Y[k], outputs x inputs) by
/// modal superposition with modal damping ζ of the modes (mass-normalised `Phi`, n x r,
/// eigenvalues λ_r = ω_r², rad²/s²) with 0 < f_r ≤ cutoff_hz:
///   Y[k] = Σ_r φ_r,out (φ_rᵀ B) g_r(k Δt),
///   g_r(t) = e^{−ζω_r t} [−2ζω_r cos ω_dr t + ω_r (2ζ² − 1)/√(1 − ζ²) sin ω_dr t],  ω_dr = ω_r√(1 − ζ²),
/// the second derivative of the modal unit-impulse response e^{−ζωt} sin(ω_d t)/ω_d for
/// t > 0 (the δ at t = 0 is not sampled). Unit: (m/s²)/(N·s) for SI input. Rigid-body
/// modes (λ ≤ 0) give no acceleration for t > 0 and are skipped.
std::vector<Eigen::MatrixXd> impulse_accelerations(const Eigen::Ref<const Eigen::MatrixXd>& Phi,
                                                   const Eigen::Ref<const Eigen::VectorXd>& eigenvalues, double zeta,
                                                   const std::vector<Eigen::Index>& outputs,
                                                   const Eigen::Ref<const Eigen::MatrixXd>& inputs, double dt,
                                                   Eigen::Index samples, double cutoff_hz);

/// Adds measurement noise in place: per channel (output, input) Gaussian noise of σ =
/// noise_pct/100 · RMS of the channel (seeded Box–Muller, samples in order k, input,
/// output), then rounds each channel to `adc_bits` bits of its peak (0: no rounding).
void add_measurement_noise(std::vector<Eigen::MatrixXd>& markov, double noise_pct, int adc_bits, std::uint64_t seed);

/// Real-ised shape: Re(e^{−iθ} ψ) with θ = ½ arg Σ_k ψ_k², the rotation that makes the
/// real part largest (exact for a mode with one common phase).
Eigen::VectorXd realised_shape(const Eigen::Ref<const Eigen::VectorXcd>& psi);

/// One FE target against the identified modes.
struct TargetMatch {
  bool identified = false;
  int mode = -1;                  ///< index into PlacementEvaluation::identified
  double hz = 0, zeta = 0;        ///< of the identified mode
  double frequency_error_pct = 0; ///< 100 (f_id − f_FE)/f_FE
  double mac = 0;                 ///< of the real-ised shape against the FE shape at the sensors
};

struct PlacementEvaluation {
  double dt = 0;              ///< s
  double bandwidth_hz = 0;    ///< B
  Eigen::Index samples = 0;
  int response_modes = 0;     ///< elastic modes in the response (0 < f ≤ B)
  std::vector<Eigen::Index> orders;  ///< ERA orders of the stabilisation diagram
  std::vector<identification::ClusteredMode> identified;  ///< every stable mode, by frequency
  std::vector<TargetMatch> targets;                        ///< per FE target
  int identified_count = 0;
  double max_frequency_error_pct = 0;  ///< max |error| over identified targets; NaN when none
  /// Cross-orthogonality of the identified targets' real-ised shapes (rows, in target
  /// order) against every FE target (columns) with the SEREP mass of the targets on the
  /// sensors, each mode at unit generalised mass: X_ij = ψ_iᵀ M_S φ_j / √(ψ_iᵀM_Sψ_i φ_jᵀM_Sφ_j).
  ReductionStatus xor_status = ReductionStatus::Ok;
  std::string xor_message;
  Eigen::MatrixXd xor_matrix;
  std::vector<int> xor_rows;  ///< the target of each row
  double min_diagonal_xor = 0, max_offdiagonal_xor = 0;  ///< |X| at (row, its target) and elsewhere; NaN when none
};

/// The simulated test of a placement. `Phi` (n x r, mass-normalised) and `eigenvalues` are
/// the solved modes of the full model, which must reach above the band B (else the
/// response would miss modes: InputError saying how far they reach); `targets` are the
/// columns of the target modes; `sensors` the a-set rows measured; `inputs` (n x E) the
/// exciters' input patterns. K and M (n x n) are for the SEREP mass.
PlacementEvaluation evaluate_placement(const Eigen::SparseMatrix<double>& K, const Eigen::SparseMatrix<double>& M,
                                       const Eigen::Ref<const Eigen::MatrixXd>& Phi,
                                       const Eigen::Ref<const Eigen::VectorXd>& eigenvalues,
                                       const std::vector<Eigen::Index>& targets, const std::vector<Eigen::Index>& sensors,
                                       const Eigen::Ref<const Eigen::MatrixXd>& inputs,
                                       const SimulatedTestOptions& options = {});

/// The band B of a test of these targets (Hz): bandwidth_factor · the highest target frequency.
double evaluation_bandwidth(const Eigen::Ref<const Eigen::VectorXd>& eigenvalues, const std::vector<Eigen::Index>& targets,
                            const SimulatedTestOptions& options = {});

}  // namespace ssid::estimator::pretest
