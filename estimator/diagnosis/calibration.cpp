#include "estimator/diagnosis/calibration.hpp"

#include <algorithm>
#include <boost/math/special_functions/beta.hpp>
#include <boost/math/special_functions/gamma.hpp>
#include <cmath>
#include <random>
#include <stdexcept>
#include <string>

#include "formats/parse_error.hpp"

namespace ssid::estimator::diagnosis {

namespace {

/// W_gᵀW_g per group.
void group_gram(const Eigen::MatrixXd& W, const std::vector<int>& group, Eigen::MatrixXd out[kRowGroups]) {
  for (int g = 0; g < kRowGroups; ++g) {
    Eigen::VectorXd mask(W.rows());
    for (Eigen::Index i = 0; i < W.rows(); ++i) mask(i) = group[static_cast<std::size_t>(i)] == g ? 1.0 : 0.0;
    out[g] = W.transpose() * mask.asDiagonal() * W;
  }
}

/// The noise fixed point of the file comment for residual `e` with prior offset `theta`.
NoiseScale noise_fixed_point(const Eigen::MatrixXd& W, const std::vector<int>& group, const Eigen::MatrixXd WW[kRowGroups],
                             const Eigen::Ref<const Eigen::VectorXd>& e, const Eigen::Ref<const Eigen::VectorXd>& theta,
                             bool estimate, int min_dof) {
  NoiseScale ns;
  ns.estimated = estimate;
  const auto p = W.cols();
  for (Eigen::Index i = 0; i < e.size(); ++i) {
    const int g = group[static_cast<std::size_t>(i)];
    ns.rows[g] += 1;
    ns.chi2[g] += e(i) * e(i);
  }
  Eigen::VectorXd We[kRowGroups];
  for (int g = 0; g < kRowGroups; ++g) We[g] = Eigen::VectorXd::Zero(p);
  for (Eigen::Index i = 0; i < e.size(); ++i) We[group[static_cast<std::size_t>(i)]] += W.row(i).transpose() * e(i);
  double c[kRowGroups] = {1.0, 1.0};
  for (int iter = 0; iter < 100; ++iter) {
    Eigen::MatrixXd H = Eigen::MatrixXd::Identity(p, p);
    Eigen::VectorXd b = -theta;
    for (int g = 0; g < kRowGroups; ++g) {
      H += c[g] * WW[g];
      b += c[g] * We[g];
    }
    const Eigen::LDLT<Eigen::MatrixXd> Hl(H);
    const Eigen::VectorXd delta = Hl.solve(b);
    const Eigen::VectorXd r = e - W * delta;
    double rss[kRowGroups] = {0.0, 0.0};
    for (Eigen::Index i = 0; i < r.size(); ++i) rss[group[static_cast<std::size_t>(i)]] += r(i) * r(i);
    for (int g = 0; g < kRowGroups; ++g)
      ns.dof[g] = ns.rows[g] - c[g] * (p > 0 ? Hl.solve(WW[g]).trace() : 0.0);
    if (!estimate) break;
    double next[kRowGroups];
    bool pooled = false;
    for (int g = 0; g < kRowGroups; ++g)
      if (ns.rows[g] > 0 && ns.dof[g] < min_dof) pooled = true;
    double rss_all = 0, dof_all = 0;
    for (int g = 0; g < kRowGroups; ++g) {
      rss_all += rss[g];
      dof_all += ns.dof[g];
    }
    if (!(dof_all > 0))
      throw formats::InputError("cannot estimate the measurement noise: the fit of the deck's parameters leaves no degree of "
                                "freedom in the " + std::to_string(ns.rows[0] + ns.rows[1]) +
                                " measured values (give the noise instead: --noise given, study \"noise\": \"given\")");
    for (int g = 0; g < kRowGroups; ++g) {
      const double s2 = pooled || ns.rows[g] == 0 ? rss_all / dof_all : rss[g] / ns.dof[g];
      next[g] = s2 > 0 ? 1.0 / s2 : 1.0;
    }
    ns.pooled = pooled;
    const double change = std::max(std::abs(next[0] / c[0] - 1.0), std::abs(next[1] / c[1] - 1.0));
    c[0] = next[0];
    c[1] = next[1];
    if (change < 1e-12) break;
  }
  for (int g = 0; g < kRowGroups; ++g) ns.scale[g] = estimate ? 1.0 / std::sqrt(c[g]) : 1.0;
  return ns;
}

}  // namespace

int LinearUpdate::blocks() const {
  int n = 0;
  for (int b : block) n = std::max(n, b + 1);
  return n;
}

NoiseScale estimate_noise(const LinearUpdate& lu, const Eigen::Ref<const Eigen::VectorXd>& e, bool estimate, int min_dof) {
  Eigen::MatrixXd WW[kRowGroups];
  group_gram(lu.W, lu.group, WW);
  return noise_fixed_point(lu.W, lu.group, WW, e, lu.theta, estimate, min_dof);
}

double chi2_upper_tail(double chi2, double dof) {
  if (!(dof > 0)) return 1.0;
  return boost::math::gamma_q(0.5 * dof, 0.5 * std::max(chi2, 0.0));
}

double chi2_quantile_upper(double p, double dof) {
  if (!(dof > 0) || !(p > 0 && p < 1)) throw std::invalid_argument("chi2_quantile_upper: needs dof > 0 and 0 < p < 1");
  return 2.0 * boost::math::gamma_q_inv(0.5 * dof, p);
}

double tail_upper_bound(int exceed, int replicates, double confidence) {
  if (replicates <= 0 || exceed >= replicates) return 1.0;
  return boost::math::ibeta_inv(static_cast<double>(exceed + 1), static_cast<double>(replicates - exceed), confidence);
}

Screening::Screening(LinearUpdate null, Eigen::MatrixXd candidates, CalibrationOptions options)
    : m_null(std::move(null)), m_U(std::move(candidates)), m_opt(options) {
  const auto m = m_null.e.size();
  if (m_null.W.rows() != m || m_U.rows() != m || static_cast<Eigen::Index>(m_null.group.size()) != m ||
      static_cast<Eigen::Index>(m_null.block.size()) != m || m_null.theta.size() != m_null.W.cols())
    throw std::invalid_argument("Screening: the residual, sensitivities, candidates and row labels disagree in size");
  m_mask = Eigen::MatrixXd::Zero(m, kRowGroups);
  for (Eigen::Index i = 0; i < m; ++i) m_mask(i, m_null.group[static_cast<std::size_t>(i)]) = 1.0;
  group_gram(m_null.W, m_null.group, m_WW);
  m_A.resize(m_U.cols(), kRowGroups);
  for (int g = 0; g < kRowGroups; ++g) {
    const Eigen::MatrixXd Ug = m_mask.col(g).asDiagonal() * m_U;
    m_A.col(g) = Ug.colwise().squaredNorm().transpose();
    m_B[g] = m_null.W.transpose() * Ug;
  }
  m_noise = noise_fixed_point(m_null.W, m_null.group, m_WW, m_null.e, m_null.theta, m_opt.estimate_noise, m_opt.min_dof);
  const Fit f = fit(m_null.e, m_null.theta, m_noise);
  m_gains = gains_from(f, group_products(f.e));
}

Screening::Fit Screening::fit(const Eigen::Ref<const Eigen::VectorXd>& e, const Eigen::Ref<const Eigen::VectorXd>& theta,
                              const NoiseScale& ns) const {
  const auto p = m_null.W.cols();
  Fit f;
  Eigen::MatrixXd H = Eigen::MatrixXd::Identity(p, p);
  Eigen::VectorXd b = -theta;
  for (int g = 0; g < kRowGroups; ++g) {
    f.c[g] = 1.0 / (ns.scale[g] * ns.scale[g]);
    H += f.c[g] * m_WW[g];
    b += f.c[g] * (m_null.W.transpose() * m_mask.col(g).cwiseProduct(e));
  }
  f.H.compute(H);
  f.e = e - m_null.W * f.H.solve(b);
  for (int g = 0; g < kRowGroups; ++g) {
    const Eigen::VectorXd eg = m_mask.col(g).cwiseProduct(f.e);
    f.rss[g] = eg.squaredNorm();
    f.We[g] = m_null.W.transpose() * eg;
    f.dof[g] = ns.rows[g] - f.c[g] * (p > 0 ? f.H.solve(m_WW[g]).trace() : 0.0);
  }
  return f;
}

Eigen::MatrixXd Screening::group_products(const Eigen::Ref<const Eigen::VectorXd>& e) const {
  Eigen::MatrixXd out(m_U.cols(), kRowGroups);
  for (int g = 0; g < kRowGroups; ++g) out.col(g) = m_U.transpose() * m_mask.col(g).cwiseProduct(e);
  return out;
}

Eigen::VectorXd Screening::gains_from(const Fit& f, const Eigen::Ref<const Eigen::MatrixXd>& Ute) const {
  const auto K = m_U.cols();
  const auto p = m_null.W.cols();
  Eigen::VectorXd G(K);
  for (Eigen::Index k = 0; k < K; ++k) {
    Eigen::VectorXd b = Eigen::VectorXd::Zero(p);
    double a = 0, g = 0;
    for (int q = 0; q < kRowGroups; ++q) {
      b += f.c[q] * m_B[q].col(k);
      a += f.c[q] * m_A(k, q);
      g += f.c[q] * Ute(k, q);
    }
    const Eigen::VectorXd h = p > 0 ? Eigen::VectorXd(f.H.solve(b)) : Eigen::VectorXd();
    const double s = std::max(a - (p > 0 ? b.dot(h) : 0.0), 0.0);
    if (!m_opt.estimate_noise) {  // the assumed σ is the noise: the Gaussian evidence gain
      G(k) = 0.5 * g * g / (s + 1.0) - 0.5 * std::log1p(s);
      continue;
    }
    const double beta = g / (s + 1.0);
    double gain = -0.5 * std::log1p(s);
    for (int q = 0; q < kRowGroups; ++q) {
      if (!(f.rss[q] > 0) || !(f.dof[q] > 0)) continue;
      const double ue = Ute(k, q) - (p > 0 ? h.dot(f.We[q]) : 0.0);
      const double uu = m_A(k, q) - (p > 0 ? 2.0 * h.dot(m_B[q].col(k)) - h.dot(m_WW[q] * h) : 0.0);
      const double rss1 = f.rss[q] - 2.0 * beta * ue + beta * beta * std::max(uu, 0.0);
      gain -= 0.5 * f.dof[q] * std::log(std::max(rss1, 1e-12 * f.rss[q]) / f.rss[q]);
    }
    G(k) = gain;
  }
  return G;
}

Eigen::VectorXd Screening::gains_for(const Eigen::Ref<const Eigen::VectorXd>& e) const {
  const NoiseScale ns = noise_fixed_point(m_null.W, m_null.group, m_WW, e, m_null.theta, m_opt.estimate_noise, m_opt.min_dof);
  const Fit f = fit(e, m_null.theta, ns);
  return gains_from(f, group_products(f.e));
}

const std::vector<double>& Screening::bootstrap() {
  const auto m = m_null.e.size();
  const auto p = m_null.W.cols();
  const int B = m_opt.replicates;
  m_maxima.clear();
  if (B <= 0 || m_U.cols() == 0) return m_maxima;
  // The fit the update makes on a replicate: (I + WᵀW) δ = Wᵀε − θ*.
  const Eigen::LDLT<Eigen::MatrixXd> H0(Eigen::MatrixXd::Identity(p, p) + m_WW[0] + m_WW[1]);
  std::mt19937_64 rng(m_opt.seed);
  std::normal_distribution<double> n01(0.0, 1.0);
  Eigen::MatrixXd Ec(m, B);      // each replicate's e(C)
  std::vector<Fit> fits;
  fits.reserve(static_cast<std::size_t>(B));
  for (int b = 0; b < B; ++b) {
    Eigen::VectorXd eps(m);
    for (Eigen::Index i = 0; i < m; ++i) eps(i) = m_noise.scale[m_null.group[static_cast<std::size_t>(i)]] * n01(rng);
    const Eigen::VectorXd delta = p > 0 ? Eigen::VectorXd(H0.solve(m_null.W.transpose() * eps - m_null.theta))
                                        : Eigen::VectorXd(Eigen::VectorXd::Zero(0));
    const Eigen::VectorXd eb = p > 0 ? Eigen::VectorXd(eps - m_null.W * delta) : eps;
    const Eigen::VectorXd theta_b = m_null.theta + delta;
    const NoiseScale ns = noise_fixed_point(m_null.W, m_null.group, m_WW, eb, theta_b, m_opt.estimate_noise, m_opt.min_dof);
    fits.push_back(fit(eb, theta_b, ns));
    Ec.col(b) = fits.back().e;
  }
  // U_gᵀ e_g(C) of every replicate at once.
  Eigen::MatrixXd Ute[kRowGroups];
  for (int g = 0; g < kRowGroups; ++g) Ute[g] = m_U.transpose() * (m_mask.col(g).asDiagonal() * Ec);
  for (int b = 0; b < B; ++b) {
    Eigen::MatrixXd prod(m_U.cols(), kRowGroups);
    for (int g = 0; g < kRowGroups; ++g) prod.col(g) = Ute[g].col(b);
    m_maxima.push_back(gains_from(fits[static_cast<std::size_t>(b)], prod).maxCoeff());
  }
  std::sort(m_maxima.begin(), m_maxima.end());
  return m_maxima;
}

int Screening::exceedances(double G) const {
  return static_cast<int>(m_maxima.end() - std::lower_bound(m_maxima.begin(), m_maxima.end(), G));
}

double Screening::false_alarm(double G) const {
  return (1.0 + exceedances(G)) / (static_cast<double>(m_maxima.size()) + 1.0);
}

HeldOutGain Screening::held_out(int k) const {
  const auto m = m_null.e.size();
  const auto p = m_null.W.cols();
  double c[kRowGroups];
  for (int g = 0; g < kRowGroups; ++g) c[g] = 1.0 / (m_noise.scale[g] * m_noise.scale[g]);
  Eigen::VectorXd cw(m);
  for (Eigen::Index i = 0; i < m; ++i) cw(i) = c[m_null.group[static_cast<std::size_t>(i)]];
  // Rows of each paired mode.
  std::vector<std::vector<Eigen::Index>> rows(static_cast<std::size_t>(m_null.blocks()));
  for (Eigen::Index i = 0; i < m; ++i) rows[static_cast<std::size_t>(m_null.block[static_cast<std::size_t>(i)])].push_back(i);
  auto cv = [&](const Eigen::MatrixXd& X, const Eigen::VectorXd& theta, double out[kRowGroups]) {
    const auto q = X.cols();
    const Eigen::MatrixXd A = Eigen::MatrixXd::Identity(q, q) + X.transpose() * cw.asDiagonal() * X;
    const Eigen::VectorXd b = X.transpose() * cw.cwiseProduct(m_null.e) - theta;
    out[0] = out[1] = 0;
    for (const auto& idx : rows) {
      if (idx.empty()) continue;
      Eigen::MatrixXd Xi(static_cast<Eigen::Index>(idx.size()), q);
      Eigen::VectorXd ei(static_cast<Eigen::Index>(idx.size())), ci(static_cast<Eigen::Index>(idx.size()));
      for (std::size_t r = 0; r < idx.size(); ++r) {
        Xi.row(static_cast<Eigen::Index>(r)) = X.row(idx[r]);
        ei(static_cast<Eigen::Index>(r)) = m_null.e(idx[r]);
        ci(static_cast<Eigen::Index>(r)) = cw(idx[r]);
      }
      const Eigen::MatrixXd Ai = A - Xi.transpose() * ci.asDiagonal() * Xi;
      const Eigen::VectorXd bi = b - Xi.transpose() * ci.cwiseProduct(ei);
      const Eigen::VectorXd ri = ei - Xi * Ai.ldlt().solve(bi);
      for (std::size_t r = 0; r < idx.size(); ++r)
        out[m_null.group[static_cast<std::size_t>(idx[r])]] += ci(static_cast<Eigen::Index>(r)) * ri(static_cast<Eigen::Index>(r)) *
                                                                 ri(static_cast<Eigen::Index>(r));
    }
  };
  HeldOutGain h;
  double null_cv[kRowGroups], ext_cv[kRowGroups];
  cv(m_null.W, m_null.theta, null_cv);
  Eigen::MatrixXd X(m, p + 1);
  X << m_null.W, m_U.col(k);
  Eigen::VectorXd theta(p + 1);
  theta << m_null.theta, 0.0;
  cv(X, theta, ext_cv);
  for (int g = 0; g < kRowGroups; ++g) {
    h.null_cv[g] = null_cv[g];
    h.gain[g] = null_cv[g] - ext_cv[g];
  }
  return h;
}

}  // namespace ssid::estimator::diagnosis
