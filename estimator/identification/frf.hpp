#pragma once
/// \file frf.hpp
/// Frequency response functions from time records: Welch-averaged auto- and
/// cross-spectra, the H1, H2 and Hv estimators (several references at once),
/// ordinary and multiple coherence, and the windows of random and impact testing.
///
/// Conventions (docs/identification.md, "FRFs from time data"):
/// - records are matrices of samples × channels, sampled every `dt` seconds;
///   x are the references (forces), y the responses;
/// - segment m of length N starts at sample m·(N − overlap); its windowed DFT is
///   X_m(f_k) = Σ_n w_x[n] x[m·step + n] e^{−2πi kn/N}, lines f_k = k/(N·dt) Hz,
///   k = 0 … ⌊N/2⌋ (one-sided);
/// - spectra are one-sided densities averaged over the M segments,
///   G_ab(f_k) = c_k/(M·fs·Σ w²) Σ_m A_m(f_k) B_m(f_k)^H,  c_k = 2 except at f = 0 and
///   the Nyquist line (c_k = 1), fs = 1/dt;  unit: (unit of a)·(unit of b)/Hz.
///   G_yx(k, i) is therefore scipy.signal.csd(x_i, y_k, …, detrend=False);
/// - H (no × ni per line) maps the references to the responses, y = H x;
///   unit: (unit of y)/(unit of x), e.g. (m/s²)/N.
#include <Eigen/Core>
#include <complex>
#include <vector>

namespace ssid::estimator::identification {

/// Window shapes (n = 0 … N−1 within a segment of N samples).
enum class WindowKind {
  Rectangular,  ///< w = 1
  Hann,         ///< w = ½ − ½ cos(2πn/N) (periodic form, as scipy's get_window("hann", N))
  FlatTop,      ///< w = Σ_j (−1)^j a_j cos(2πjn/N), a = 0.21557895, 0.41663158, 0.277263158,
                ///< 0.083578947, 0.006947368 (periodic; scipy's "flattop")
  Force,        ///< impact force window: 1 for n < ⌈force_fraction·N⌉, then 0
  Exponential   ///< impact response window: w = exp(−n·dt/τ); adds 1/τ (1/s) to every pole's decay rate
};

struct Window {
  WindowKind kind = WindowKind::Hann;
  double force_fraction = 0.1;   ///< Force: fraction of the segment kept (0, 1]
  double exponential_tau = 1.0;  ///< Exponential: time constant τ, s (> 0)
};

/// The N samples of a window; `dt` (s) is used by the exponential window only.
/// Throws formats::InputError for N < 1 or a parameter out of range.
Eigen::VectorXd window_samples(const Window& window, Eigen::Index n, double dt);

/// Welch averaging: segment length N (samples), overlap (samples, 0 ≤ overlap < N),
/// the window of the references and of the responses (the same unless impact testing:
/// force window on x, exponential window on y).
struct WelchOptions {
  Eigen::Index segment_length = 1024;
  Eigen::Index overlap = -1;  ///< < 0: N/2
  Window reference_window{};
  Window response_window{};
};

/// Averaged one-sided spectra, per frequency line k:
///   gxx[k] = G_xx (ni × ni, Hermitian), gyx[k] = G_yx (no × ni), gyy[k] = diag(G_yy) (no, real).
/// With different reference and response windows every spectrum is scaled by the
/// response window's Σw², so that H = G_yx G_xx⁻¹ is the ratio of the windowed transforms.
struct Spectra {
  Eigen::VectorXd frequency_hz;              ///< f_k = k/(N·dt), Hz
  std::vector<Eigen::MatrixXcd> gxx;         ///< unit_x²/Hz
  std::vector<Eigen::MatrixXcd> gyx;         ///< unit_y·unit_x/Hz
  std::vector<Eigen::VectorXd> gyy;          ///< unit_y²/Hz
  Eigen::Index segments = 0;                 ///< M, the number of averages
};

/// Welch spectra of references x (samples × ni) and responses y (samples × no).
/// Throws formats::InputError when the records differ in length, are shorter than
/// one segment, have no channel, or `dt` ≤ 0.
Spectra welch_spectra(const Eigen::Ref<const Eigen::MatrixXd>& x, const Eigen::Ref<const Eigen::MatrixXd>& y,
                      double dt, const WelchOptions& options);

/// Which FRF estimator:
/// - H1 = G_yx G_xx⁻¹ (least squares with noise on the responses; several references);
/// - H2: per response k, H2_k = G_{y_k y_k} / G_{x y_k}, with G_{x y_k} = conj(G_yx(k, 0))
///   (noise on the reference; one reference only);
/// - Hv: per response k, with z = [x; y_k] and G_zz its (ni+1)² spectral matrix, the
///   eigenvector v of G_zz's smallest eigenvalue scaled so that v_last = 1 gives
///   H_k = −conj(v_1…ni)ᵀ (total least squares: noise on both).
enum class FrfEstimator { H1, H2, Hv };

/// FRFs and coherences per frequency line.
struct FrfEstimate {
  Eigen::VectorXd frequency_hz;       ///< Hz
  std::vector<Eigen::MatrixXcd> h;    ///< per line, no × ni, unit_y/unit_x
  /// Ordinary coherence γ²_ki = |G_yx(k,i)|² / (G_xx(i,i) G_yy(k,k)), lines × (no·ni),
  /// column k + no·i; dimensionless, in [0, 1].
  Eigen::MatrixXd coherence;
  /// Multiple coherence of response k with all references,
  /// γ²_k:x = G_yx(k,:) G_xx⁻¹ G_yx(k,:)ᴴ / G_yy(k,k), lines × no; in [0, 1].
  Eigen::MatrixXd multiple_coherence;
  Eigen::Index segments = 0;
};

/// FRFs from averaged spectra. Throws formats::InputError for H2 with more than
/// one reference. A line where G_xx is singular (e.g. the references are not
/// excited there, or they are fully correlated) gets NaN in h and the coherences.
FrfEstimate estimate_frf(const Spectra& spectra, FrfEstimator estimator = FrfEstimator::H1);

/// welch_spectra followed by estimate_frf.
FrfEstimate estimate_frf(const Eigen::Ref<const Eigen::MatrixXd>& x, const Eigen::Ref<const Eigen::MatrixXd>& y,
                         double dt, const WelchOptions& options, FrfEstimator estimator = FrfEstimator::H1);

}  // namespace ssid::estimator::identification
