#pragma once
// Three masses on springs along X, as a deck and as dense K and M written out by hand:
// the independent reference of the FRF tests (test_cli_frf.cpp, test_cli_frf_comparison.cpp).
#include <Eigen/Dense>
#include <cmath>
#include <cstdio>
#include <complex>
#include <string>

/// Three masses in X (2, 1, 1.5 kg at grids 1, 2, 3; PS 23456 leaves X only), springs
/// k1 (default 4e4 N/m) grid 1 to ground, 1.5e4 N/m 1–2, 1e4 N/m 2–3.
inline std::string spring_deck_text(double k1 = 4e4) {
  char k[32];
  std::snprintf(k, sizeof k, "%.1f", k1);  // 40000.0: within a field's 8 characters below 1e6
  return R"(SOL 103
CEND
BEGIN BULK
GRID,1,,0.,0.,0.,,23456
GRID,2,,1.,0.,0.,,23456
GRID,3,,2.,0.,0.,,23456
CELAS2,11,)" + std::string(k) + R"(,1,1
CELAS2,12,1.5E4,1,1,2,1
CELAS2,13,1.0E4,2,1,3,1
CONM2,21,1,,2.0
CONM2,22,2,,1.0
CONM2,23,3,,1.5
ENDDATA
)";
}

struct Spring3 {
  using cd = std::complex<double>;
  Eigen::Matrix3d M, K;
  Eigen::Vector3d lambda;  ///< ω_r², ascending
  Eigen::Matrix3d phi;     ///< mass-normalised (Eigen's generalized solver: ΦᵀMΦ = I)
  explicit Spring3(double k1 = 4e4) {
    M = Eigen::Vector3d(2.0, 1.0, 1.5).asDiagonal();
    const double k2 = 1.5e4, k3 = 1e4;
    K << k1 + k2, -k2, 0, -k2, k2 + k3, -k3, 0, -k3, k3;
    Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::Matrix3d> es(K, M);
    lambda = es.eigenvalues();
    phi = es.eigenvectors();
  }
  /// (K − ω²M + iωC)⁻¹ with modal damping ζ_r: C = M Φ diag(2ζ_rω_r) Φᵀ M.
  Eigen::Matrix3cd direct(double f, const Eigen::Vector3d& zeta) const {
    const double w = 2 * M_PI * f;
    Eigen::Vector3d c;
    for (int r = 0; r < 3; ++r) c(r) = 2 * zeta(r) * std::sqrt(lambda(r));
    const Eigen::Matrix3d C = M * phi * c.asDiagonal() * phi.transpose() * M;
    const Eigen::Matrix3cd D = K.cast<cd>() - w * w * M.cast<cd>() + cd(0, w) * C.cast<cd>();
    return D.partialPivLu().solve(Eigen::Matrix3cd::Identity());
  }
};

