#include "estimator/multilevel/block_ops.hpp"

#include "estimator/dense_blas.hpp"

#include <algorithm>
#include <stdexcept>
#include <thread>
#include <vector>

namespace ssid::estimator::multilevel {

long worker_threads() { return std::min<long>(std::max(1u, std::thread::hardware_concurrency()), 64); }

long parallel_parts(long n, const std::function<void(long, long, long)>& body, long serial_below) {
  const long threads = worker_threads();
  if (n < serial_below || threads == 1) {
    body(0, 0, n);
    return 1;
  }
  std::vector<std::thread> pool;
  const long chunk = (n + threads - 1) / threads;
  for (long t = 1; t < threads; ++t) {
    const long b = t * chunk, e = std::min(n, b + chunk);
    if (b < e) pool.emplace_back(body, t, b, e);
  }
  body(0, 0, std::min(n, chunk));
  for (auto& th : pool) th.join();
  return threads;
}

void parallel_for(long n, const std::function<void(long, long)>& body, long serial_below) {
  parallel_parts(n, [&body](long, long begin, long end) { body(begin, end); }, serial_below);
}

namespace {

/// How a product is written into Y.
enum class Into { Overwrite, Residual, Subtract, Add };  // Y = AX, Y = B − AX, Y −= AX, Y += AX

// Y.row(i) (per `into`) Σ over the stored entries (j, a) of outer index i of a X.row(j).
template <class Sparse, class T>
void outer_rows_times(const Sparse& A, const RowBlockOf<T>& X, RowBlockOf<T>& Y, Into into = Into::Overwrite,
                      const RowBlockOf<T>* base = nullptr) {
  const long rows = A.outerSize(), b = X.cols();
  if (into == Into::Overwrite || into == Into::Residual) Y.resize(rows, b);
  else if (Y.rows() != rows || Y.cols() != b) throw std::invalid_argument("sparse block product: Y's shape");
  if (into == Into::Residual && (base->rows() != rows || base->cols() != b))
    throw std::invalid_argument("sparse block product: the base block's shape");
  const auto* outer = A.outerIndexPtr();
  const auto* inner = A.innerIndexPtr();
  const T* val = A.valuePtr();
  const T* x = X.data();
  const T* bs = base ? base->data() : nullptr;
  T* y = Y.data();
  const T sign = (into == Into::Residual || into == Into::Subtract) ? T(-1) : T(1);
  parallel_for(rows, [=](long begin, long end) {
    for (long i = begin; i < end; ++i) {
      T* __restrict yi = y + i * b;  // Y never overlaps X or the base
      if (into == Into::Overwrite)
        for (long c = 0; c < b; ++c) yi[c] = T(0);
      else if (into == Into::Residual)
        for (long c = 0; c < b; ++c) yi[c] = bs[i * b + c];
      for (auto p = outer[i]; p < outer[i + 1]; ++p) {
        const T a = sign * val[p];
        const T* __restrict xj = x + static_cast<long>(inner[p]) * b;
#pragma GCC ivdep
        for (long c = 0; c < b; ++c) yi[c] += a * xj[c];
      }
    }
  });
}

template <class T>
void check_symmetric(const SparseOf<T>& A, const RowBlockOf<T>& X) {
  if (!A.isCompressed() || A.rows() != A.cols() || A.cols() != X.rows())
    throw std::invalid_argument("sym_times: A must be square, compressed and match X");
}

}  // namespace

template <class T>
void sym_times(const SparseOf<T>& A, const RowBlockOf<T>& X, RowBlockOf<T>& Y) {
  check_symmetric(A, X);
  outer_rows_times(A, X, Y);
}

template <class T>
void sym_residual(const SparseOf<T>& A, const RowBlockOf<T>& X, const RowBlockOf<T>& B, RowBlockOf<T>& Y) {
  check_symmetric(A, X);
  outer_rows_times(A, X, Y, Into::Residual, &B);
}

template <class T>
void sym_subtract(const SparseOf<T>& A, const RowBlockOf<T>& X, RowBlockOf<T>& Y) {
  check_symmetric(A, X);
  outer_rows_times(A, X, Y, Into::Subtract);
}

template <class T>
void times_add(const SparseRowOf<T>& A, const RowBlockOf<T>& X, RowBlockOf<T>& Y) {
  if (!A.isCompressed() || A.cols() != X.rows()) throw std::invalid_argument("times_add: A must be compressed and match X");
  outer_rows_times(A, X, Y, Into::Add);
}

template <class T>
void times(const SparseRowOf<T>& A, const RowBlockOf<T>& X, RowBlockOf<T>& Y) {
  if (!A.isCompressed() || A.cols() != X.rows()) throw std::invalid_argument("times: A must be compressed and match X");
  outer_rows_times(A, X, Y);
}

template <class T>
void transpose_times(const SparseOf<T>& A, const RowBlockOf<T>& X, RowBlockOf<T>& Y) {
  if (!A.isCompressed() || A.rows() != X.rows())
    throw std::invalid_argument("transpose_times: A must be compressed and match X");
  outer_rows_times(A, X, Y);  // column j of A is row j of Aᵀ
}

template <class From, class To>
void convert(const RowBlockOf<From>& X, RowBlockOf<To>& Y) {
  Y.resize(X.rows(), X.cols());
  const long b = X.cols();
  const From* x = X.data();
  To* y = Y.data();
  parallel_for(X.rows(), [=](long begin, long end) {
    for (long i = begin * b; i < end * b; ++i) y[i] = static_cast<To>(x[i]);
  });
}

#define SSID_BLOCK_OPS(T)                                                                                \
  template void sym_times<T>(const SparseOf<T>&, const RowBlockOf<T>&, RowBlockOf<T>&);                  \
  template void sym_residual<T>(const SparseOf<T>&, const RowBlockOf<T>&, const RowBlockOf<T>&,          \
                                RowBlockOf<T>&);                                                         \
  template void sym_subtract<T>(const SparseOf<T>&, const RowBlockOf<T>&, RowBlockOf<T>&);               \
  template void times_add<T>(const SparseRowOf<T>&, const RowBlockOf<T>&, RowBlockOf<T>&);               \
  template void times<T>(const SparseRowOf<T>&, const RowBlockOf<T>&, RowBlockOf<T>&);                   \
  template void transpose_times<T>(const SparseOf<T>&, const RowBlockOf<T>&, RowBlockOf<T>&);
SSID_BLOCK_OPS(double)
SSID_BLOCK_OPS(float)
#undef SSID_BLOCK_OPS
template void convert<double, float>(const RowBlockOf<double>&, RowBlockOf<float>&);
template void convert<float, double>(const RowBlockOf<float>&, RowBlockOf<double>&);

namespace {

/// Rows per thread below which a dense product is left to one BLAS call.
constexpr long kSplitRows = 8192;

}  // namespace

SparseMatrix parallel_product(const SparseMatrix& A, const SparseMatrix& B) {
  if (A.cols() != B.rows()) throw std::invalid_argument("parallel_product: shapes do not agree");
  const long threads = worker_threads(), nc = B.cols();
  if (threads == 1 || nc < 64) return SparseMatrix(A * B);
  // One part per thread, by columns (parts left empty where a thread had none).
  std::vector<SparseMatrix> parts(static_cast<size_t>(threads));
  parallel_parts(
      nc,
      [&](long t, long begin, long end) {
        SparseMatrix& part = parts[static_cast<size_t>(t)];
        part = A * B.middleCols(begin, end - begin);
        part.makeCompressed();
      },
      0);
  long nnz = 0;
  for (const auto& part : parts) nnz += part.nonZeros();
  SparseMatrix C(A.rows(), nc);
  C.resizeNonZeros(nnz);
  long col = 0, at = 0;
  for (const auto& part : parts) {
    for (long j = 0; j < part.cols(); ++j) C.outerIndexPtr()[col + j] = static_cast<int>(at + part.outerIndexPtr()[j]);
    std::copy(part.innerIndexPtr(), part.innerIndexPtr() + part.nonZeros(), C.innerIndexPtr() + at);
    std::copy(part.valuePtr(), part.valuePtr() + part.nonZeros(), C.valuePtr() + at);
    col += part.cols();
    at += part.nonZeros();
  }
  C.outerIndexPtr()[nc] = static_cast<int>(at);
  return C;
}

SparseMatrix galerkin_lower(const SparseMatrix& B, const SparseMatrix& P, const SparseRowMatrix& Prow,
                            const std::vector<long>& starts) {
  const long n = P.rows(), nc = P.cols();
  if (B.rows() != n || B.cols() != n || Prow.rows() != n || Prow.cols() != nc || !B.isCompressed() ||
      !P.isCompressed() || !Prow.isCompressed() || starts.empty() || starts.front() != 0 || starts.back() != nc)
    throw std::invalid_argument("galerkin_lower: shapes, compression or column blocks do not agree");
  const long nblocks = static_cast<long>(starts.size()) - 1;
  struct Column {
    std::vector<int> rows;
    std::vector<double> values;
  };
  std::vector<Column> columns(static_cast<size_t>(nc));
  parallel_for(
      nblocks,
      [&](long begin, long end) {
        std::vector<long> mark(static_cast<size_t>(n), -1), cmark(static_cast<size_t>(nc), -1);
        std::vector<long> touched, ctouched;
        std::vector<double> Y, G;  // B P_block rows, Pᵀ (B P_block) rows; block width w
        for (long blk = begin; blk < end; ++blk) {
          const long c0 = starts[static_cast<size_t>(blk)], w = starts[static_cast<size_t>(blk) + 1] - c0;
          touched.clear(), Y.clear();
          for (long j = 0; j < w; ++j)
            for (SparseMatrix::InnerIterator pit(P, c0 + j); pit; ++pit)
              for (SparseMatrix::InnerIterator bit(B, pit.row()); bit; ++bit) {  // column = row of B
                long& m = mark[static_cast<size_t>(bit.row())];
                if (m < 0) {
                  m = static_cast<long>(touched.size());
                  touched.push_back(bit.row());
                  Y.resize(Y.size() + static_cast<size_t>(w), 0.0);
                }
                Y[static_cast<size_t>(m * w + j)] += bit.value() * pit.value();
              }
          ctouched.clear(), G.clear();
          for (size_t t = 0; t < touched.size(); ++t) {
            const long i = touched[t];
            const double* y = Y.data() + t * static_cast<size_t>(w);
            for (SparseRowMatrix::InnerIterator qit(Prow, i); qit; ++qit) {
              const long q = qit.col();
              if (q < c0) continue;  // the lower triangle only
              long& m = cmark[static_cast<size_t>(q)];
              if (m < 0) {
                m = static_cast<long>(ctouched.size());
                ctouched.push_back(q);
                G.resize(G.size() + static_cast<size_t>(w), 0.0);
              }
              double* g = G.data() + m * w;
              for (long j = 0; j < w; ++j) g[j] += qit.value() * y[j];
            }
            mark[static_cast<size_t>(i)] = -1;
          }
          std::vector<long> order(ctouched.size());
          for (size_t k = 0; k < order.size(); ++k) order[k] = static_cast<long>(k);
          std::sort(order.begin(), order.end(), [&](long a, long b) { return ctouched[static_cast<size_t>(a)] < ctouched[static_cast<size_t>(b)]; });
          for (long j = 0; j < w; ++j) {
            Column& col = columns[static_cast<size_t>(c0 + j)];
            for (const long k : order) {
              const long q = ctouched[static_cast<size_t>(k)];
              if (q >= c0 + j) col.rows.push_back(static_cast<int>(q)), col.values.push_back(G[static_cast<size_t>(k * w + j)]);
            }
          }
          for (const long q : ctouched) cmark[static_cast<size_t>(q)] = -1;
        }
      },
      2);
  long nnz = 0;
  for (const auto& c : columns) nnz += static_cast<long>(c.rows.size());
  SparseMatrix L(nc, nc);
  L.resizeNonZeros(nnz);
  long at = 0;
  for (long j = 0; j < nc; ++j) {
    L.outerIndexPtr()[j] = static_cast<int>(at);
    const Column& c = columns[static_cast<size_t>(j)];
    std::copy(c.rows.begin(), c.rows.end(), L.innerIndexPtr() + at);
    std::copy(c.values.begin(), c.values.end(), L.valuePtr() + at);
    at += static_cast<long>(c.rows.size());
  }
  L.outerIndexPtr()[nc] = static_cast<int>(at);
  return L;
}

Eigen::MatrixXd gram(const RowBlock& X, const RowBlock& Y, long rows) {
  if (X.rows() != Y.rows()) throw std::invalid_argument("gram: blocks of different lengths");
  const long m = rows < 0 ? static_cast<long>(X.rows()) : std::min<long>(rows, X.rows());
  Eigen::MatrixXd G = Eigen::MatrixXd::Zero(X.cols(), Y.cols());
  if (m == 0 || X.cols() == 0 || Y.cols() == 0) return G;
  // Xᵀ Y = (Xc)(Yc)ᵀ; rows [b, e) of a row-major block are its values [b·cols, e·cols).
  // Split by rows, one serial BLAS call per thread, partial sums added.
  const long bx = X.cols(), by = Y.cols();
  auto part = [&](long b, long e, Eigen::MatrixXd& out) {
    detail::gemm(false, true, 1.0, Eigen::Map<const Eigen::MatrixXd>(X.data() + b * bx, bx, e - b),
                 Eigen::Map<const Eigen::MatrixXd>(Y.data() + b * by, by, e - b), 0.0, out);
  };
  if (m < kSplitRows * worker_threads()) {
    part(0, m, G);
    return G;
  }
  const detail::SerialBlas serial;
  std::vector<Eigen::MatrixXd> partial(static_cast<size_t>(worker_threads()), Eigen::MatrixXd::Zero(bx, by));
  const long parts = parallel_parts(m, [&](long t, long b, long e) { part(b, e, partial[static_cast<size_t>(t)]); });
  for (long t = 0; t < parts; ++t) G += partial[static_cast<size_t>(t)];  // in order: the same bits every run
  return G;
}

void times_dense_into(const RowBlock& X, const Eigen::Ref<const Eigen::MatrixXd>& C, double beta, RowBlock& Y) {
  if (X.cols() != C.rows()) throw std::invalid_argument("times_dense_into: shapes do not agree");
  if (beta == 0.0) Y.resize(X.rows(), C.cols());
  else if (Y.rows() != X.rows() || Y.cols() != C.cols()) throw std::invalid_argument("times_dense_into: Y's shape");
  if (Y.size() == 0) return;
  // (X C)ᵀ = Cᵀ Xᵀ, column range [b, e) of Yc = rows [b, e) of Y: one serial BLAS call per thread.
  const long k = X.cols(), c = Y.cols();
  auto part = [&](long b, long e) {
    Eigen::Map<Eigen::MatrixXd> Yc(Y.data() + b * c, c, e - b);
    detail::gemm(true, false, 1.0, C, Eigen::Map<const Eigen::MatrixXd>(X.data() + b * k, k, e - b), beta, Yc);
  };
  const long n = X.rows();
  if (n < kSplitRows * worker_threads()) {
    part(0, n);
    return;
  }
  const detail::SerialBlas serial;
  parallel_for(n, part);
}

}  // namespace ssid::estimator::multilevel
