#include "estimator/identification/era.hpp"

#include <Eigen/Dense>
#include <unsupported/Eigen/FFT>
#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "estimator/identification/modal_indicators.hpp"
#include "formats/parse_error.hpp"

namespace ssid::estimator::identification {

using formats::InputError;
using cd = std::complex<double>;

namespace {

/// Block Hankel matrix H(k): block (i, j) = Y[k + i + j], i < r, j < s.
Eigen::MatrixXd hankel(const std::vector<Eigen::MatrixXd>& Y, Eigen::Index k, Eigen::Index r, Eigen::Index s) {
  const Eigen::Index no = Y[0].rows(), ni = Y[0].cols();
  Eigen::MatrixXd H(r * no, s * ni);
  for (Eigen::Index i = 0; i < r; ++i)
    for (Eigen::Index j = 0; j < s; ++j)
      H.block(i * no, j * ni, no, ni) = Y[static_cast<std::size_t>(k + i + j)];
  return H;
}

/// The decomposition that every order truncates: H0 = U Σ Vᵀ, with H1 the shifted matrix,
/// and (ERA/DC) H(0) of the data for B.
struct Decomposition {
  Eigen::MatrixXd U, V, H1, data_h0;
  /// U_Nᵀ H1 V_N for the largest order N: order n's A needs its leading n × n block only
  /// (U_n, V_n are the first n columns of U, V), so the product through the Hankel
  /// matrix is made once, not once per order.
  Eigen::MatrixXd G;
  Eigen::VectorXd sigma;
  Eigen::Index r = 0, s = 0, no = 0, ni = 0;
  Eigen::Index last_exponent = 0;  ///< the realized observability's last no rows are C A^this
  bool dc = false;
};

Decomposition decompose(const std::vector<Eigen::MatrixXd>& Y, const EraOptions& o, Eigen::Index max_order) {
  if (Y.empty()) throw InputError("ERA: no Markov parameters");
  if (!(o.dt > 0)) throw InputError(fmt::format("ERA: sample interval {} s (expected > 0)", o.dt));
  const Eigen::Index no = Y[0].rows(), ni = Y[0].cols();
  if (no < 1 || ni < 1) throw InputError("ERA: Markov parameters of size 0");
  for (std::size_t k = 0; k < Y.size(); ++k)
    if (Y[k].rows() != no || Y[k].cols() != ni)
      throw InputError(fmt::format("ERA: Markov parameter {} is {}×{} (expected {}×{} as the first)", k, Y[k].rows(),
                                   Y[k].cols(), no, ni));
  const auto K = static_cast<Eigen::Index>(Y.size());
  const Eigen::Index xi = o.dc_blocks;
  if (xi < 0) throw InputError(fmt::format("ERA/DC: {} correlation blocks (expected ≥ 0)", xi));
  // Defaults: enough block rows for the order (and at least 2 orders of margin), the
  // remaining data in the columns (more columns average more noise), capped for cost.
  // Never fewer than 4 block rows: with many outputs one row would hold the order, but
  // a Hankel matrix of one block row has no time shift down its rows, its left singular
  // vectors are the outputs' spatial pattern alone, and the noise of H(1) passes into A
  // unfiltered (240 noisy accelerances of a simulated shaker test realized nothing but
  // over-damped poles at every order with one block row, all 12 modes of the band with
  // two or more; tests/cli/test_cli_mpi_shaker_test.cpp).
  Eigen::Index r = o.block_rows;
  if (r <= 0) r = std::max<Eigen::Index>({(2 * max_order + no - 1) / no, (60 + no - 1) / no, 4});
  Eigen::Index s = o.block_cols;
  if (s <= 0) s = std::min<Eigen::Index>(K - r - 2 * xi, std::max<Eigen::Index>(r, 4000 / ni));
  if (r < 1 || s < 1 || r + s + 2 * xi > K)
    throw InputError(fmt::format(
        "ERA: {} Markov parameters are too few for {} block rows, {} block columns and {} correlation blocks "
        "(needs rows + columns + 2·blocks ≤ {})",
        K, r, s, xi, K));
  Decomposition d;
  d.r = r;
  d.s = s;
  d.no = no;
  d.ni = ni;
  d.dc = xi > 0;
  d.last_exponent = r - 1 + xi;  // ERA/DC: block row i of 𝓗(0) is O Aⁱ, O = [C; CA; …; CA^{r−1}]
  Eigen::MatrixXd H0;
  if (!d.dc) {
    H0 = hankel(Y, 0, r, s);
    d.H1 = hankel(Y, 1, r, s);
  } else {
    // R(k) = H(k) H(0)ᵀ; 𝓗(k) has block (i, j) = R(k + i + j), i, j = 0 … ξ.
    d.data_h0 = hankel(Y, 0, r, s);
    std::vector<Eigen::MatrixXd> R(static_cast<std::size_t>(2 * xi + 2));
    for (Eigen::Index k = 0; k < 2 * xi + 2; ++k)
      R[static_cast<std::size_t>(k)] = hankel(Y, k, r, s) * d.data_h0.transpose();
    const Eigen::Index b = r * no;
    H0.resize((xi + 1) * b, (xi + 1) * b);
    d.H1.resize((xi + 1) * b, (xi + 1) * b);
    for (Eigen::Index i = 0; i <= xi; ++i)
      for (Eigen::Index j = 0; j <= xi; ++j) {
        H0.block(i * b, j * b, b, b) = R[static_cast<std::size_t>(i + j)];
        d.H1.block(i * b, j * b, b, b) = R[static_cast<std::size_t>(i + j + 1)];
      }
  }
  if (max_order > std::min(H0.rows(), H0.cols()))
    throw InputError(fmt::format("ERA: order {} exceeds the Hankel matrix's size {}×{} (more block rows needed)",
                                 max_order, H0.rows(), H0.cols()));
  Eigen::BDCSVD<Eigen::MatrixXd> svd(H0, Eigen::ComputeThinU | Eigen::ComputeThinV);
  d.U = svd.matrixU();
  d.V = svd.matrixV();
  d.sigma = svd.singularValues();
  const Eigen::Index N = std::min<Eigen::Index>(max_order, d.sigma.size());
  d.G = d.U.leftCols(N).transpose() * (d.H1 * d.V.leftCols(N));
  return d;
}

/// Weighted agreement of predicted and realized modal amplitudes (one EMAC factor):
///   Σ_j |p_j|² ρ_j w_j / Σ_j |p_j|², ρ_j = min(|p_j|/|q_j|, |q_j|/|p_j|),
///   w_j = max(0, 1 − |arg(q_j/p_j)|/(π/4)).
double amplitude_coherence(const Eigen::VectorXcd& predicted, const Eigen::VectorXcd& realized) {
  double num = 0, den = 0;
  for (Eigen::Index j = 0; j < predicted.size(); ++j) {
    const double ap = std::abs(predicted(j)), aq = std::abs(realized(j));
    const double weight = ap * ap;
    den += weight;
    if (ap == 0 || aq == 0) continue;
    const double rho = std::min(ap / aq, aq / ap);
    const double w = std::max(0.0, 1.0 - std::abs(std::arg(realized(j) / predicted(j))) / (M_PI / 4));
    num += weight * rho * w;
  }
  return den > 0 ? num / den : 0.0;
}

EraResult realize(const Decomposition& d, Eigen::Index n, double dt) {
  EraResult res;
  res.order = n;
  res.singular_values = d.sigma;
  if (n < 1) throw InputError(fmt::format("ERA: order {} (expected ≥ 1)", n));
  if (n > d.sigma.size())
    throw InputError(fmt::format("ERA: order {} exceeds the {} singular values", n, d.sigma.size()));
  if (!(d.sigma(n - 1) > d.sigma(0) * 1e-13)) return res;  // beyond the numerical rank: no realization
  const Eigen::VectorXd sq = d.sigma.head(n).cwiseSqrt();
  const Eigen::VectorXd isq = sq.cwiseInverse();
  if (n > d.G.rows()) throw InputError(fmt::format("ERA: order {} above the decomposition's {}", n, d.G.rows()));
  res.A = isq.asDiagonal() * d.G.topLeftCorner(n, n) * isq.asDiagonal();
  const Eigen::MatrixXd P = d.U.leftCols(n) * sq.asDiagonal();  // observability (block rows of no)
  res.C = P.topRows(d.no);
  // Controllability's first and last block columns (plain ERA only): B, and what EMAC's
  // input factor compares (the rest of the n × s·ni matrix is never read).
  Eigen::MatrixXd Q_last;
  if (!d.dc) {
    res.B = sq.asDiagonal() * d.V.topLeftCorner(d.ni, n).transpose();
    Q_last = sq.asDiagonal() * d.V.block((d.s - 1) * d.ni, 0, d.ni, n).transpose();
  } else {
    const Eigen::MatrixXd P0 = P.topRows(d.r * d.no);
    res.B = P0.completeOrthogonalDecomposition().solve(d.data_h0).leftCols(d.ni);
  }

  Eigen::EigenSolver<Eigen::MatrixXd> eig(res.A);
  if (eig.info() != Eigen::Success) return res;
  const Eigen::VectorXcd z = eig.eigenvalues();
  const Eigen::MatrixXcd Psi = eig.eigenvectors();
  Eigen::PartialPivLU<Eigen::MatrixXcd> lu(Psi);
  const Eigen::MatrixXcd L = lu.solve(res.B.cast<cd>());     // n × ni
  const Eigen::MatrixXcd Cm = res.C.cast<cd>() * Psi;        // no × n
  const Eigen::MatrixXcd Pm = P.cast<cd>() * Psi;            // realized observability, modal
  Eigen::MatrixXcd Qm_last;
  if (!d.dc) Qm_last = lu.solve(Q_last.cast<cd>());          // realized controllability's last block, modal

  for (Eigen::Index m = 0; m < n; ++m) {
    if (z(m).imag() < 0) continue;  // one of each conjugate pair
    if (std::abs(z(m)) == 0) continue;
    IdentifiedPole p;
    p.lambda = std::log(z(m)) / dt;
    const double w = std::abs(p.lambda);
    p.hz = w / (2 * M_PI);
    p.zeta = w > 0 ? -p.lambda.real() / w : 0.0;
    p.shape = Cm.col(m);
    p.participation = L.row(m).transpose();
    double geometric = 0, zk = 1;
    for (Eigen::Index k = 0; k < d.s; ++k, zk *= std::abs(z(m))) geometric += zk;
    p.msv = std::sqrt(p.shape.norm() * p.participation.norm() * geometric);
    const cd zr = std::pow(z(m), static_cast<double>(d.last_exponent));
    const double emac_out = amplitude_coherence(p.shape * zr, Pm.col(m).tail(d.no));
    double emac_in = 1.0;
    if (!d.dc) {
      const cd zs = std::pow(z(m), static_cast<double>(d.s - 1));
      emac_in = amplitude_coherence(p.participation * zs, Qm_last.row(m).transpose());
    }
    p.emac = emac_out * emac_in;
    p.mpc = modal_phase_collinearity(p.shape);
    p.mpd = mean_phase_deviation(p.shape);
    p.cmi = p.emac * p.mpc;
    res.poles.push_back(std::move(p));
  }
  std::sort(res.poles.begin(), res.poles.end(),
            [](const IdentifiedPole& a, const IdentifiedPole& b) { return a.hz < b.hz; });
  return res;
}

}  // namespace

EraResult era(const std::vector<Eigen::MatrixXd>& markov, const EraOptions& options) {
  const Decomposition d = decompose(markov, options, options.order);
  return realize(d, options.order, options.dt);
}

std::vector<EraResult> era_orders(const std::vector<Eigen::MatrixXd>& markov, const EraOptions& options,
                                  const std::vector<Eigen::Index>& orders) {
  if (orders.empty()) throw InputError("ERA: no model orders");
  const Eigen::Index max_order = *std::max_element(orders.begin(), orders.end());
  const Decomposition d = decompose(markov, options, max_order);
  std::vector<EraResult> out;
  out.reserve(orders.size());
  for (const Eigen::Index n : orders) out.push_back(realize(d, n, options.dt));
  return out;
}

std::vector<Eigen::MatrixXd> markov_from_records(const Eigen::Ref<const Eigen::MatrixXd>& records) {
  std::vector<Eigen::MatrixXd> Y(static_cast<std::size_t>(records.rows()));
  for (Eigen::Index k = 0; k < records.rows(); ++k) Y[static_cast<std::size_t>(k)] = records.row(k).transpose();
  return Y;
}

std::vector<Eigen::MatrixXd> markov_from_frf(const std::vector<Eigen::MatrixXcd>& frf, double df) {
  if (frf.size() < 2) throw InputError(fmt::format("Markov parameters from FRFs: {} lines (expected at least 2)", frf.size()));
  if (!(df > 0)) throw InputError(fmt::format("Markov parameters from FRFs: line spacing {} Hz (expected > 0)", df));
  const Eigen::Index no = frf[0].rows(), ni = frf[0].cols();
  for (std::size_t k = 0; k < frf.size(); ++k)
    if (frf[k].rows() != no || frf[k].cols() != ni)
      throw InputError(fmt::format("Markov parameters from FRFs: line {} is {}×{} (expected {}×{} as the first)", k,
                                   frf[k].rows(), frf[k].cols(), no, ni));
  const auto half = static_cast<Eigen::Index>(frf.size()) - 1;
  const Eigen::Index N = 2 * half;
  std::vector<Eigen::MatrixXd> Y(static_cast<std::size_t>(N), Eigen::MatrixXd(no, ni));
  Eigen::FFT<double> fft;
  std::vector<cd> spec(static_cast<std::size_t>(N));
  std::vector<cd> time;
  for (Eigen::Index i = 0; i < ni; ++i)
    for (Eigen::Index o = 0; o < no; ++o) {
      for (Eigen::Index k = 0; k <= half; ++k) spec[static_cast<std::size_t>(k)] = frf[static_cast<std::size_t>(k)](o, i);
      // The Nyquist line of a real sequence is real: its imaginary part has no partner.
      spec[static_cast<std::size_t>(half)] = spec[static_cast<std::size_t>(half)].real();
      for (Eigen::Index k = 1; k < half; ++k)
        spec[static_cast<std::size_t>(N - k)] = std::conj(frf[static_cast<std::size_t>(k)](o, i));
      fft.inv(time, spec);  // (1/N) Σ_k S_k e^{2πikn/N}
      for (Eigen::Index n = 0; n < N; ++n)
        Y[static_cast<std::size_t>(n)](o, i) = time[static_cast<std::size_t>(n)].real() * static_cast<double>(N) * df;
    }
  return Y;
}

}  // namespace ssid::estimator::identification
