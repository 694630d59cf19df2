#pragma once
/// \file zero_energy_modes.hpp
/// The exact zero-energy modes inside a near-null space: the combinations z = B c
/// of a model's rigid-body modes B that are eigenvectors of K φ = λ M φ (all six for
/// a free structure, none for a clamped one, some for one supported in a few
/// directions only).
///
/// Why: an eigen-solver need not find what is known. Taken out first, they leave
/// the multilevel method's LOBPCG the elastic modes only (35 instead of 41 for the
/// benchmark's free lattices: a block of 45 columns instead of 51). Block Lanczos
/// gains nothing from it (17 block solves instead of 18 on the 94k lattice, within
/// the noise of its time), so the direct path does not use it.
#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace ssid::estimator {

struct ZeroEnergyModes {
  Eigen::VectorXd lambda;  ///< their eigenvalues (round-off around 0), ascending
  Eigen::MatrixXd z;       ///< n x r, M-orthonormal
};

/// The eigenpairs (λ, c) of the projected pencil (Bᵀ K B, Bᵀ M B) whose vector
/// z = B c has ‖(K − λM) z‖ ≤ tol ‖(K − σM) z‖ and |λ| ≤ tol (λ − σ) (σ the
/// solver's shift, below the spectrum), at most `max_modes` of them, lowest first. None when B is empty or
/// carries no mass.
ZeroEnergyModes zero_energy_modes(const Eigen::SparseMatrix<double>& K, const Eigen::SparseMatrix<double>& M,
                                  double sigma, const Eigen::MatrixXd& B, double tol, int max_modes);

}  // namespace ssid::estimator
