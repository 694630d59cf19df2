#pragma once
/// \file era.hpp
/// The Eigensystem Realization Algorithm (ERA, Juang and Pappa 1985) and ERA with
/// data correlations (ERA/DC, Juang, Cooper and Wright 1988), the methods of the seed
/// report's ERA identifications (SAND97-0962, the MPI free-decay linearity check and
/// the sensor/exciter placement studies that "sent [time responses] to ERA", and the
/// ERA/DC column of the ARMAX paper's Table 10). Equations: docs/identification.md.
///
/// Input: a sequence of Markov parameters Y[k] = C Aᵏ B (no × ni), k = 0, 1, …, sampled
/// every dt seconds:
/// - impulse responses: Y[k] = h(k·dt), the continuous impulse response (unit: response
///   per unit impulse, e.g. (m/s²)/(N·s)); the identified B and residues are then those
///   of the continuous system, H(s) = Σ_r c_r l_rᵀ/(s − λ_r);
/// - free decays: Y[k] = y(k·dt) with one column per decay (B = the initial states).
#include <Eigen/Core>
#include <complex>
#include <vector>

namespace ssid::estimator::identification {

/// One identified pole with its shape and quality indicators.
struct IdentifiedPole {
  std::complex<double> lambda;  ///< continuous pole λ = ln(z)/dt, rad/s
  double hz = 0;                ///< |λ|/(2π), Hz (undamped natural frequency)
  double zeta = 0;              ///< −Re λ / |λ|, dimensionless (negative: growing, unstable)
  Eigen::VectorXcd shape;       ///< c_r = C ψ_r at the outputs (no), the output scaling of the realization
  Eigen::VectorXcd participation;  ///< l_r = (Ψ⁻¹B) row r (ni): initial modal amplitudes per input
  double msv = 0;    ///< modal singular value (see era.cpp: ‖c_r‖‖l_r‖ √(Σ_{k<K}|z_r|^{2k}))
  double emac = 0;   ///< extended modal amplitude coherence, EMAC_out·EMAC_in ∈ [0, 1]
  double mpc = 0;    ///< modal phase collinearity of `shape` ∈ [0, 1]
  double mpd = 0;    ///< mean phase deviation of `shape`, degrees
  double cmi = 0;    ///< consistent mode indicator, EMAC·MPC ∈ [0, 1]
};

/// A realization of a given order and its poles (one of each conjugate pair, the one
/// with Im λ ≥ 0; real poles are kept too, with hz = |λ|/2π).
struct EraResult {
  Eigen::Index order = 0;
  Eigen::VectorXd singular_values;  ///< of the Hankel (or correlation) matrix, all of them, descending
  std::vector<IdentifiedPole> poles;  ///< ordered by frequency
  Eigen::MatrixXd A, B, C;            ///< the discrete realization (order × order, order × ni, no × order)
};

struct EraOptions {
  Eigen::Index order = 0;        ///< n, the state dimension (even for n/2 modes); ≤ rows of the Hankel matrix
  Eigen::Index block_rows = 0;   ///< r: block rows of the Hankel matrix; 0: chosen from the data
  Eigen::Index block_cols = 0;   ///< s: block columns; 0: chosen from the data
  /// ERA/DC: correlation blocks R(k) = H(k) H(0)ᵀ arranged in a (ξ+1)×(ξ+1) block Hankel
  /// matrix with lag step τ = 1; 0: plain ERA.
  Eigen::Index dc_blocks = 0;
  double dt = 1;  ///< sample interval, s
};

/// ERA (or ERA/DC) of the Markov parameters `markov` (each no × ni, all the same size).
/// Needs r + s (+ ξ for ERA/DC) Markov parameters. Throws formats::InputError when they
/// are too few for the requested sizes, the order exceeds the Hankel matrix's rank
/// bound, or dt ≤ 0.
EraResult era(const std::vector<Eigen::MatrixXd>& markov, const EraOptions& options);

/// ERA at each order of `orders` from one SVD of the Hankel matrix (the usual way of
/// building a stabilisation diagram: truncating the same decomposition).
std::vector<EraResult> era_orders(const std::vector<Eigen::MatrixXd>& markov, const EraOptions& options,
                                  const std::vector<Eigen::Index>& orders);

/// Markov parameters from time records: samples × channels of responses as one
/// free-decay or impulse-response set, no × 1 each (one "input"). Convenience for
/// single-reference data: Y[k] = records.row(k)ᵀ.
std::vector<Eigen::MatrixXd> markov_from_records(const Eigen::Ref<const Eigen::MatrixXd>& records);

/// Markov parameters (the impulse response h(n·dt), dt = 1/(N·df)) from one-sided FRF lines
/// f_k = k·df, k = 0 … N/2 (the last line at the Nyquist frequency), each no × ni:
///   h[n] = df Σ_{k=−N/2+1}^{N/2} H(f_k) e^{2πi kn/N},  H(−f) = conj H(f),  n = 0 … N−1.
/// Unit: the FRF's per second (e.g. m/N → m/(N·s)). The result is the impulse response
/// wrapped over the period N·dt, which keeps the poles of a decaying response (each
/// exponential only gains the factor 1/(1 − e^{λ N dt})); the lines being cut at the
/// Nyquist frequency is what makes it approximate. Use the first part of the sequence
/// (the tail carries the wrap-around). Throws formats::InputError for fewer than 2 lines,
/// unequal sizes or df ≤ 0.
std::vector<Eigen::MatrixXd> markov_from_frf(const std::vector<Eigen::MatrixXcd>& frf, double df);

}  // namespace ssid::estimator::identification
