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

}  // namespace ssid::estimator::identification
