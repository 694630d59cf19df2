#pragma once
/// \file data_checks.hpp
/// The test-data quality checks the seed's testers ran on the MPI truss (seed report,
/// "A Modal Test of a Space-Truss…"): reciprocity of driving-point pairs, linearity (the
/// same FRF at two force levels), coherence, and frequency resolution against the
/// damping of the peaks. Each returns figures; `ssid identify check` turns them into
/// verdicts (docs/identification.md, "ssid identify check").
#include <Eigen/Core>
#include <string>
#include <vector>

namespace ssid::estimator::identification {

/// Two FRFs of the same lines compared.
struct FrfDifference {
  /// e = ‖a − b‖₂ / √(‖a‖₂ ‖b‖₂) over the lines: 0 for equal FRFs, about the relative
  /// difference for similar ones (dimensionless).
  double error = 0;
  double frac = 0;            ///< frequency response assurance criterion, in [0, 1]
  double peak_hz_a = 0;       ///< frequency of a's largest |value|, Hz
  double peak_hz_b = 0;       ///< frequency of b's largest |value|, Hz
};

/// Compares FRFs a and b at the frequencies f (Hz). Throws formats::InputError when the
/// sizes differ or there are no lines; a zero FRF gives error NaN.
FrfDifference compare_frfs(const Eigen::Ref<const Eigen::VectorXd>& f, const Eigen::Ref<const Eigen::VectorXcd>& a,
                           const Eigen::Ref<const Eigen::VectorXcd>& b);

/// A band of consecutive lines where the coherence is below a threshold.
struct LowCoherenceBand {
  double lo_hz = 0, hi_hz = 0;  ///< first and last line of the band, Hz
  double min = 0;               ///< the lowest coherence in it
  Eigen::Index lines = 0;       ///< number of lines
};

/// The bands of consecutive lines with coherence < threshold (NaN counts as below).
std::vector<LowCoherenceBand> low_coherence_bands(const Eigen::Ref<const Eigen::VectorXd>& f,
                                                  const Eigen::Ref<const Eigen::VectorXd>& coherence, double threshold);

/// One resonance peak and how well the lines resolve it.
struct PeakResolution {
  double hz = 0;            ///< the peak line, Hz
  /// Half-power bandwidth 2ζf, Hz: from the FRF (the band around the peak where the
  /// magnitude is ≥ peak/√2, its ends interpolated linearly between lines), or 2ζf with
  /// the identified ζ when one was given.
  double half_power_hz = 0;
  double zeta = 0;          ///< half_power_hz / (2 hz)
  double lines = 0;         ///< half_power_hz / Δf: lines across the half-power band
  bool from_identified = false;
};

/// Peaks of the magnitude |a| (e.g. the sum of the FRFs' magnitudes) at evenly spaced lines
/// f: local maxima of at least `min_fraction` of the largest value whose magnitude falls
/// below peak/√2 on both sides before it rises above the peak (an isolated resonance).
/// With identified modes (hz, zeta), a peak within `tol` (relative) of one takes its ζ.
/// Throws formats::InputError for fewer than 3 lines or uneven lines.
std::vector<PeakResolution> peak_resolution(const Eigen::Ref<const Eigen::VectorXd>& f,
                                            const Eigen::Ref<const Eigen::VectorXd>& magnitude,
                                            const std::vector<std::pair<double, double>>& identified = {},
                                            double tol = 0.05, double min_fraction = 0.05);

/// The dominant mode of one segment of a free decay.
struct DecaySegment {
  double start_s = 0;  ///< the segment's first sample, s from the record's start
  double rms = 0;      ///< RMS of the segment over its samples and channels (the records' unit)
  double hz = 0;       ///< dominant pole's frequency |λ|/2π, Hz (NaN when ERA found none)
  double zeta = 0;     ///< its damping ratio
};

/// The seed's linearity check on free decays ("analyzed in overlapping segments using
/// ERA to calculate the dominant modal frequency as a function of time"): ERA of order
/// `order` (or the highest even order below it whose singular value exceeds 1e-9 of the
/// largest: noise-free data of few modes have no more) on each segment of `segment` samples, starting every `step` samples, the
/// records (samples × channels, every dt s) taken as one free decay (Markov parameters
/// Y[k] = records.row(k)ᵀ); the dominant pole is the one of largest modal singular value
/// among the poles with Im λ > 0 and 0 < ζ < 0.2. A linear structure's frequency does not
/// move as the amplitude decays; a hardening (softening) one's falls (rises).
/// Throws formats::InputError when the records are shorter than one segment, step < 1,
/// or dt ≤ 0.
std::vector<DecaySegment> decay_segments(const Eigen::Ref<const Eigen::MatrixXd>& records, double dt,
                                         Eigen::Index segment, Eigen::Index step, Eigen::Index order = 8);

}  // namespace ssid::estimator::identification
