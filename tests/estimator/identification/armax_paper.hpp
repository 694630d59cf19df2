#pragma once
/// The simulated systems of the seed's ARMAX paper (seed report, Appendix A, "ARMAX
/// Identification of Vibrating Structures", Fig. 2 and Tables 1-9): the lumped chains,
/// their sampled records (white force on mass 1, noisy displacements) and their exact
/// modes from Eigen's eigenvalues. Shared by the estimator's ARMAX tests and the CLI's.
#include <Eigen/Dense>
#include <unsupported/Eigen/MatrixFunctions>
#include <cmath>
#include <complex>
#include <cstdint>
#include <random>
#include <vector>

namespace armax_test {

using Eigen::MatrixXd;
using Eigen::VectorXd;

inline constexpr double kPi = 3.14159265358979323846;

/// Standard normal numbers by Box–Muller on std::mt19937_64, the same sequence on
/// every standard library (std::normal_distribution's is not).
class NormalSequence {
 public:
  explicit NormalSequence(std::uint64_t seed) : m_rng(seed) {}
  double operator()() {
    if (m_has_spare) {
      m_has_spare = false;
      return m_spare;
    }
    const double u1 = (static_cast<double>(m_rng() >> 11) + 1.0) * 0x1.0p-53;  // (0, 1]
    const double u2 = static_cast<double>(m_rng() >> 11) * 0x1.0p-53;          // [0, 1)
    const double radius = std::sqrt(-2.0 * std::log(u1));
    m_spare = radius * std::sin(2 * kPi * u2);
    m_has_spare = true;
    return radius * std::cos(2 * kPi * u2);
  }

 private:
  std::mt19937_64 m_rng;
  bool m_has_spare = false;
  double m_spare = 0;
};

/// The paper's Fig. 2: N equal masses m, each tied to ground by a spring k and a
/// dashpot c, neighbours coupled by springs k_c. `ends_kc`: masses 1 and N also tied
/// to ground by k_c (the aperiodic 6-DOF case, k_1 = k_6 = k + k_c); `periodic`:
/// masses 1 and N coupled by k_c (the periodic case).
///
/// The paper gives k_c = 2e5 N/m and the exact frequencies and dampings, not m, k,
/// c; they follow from its Tables: every case has √(k/m)/2π = 977.47 Hz (the 2-DOF
/// first mode; k_c/k = 0.4651 from the periodic 1183.15/977.47 ratio) and
/// ζ·ω = c/2m = 63.29 s⁻¹ (Tables 2, 5, 8). m = 0.0114 kg, k = 4.3e5 N/m and
/// c = 1.443 N·s/m reproduce every "Exact" entry to the digits printed (checked
/// below). The 2-DOF case has k = k_c.
struct Lumped {
  MatrixXd M, C, K;
};

inline constexpr double kMass = 0.0114, kGround = 4.3e5, kCoupling = 2e5, kDashpot = 1.443;

inline Lumped lumped_system(int n, double kc, bool ends_kc, bool periodic) {
  Lumped s;
  s.M = kMass * MatrixXd::Identity(n, n);
  s.C = kDashpot * MatrixXd::Identity(n, n);
  s.K = kGround * MatrixXd::Identity(n, n);
  const auto spring = [&](int i, int j) {
    s.K(i, i) += kc;
    s.K(j, j) += kc;
    s.K(i, j) -= kc;
    s.K(j, i) -= kc;
  };
  for (int i = 0; i + 1 < n; ++i) spring(i, i + 1);
  if (periodic) spring(0, n - 1);
  if (ends_kc) {
    s.K(0, 0) += kc;
    s.K(n - 1, n - 1) += kc;
  }
  return s;
}

inline MatrixXd state_matrix(const Lumped& s) {
  const Eigen::Index n = s.M.rows();
  const MatrixXd Minv = s.M.inverse();
  MatrixXd A = MatrixXd::Zero(2 * n, 2 * n);
  A.topRightCorner(n, n).setIdentity();
  A.bottomLeftCorner(n, n) = -Minv * s.K;
  A.bottomRightCorner(n, n) = -Minv * s.C;
  return A;
}

struct Records {
  MatrixXd response;  ///< r × outputs, displacements with measurement noise
  MatrixXd force;     ///< r × forces, noise free (as the paper)
};

/// The state transition over one step of the continuous system, e^{A Δt}.
inline MatrixXd transition(const Lumped& s, double dt) { return (state_matrix(s) * dt).exp(); }

/// The paper's records: a white Gaussian force of variance 100 on mass 1, 2048
/// samples, displacement of the chosen masses plus white Gaussian noise of
/// standard deviation 0.05 × the response's. The force is the paper's Eq. 2, a
/// train of impulses F_n δ(t − (nΔt)⁻), for which the sampled response is exact:
///   x_n = e^{AΔt} x_{n−1} + [0; M⁻¹ e_1] F_n,  from rest
/// (an impulse changes the velocities, not the displacements), and the records obey
/// the paper's ARMAX structure, Eq. 3–5, exactly. (The paper integrated with
/// Runge–Kutta–Verner, DIVPRK; the discrete poles e^{λΔt} are the same.)
/// `forces` > 1 adds independent white forces of the same variance on masses 2, 3, ….
inline Records simulate(const Lumped& s, double dt, const std::vector<int>& outputs, std::uint64_t seed, bool noisy = true,
                 int forces = 1) {
  constexpr int kSamples = 2048;
  constexpr double kForceVariance = 100, kNoiseToSignal = 0.05;
  const Eigen::Index n = s.M.rows();
  const MatrixXd Phi = transition(s, dt);
  MatrixXd impulse = MatrixXd::Zero(2 * n, forces);
  impulse.bottomRows(n) = s.M.inverse().leftCols(forces);

  NormalSequence normal(seed);
  Records rec;
  rec.force.resize(kSamples, forces);
  for (int i = 0; i < kSamples; ++i)
    for (int j = 0; j < forces; ++j) rec.force(i, j) = std::sqrt(kForceVariance) * normal();
  rec.response.resize(kSamples, static_cast<Eigen::Index>(outputs.size()));
  VectorXd x = VectorXd::Zero(2 * n);
  for (int i = 0; i < kSamples; ++i) {
    x = Phi * x + impulse * rec.force.row(i).transpose();
    for (std::size_t j = 0; j < outputs.size(); ++j) rec.response(i, static_cast<Eigen::Index>(j)) = x(outputs[j]);
  }
  if (!noisy) return rec;
  for (Eigen::Index j = 0; j < rec.response.cols(); ++j) {
    const auto col = rec.response.col(j).array();
    const double sd = std::sqrt((col - col.mean()).square().mean());
    for (int i = 0; i < kSamples; ++i) rec.response(i, j) += kNoiseToSignal * sd * normal();
  }
  return rec;
}

/// An exact mode of the continuous system as the paper tabulates it.
struct ExactMode {
  double hz, zeta;
  int multiplicity;
  /// Ratio of the responses at the two outputs for a force on mass 1 (the paper's
  /// shape with the second output set to unity; a repeated pair's excited
  /// combination, the eigenspace projection of the force).
  double ratio;
};

/// Exact modes from the continuous problem: frequency and damping from the
/// eigenvalues λ of the state matrix (ω = |λ|, ζ = −Re λ/|λ|), shapes from
/// K v = ω² M v (C = cI is proportional), repeated frequencies merged.
inline std::vector<ExactMode> exact_modes(const Lumped& s, int first_output, int second_output) {
  const Eigen::VectorXcd lambda = Eigen::EigenSolver<MatrixXd>(state_matrix(s)).eigenvalues();
  std::vector<std::complex<double>> upper;
  for (Eigen::Index i = 0; i < lambda.size(); ++i)
    if (lambda(i).imag() > 0) upper.push_back(lambda(i));
  const Eigen::GeneralizedSelfAdjointEigenSolver<MatrixXd> gen(s.K, s.M);
  std::vector<ExactMode> modes;
  const Eigen::Index n = s.M.rows();
  for (Eigen::Index i = 0; i < n;) {
    Eigen::Index j = i;
    VectorXd residue = VectorXd::Zero(n);
    while (j < n && std::abs(gen.eigenvalues()(j) - gen.eigenvalues()(i)) <= 1e-9 * gen.eigenvalues()(i)) {
      residue += gen.eigenvectors().col(j) * gen.eigenvectors()(0, j);
      ++j;
    }
    const double omega = std::sqrt(gen.eigenvalues()(i));
    // The state-space eigenvalue of this mode: |λ| = ω for proportional damping.
    std::complex<double> closest = upper.front();
    for (const auto& l : upper)
      if (std::abs(std::abs(l) - omega) < std::abs(std::abs(closest) - omega)) closest = l;
    modes.push_back({std::abs(closest) / (2 * kPi), -closest.real() / std::abs(closest), static_cast<int>(j - i),
                     residue(first_output) / residue(second_output)});
    i = j;
  }
  return modes;
}


}  // namespace armax_test
