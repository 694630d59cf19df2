#pragma once
/// \file sensitivity.hpp
/// Eigen-sensitivities of the generalised problem K φ = λ M φ with mass-normalised
/// modes (φᵀMφ = 1), for a parameter r entering through ∂K/∂r and ∂M/∂r.
///
/// Eigenvalue (exact for a simple eigenvalue):
///   ∂λ/∂r = φᵀ (∂K − λ ∂M) φ
/// Eigenvector, Nelson's method (exact; one sparse factorisation per mode):
///   (K − λM) v = −(∂K − λ∂M − (∂λ) M) φ  with v_k = 0 at k = argmax |φ_k|,
///   c = −φᵀ M v − ½ φᵀ ∂M φ,   ∂φ = v + c φ.
/// Modal summation (the seed report's approximation, from the m computed modes):
///   ∂φ_i ≈ Σ_{j≠i} φ_j φ_jᵀ(∂K − λ_i∂M)φ_i / (λ_i − λ_j) − ½ (φ_iᵀ∂Mφ_i) φ_i.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <memory>
#include <vector>

namespace ssid::estimator {

using SparseMatrix = Eigen::SparseMatrix<double>;

/// ∂λ/∂r for one mode.
double eigenvalue_derivative(const SparseMatrix& dK, const SparseMatrix& dM, double lambda,
                             const Eigen::Ref<const Eigen::VectorXd>& phi);

/// Nelson's method: ∂φ/∂r for each parameter, one factorisation of (K − λM) for
/// all parameters of the mode. Returns n x p (p = dK.size()).
/// Throws std::runtime_error when K − λM with the pinned row is singular (a
/// repeated eigenvalue: Nelson's method needs a simple one).
Eigen::MatrixXd nelson_derivatives(const SparseMatrix& K, const SparseMatrix& M, double lambda,
                                   const Eigen::Ref<const Eigen::VectorXd>& phi,
                                   const std::vector<SparseMatrix>& dK, const std::vector<SparseMatrix>& dM);

/// Nelson's method for several modes of one pencil (K, M): the sparsity pattern
/// of K − λM (the pinned row and column kept as explicit zeros, so it is the same
/// for every mode) is analysed once (AMD ordering), and each mode only refactors
/// numerically — a sparse LDLᵀ without pivoting, which K − λM with the pinned DOF
/// (indefinite but non-singular for a simple eigenvalue) admits in practice. Every
/// solve is checked by its residual ‖A v − b‖ ≤ 1e-8 ‖b‖; a factorisation that
/// fails the check (a tiny pivot) is redone by sparse LU with partial pivoting.
/// The result is the same ∂φ as nelson_derivatives, at a fraction of the cost
/// for many modes (the estimator's sensitivities, bench/bench_estimate.cpp).
class NelsonSolver {
 public:
  NelsonSolver(const SparseMatrix& K, const SparseMatrix& M);
  ~NelsonSolver();
  NelsonSolver(const NelsonSolver&) = delete;
  NelsonSolver& operator=(const NelsonSolver&) = delete;

  /// ∂φ/∂r_j of the mode (λ, φ), n × p; throws std::runtime_error as nelson_derivatives.
  Eigen::MatrixXd derivatives(double lambda, const Eigen::Ref<const Eigen::VectorXd>& phi,
                              const std::vector<SparseMatrix>& dK, const std::vector<SparseMatrix>& dM);
  /// Modes whose LDLᵀ failed the residual check and were solved by LU (diagnostics).
  int lu_fallbacks() const { return m_fallbacks; }

 private:
  struct State;
  const SparseMatrix& m_K;
  const SparseMatrix& m_M;
  std::unique_ptr<State> m_state;
  int m_fallbacks = 0;
};

/// Modal-summation approximation of ∂φ_i/∂r from the modes Phi (n x m, mass-normalised)
/// with eigenvalues lambdas; mode index i, one parameter.
Eigen::VectorXd modal_sum_derivative(const Eigen::Ref<const Eigen::MatrixXd>& Phi,
                                     const Eigen::Ref<const Eigen::VectorXd>& lambdas, int i,
                                     const SparseMatrix& dK, const SparseMatrix& dM);

}  // namespace ssid::estimator
