#include "estimator/linalg/dense_blas.hpp"

#include <cblas.h>
#include <dlfcn.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <vector>

extern "C" {
// LAPACK (Fortran ABI; the trailing lengths are the hidden character-argument lengths).
void dsyevr_(const char* jobz, const char* range, const char* uplo, const int* n, double* a, const int* lda,
             const double* vl, const double* vu, const int* il, const int* iu, const double* abstol, int* m,
             double* w, double* z, const int* ldz, int* isuppz, double* work, const int* lwork, int* iwork,
             const int* liwork, int* info, size_t, size_t, size_t);
}

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

namespace {

// OpenBLAS's thread controls, when the BLAS loaded is OpenBLAS (null otherwise).
struct OpenBlasThreads {
  using Get = int (*)();
  using Set = void (*)(int);
  Get get = nullptr;
  Set set = nullptr;
  OpenBlasThreads() {
    get = reinterpret_cast<Get>(dlsym(RTLD_DEFAULT, "openblas_get_num_threads"));
    set = reinterpret_cast<Set>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads"));
    if (!get || !set) get = nullptr, set = nullptr;
  }
};

const OpenBlasThreads& openblas_threads() {
  static const OpenBlasThreads t;
  return t;
}

}  // namespace

BlasThreadLimit::BlasThreadLimit() {
  const OpenBlasThreads& t = openblas_threads();
  if (!t.get) return;
  const int threads = t.get();
  if (threads <= 1) return;
  t.set(1);
  m_restore = threads;
}

BlasThreadLimit::~BlasThreadLimit() {
  if (m_restore > 0) openblas_threads().set(m_restore);
}

void largest_eigenpairs(const Eigen::MatrixXd& T, long count, Eigen::VectorXd& values, Eigen::MatrixXd& vectors) {
  const Eigen::Index k = T.rows();
  if (T.cols() != k || count < 0 || count > k)
    throw std::invalid_argument("largest_eigenpairs: " + std::to_string(count) + " pairs of a " +
                                std::to_string(k) + "x" + std::to_string(T.cols()) + " matrix");
  values.resize(count);
  vectors.resize(k, count);
  if (count == 0) return;
  Eigen::MatrixXd A = T;  // dsyevr overwrites it
  const int n = to_int(k), il = to_int(k - count + 1), iu = to_int(k), lda = std::max(n, 1);
  const double vl = 0.0, vu = 0.0, abstol = 0.0;
  int m = 0, info = 0, lwork = -1, liwork = -1, iwork_query = 0;
  double work_query = 0.0;
  std::vector<int> isuppz(static_cast<size_t>(2 * count));
  Eigen::VectorXd w(k);  // dsyevr's W has n entries even when fewer pairs are wanted
  dsyevr_("V", "I", "L", &n, A.data(), &lda, &vl, &vu, &il, &iu, &abstol, &m, w.data(), vectors.data(), &lda,
          isuppz.data(), &work_query, &lwork, &iwork_query, &liwork, &info, 1, 1, 1);
  if (info == 0) {
    lwork = static_cast<int>(work_query);
    liwork = iwork_query;
    std::vector<double> work(static_cast<size_t>(std::max(lwork, 1)));
    std::vector<int> iwork(static_cast<size_t>(std::max(liwork, 1)));
    dsyevr_("V", "I", "L", &n, A.data(), &lda, &vl, &vu, &il, &iu, &abstol, &m, w.data(), vectors.data(), &lda,
            isuppz.data(), work.data(), &lwork, iwork.data(), &liwork, &info, 1, 1, 1);
  }
  if (info == 0 && m == count) {
    values = w.head(count);
    return;
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(T);  // LAPACK failed: every pair, keep the top
  values = es.eigenvalues().tail(count);
  vectors = es.eigenvectors().rightCols(count);
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
