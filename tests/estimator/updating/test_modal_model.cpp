// OperatorModel's batch of sensitivities (computed on all cores, one Nelson
// solver per thread) against the same model's mode-by-mode sensitivity(), and
// the batch's shape derivatives against central finite differences.
#include <Eigen/Dense>
#include <catch2/catch.hpp>
#include <cmath>
#include <stdexcept>

#include "estimator/updating/modal_model.hpp"

using namespace ssid::estimator;

namespace {

constexpr int n = 12;

/// Grounded chain: spring i (joining masses i−1 and i) scales with r0 for even i
/// and r1 for odd i; masses 6.. scale with r2. Distinct base values keep the
/// eigenvalues simple.
Operators chain(const Eigen::VectorXd& r) {
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n, n), M = Eigen::MatrixXd::Zero(n, n);
  std::vector<Eigen::MatrixXd> dK(3, Eigen::MatrixXd::Zero(n, n)), dM(3, Eigen::MatrixXd::Zero(n, n));
  auto spring = [](Eigen::MatrixXd& A, int i, double k) {
    A(i, i) += k;
    if (i > 0) A(i - 1, i - 1) += k, A(i - 1, i) -= k, A(i, i - 1) -= k;
  };
  for (int i = 0; i < n; ++i) {
    const double base = 1000.0 * (1.0 + 0.13 * i + 0.01 * i * i);
    const int j = i % 2;
    spring(K, i, base * r(j));
    spring(dK[static_cast<std::size_t>(j)], i, base);
    const double m = 1.0 + 0.07 * i;
    if (i >= 6) M(i, i) += m * r(2), dM[2](i, i) += m;
    else M(i, i) += m;
  }
  Operators ops;
  ops.K = K.sparseView();
  ops.M = M.sparseView();
  for (int j = 0; j < 3; ++j) {
    ops.dK.push_back(dK[static_cast<std::size_t>(j)].sparseView());
    ops.dM.push_back(dM[static_cast<std::size_t>(j)].sparseView());
  }
  return ops;
}

std::pair<Eigen::VectorXd, Eigen::MatrixXd> dense_solve(const SparseMatrix& K, const SparseMatrix& M, int nmodes) {
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es{Eigen::MatrixXd(K), Eigen::MatrixXd(M)};
  return {es.eigenvalues().head(nmodes), es.eigenvectors().leftCols(nmodes)};
}

SparseMatrix sensors() {
  SparseMatrix S(5, n);
  for (int k = 0; k < 5; ++k) S.insert(k, 2 * k + 1) = 1.0;
  return S;
}

}  // namespace

TEST_CASE("OperatorModel: a batch of sensitivities equals the mode-by-mode ones", "[estimator][modal_model]") {
  const Eigen::VectorXd r = (Eigen::VectorXd(3) << 1.1, 0.9, 1.05).finished();
  const std::vector<int> modes{7, 0, 3, 1, 5, 2, 6};
  const std::vector<bool> shapes{true, true, false, true, true, false, true};
  // Three threads whatever the machine has (so that the threaded path runs on a
  // one-core runner too), one, and the default.
  for (auto kind : {ShapeDerivative::Nelson, ShapeDerivative::ModalSum})
  for (int threads : {3, 1, 0}) {
    OperatorModel batch(chain, dense_solve, sensors(), 8, kind), single(chain, dense_solve, sensors(), 8, kind);
    batch.set_sensitivity_threads(threads);
    batch.solve(r);
    single.solve(r);
    const std::vector<ModeSensitivity> got = batch.sensitivities(modes, shapes);
    REQUIRE(got.size() == modes.size());
    for (std::size_t k = 0; k < modes.size(); ++k) {
      CAPTURE(k, modes[k], static_cast<int>(kind), threads);
      const ModeSensitivity want = single.sensitivity(modes[k], shapes[k]);
      // Each mode is computed alone whichever thread takes it: the same bits.
      CHECK(got[k].d_eigenvalue == want.d_eigenvalue);
      CHECK(got[k].d_sensor_shape.size() == (shapes[k] ? 5 * 3 : 0));
      CHECK(got[k].d_sensor_shape == want.d_sensor_shape);
    }
    // A second batch reuses the solvers: still the same values.
    const std::vector<ModeSensitivity> again = batch.sensitivities(modes, shapes);
    for (std::size_t k = 0; k < modes.size(); ++k) CHECK(again[k].d_sensor_shape == got[k].d_sensor_shape);
  }
}

TEST_CASE("OperatorModel: batch shape derivatives match central finite differences", "[estimator][modal_model]") {
  const Eigen::VectorXd r = (Eigen::VectorXd(3) << 1.1, 0.9, 1.05).finished();
  OperatorModel model(chain, dense_solve, sensors(), 8);
  const ModalSolution base = model.solve(r);
  const std::vector<int> modes{0, 4, 7};
  const std::vector<ModeSensitivity> got = model.sensitivities(modes, {true, true, true});
  const double h = 1e-6;
  for (int j = 0; j < 3; ++j) {
    Eigen::VectorXd rp = r, rm = r;
    rp(j) += h, rm(j) -= h;
    OperatorModel probe(chain, dense_solve, sensors(), 8);
    const ModalSolution sp = probe.solve(rp), sm = probe.solve(rm);
    for (std::size_t k = 0; k < modes.size(); ++k) {
      const int i = modes[k];
      // Mass-normalised modes carry an arbitrary sign: align with the base solve.
      const Eigen::VectorXd up = sp.sensor_shapes.col(i) * (sp.tracking_shapes.col(i).dot(base.tracking_shapes.col(i)) < 0 ? -1.0 : 1.0);
      const Eigen::VectorXd um = sm.sensor_shapes.col(i) * (sm.tracking_shapes.col(i).dot(base.tracking_shapes.col(i)) < 0 ? -1.0 : 1.0);
      const Eigen::VectorXd fd = (up - um) / (2 * h);
      CAPTURE(j, i);
      CHECK((got[k].d_sensor_shape.col(j) - fd).norm() <= 1e-6 * std::max(1.0, fd.norm()));
      const double dl = (sp.eigenvalues(i) - sm.eigenvalues(i)) / (2 * h);
      CHECK(got[k].d_eigenvalue(j) == Approx(dl).epsilon(1e-6));
    }
  }
}

TEST_CASE("OperatorModel: a mode that cannot be differentiated fails the batch as it fails alone",
          "[estimator][modal_model]") {
  // The chain and two identical, uncoupled oscillators: their eigenvalue is double,
  // and Nelson's method needs a simple one.
  auto twins = [](const Eigen::VectorXd& r) {
    Operators ops = chain(r);
    const int m = n + 2;
    auto widen = [m](const SparseMatrix& A) {
      Eigen::MatrixXd D = Eigen::MatrixXd::Zero(m, m);
      D.topLeftCorner(n, n) = Eigen::MatrixXd(A);
      return SparseMatrix(D.sparseView());
    };
    Eigen::MatrixXd K = Eigen::MatrixXd(widen(ops.K)), M = Eigen::MatrixXd(widen(ops.M));
    K(n, n) = K(n + 1, n + 1) = 700.0;
    M(n, n) = M(n + 1, n + 1) = 1.0;
    ops.K = K.sparseView(), ops.M = M.sparseView();
    for (auto& d : ops.dK) d = widen(d);
    for (auto& d : ops.dM) d = widen(d);
    return ops;
  };
  SparseMatrix S(2, n + 2);
  S.insert(0, 1) = 1.0, S.insert(1, n) = 1.0;
  const Eigen::VectorXd r = Eigen::VectorXd::Ones(3);
  OperatorModel alone(twins, dense_solve, S, 6), batch(twins, dense_solve, S, 6);
  const ModalSolution sol = alone.solve(r);
  batch.solve(r);
  batch.set_sensitivity_threads(3);
  std::vector<int> repeated;
  for (int i = 0; i + 1 < 6; ++i)
    if (std::abs(sol.eigenvalues(i + 1) - sol.eigenvalues(i)) < 1e-9 * sol.eigenvalues(i)) repeated = {i, i + 1};
  REQUIRE(repeated.size() == 2);
  std::string alone_error;
  try {
    alone.sensitivity(repeated[0], true);
  } catch (const std::runtime_error& e) {
    alone_error = e.what();
  }
  REQUIRE_FALSE(alone_error.empty());
  const std::vector<int> modes{0, 1, 2, 3, 4, 5};
  CHECK_THROWS_WITH(batch.sensitivities(modes, std::vector<bool>(6, true)), alone_error);
  // Without shape derivatives the same modes are fine.
  CHECK(batch.sensitivities(modes, std::vector<bool>(6, false)).size() == 6);
}

TEST_CASE("OperatorModel: a batch refuses modes it has not and mismatched flags", "[estimator][modal_model]") {
  OperatorModel model(chain, dense_solve, sensors(), 4);
  model.solve(Eigen::VectorXd::Ones(3));
  CHECK_THROWS_AS(model.sensitivities({0, 4}, {true, true}), std::out_of_range);
  CHECK_THROWS_AS(model.sensitivities({0, 1}, {true}), std::invalid_argument);
  CHECK(model.sensitivities({}, {}).empty());
}
