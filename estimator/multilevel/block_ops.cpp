#include "estimator/multilevel/block_ops.hpp"

#include "estimator/dense_blas.hpp"

#include <stdexcept>

namespace ssid::estimator::multilevel {

namespace {

// Y.row(i) = Σ over the stored entries (j, a) of outer index i of a X.row(j).
template <class Sparse>
void outer_rows_times(const Sparse& A, const RowBlock& X, RowBlock& Y) {
  const long rows = A.outerSize(), b = X.cols();
  Y.resize(rows, b);
  const auto* outer = A.outerIndexPtr();
  const auto* inner = A.innerIndexPtr();
  const double* val = A.valuePtr();
  const double* x = X.data();
  double* y = Y.data();
#pragma omp parallel for schedule(static)
  for (long i = 0; i < rows; ++i) {
    double* yi = y + i * b;
    for (long c = 0; c < b; ++c) yi[c] = 0.0;
    for (auto p = outer[i]; p < outer[i + 1]; ++p) {
      const double a = val[p];
      const double* xj = x + static_cast<long>(inner[p]) * b;
#pragma omp simd
      for (long c = 0; c < b; ++c) yi[c] += a * xj[c];
    }
  }
}

Eigen::Map<const Eigen::MatrixXd> as_columns(const RowBlock& X) {
  return {X.data(), X.cols(), X.rows()};  // the b x n column-major matrix Xᵀ
}

}  // namespace

void sym_times(const SparseMatrix& A, const RowBlock& X, RowBlock& Y) {
  if (!A.isCompressed() || A.rows() != A.cols() || A.cols() != X.rows())
    throw std::invalid_argument("sym_times: A must be square, compressed and match X");
  outer_rows_times(A, X, Y);
}

void times(const SparseRowMatrix& A, const RowBlock& X, RowBlock& Y) {
  if (!A.isCompressed() || A.cols() != X.rows()) throw std::invalid_argument("times: A must be compressed and match X");
  outer_rows_times(A, X, Y);
}

void transpose_times(const SparseMatrix& A, const RowBlock& X, RowBlock& Y) {
  if (!A.isCompressed() || A.rows() != X.rows())
    throw std::invalid_argument("transpose_times: A must be compressed and match X");
  outer_rows_times(A, X, Y);  // column j of A is row j of Aᵀ
}

Eigen::MatrixXd gram(const RowBlock& X, const RowBlock& Y) {
  if (X.rows() != Y.rows()) throw std::invalid_argument("gram: blocks of different lengths");
  Eigen::MatrixXd G(X.cols(), Y.cols());
  if (X.rows() == 0) return G.setZero();
  detail::gemm(false, true, 1.0, as_columns(X), as_columns(Y), 0.0, G);  // Xᵀ Y = (Xc)(Yc)ᵀ
  return G;
}

RowBlock times_dense(const RowBlock& X, const Eigen::Ref<const Eigen::MatrixXd>& C) {
  if (X.cols() != C.rows()) throw std::invalid_argument("times_dense: shapes do not agree");
  RowBlock Y(X.rows(), C.cols());
  if (X.rows() == 0 || C.cols() == 0) return Y.setZero();
  Eigen::Map<Eigen::MatrixXd> Yc(Y.data(), Y.cols(), Y.rows());
  if (C.rows() == 0) { Yc.setZero(); return Y; }
  detail::gemm(true, false, 1.0, C, as_columns(X), 0.0, Yc);  // (X C)ᵀ = Cᵀ Xᵀ
  return Y;
}

}  // namespace ssid::estimator::multilevel
