#pragma once
/// \file armax.hpp
/// The seed's multistage ARMAX identification (seed report, Appendix A, "ARMAX
/// Identification of Vibrating Structures", Mignolet & Red-Horse; docs/armax.md).
///
/// The p observed responses x_n and the measured forces f_n of a linear structure
/// admit the ARMAX representation (paper Eq. 20)
///   Σ_{k=0}^{s} A_k x_{n-k} = Σ_{l=0}^{s-1} B_l f_{n-l} + Σ_{k=0}^{s} C_k e_n-k,  A_0 = I_p,
/// whose AR roots z (det A(z) = 0, Eq. 11) are the structure's poles z = e^{λΔt}
/// (Eq. 12) and whose mode shapes at the outputs are the null vectors of A(z)
/// (Eq. 11–16). The estimate minimises the maximum-likelihood error (Eq. 22) in four
/// steps (paper Fig. 1):
///   1. a long prior ARX model of order m (Eq. 28–33, Ĉ_0 = I as the paper's results);
///   2. initial MA parameters C⁽¹⁾ from C(z)Â(z) ≈ A(z) (Eq. 35–37);
///   3. AR and exogenous parameters from the data prefiltered by C⁽ⁱ⁾(z)⁻¹ (Eq. 38–50);
///   4. MA parameters refitted to Â(z)A(z)⁻¹ (Eq. 51–54);
/// steps 3–4 repeat until ε_ML is stationary.
#include <Eigen/Core>
#include <complex>
#include <vector>

namespace ssid::estimator::identification {

/// Orders and iteration controls of one ARMAX identification.
struct ArmaxOptions {
  /// s: the AR and MA order (the exogenous order is s − 1). With p outputs a model
  /// of order s has p·s discrete poles; s = 2N/p for N modes without noise.
  int ar_order = 0;
  /// m: the order of the prior ARX model of step 1 (the paper: 45–65 for p = 2,
  /// 90–130 for p = 1).
  int arx_order = 0;
  /// q: samples of W(z) = Â(z)A(z)⁻¹ kept in step 4 (paper Eq. 54: q = 800).
  int ma_impulse_length = 800;
  /// Most passes of steps 3–4.
  int max_iterations = 50;
  /// Steps 3–4 stop at the first pass whose maximum-likelihood error ε_ML (Eq. 22)
  /// differs from the previous pass's by less than this fraction; that pass is the
  /// result (without convergence, the pass with the lowest ε_ML).
  double tolerance = 1e-3;
};

/// One identified discrete pole: a complex-conjugate pair once (Im z > 0) or a real root.
struct ArmaxPole {
  std::complex<double> z;  ///< discrete pole (dimensionless)
  double hz = 0;           ///< natural frequency |ln z| / (2π Δt), Hz (paper Eq. 14)
  double zeta = 0;         ///< damping ratio −ln|z| / |ln z| (paper Eq. 15)
  bool real = false;       ///< a real root: no oscillation, never a structural mode
  /// Mode shape at the outputs: the null vector of A(z) (paper, after Eq. 16),
  /// scaled so that its largest-magnitude component is 1 (real).
  Eigen::VectorXcd shape;
};

/// An ARMAX model and its poles. Coefficients are in the units of the records given.
struct ArmaxModel {
  std::vector<Eigen::MatrixXd> ar;   ///< A_0 … A_s, p × p, A_0 = I
  std::vector<Eigen::MatrixXd> exo;  ///< B_0 … B_{s−1}, p × (number of inputs)
  std::vector<Eigen::MatrixXd> ma;   ///< C_0 … C_s, p × p
  std::vector<ArmaxPole> poles;      ///< ascending frequency; p·s roots in all
  int iterations = 0;                ///< passes of steps 3–4 made
  bool converged = false;            ///< ε_ML became stationary within max_iterations
  double ml_error = 0;               ///< ε_ML per sample of the kept pass, records scaled to unit RMS
};

/// Identifies an ARMAX model from responses and forces sampled at dt.
/// \param outputs r × p responses (one column per measured DOF, any unit)
/// \param inputs  r × q forces (one column per force record; at least one)
/// \param dt      sampling interval, s (> 0)
/// Throws formats::InputError for empty or mismatched records, orders < 1, or too
/// few samples for the regressions.
ArmaxModel identify_armax(const Eigen::Ref<const Eigen::MatrixXd>& outputs,
                          const Eigen::Ref<const Eigen::MatrixXd>& inputs, double dt,
                          const ArmaxOptions& options);

/// Bytes the largest step (step 3's prefiltered regression: p² sequences U_αβ of p ×
/// `samples` values and its regression matrix of samples·p rows by s·p·(p + q)
/// columns) holds for `outputs` p, `inputs` q and AR order s: it grows as p³, so
/// ARMAX is for a few responses (the paper's p = 1, 2), not a test's hundreds.
double armax_memory_bytes(Eigen::Index samples, Eigen::Index outputs, Eigen::Index inputs, int ar_order);

/// The poles and mode shapes of an AR matrix polynomial A_0 … A_s (A_0 = I):
/// the p·s roots of det(Σ A_k z^{-k}) = 0 from the block companion matrix, each
/// pair once, converted to Hz and damping ratio at sampling interval dt (s).
std::vector<ArmaxPole> armax_poles(const std::vector<Eigen::MatrixXd>& ar, double dt);

}  // namespace ssid::estimator::identification
