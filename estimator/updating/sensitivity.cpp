#include "estimator/updating/sensitivity.hpp"

#include <Eigen/SparseCholesky>
#include <Eigen/SparseLU>
#include <stdexcept>

#include "formats/parse_error.hpp"

namespace ssid::estimator {

double eigenvalue_derivative(const SparseMatrix& dK, const SparseMatrix& dM, double lambda,
                             const Eigen::Ref<const Eigen::VectorXd>& phi) {
  return phi.dot(dK * phi) - lambda * phi.dot(dM * phi);
}

Eigen::MatrixXd nelson_derivatives(const SparseMatrix& K, const SparseMatrix& M, double lambda,
                                   const Eigen::Ref<const Eigen::VectorXd>& phi,
                                   const std::vector<SparseMatrix>& dK, const std::vector<SparseMatrix>& dM) {
  const int n = static_cast<int>(K.rows());
  int k = 0;
  phi.cwiseAbs().maxCoeff(&k);
  // A = K − λM with row and column k replaced by the identity's.
  SparseMatrix A = K - lambda * M;
  for (int c = 0; c < A.outerSize(); ++c)
    for (SparseMatrix::InnerIterator it(A, c); it; ++it)
      if (it.row() == k || it.col() == k) it.valueRef() = (it.row() == it.col()) ? 1.0 : 0.0;
  if (A.coeff(k, k) != 1.0) A.coeffRef(k, k) = 1.0;
  A.prune(0.0);
  A.makeCompressed();
  Eigen::SparseLU<SparseMatrix> lu;
  lu.analyzePattern(A);
  lu.factorize(A);
  if (lu.info() != Eigen::Success)
    throw formats::NumericalError("Nelson's method: K - lambda M is singular with the pinned DOF (repeated eigenvalue?)");
  const Eigen::VectorXd Mphi = M * phi;
  Eigen::MatrixXd out(n, static_cast<int>(dK.size()));
  for (std::size_t p = 0; p < dK.size(); ++p) {
    const double dl = eigenvalue_derivative(dK[p], dM[p], lambda, phi);
    Eigen::VectorXd rhs = -(dK[p] * phi - lambda * (dM[p] * phi) - dl * Mphi);
    rhs(k) = 0.0;
    Eigen::VectorXd v = lu.solve(rhs);
    if (lu.info() != Eigen::Success) throw formats::NumericalError("Nelson's method: solve failed");
    const double c = -Mphi.dot(v) - 0.5 * phi.dot(dM[p] * phi);
    out.col(static_cast<int>(p)) = v + c * phi;
  }
  return out;
}

namespace {

/// The right-hand sides of Nelson's equations for every parameter, with the pinned entry zeroed.
Eigen::MatrixXd nelson_rhs(double lambda, const Eigen::Ref<const Eigen::VectorXd>& phi, const Eigen::VectorXd& Mphi,
                           const std::vector<SparseMatrix>& dK, const std::vector<SparseMatrix>& dM, int k) {
  Eigen::MatrixXd rhs(phi.size(), static_cast<Eigen::Index>(dK.size()));
  for (std::size_t p = 0; p < dK.size(); ++p) {
    const double dl = eigenvalue_derivative(dK[p], dM[p], lambda, phi);
    Eigen::VectorXd r = -(dK[p] * phi - lambda * (dM[p] * phi) - dl * Mphi);
    r(k) = 0.0;
    rhs.col(static_cast<Eigen::Index>(p)) = r;
  }
  return rhs;
}

}  // namespace

struct NelsonSolver::State {
  SparseMatrix Z;  ///< zero diagonal: puts every diagonal entry in the pattern
  SparseMatrix A;  ///< K − λM on the union pattern of K, M and the diagonal
  Eigen::SimplicialLDLT<SparseMatrix, Eigen::Lower, Eigen::AMDOrdering<int>> ldlt;
  bool analysed = false;
};

NelsonSolver::NelsonSolver(const SparseMatrix& K, const SparseMatrix& M) : m_K(K), m_M(M), m_state(std::make_unique<State>()) {
  if (K.rows() != K.cols() || M.rows() != K.rows() || M.cols() != K.cols())
    throw std::invalid_argument("NelsonSolver: K and M must be square and of the same size");
  SparseMatrix Z(K.rows(), K.cols());
  std::vector<Eigen::Triplet<double>> diag;
  for (Eigen::Index i = 0; i < K.rows(); ++i) diag.emplace_back(static_cast<int>(i), static_cast<int>(i), 0.0);
  Z.setFromTriplets(diag.begin(), diag.end());
  m_state->Z = std::move(Z);
}

NelsonSolver::~NelsonSolver() = default;

Eigen::MatrixXd NelsonSolver::derivatives(double lambda, const Eigen::Ref<const Eigen::VectorXd>& phi,
                                          const std::vector<SparseMatrix>& dK, const std::vector<SparseMatrix>& dM) {
  SparseMatrix& A = m_state->A;
  int k = 0;
  phi.cwiseAbs().maxCoeff(&k);
  // K − λM + 0·I: a sparse sum keeps the union pattern (explicit zeros too), so
  // the pattern is the same for every mode. Then row and column k are pinned.
  A = m_K - lambda * m_M + m_state->Z;
  for (int c = 0; c < A.outerSize(); ++c)
    for (SparseMatrix::InnerIterator it(A, c); it; ++it)
      if (it.row() == k || it.col() == k) it.valueRef() = (it.row() == it.col()) ? 1.0 : 0.0;
  if (!m_state->analysed) {
    m_state->ldlt.analyzePattern(A);
    m_state->analysed = true;
  }
  m_state->ldlt.factorize(A);
  const Eigen::VectorXd Mphi = m_M * phi;
  const Eigen::MatrixXd rhs = nelson_rhs(lambda, phi, Mphi, dK, dM, k);
  Eigen::MatrixXd v;
  bool good = m_state->ldlt.info() == Eigen::Success;
  if (good) {
    v = m_state->ldlt.solve(rhs);
    const double scale = std::max(rhs.norm(), 1e-300);
    good = m_state->ldlt.info() == Eigen::Success && v.allFinite() &&
           (A.selfadjointView<Eigen::Lower>() * v - rhs).norm() <= 1e-8 * scale + 1e-300;
  }
  if (!good) {
    ++m_fallbacks;
    return nelson_derivatives(m_K, m_M, lambda, phi, dK, dM);
  }
  Eigen::MatrixXd out(phi.size(), static_cast<Eigen::Index>(dK.size()));
  for (std::size_t p = 0; p < dK.size(); ++p) {
    const auto j = static_cast<Eigen::Index>(p);
    const double c = -Mphi.dot(v.col(j)) - 0.5 * phi.dot(dM[p] * phi);
    out.col(j) = v.col(j) + c * phi;
  }
  return out;
}

Eigen::VectorXd modal_sum_derivative(const Eigen::Ref<const Eigen::MatrixXd>& Phi,
                                     const Eigen::Ref<const Eigen::VectorXd>& lambdas, int i,
                                     const SparseMatrix& dK, const SparseMatrix& dM) {
  const Eigen::VectorXd phi = Phi.col(i);
  const Eigen::VectorXd f = dK * phi - lambdas(i) * (dM * phi);
  Eigen::VectorXd d = -0.5 * phi.dot(dM * phi) * phi;
  for (int j = 0; j < Phi.cols(); ++j) {
    if (j == i) continue;
    const double gap = lambdas(i) - lambdas(j);
    if (gap == 0.0) continue;  // repeated eigenvalue: the term is undefined; skip
    d += Phi.col(j) * (Phi.col(j).dot(f) / gap);
  }
  return d;
}

}  // namespace ssid::estimator
