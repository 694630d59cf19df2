#include "estimator/identification/frf.hpp"

#include <Eigen/Dense>
#include <unsupported/Eigen/FFT>
#include <cmath>
#include <fmt/format.h>
#include <limits>

#include "formats/parse_error.hpp"

namespace ssid::estimator::identification {

using formats::InputError;
using cd = std::complex<double>;

Eigen::VectorXd window_samples(const Window& window, Eigen::Index n, double dt) {
  if (n < 1) throw InputError(fmt::format("window: segment length {} (expected at least 1 sample)", n));
  Eigen::VectorXd w(n);
  const double two_pi = 2.0 * M_PI;
  const double N = static_cast<double>(n);
  switch (window.kind) {
    case WindowKind::Rectangular:
      w.setOnes();
      break;
    case WindowKind::Hann:
      for (Eigen::Index i = 0; i < n; ++i) w(i) = 0.5 - 0.5 * std::cos(two_pi * static_cast<double>(i) / N);
      break;
    case WindowKind::FlatTop: {
      static constexpr double a[5] = {0.21557895, 0.41663158, 0.277263158, 0.083578947, 0.006947368};
      for (Eigen::Index i = 0; i < n; ++i) {
        double s = 0;
        for (int j = 0; j < 5; ++j)
          s += ((j % 2) ? -a[j] : a[j]) * std::cos(two_pi * j * static_cast<double>(i) / N);
        w(i) = s;
      }
      break;
    }
    case WindowKind::Force: {
      if (!(window.force_fraction > 0 && window.force_fraction <= 1))
        throw InputError(fmt::format("force window: fraction {} (expected 0 < fraction ≤ 1)", window.force_fraction));
      const auto kept = static_cast<Eigen::Index>(std::ceil(window.force_fraction * N));
      for (Eigen::Index i = 0; i < n; ++i) w(i) = i < kept ? 1.0 : 0.0;
      break;
    }
    case WindowKind::Exponential:
      if (!(window.exponential_tau > 0))
        throw InputError(fmt::format("exponential window: time constant {} s (expected > 0)", window.exponential_tau));
      if (!(dt > 0)) throw InputError(fmt::format("exponential window: sample interval {} s (expected > 0)", dt));
      for (Eigen::Index i = 0; i < n; ++i) w(i) = std::exp(-static_cast<double>(i) * dt / window.exponential_tau);
      break;
  }
  return w;
}

namespace {

/// One-sided windowed DFTs of every channel of one segment: lines × channels.
Eigen::MatrixXcd segment_dft(const Eigen::Ref<const Eigen::MatrixXd>& records, Eigen::Index start,
                             const Eigen::VectorXd& w, Eigen::Index lines, Eigen::FFT<double>& fft) {
  const Eigen::Index n = w.size();
  Eigen::MatrixXcd out(lines, records.cols());
  std::vector<double> in(static_cast<std::size_t>(n));
  std::vector<cd> spec;
  for (Eigen::Index c = 0; c < records.cols(); ++c) {
    for (Eigen::Index i = 0; i < n; ++i) in[static_cast<std::size_t>(i)] = w(i) * records(start + i, c);
    fft.fwd(spec, in);
    for (Eigen::Index k = 0; k < lines; ++k) out(k, c) = spec[static_cast<std::size_t>(k)];
  }
  return out;
}

}  // namespace

Spectra welch_spectra(const Eigen::Ref<const Eigen::MatrixXd>& x, const Eigen::Ref<const Eigen::MatrixXd>& y,
                      double dt, const WelchOptions& options) {
  const Eigen::Index n = options.segment_length;
  const Eigen::Index overlap = options.overlap < 0 ? n / 2 : options.overlap;
  if (!(dt > 0)) throw InputError(fmt::format("spectra: sample interval {} s (expected > 0)", dt));
  if (x.cols() < 1 || y.cols() < 1)
    throw InputError(fmt::format("spectra: {} reference and {} response channels (expected at least 1 of each)",
                                 x.cols(), y.cols()));
  if (x.rows() != y.rows())
    throw InputError(fmt::format("spectra: references have {} samples, responses {} (expected the same)", x.rows(),
                                 y.rows()));
  if (n < 2) throw InputError(fmt::format("spectra: segment length {} (expected at least 2 samples)", n));
  if (overlap >= n)
    throw InputError(fmt::format("spectra: overlap {} samples with segments of {} (expected overlap < segment)",
                                 overlap, n));
  if (x.rows() < n)
    throw InputError(fmt::format("spectra: records of {} samples are shorter than one segment ({})", x.rows(), n));

  const Eigen::VectorXd wx = window_samples(options.reference_window, n, dt);
  const Eigen::VectorXd wy = window_samples(options.response_window, n, dt);
  const Eigen::Index step = n - overlap;
  const Eigen::Index segments = (x.rows() - n) / step + 1;
  const Eigen::Index lines = n / 2 + 1;
  const Eigen::Index ni = x.cols(), no = y.cols();

  Spectra s;
  s.segments = segments;
  s.frequency_hz.resize(lines);
  for (Eigen::Index k = 0; k < lines; ++k) s.frequency_hz(k) = static_cast<double>(k) / (static_cast<double>(n) * dt);
  s.gxx.assign(static_cast<std::size_t>(lines), Eigen::MatrixXcd::Zero(ni, ni));
  s.gyx.assign(static_cast<std::size_t>(lines), Eigen::MatrixXcd::Zero(no, ni));
  s.gyy.assign(static_cast<std::size_t>(lines), Eigen::VectorXd::Zero(no));

  Eigen::FFT<double> fft;
  for (Eigen::Index m = 0; m < segments; ++m) {
    const Eigen::MatrixXcd X = segment_dft(x, m * step, wx, lines, fft);
    const Eigen::MatrixXcd Y = segment_dft(y, m * step, wy, lines, fft);
    for (Eigen::Index k = 0; k < lines; ++k) {
      const auto kk = static_cast<std::size_t>(k);
      const Eigen::VectorXcd xk = X.row(k).transpose();
      const Eigen::VectorXcd yk = Y.row(k).transpose();
      s.gxx[kk].noalias() += xk * xk.adjoint();
      s.gyx[kk].noalias() += yk * xk.adjoint();
      s.gyy[kk] += yk.cwiseAbs2();
    }
  }
  // Density scale: one shared factor (the response window's) so ratios of spectra are
  // ratios of the windowed transforms.
  const double base = 1.0 / (static_cast<double>(segments) * wy.squaredNorm() / dt);
  for (Eigen::Index k = 0; k < lines; ++k) {
    const bool single = k == 0 || (n % 2 == 0 && k == lines - 1);
    const double c = (single ? 1.0 : 2.0) * base;
    const auto kk = static_cast<std::size_t>(k);
    s.gxx[kk] *= c;
    s.gyx[kk] *= c;
    s.gyy[kk] *= c;
  }
  return s;
}

FrfEstimate estimate_frf(const Spectra& spectra, FrfEstimator estimator) {
  const auto lines = spectra.frequency_hz.size();
  if (lines == 0 || spectra.gxx.size() != static_cast<std::size_t>(lines))
    throw InputError("FRF: no spectra (expected welch_spectra's result)");
  const Eigen::Index ni = spectra.gxx[0].rows(), no = spectra.gyx[0].rows();
  if (estimator == FrfEstimator::H2 && ni != 1)
    throw InputError(fmt::format("FRF: H2 with {} references (expected 1; use H1 or Hv with several)", ni));

  const double nan = std::numeric_limits<double>::quiet_NaN();
  FrfEstimate out;
  out.frequency_hz = spectra.frequency_hz;
  out.segments = spectra.segments;
  out.h.assign(static_cast<std::size_t>(lines), Eigen::MatrixXcd::Constant(no, ni, cd(nan, nan)));
  out.coherence = Eigen::MatrixXd::Constant(lines, no * ni, nan);
  out.multiple_coherence = Eigen::MatrixXd::Constant(lines, no, nan);

  for (Eigen::Index k = 0; k < lines; ++k) {
    const auto kk = static_cast<std::size_t>(k);
    const Eigen::MatrixXcd& Gxx = spectra.gxx[kk];
    const Eigen::MatrixXcd& Gyx = spectra.gyx[kk];
    const Eigen::VectorXd& Gyy = spectra.gyy[kk];
    for (Eigen::Index i = 0; i < ni; ++i)
      for (Eigen::Index r = 0; r < no; ++r) {
        const double den = Gxx(i, i).real() * Gyy(r);
        if (den > 0) out.coherence(k, r + no * i) = std::norm(Gyx(r, i)) / den;
      }
    // G_xx singular at this line (relative to its size): leave NaN.
    Eigen::LDLT<Eigen::MatrixXcd> ldlt(Gxx);
    const double scale = Gxx.diagonal().real().maxCoeff();
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXcd> gxx_eig(Gxx, Eigen::EigenvaluesOnly);
    if (!(scale > 0) || gxx_eig.eigenvalues().minCoeff() <= 1e-13 * scale) continue;
    // H1ᵀ = G_xx⁻ᵀ G_yxᵀ  ⇔  H1 = G_yx G_xx⁻¹ (G_xx Hermitian: solve with its adjoint).
    const Eigen::MatrixXcd h1 = ldlt.solve(Gyx.adjoint()).adjoint();
    for (Eigen::Index r = 0; r < no; ++r)
      if (Gyy(r) > 0)
        out.multiple_coherence(k, r) = (h1.row(r) * Gyx.row(r).adjoint())(0, 0).real() / Gyy(r);
    switch (estimator) {
      case FrfEstimator::H1:
        out.h[kk] = h1;
        break;
      case FrfEstimator::H2:
        for (Eigen::Index r = 0; r < no; ++r)
          if (std::abs(Gyx(r, 0)) > 0) out.h[kk](r, 0) = Gyy(r) / std::conj(Gyx(r, 0));
        break;
      case FrfEstimator::Hv:
        for (Eigen::Index r = 0; r < no; ++r) {
          Eigen::MatrixXcd Gzz(ni + 1, ni + 1);
          Gzz.topLeftCorner(ni, ni) = Gxx;
          Gzz.bottomLeftCorner(1, ni) = Gyx.row(r);
          Gzz.topRightCorner(ni, 1) = Gyx.row(r).adjoint();
          Gzz(ni, ni) = Gyy(r);
          Eigen::SelfAdjointEigenSolver<Eigen::MatrixXcd> eig(Gzz);
          const Eigen::VectorXcd v = eig.eigenvectors().col(0);  // smallest eigenvalue first
          if (std::abs(v(ni)) == 0) continue;
          const Eigen::VectorXcd vs = v / v(ni);
          out.h[kk].row(r) = -vs.head(ni).conjugate().transpose();
        }
        break;
    }
  }
  return out;
}

FrfEstimate estimate_frf(const Eigen::Ref<const Eigen::MatrixXd>& x, const Eigen::Ref<const Eigen::MatrixXd>& y,
                         double dt, const WelchOptions& options, FrfEstimator estimator) {
  return estimate_frf(welch_spectra(x, y, dt, options), estimator);
}

}  // namespace ssid::estimator::identification
