#pragma once
/// \file dense_blas.hpp
/// Tall-skinny dense products of the block Lanczos iteration through the
/// system BLAS (cblas_dgemm), and its Ritz pairs through LAPACK (dsyevr).
/// Why not Eigen's own product: Eigen is compiled for the baseline instruction
/// set and runs on one thread, while the system BLAS
/// (OpenBLAS on Debian, libopenblas0-pthread) dispatches at run time to the
/// machine's widest vector kernels and uses every core. The same library is the
/// one CHOLMOD's supernodal factorisation runs on.
#include <Eigen/Core>

namespace ssid::estimator::detail {

/// C = α op(A) op(B) + β C, op(X) = Xᵀ when the flag is set. Column-major
/// blocks with any outer stride (leftCols/middleCols of a matrix are fine).
/// Throws std::invalid_argument when the shapes do not agree.
void gemm(bool trans_a, bool trans_b, double alpha, const Eigen::Ref<const Eigen::MatrixXd>& A,
          const Eigen::Ref<const Eigen::MatrixXd>& B, double beta, Eigen::Ref<Eigen::MatrixXd> C);

/// The `count` largest eigenvalues of the symmetric matrix T (lower triangle
/// read), ascending, and their orthonormal eigenvectors (T.rows() x count), by
/// LAPACK's dsyevr (tridiagonal reduction, then MRRR for the wanted pairs only:
/// about 4/3 k³ + O(k² count) flops against 9 k³ for every pair). Falls back to
/// Eigen's SelfAdjointEigenSolver when LAPACK reports a failure.
void largest_eigenpairs(const Eigen::MatrixXd& T, long count, Eigen::VectorXd& values, Eigen::MatrixXd& vectors);

/// Aᵀ B as a new matrix.
Eigen::MatrixXd at_b(const Eigen::Ref<const Eigen::MatrixXd>& A, const Eigen::Ref<const Eigen::MatrixXd>& B);

/// A B as a new matrix.
Eigen::MatrixXd a_b(const Eigen::Ref<const Eigen::MatrixXd>& A, const Eigen::Ref<const Eigen::MatrixXd>& B);

}  // namespace ssid::estimator::detail
