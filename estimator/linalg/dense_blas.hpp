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

/// Holds the system BLAS to one thread while it lives, when that BLAS is OpenBLAS
/// (found at run time: openblas_set_num_threads; any other BLAS is left as it is),
/// and restores the thread count it found. Why: callers that split their own work
/// over the cores (several single-threaded BLAS calls at once) would otherwise
/// have each call hand work to OpenBLAS's threads, and those threads spin, yielding,
/// for a while after each call, competing for the cores they run on. Not for
/// nesting across threads: the thread count is the process's.
class BlasThreadLimit {
 public:
  BlasThreadLimit();
  ~BlasThreadLimit();
  BlasThreadLimit(const BlasThreadLimit&) = delete;
  BlasThreadLimit& operator=(const BlasThreadLimit&) = delete;

 private:
  int m_restore = 0;  // the thread count to restore; 0: nothing was changed
};

/// Aᵀ B as a new matrix.
Eigen::MatrixXd at_b(const Eigen::Ref<const Eigen::MatrixXd>& A, const Eigen::Ref<const Eigen::MatrixXd>& B);

/// A B as a new matrix.
Eigen::MatrixXd a_b(const Eigen::Ref<const Eigen::MatrixXd>& A, const Eigen::Ref<const Eigen::MatrixXd>& B);

}  // namespace ssid::estimator::detail
