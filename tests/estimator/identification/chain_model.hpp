#pragma once
/// A 3-DOF spring–mass–damper chain (DOF 0 grounded) for the identification tests, with
/// its exact poles and shapes (dense eigen-solve of the first-order state matrix) and
/// exact Markov parameters (the sampled impulse response, by the matrix exponential).
#include <Eigen/Dense>
#include <algorithm>
#include <complex>
#include <unsupported/Eigen/MatrixFunctions>
#include <vector>

#include "translators/synthetic_modes.hpp"

namespace ident_test {

using cd = std::complex<double>;

/// Chain matrix of element values v (v[0] to ground, v[i] between DOF i−1 and i).
inline Eigen::MatrixXd chain(const std::vector<double>& v) {
  const auto n = static_cast<Eigen::Index>(v.size());
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n, n);
  K(0, 0) += v[0];
  for (Eigen::Index i = 1; i < n; ++i) {
    const double s = v[static_cast<std::size_t>(i)];
    K(i - 1, i - 1) += s;
    K(i, i) += s;
    K(i - 1, i) -= s;
    K(i, i - 1) -= s;
  }
  return K;
}

struct ChainModel {
  Eigen::MatrixXd M, C, K;
  std::vector<Eigen::Index> drive;  ///< DOFs with a force input
  Eigen::MatrixXd Ac, Bc, Cc;       ///< ẋ = Ac x + Bc f, y = Cc x (displacements), x = [u; u̇]

  ChainModel(const Eigen::MatrixXd& m, const Eigen::MatrixXd& c, const Eigen::MatrixXd& k,
             std::vector<Eigen::Index> d)
      : M(m), C(c), K(k), drive(std::move(d)) {
    const Eigen::Index n = M.rows();
    const Eigen::MatrixXd Mi = M.inverse();
    Ac = Eigen::MatrixXd::Zero(2 * n, 2 * n);
    Ac.topRightCorner(n, n).setIdentity();
    Ac.bottomLeftCorner(n, n) = -Mi * K;
    Ac.bottomRightCorner(n, n) = -Mi * C;
    Bc = Eigen::MatrixXd::Zero(2 * n, static_cast<Eigen::Index>(drive.size()));
    for (std::size_t j = 0; j < drive.size(); ++j)
      Bc.bottomRows(n).col(static_cast<Eigen::Index>(j)) = Mi.col(drive[j]);
    Cc = Eigen::MatrixXd::Zero(n, 2 * n);
    Cc.leftCols(n).setIdentity();
  }

  /// Y[k] = Cc e^{Ac k dt} Bc, k = 0 … count−1.
  std::vector<Eigen::MatrixXd> markov(double dt, Eigen::Index count) const {
    const Eigen::MatrixXd Ad = (Ac * dt).exp();
    std::vector<Eigen::MatrixXd> Y;
    Eigen::MatrixXd X = Bc;
    for (Eigen::Index k = 0; k < count; ++k) {
      Y.push_back(Cc * X);
      X = Ad * X;
    }
    return Y;
  }

  /// Exact poles with Im > 0 by frequency, and their displacement shapes.
  void exact(std::vector<cd>& poles, std::vector<Eigen::VectorXcd>& shapes) const {
    Eigen::EigenSolver<Eigen::MatrixXd> es(Ac);
    std::vector<std::pair<cd, Eigen::VectorXcd>> p;
    for (Eigen::Index i = 0; i < Ac.rows(); ++i)
      if (es.eigenvalues()(i).imag() > 0) p.emplace_back(es.eigenvalues()(i), (Cc.cast<cd>() * es.eigenvectors().col(i)));
    std::sort(p.begin(), p.end(), [](const auto& a, const auto& b) { return std::abs(a.first) < std::abs(b.first); });
    poles.clear();
    shapes.clear();
    for (auto& q : p) {
      poles.push_back(q.first);
      shapes.push_back(q.second);
    }
  }
};

/// The chain of the tests: masses 1, 2, 1.5 kg, springs 2e4, 1.5e4, 1e4 N/m; dashpots
/// 4, 2, 6 N·s/m (not proportional: complex modes) or Rayleigh C = αM + βK.
inline ChainModel chain_model(bool proportional, std::vector<Eigen::Index> drive) {
  Eigen::MatrixXd M = Eigen::Vector3d(1.0, 2.0, 1.5).asDiagonal();
  const Eigen::MatrixXd K = chain({2e4, 1.5e4, 1e4});
  const Eigen::MatrixXd C = proportional ? Eigen::MatrixXd(0.5 * M + 2e-4 * K) : chain({4.0, 2.0, 6.0});
  return ChainModel(M, C, K, std::move(drive));
}

/// Markov parameters with noise: each output channel gets independent normal noise of
/// `level` × that channel's RMS over the record.
inline std::vector<Eigen::MatrixXd> with_noise(std::vector<Eigen::MatrixXd> Y, double level, std::uint64_t seed) {
  ssid::translators::NormalDeviates z(seed);
  const Eigen::Index no = Y[0].rows(), ni = Y[0].cols();
  Eigen::MatrixXd rms = Eigen::MatrixXd::Zero(no, ni);
  for (const auto& y : Y) rms += y.cwiseAbs2();
  rms = (rms / static_cast<double>(Y.size())).cwiseSqrt();
  for (auto& y : Y)
    for (Eigen::Index j = 0; j < ni; ++j)
      for (Eigen::Index i = 0; i < no; ++i) y(i, j) += level * rms(i, j) * z();
  return Y;
}

}  // namespace ident_test
