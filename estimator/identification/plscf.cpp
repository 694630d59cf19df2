#include "estimator/identification/plscf.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "estimator/identification/modal_indicators.hpp"
#include "formats/parse_error.hpp"

namespace ssid::estimator::identification {

using formats::InputError;
using formats::NumericalError;
using cd = std::complex<double>;

namespace {

/// The lines of the band, checked.
struct Band {
  std::vector<Eigen::Index> lines;  ///< indices into the input lines
  Eigen::Index no = 0, ni = 0;
  double hz_top = 0;                ///< the band's highest line, Hz
};

Band band_lines(const Eigen::Ref<const Eigen::VectorXd>& hz, const std::vector<Eigen::MatrixXcd>& frf,
                const PlscfOptions& o, const char* who) {
  if (frf.empty()) throw InputError(fmt::format("{}: no FRF lines", who));
  if (hz.size() != static_cast<Eigen::Index>(frf.size()))
    throw InputError(fmt::format("{}: {} frequencies for {} FRF lines (expected one per line)", who, hz.size(),
                                 frf.size()));
  if (!(o.hz_min <= o.hz_max))
    throw InputError(fmt::format("{}: band {} … {} Hz (expected min ≤ max)", who, o.hz_min, o.hz_max));
  Band b;
  b.no = frf[0].rows();
  b.ni = frf[0].cols();
  if (b.no < 1 || b.ni < 1) throw InputError(fmt::format("{}: FRF lines of size {}×{}", who, b.no, b.ni));
  for (std::size_t k = 0; k < frf.size(); ++k) {
    if (frf[k].rows() != b.no || frf[k].cols() != b.ni)
      throw InputError(fmt::format("{}: line {} is {}×{} (expected {}×{} as the first)", who, k, frf[k].rows(),
                                   frf[k].cols(), b.no, b.ni));
    const double f = hz(static_cast<Eigen::Index>(k));
    if (!(f > 0 && f >= o.hz_min && f <= o.hz_max)) continue;
    if (!frf[k].allFinite())
      throw InputError(fmt::format("{}: line {} ({} Hz) is not finite (NaN or infinite values)", who, k, f));
    b.lines.push_back(static_cast<Eigen::Index>(k));
    b.hz_top = std::max(b.hz_top, f);
  }
  if (b.lines.empty())
    throw InputError(fmt::format("{}: no line above 0 Hz in the band {} … {} Hz", who, o.hz_min, o.hz_max));
  return b;
}

/// Unit norm, the largest component real and positive (one participation vector per pole,
/// comparable across orders).
Eigen::VectorXcd normalise_participation(Eigen::VectorXcd l) {
  Eigen::Index big = 0;
  l.cwiseAbs().maxCoeff(&big);
  const double a = std::abs(l(big));
  if (a > 0) l *= std::conj(l(big)) / a / l.norm();
  return l;
}

/// The reduced normal equations' ingredients for the largest order P, shared by all orders
/// (docs/identification.md): R = L Lᵀ, the rows of G_o = L⁻¹S_o of every response o
/// (z_rows[r] is no × (P+1)·ni, row o = row r of G_o), and Σ_o T_o.
struct Reduction {
  Eigen::MatrixXd chol_l;               ///< L, lower triangular, (P+1)²
  std::vector<Eigen::MatrixXd> z_rows;  ///< P+1 of no × (P+1)ni
  Eigen::MatrixXd t_sum;                ///< (P+1)ni square
  Eigen::VectorXd weight;               ///< per response: 1/RMS of its FRFs over the band
  double dt = 0;                        ///< s
};

Reduction reduce(const Eigen::Ref<const Eigen::VectorXd>& hz, const std::vector<Eigen::MatrixXcd>& frf, const Band& b,
                 Eigen::Index P) {
  const Eigen::Index nf = static_cast<Eigen::Index>(b.lines.size()), no = b.no, ni = b.ni;
  Reduction red;
  red.dt = 1.0 / (2.0 * b.hz_top);
  // Weighted data, column o·ni + a = response o, reference a.
  red.weight = Eigen::VectorXd::Zero(no);
  for (const Eigen::Index k : b.lines) red.weight += frf[static_cast<std::size_t>(k)].rowwise().squaredNorm();
  for (Eigen::Index o = 0; o < no; ++o) {
    const double rms = std::sqrt(red.weight(o) / static_cast<double>(nf * ni));
    red.weight(o) = rms > 0 ? 1.0 / rms : 1.0;  // a response without signal adds nothing either way
  }
  Eigen::MatrixXcd hw(nf, no * ni);
  for (Eigen::Index k = 0; k < nf; ++k) {
    const Eigen::MatrixXcd& h = frf[static_cast<std::size_t>(b.lines[static_cast<std::size_t>(k)])];
    for (Eigen::Index o = 0; o < no; ++o)
      for (Eigen::Index a = 0; a < ni; ++a) hw(k, o * ni + a) = red.weight(o) * h(o, a);
  }
  // z_k^d for the lags d = −P … P (column d + P).
  Eigen::MatrixXcd zpow(nf, 2 * P + 1);
  for (Eigen::Index k = 0; k < nf; ++k) {
    const double theta = 2 * M_PI * hz(b.lines[static_cast<std::size_t>(k)]) * red.dt;
    for (Eigen::Index d = -P; d <= P; ++d) zpow(k, d + P) = std::polar(1.0, theta * static_cast<double>(d));
  }
  // The Toeplitz sums: r0(d) = Σ_k z^d, s(d) = Σ_k z^d H_w(k), t(d) = Σ_k z^d H_w(k)ᴴH_w(k).
  const Eigen::VectorXcd r0 = zpow.rightCols(P + 1).colwise().sum().transpose();
  const Eigen::MatrixXcd sd = zpow.transpose() * hw;  // (2P+1) × no·ni
  Eigen::MatrixXcd gram(nf, ni * ni);
  for (Eigen::Index k = 0; k < nf; ++k)
    for (Eigen::Index a = 0; a < ni; ++a)
      for (Eigen::Index c = 0; c < ni; ++c) {
        cd sum = 0;
        for (Eigen::Index o = 0; o < no; ++o) sum += std::conj(hw(k, o * ni + a)) * hw(k, o * ni + c);
        gram(k, a * ni + c) = sum;
      }
  const Eigen::MatrixXcd td = zpow.rightCols(P + 1).transpose() * gram;  // (P+1) × ni², d = 0 … P

  Eigen::MatrixXd R(P + 1, P + 1);
  for (Eigen::Index r = 0; r <= P; ++r)
    for (Eigen::Index s = 0; s <= P; ++s) R(r, s) = r0(std::abs(s - r)).real();
  const Eigen::Index n = (P + 1) * ni;
  red.t_sum.resize(n, n);
  for (Eigen::Index r = 0; r <= P; ++r)
    for (Eigen::Index s = 0; s <= P; ++s)
      for (Eigen::Index a = 0; a < ni; ++a)
        for (Eigen::Index c = 0; c < ni; ++c)
          red.t_sum(r * ni + a, s * ni + c) =
              s >= r ? td(s - r, a * ni + c).real() : td(r - s, c * ni + a).real();  // t(−d) = t(d)ᴴ
  const Eigen::LLT<Eigen::MatrixXd> llt(R);
  if (llt.info() != Eigen::Success)
    throw NumericalError(fmt::format("pLSCF: the basis Gram matrix of order {} over {} lines is not positive definite",
                                     P, nf));
  red.chol_l = llt.matrixL();
  red.z_rows.assign(static_cast<std::size_t>(P + 1), Eigen::MatrixXd(no, n));
  Eigen::MatrixXd S(P + 1, n);
  for (Eigen::Index o = 0; o < no; ++o) {
    for (Eigen::Index r = 0; r <= P; ++r)
      for (Eigen::Index s = 0; s <= P; ++s)
        for (Eigen::Index a = 0; a < ni; ++a) S(r, s * ni + a) = -sd(s - r + P, o * ni + a).real();
    red.chol_l.triangularView<Eigen::Lower>().solveInPlace(S);
    for (Eigen::Index r = 0; r <= P; ++r) red.z_rows[static_cast<std::size_t>(r)].row(o) = S.row(r);
  }
  return red;
}

/// The poles of order p from its denominator α ((p+1)·ni × ni, α_p = I) and numerators
/// β ((p+1) × no·ni, weighted).
std::vector<IdentifiedPole> poles_of(const Eigen::MatrixXd& alpha, const Eigen::MatrixXd& beta, Eigen::Index p,
                                     const Reduction& red) {
  const Eigen::Index ni = alpha.cols(), no = red.weight.size();
  const Eigen::Index n = p * ni;
  // Companion matrix of Σ z^j α_jᵀ: its eigenvectors are [l; z l; …; z^{p−1} l].
  Eigen::MatrixXd comp = Eigen::MatrixXd::Zero(n, n);
  if (p > 1) comp.topRightCorner(n - ni, n - ni).setIdentity();
  for (Eigen::Index j = 0; j < p; ++j) comp.block(n - ni, j * ni, ni, ni) = -alpha.block(j * ni, 0, ni, ni).transpose();
  const Eigen::EigenSolver<Eigen::MatrixXd> es(comp, false);
  if (es.info() != Eigen::Success) return {};
  std::vector<IdentifiedPole> out;
  for (Eigen::Index m = 0; m < n; ++m) {
    const cd z = es.eigenvalues()(m);
    if (z.imag() < 0 || std::abs(z) == 0) continue;  // one of each conjugate pair
    IdentifiedPole pole;
    pole.lambda = std::log(z) / red.dt;
    const double w = std::abs(pole.lambda);
    pole.hz = w / (2 * M_PI);
    pole.zeta = w > 0 ? -pole.lambda.real() / w : 0.0;
    // A(z) and its null vectors: lᵀA(z) = 0 (participation), A(z) v = 0 (the residue's row space).
    Eigen::MatrixXcd az = Eigen::MatrixXcd::Zero(ni, ni);
    Eigen::VectorXcd zj(p + 1);
    cd zk = 1;
    for (Eigen::Index j = 0; j <= p; ++j, zk *= z) {
      zj(j) = zk;
      az += zk * alpha.block(j * ni, 0, ni, ni).cast<cd>();
    }
    const Eigen::JacobiSVD<Eigen::MatrixXcd> svd(az, Eigen::ComputeFullU | Eigen::ComputeFullV);
    const Eigen::VectorXcd v = svd.matrixV().col(ni - 1);
    pole.participation = normalise_participation(svd.matrixU().col(ni - 1).conjugate());
    const Eigen::VectorXcd bz = beta.transpose().cast<cd>() * zj;  // B_o(z), row o·ni + a
    pole.shape.resize(no);
    for (Eigen::Index o = 0; o < no; ++o)
      pole.shape(o) = bz.segment(o * ni, ni).cwiseProduct(v).sum() / red.weight(o);  // Σ_a B_oa(z) v_a
    pole.mpc = modal_phase_collinearity(pole.shape);
    pole.mpd = mean_phase_deviation(pole.shape);
    out.push_back(std::move(pole));
  }
  std::sort(out.begin(), out.end(), [](const IdentifiedPole& a, const IdentifiedPole& b) { return a.hz < b.hz; });
  return out;
}

}  // namespace

std::vector<OrderPoles> plscf_orders(const Eigen::Ref<const Eigen::VectorXd>& frequency_hz,
                                     const std::vector<Eigen::MatrixXcd>& frf, const PlscfOptions& options,
                                     const std::vector<Eigen::Index>& orders, const Progress& progress) {
  if (orders.empty()) throw InputError("pLSCF: no model orders");
  for (std::size_t i = 0; i < orders.size(); ++i) {
    if (orders[i] < 1) throw InputError(fmt::format("pLSCF: model order {} (expected ≥ 1)", orders[i]));
    if (i > 0 && orders[i] <= orders[i - 1])
      throw InputError(fmt::format("pLSCF: order {} listed after order {} (expected increasing orders)", orders[i],
                                   orders[i - 1]));
  }
  const Band b = band_lines(frequency_hz, frf, options, "pLSCF");
  const Eigen::Index P = orders.back(), ni = b.ni, no = b.no;
  const auto nf = static_cast<Eigen::Index>(b.lines.size());
  if (nf <= P + 1)
    throw InputError(fmt::format("pLSCF: {} lines in the band {} … {} Hz are too few for model order {} (needs more "
                                 "than {})",
                                 nf, options.hz_min, options.hz_max, P, P + 1));
  report(progress, "pLSCF normal equations", 0.0);
  const Reduction red = reduce(frequency_hz, frf, b, P);

  // C accumulates Σ_o Σ_{r ≤ p} (row r of G_o)ᵀ(row r of G_o): its leading block is
  // Σ_o S_oᵀR_p⁻¹S_o of order p, because L_p is L's leading block.
  const Eigen::Index n_max = (P + 1) * ni;
  Eigen::MatrixXd C = Eigen::MatrixXd::Zero(n_max, n_max);
  Eigen::Index rows_added = 0;
  std::vector<OrderPoles> out;
  out.reserve(orders.size());
  for (std::size_t i = 0; i < orders.size(); ++i) {
    const Eigen::Index p = orders[i], n = (p + 1) * ni;
    report(progress, "pLSCF orders", static_cast<long>(i), static_cast<long>(orders.size()),
           fmt::format("order {}", p));
    for (; rows_added <= p; ++rows_added)
      C.selfadjointView<Eigen::Lower>().rankUpdate(red.z_rows[static_cast<std::size_t>(rows_added)].transpose());
    // The reduced normal matrix M = Σ_o (T_o − S_oᵀR⁻¹S_o), lower triangle only (C's valid part).
    const Eigen::MatrixXd M = red.t_sum.topLeftCorner(n, n) - C.topLeftCorner(n, n);
    // α_p = I: M_aa α_{0…p−1} = −M_ab, M_ab = M_baᵀ.
    Eigen::MatrixXd alpha(n, ni);
    const Eigen::LDLT<Eigen::MatrixXd, Eigen::Lower> ldlt(M.topLeftCorner(p * ni, p * ni));
    alpha.topRows(p * ni) = -ldlt.solve(M.bottomLeftCorner(ni, p * ni).transpose());
    alpha.bottomRows(ni).setIdentity();
    OrderPoles op{p, {}};
    if (ldlt.info() == Eigen::Success && alpha.allFinite()) {
      // β_o = −R_p⁻¹ S_o α = −L_p⁻ᵀ (G_o α), all responses at once: column o·ni + a.
      Eigen::MatrixXd beta(p + 1, no * ni);
      for (Eigen::Index r = 0; r <= p; ++r) {
        const Eigen::MatrixXd ga = red.z_rows[static_cast<std::size_t>(r)].leftCols(n) * alpha;  // no × ni
        for (Eigen::Index o = 0; o < no; ++o) beta.block(r, o * ni, 1, ni) = -ga.row(o);
      }
      red.chol_l.topLeftCorner(p + 1, p + 1).transpose().triangularView<Eigen::Upper>().solveInPlace(beta);
      op.poles = poles_of(alpha, beta, p, red);
    }
    out.push_back(std::move(op));
  }
  report(progress, "pLSCF orders", static_cast<long>(orders.size()), static_cast<long>(orders.size()));
  return out;
}

std::vector<IdentifiedPole> mode_poles(const StabilisationResult& chosen, const std::vector<OrderPoles>& orders) {
  std::vector<IdentifiedPole> out;
  for (std::size_t m = 0; m < chosen.modes.size(); ++m) {
    const DiagramPole* last = nullptr;
    for (const DiagramPole& d : chosen.diagram)
      if (d.mode == static_cast<int>(m) && (!last || d.order > last->order)) last = &d;
    if (!last) throw InputError(fmt::format("pLSCF: mode {} has no pole in the diagram", m + 1));
    const auto op =
        std::find_if(orders.begin(), orders.end(), [&](const OrderPoles& o) { return o.order == last->order; });
    if (op == orders.end() || last->index >= op->poles.size())
      throw InputError(fmt::format("pLSCF: mode {} refers to order {}, pole {}, which the orders do not have", m + 1,
                                   last->order, last->index + 1));
    out.push_back(op->poles[last->index]);
  }
  return out;
}

LsfdResult lsfd(const Eigen::Ref<const Eigen::VectorXd>& frequency_hz, const std::vector<Eigen::MatrixXcd>& frf,
                const std::vector<IdentifiedPole>& poles, const PlscfOptions& options) {
  const Band b = band_lines(frequency_hz, frf, options, "LSFD");
  const Eigen::Index no = b.no, ni = b.ni, nf = static_cast<Eigen::Index>(b.lines.size());
  const auto nm = static_cast<Eigen::Index>(poles.size());
  if (poles.empty()) throw InputError("LSFD: no pole");
  for (std::size_t r = 0; r < poles.size(); ++r) {
    if (!(poles[r].lambda.imag() > 0))
      throw InputError(fmt::format("LSFD: pole {} is λ = {} {:+}i rad/s (expected Im λ > 0)", r + 1,
                                   poles[r].lambda.real(), poles[r].lambda.imag()));
    if (poles[r].participation.size() != ni)
      throw InputError(fmt::format("LSFD: pole {} has {} participation factors (expected {}, one per reference)", r + 1,
                                   poles[r].participation.size(), ni));
  }
  const Eigen::Index cols = 2 * nm + 2 * ni, rows = 2 * nf * ni;
  if (rows < cols)
    throw InputError(fmt::format("LSFD: {} lines × {} references give {} equations for {} unknowns per response", nf, ni,
                                 rows, cols));
  // Rows: line k, reference j (real part at k·ni + j, imaginary part nf·ni further); columns:
  // Re ψ_r, Im ψ_r per mode, then LR_j, UR_j.
  Eigen::MatrixXd D = Eigen::MatrixXd::Zero(rows, cols), Y(rows, no);
  for (Eigen::Index k = 0; k < nf; ++k) {
    const Eigen::Index line = b.lines[static_cast<std::size_t>(k)];
    const double w = 2 * M_PI * frequency_hz(line);
    const cd iw(0, w);
    for (Eigen::Index j = 0; j < ni; ++j) {
      const Eigen::Index re = k * ni + j, im = re + nf * ni;
      for (Eigen::Index r = 0; r < nm; ++r) {
        const IdentifiedPole& p = poles[static_cast<std::size_t>(r)];
        const cd a = p.participation(j) / (iw - p.lambda);
        const cd c = std::conj(p.participation(j)) / (iw - std::conj(p.lambda));
        const cd on_re = a + c, on_im = cd(0, 1) * (a - c);  // ψ = x + iy: x·(a + c) + y·i(a − c)
        D(re, 2 * r) = on_re.real();
        D(im, 2 * r) = on_re.imag();
        D(re, 2 * r + 1) = on_im.real();
        D(im, 2 * r + 1) = on_im.imag();
      }
      D(re, 2 * nm + j) = -1.0 / (w * w);
      D(re, 2 * nm + ni + j) = 1.0;
      const Eigen::MatrixXcd& h = frf[static_cast<std::size_t>(line)];
      for (Eigen::Index o = 0; o < no; ++o) {
        Y(re, o) = h(o, j).real();
        Y(im, o) = h(o, j).imag();
      }
    }
  }
  // Columns differ by orders of magnitude (1/ω² against resonances): scale them to unit norm.
  Eigen::VectorXd scale = D.colwise().norm().transpose();
  for (Eigen::Index c = 0; c < cols; ++c) scale(c) = scale(c) > 0 ? 1.0 / scale(c) : 1.0;
  const Eigen::MatrixXd Ds = D * scale.asDiagonal();
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(Ds);
  const Eigen::MatrixXd X = scale.asDiagonal() * qr.solve(Y);
  LsfdResult res;
  const double data = Y.norm();
  res.fit_error = data > 0 ? (D * X - Y).norm() / data : 0.0;
  res.lower_residual = X.middleRows(2 * nm, ni).transpose();
  res.upper_residual = X.middleRows(2 * nm + ni, ni).transpose();
  res.modes = poles;
  for (Eigen::Index r = 0; r < nm; ++r) {
    IdentifiedPole& p = res.modes[static_cast<std::size_t>(r)];
    p.shape.resize(no);
    for (Eigen::Index o = 0; o < no; ++o) p.shape(o) = cd(X(2 * r, o), X(2 * r + 1, o));
    p.mpc = modal_phase_collinearity(p.shape);
    p.mpd = mean_phase_deviation(p.shape);
  }
  return res;
}

std::vector<Eigen::MatrixXcd> lsfd_synthesis(const Eigen::Ref<const Eigen::VectorXd>& frequency_hz, const LsfdResult& fit) {
  std::vector<Eigen::MatrixXcd> out;
  out.reserve(static_cast<std::size_t>(frequency_hz.size()));
  for (Eigen::Index k = 0; k < frequency_hz.size(); ++k) {
    const double f = frequency_hz(k);
    if (!(f > 0)) throw InputError(fmt::format("LSFD synthesis: line {} at {} Hz (expected > 0 Hz)", k, f));
    const double w = 2 * M_PI * f;
    const cd iw(0, w);
    Eigen::MatrixXcd h = fit.upper_residual.cast<cd>() - fit.lower_residual.cast<cd>() / (w * w);
    for (const IdentifiedPole& p : fit.modes)
      h += p.shape * p.participation.transpose() / (iw - p.lambda) +
           p.shape.conjugate() * p.participation.adjoint() / (iw - std::conj(p.lambda));
    out.push_back(std::move(h));
  }
  return out;
}

}  // namespace ssid::estimator::identification
