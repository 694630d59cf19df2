#include "estimator/dense_blas.hpp"

#include <cblas.h>

#include <limits>
#include <stdexcept>
#include <string>

namespace ssid::estimator::detail {

namespace {

int to_int(Eigen::Index v) {
  if (v > std::numeric_limits<int>::max())
    throw std::invalid_argument("gemm: dimension " + std::to_string(v) + " exceeds the BLAS integer range");
  return static_cast<int>(v);
}

}  // namespace

void gemm(bool trans_a, bool trans_b, double alpha, const Eigen::Ref<const Eigen::MatrixXd>& A,
          const Eigen::Ref<const Eigen::MatrixXd>& B, double beta, Eigen::Ref<Eigen::MatrixXd> C) {
  const Eigen::Index m = trans_a ? A.cols() : A.rows();
  const Eigen::Index k = trans_a ? A.rows() : A.cols();
  const Eigen::Index kb = trans_b ? B.cols() : B.rows();
  const Eigen::Index n = trans_b ? B.rows() : B.cols();
  if (k != kb || C.rows() != m || C.cols() != n)
    throw std::invalid_argument("gemm: shapes do not agree (" + std::to_string(m) + "x" + std::to_string(k) +
                                " times " + std::to_string(kb) + "x" + std::to_string(n) + " into " +
                                std::to_string(C.rows()) + "x" + std::to_string(C.cols()) + ")");
  if (m == 0 || n == 0) return;
  if (k == 0) {
    if (beta == 0.0) C.setZero();
    else C *= beta;
    return;
  }
  cblas_dgemm(CblasColMajor, trans_a ? CblasTrans : CblasNoTrans, trans_b ? CblasTrans : CblasNoTrans, to_int(m),
              to_int(n), to_int(k), alpha, A.data(), to_int(std::max<Eigen::Index>(A.outerStride(), 1)), B.data(),
              to_int(std::max<Eigen::Index>(B.outerStride(), 1)), beta, C.data(),
              to_int(std::max<Eigen::Index>(C.outerStride(), 1)));
}

Eigen::MatrixXd at_b(const Eigen::Ref<const Eigen::MatrixXd>& A, const Eigen::Ref<const Eigen::MatrixXd>& B) {
  Eigen::MatrixXd C(A.cols(), B.cols());
  gemm(true, false, 1.0, A, B, 0.0, C);
  return C;
}

Eigen::MatrixXd a_b(const Eigen::Ref<const Eigen::MatrixXd>& A, const Eigen::Ref<const Eigen::MatrixXd>& B) {
  Eigen::MatrixXd C(A.rows(), B.cols());
  gemm(false, false, 1.0, A, B, 0.0, C);
  return C;
}

}  // namespace ssid::estimator::detail
