#include "estimator/identification/armax.hpp"

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "formats/parse_error.hpp"

namespace ssid::estimator::identification {

namespace {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;
using MatrixList = std::vector<MatrixXd>;

constexpr double kPi = 3.14159265358979323846;

/// Least-squares solution of  G X ≈ T  by Householder QR with column pivoting
/// (the normal equations of the paper, Eq. 30, 37, 48, 54, squared the condition
/// number; the QR solves the same minimisation without forming them).
MatrixXd least_squares(const MatrixXd& G, const MatrixXd& T) { return G.colPivHouseholderQr().solve(T); }

/// Each column divided by its RMS so that the regressions weigh forces and
/// responses of very different magnitudes alike (and the outputs' equal-variance
/// noise assumption, Eq. 21, holds for noise proportional to the signal).
VectorXd column_rms(const MatrixXd& X) {
  VectorXd s(X.cols());
  for (Index j = 0; j < X.cols(); ++j) {
    s(j) = std::sqrt(X.col(j).squaredNorm() / static_cast<double>(X.rows()));
    if (!(s(j) > 0) || !std::isfinite(s(j)))
      throw formats::InputError("ARMAX: record " + std::to_string(j + 1) + " is zero or not finite");
  }
  return s;
}

/// Step 1 (Eq. 28–33): the prior ARX model of order m,
///   x_n + Σ_{k=1}^{m} Â_k x_{n−k} = Σ_{l=0}^{m} B̂_l f_{n−l} + e_n,
/// fitted over n = m … r−1. Returns Â_0 … Â_m.
MatrixList prior_arx(const MatrixXd& x, const MatrixXd& f, int m) {
  const Index r = x.rows(), p = x.cols(), q = f.cols();
  const Index rows = r - m;
  MatrixXd G(rows, m * p + (m + 1) * q);
  MatrixXd T(rows, p);
  for (Index i = 0; i < rows; ++i) {
    const Index n = i + m;
    for (Index k = 1; k <= m; ++k) G.block(i, (k - 1) * p, 1, p) = -x.row(n - k);
    for (Index l = 0; l <= m; ++l) G.block(i, m * p + l * q, 1, q) = f.row(n - l);
    T.row(i) = x.row(n);
  }
  const MatrixXd theta = least_squares(G, T);
  MatrixList a_hat(static_cast<std::size_t>(m + 1));
  a_hat[0] = MatrixXd::Identity(p, p);
  for (Index k = 1; k <= m; ++k) a_hat[static_cast<std::size_t>(k)] = theta.block((k - 1) * p, 0, p, p).transpose();
  return a_hat;
}

/// Â_n, zero outside 0 … m.
MatrixXd coefficient(const MatrixList& a, Index n, Index p) {
  if (n < 0 || n >= static_cast<Index>(a.size())) return MatrixXd::Zero(p, p);
  return a[static_cast<std::size_t>(n)];
}

/// Step 2 (Eq. 35–37): C⁽¹⁾ with C_0 = Ĉ_0 = I making C(z)Â(z) a polynomial of
/// degree s, i.e. the coefficients n = s+1 … m+s of the product vanish in the
/// least-squares sense: Σ_{l=1}^{s} C_l Â_{n−l} ≈ −Â_n. (A⁽¹⁾ would be the
/// product's first s coefficients; step 3 re-estimates it from the data.)
MatrixList initial_ma(const MatrixList& a_hat, int s) {
  const Index p = a_hat[0].rows();
  const Index m = static_cast<Index>(a_hat.size()) - 1;
  const Index rows = m * p;
  MatrixXd G = MatrixXd::Zero(rows, s * p);
  MatrixXd T(rows, p);
  for (Index i = 0; i < m; ++i) {
    const Index n = s + 1 + i;
    for (Index l = 1; l <= s; ++l) G.block(i * p, (l - 1) * p, p, p) = coefficient(a_hat, n - l, p).transpose();
    T.block(i * p, 0, p, p) = -coefficient(a_hat, n, p).transpose();
  }
  const MatrixXd X = least_squares(G, T);
  MatrixList c(static_cast<std::size_t>(s + 1));
  c[0] = MatrixXd::Identity(p, p);
  for (Index l = 1; l <= s; ++l) c[static_cast<std::size_t>(l)] = X.block((l - 1) * p, 0, p, p).transpose();
  return c;
}

/// Block companion matrix of z^s I + P_1 z^{s−1} + … + P_s (P_0 must be I); its
/// eigenvalues are the roots of det(Σ P_k z^{−k}) = 0.
MatrixXd companion(const MatrixList& P) {
  const Index p = P[0].rows();
  const Index s = static_cast<Index>(P.size()) - 1;
  MatrixXd L = MatrixXd::Zero(s * p, s * p);
  for (Index k = 1; k <= s; ++k) L.block(0, (k - 1) * p, p, p) = -P[static_cast<std::size_t>(k)];
  if (s > 1) L.block(p, 0, (s - 1) * p, (s - 1) * p).setIdentity();
  return L;
}

/// C(z)⁻¹ must be a stable filter (prefiltering, Eq. 40, runs it forward). Roots of
/// det C(z) on or outside the unit circle are pulled inside by the radial scaling
/// C_k → C_k ρ^k (roots → ρ·roots), which keeps C_0 and the shape of C(z).
void stabilise_ma(MatrixList& c) {
  MatrixList monic(c.size());
  const MatrixXd c0_inv = c[0].inverse();
  for (std::size_t k = 0; k < c.size(); ++k) monic[k] = c0_inv * c[k];
  const Eigen::VectorXcd roots = Eigen::EigenSolver<MatrixXd>(companion(monic), false).eigenvalues();
  const double largest = roots.size() > 0 ? roots.cwiseAbs().maxCoeff() : 0.0;
  constexpr double kMaxRadius = 0.995;
  if (largest < kMaxRadius) return;
  const double rho = kMaxRadius / largest;
  double scale = 1;
  for (auto& ck : c) {
    ck *= scale;
    scale *= rho;
  }
}

/// Step 3a (Eq. 40, 45–46): Q = C(z)⁻¹ R for a vector sequence R (columns = time):
///   C_0 Q_n = R_n − Σ_{k=1}^{s} C_k Q_{n−k},  Q_n = 0 for n < 0.
MatrixXd prefilter(const MatrixList& c, const Eigen::PartialPivLU<MatrixXd>& c0, const MatrixXd& R) {
  const Index s = static_cast<Index>(c.size()) - 1;
  MatrixXd Q(R.rows(), R.cols());
  for (Index n = 0; n < R.cols(); ++n) {
    VectorXd rhs = R.col(n);
    for (Index k = 1; k <= std::min(s, n); ++k) rhs.noalias() -= c[static_cast<std::size_t>(k)] * Q.col(n - k);
    Q.col(n) = c0.solve(rhs);
  }
  return Q;
}

/// Step 3 (Eq. 41–50): A_1 … A_s and B_0 … B_{s−1} minimising the prefiltered error
///   Σ_n ‖ Σ_α U_αα(n) + Σ_{k,α,β} A_{k,αβ} U_αβ(n−k) − Σ_{l,γ,δ} B_{l,γδ} V_γδ(n−l) ‖²
/// with U_αβ = C⁻¹ u_α x_β and V_γδ = C⁻¹ u_γ f_δ (u_α the α-th unit vector).
/// Returns that minimum per sample (ε_ML of Eq. 47).
double update_ar_exo(const MatrixXd& x, const MatrixXd& f, const MatrixList& c, int s, MatrixList& a,
                     MatrixList& b) {
  const Index r = x.rows(), p = x.cols(), q = f.cols();
  const Eigen::PartialPivLU<MatrixXd> c0(c[0]);
  // U[α + p β] and V[γ + p δ]: p × r sequences.
  std::vector<MatrixXd> U(static_cast<std::size_t>(p * p)), V(static_cast<std::size_t>(p * q));
  for (Index beta = 0; beta < p; ++beta)
    for (Index alpha = 0; alpha < p; ++alpha) {
      MatrixXd R = MatrixXd::Zero(p, r);
      R.row(alpha) = x.col(beta).transpose();
      U[static_cast<std::size_t>(alpha + p * beta)] = prefilter(c, c0, R);
    }
  for (Index delta = 0; delta < q; ++delta)
    for (Index gamma = 0; gamma < p; ++gamma) {
      MatrixXd R = MatrixXd::Zero(p, r);
      R.row(gamma) = f.col(delta).transpose();
      V[static_cast<std::size_t>(gamma + p * delta)] = prefilter(c, c0, R);
    }
  const Index n_a = s * p * p, n_b = s * p * q;
  const Index first = s, samples = r - first;
  MatrixXd G(samples * p, n_a + n_b);
  VectorXd T(samples * p);
  for (Index i = 0; i < samples; ++i) {
    const Index n = first + i;
    auto rows = G.middleRows(i * p, p);
    // Column order of Eq. 49–50: k, then β, then α (A_{k,αβ}); l, then δ, then γ.
    for (Index k = 1; k <= s; ++k)
      for (Index ab = 0; ab < p * p; ++ab) rows.col((k - 1) * p * p + ab) = U[static_cast<std::size_t>(ab)].col(n - k);
    for (Index l = 0; l < s; ++l)
      for (Index gd = 0; gd < p * q; ++gd)
        rows.col(n_a + l * p * q + gd) = -V[static_cast<std::size_t>(gd)].col(n - l);
    VectorXd t = VectorXd::Zero(p);
    for (Index alpha = 0; alpha < p; ++alpha) t += U[static_cast<std::size_t>(alpha + p * alpha)].col(n);
    T.segment(i * p, p) = -t;
  }
  const VectorXd z = least_squares(G, T);
  a.assign(static_cast<std::size_t>(s + 1), MatrixXd::Zero(p, p));
  a[0] = MatrixXd::Identity(p, p);
  for (Index k = 1; k <= s; ++k)
    a[static_cast<std::size_t>(k)] = Eigen::Map<const MatrixXd>(z.data() + (k - 1) * p * p, p, p);
  b.assign(static_cast<std::size_t>(s), MatrixXd::Zero(p, q));
  for (Index l = 0; l < s; ++l)
    b[static_cast<std::size_t>(l)] = Eigen::Map<const MatrixXd>(z.data() + n_a + l * p * q, p, q);
  // ε_ML per sample, in the units of the scaled records.
  return (G * z - T).squaredNorm() / static_cast<double>(samples);
}

/// Step 4 (Eq. 51–54): W_n = Â_n − Σ_{k=1}^{s} W_{n−k} A_k (n = 0 … q, Eq. 53), then
/// C_0 … C_s minimising Σ_n ‖Σ_k C_k W_{n−k} − δ_{n0} I‖² (Eq. 54).
MatrixList update_ma(const MatrixList& a_hat, const MatrixList& a, int s, int q) {
  const Index p = a[0].rows();
  MatrixList w(static_cast<std::size_t>(q + 1));
  for (Index n = 0; n <= q; ++n) {
    MatrixXd wn = coefficient(a_hat, n, p);
    for (Index k = 1; k <= std::min<Index>(s, n); ++k)
      wn.noalias() -= w[static_cast<std::size_t>(n - k)] * a[static_cast<std::size_t>(k)];
    w[static_cast<std::size_t>(n)] = std::move(wn);
  }
  const Index blocks = q + s + 1;
  MatrixXd G = MatrixXd::Zero(blocks * p, (s + 1) * p);
  MatrixXd T = MatrixXd::Zero(blocks * p, p);
  for (Index n = 0; n < blocks; ++n)
    for (Index k = 0; k <= s; ++k)
      if (n - k >= 0 && n - k <= q) G.block(n * p, k * p, p, p) = w[static_cast<std::size_t>(n - k)].transpose();
  T.topRows(p).setIdentity();
  const MatrixXd X = least_squares(G, T);
  MatrixList c(static_cast<std::size_t>(s + 1));
  for (Index k = 0; k <= s; ++k) c[static_cast<std::size_t>(k)] = X.block(k * p, 0, p, p).transpose();
  return c;
}

void check_input(const Eigen::Ref<const MatrixXd>& outputs, const Eigen::Ref<const MatrixXd>& inputs, double dt,
                 const ArmaxOptions& o) {
  using formats::InputError;
  if (outputs.cols() < 1) throw InputError("ARMAX: no response records");
  if (inputs.cols() < 1) throw InputError("ARMAX: no force records");
  if (outputs.rows() != inputs.rows())
    throw InputError("ARMAX: " + std::to_string(outputs.rows()) + " response samples but " +
                     std::to_string(inputs.rows()) + " force samples; the records must have the same length");
  if (!(dt > 0) || !std::isfinite(dt)) throw InputError("ARMAX: the sampling interval must be positive");
  if (o.ar_order < 1) throw InputError("ARMAX: the AR order s must be at least 1");
  if (o.arx_order < o.ar_order)
    throw InputError("ARMAX: the prior ARX order m (" + std::to_string(o.arx_order) +
                     ") must be at least the AR order s (" + std::to_string(o.ar_order) + ")");
  if (o.ma_impulse_length < o.arx_order)
    throw InputError("ARMAX: q (" + std::to_string(o.ma_impulse_length) + ") must be at least m (" +
                     std::to_string(o.arx_order) + ")");
  if (o.max_iterations < 1) throw InputError("ARMAX: at least one pass of steps 3-4 is needed");
  const Index p = outputs.cols(), q = inputs.cols(), r = outputs.rows();
  const Index arx_unknowns = o.arx_order * p + (o.arx_order + 1) * q;
  if (r - o.arx_order < 2 * arx_unknowns)
    throw InputError("ARMAX: " + std::to_string(r) + " samples are too few for a prior ARX model of order " +
                     std::to_string(o.arx_order) + " (" + std::to_string(arx_unknowns) +
                     " unknowns per output; at least twice as many equations are required)");
}

}  // namespace

double armax_memory_bytes(Eigen::Index samples, Eigen::Index outputs, Eigen::Index inputs, int ar_order) {
  const double r = static_cast<double>(samples), p = static_cast<double>(outputs), q = static_cast<double>(inputs);
  return sizeof(double) * r * p * (p * p + p * q + ar_order * p * (p + q));
}

std::vector<ArmaxPole> armax_poles(const std::vector<Eigen::MatrixXd>& ar, double dt) {
  const Index p = ar.at(0).rows();
  const Index s = static_cast<Index>(ar.size()) - 1;
  std::vector<ArmaxPole> poles;
  if (s < 1) return poles;
  const Eigen::VectorXcd roots = Eigen::EigenSolver<MatrixXd>(companion(ar), false).eigenvalues();
  for (Index i = 0; i < roots.size(); ++i) {
    const std::complex<double> z = roots(i);
    const bool real = std::abs(z.imag()) <= 1e-12 * std::max(1.0, std::abs(z));
    if (!real && z.imag() < 0) continue;  // the conjugate of a pole listed once
    ArmaxPole pole;
    pole.z = real ? std::complex<double>(z.real(), 0) : z;
    pole.real = real;
    const std::complex<double> lambda_dt = std::log(pole.z);  // λΔt, Eq. 12
    pole.hz = std::abs(lambda_dt) / (2 * kPi * dt);
    // z = 0 (an infinitely fast real decay) has no finite frequency.
    pole.zeta = std::isfinite(pole.hz) ? -lambda_dt.real() / std::abs(lambda_dt) : 1.0;
    // Shape: the null vector of A(z) = Σ A_k z^{−k}, the right singular vector of its
    // smallest singular value.
    Eigen::MatrixXcd A = Eigen::MatrixXcd::Zero(p, p);
    std::complex<double> zk = 1;
    for (Index k = 0; k <= s; ++k) {
      A += ar[static_cast<std::size_t>(k)].cast<std::complex<double>>() * zk;
      zk /= pole.z;
    }
    const Eigen::JacobiSVD<Eigen::MatrixXcd> svd(A, Eigen::ComputeFullV);
    Eigen::VectorXcd phi = svd.matrixV().col(p - 1);
    Index big = 0;
    phi.cwiseAbs().maxCoeff(&big);
    pole.shape = phi / phi(big);
    poles.push_back(std::move(pole));
  }
  std::sort(poles.begin(), poles.end(), [](const ArmaxPole& a, const ArmaxPole& b) { return a.hz < b.hz; });
  return poles;
}

ArmaxModel identify_armax(const Eigen::Ref<const Eigen::MatrixXd>& outputs,
                          const Eigen::Ref<const Eigen::MatrixXd>& inputs, double dt, const ArmaxOptions& options) {
  check_input(outputs, inputs, dt, options);
  const int s = options.ar_order;
  // Work on records scaled to unit RMS; x = S_x x̃, f = S_f f̃ gives
  // A_k = S_x Ã_k S_x⁻¹, B_l = S_x B̃_l S_f⁻¹, C_k = S_x C̃_k S_x⁻¹ (same roots).
  const VectorXd sx = column_rms(outputs), sf = column_rms(inputs);
  const MatrixXd x = outputs * sx.cwiseInverse().asDiagonal();
  const MatrixXd f = inputs * sf.cwiseInverse().asDiagonal();

  const MatrixList a_hat = prior_arx(x, f, options.arx_order);  // step 1
  MatrixList c = initial_ma(a_hat, s);                           // step 2
  // Steps 3–4 alternate until the maximum-likelihood error ε_ML (Eq. 22, the
  // prefiltered residual of step 3) is stationary: two passes within the relative
  // tolerance. It is not monotone (the first passes can raise it while C(z) is still
  // far off), and once stationary the over-specified noise roots of A and C keep
  // drifting toward cancelling each other on the unit circle while the structural
  // roots stay put, so the iteration stops there. Without convergence the pass with
  // the lowest ε_ML is kept.
  MatrixList a, b, best_a, best_b, best_c;
  double best_eps = std::numeric_limits<double>::infinity();
  double previous_eps = std::numeric_limits<double>::quiet_NaN();
  ArmaxModel model;
  for (int it = 1; it <= options.max_iterations; ++it) {
    stabilise_ma(c);
    const double eps = update_ar_exo(x, f, c, s, a, b);  // step 3
    model.iterations = it;
    const bool stationary = std::isfinite(eps) && std::abs(eps - previous_eps) <= options.tolerance * previous_eps;
    if (stationary || (std::isfinite(eps) && eps < best_eps)) {
      best_eps = eps;
      best_a = a;
      best_b = b;
      best_c = c;
    }
    if (stationary) {
      model.converged = true;
      break;
    }
    previous_eps = eps;
    if (it < options.max_iterations) c = update_ma(a_hat, a, s, options.ma_impulse_length);  // step 4
  }
  if (!std::isfinite(best_eps))
    throw formats::NumericalError("ARMAX: the prefiltered least-squares fit of step 3 did not give a finite error");
  model.ml_error = best_eps;

  const auto Sx = sx.asDiagonal();
  const MatrixXd Sx_inv = sx.cwiseInverse().asDiagonal();
  const MatrixXd Sf_inv = sf.cwiseInverse().asDiagonal();
  for (auto& ak : best_a) model.ar.push_back(Sx * ak * Sx_inv);
  for (auto& bl : best_b) model.exo.push_back(Sx * bl * Sf_inv);
  for (auto& ck : best_c) model.ma.push_back(Sx * ck * Sx_inv);
  model.poles = armax_poles(model.ar, dt);
  return model;
}

}  // namespace ssid::estimator::identification
