// Iterative Bayesian updating on a spring–mass chain whose truth is known:
// the estimator must recover hidden parameters, and its posterior covariance
// must equal Eq. (8) built from finite-difference sensitivities at the answer.
#include <Eigen/Dense>
#include <catch2/catch.hpp>
#include <cmath>

#include "estimator/updating/modal_model.hpp"
#include "estimator/updating/updating.hpp"
#include "formats/parse_error.hpp"

using namespace ssid::estimator;

namespace {

constexpr int n = 8;  // masses; spring 0 grounds mass 0, spring i joins i−1 and i

/// Chain: springs 0–3 scale with r0, springs 4–7 with r1, masses 4–7 with r2 (when present).
Operators chain(const Eigen::VectorXd& r) {
  const int p = static_cast<int>(r.size());
  auto spring = [](Eigen::MatrixXd& K, int i, double k) {
    K(i, i) += k;
    if (i > 0) { K(i - 1, i - 1) += k; K(i - 1, i) -= k; K(i, i - 1) -= k; }
  };
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n, n), M = Eigen::MatrixXd::Zero(n, n);
  std::vector<Eigen::MatrixXd> dK(p, Eigen::MatrixXd::Zero(n, n)), dM(p, Eigen::MatrixXd::Zero(n, n));
  for (int i = 0; i < n; ++i) {
    const double base = 1000.0 * (1.0 + 0.1 * i);
    const int j = i < 4 ? 0 : 1;
    spring(K, i, base * r(j));
    spring(dK[j], i, base);
    const double m = 1.0 + 0.05 * i;
    if (p > 2 && i >= 4) { M(i, i) += m * r(2); dM[2](i, i) += m; }
    else M(i, i) += m;
  }
  Operators ops;
  ops.K = K.sparseView();
  ops.M = M.sparseView();
  for (int j = 0; j < p; ++j) {
    ops.dK.push_back(dK[j].sparseView());
    ops.dM.push_back(dM[j].sparseView());
  }
  return ops;
}

std::pair<Eigen::VectorXd, Eigen::MatrixXd> dense_solve(const SparseMatrix& K, const SparseMatrix& M, int nmodes) {
  const Eigen::MatrixXd Kd(K), Md(M);
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(Kd, Md);
  return {es.eigenvalues().head(nmodes), es.eigenvectors().leftCols(nmodes)};
}

SparseMatrix sensors(std::vector<int> dofs) {
  SparseMatrix S(static_cast<Eigen::Index>(dofs.size()), n);
  for (std::size_t k = 0; k < dofs.size(); ++k) S.insert(static_cast<Eigen::Index>(k), dofs[k]) = 1.0;
  return S;
}

std::vector<MeasuredMode> measure(const Eigen::VectorXd& truth, const SparseMatrix& S, int nmeasured,
                                  double freq_std_pct, double shape_std) {
  const Operators ops = chain(truth);
  auto [lambda, phi] = dense_solve(ops.K, ops.M, nmeasured);
  std::vector<MeasuredMode> out;
  for (int i = 0; i < nmeasured; ++i) {
    MeasuredMode m;
    m.id = 101 + i;
    m.frequency_hz = std::sqrt(lambda(i)) / (2 * M_PI);
    m.frequency_std_hz = m.frequency_hz * freq_std_pct / 100.0;
    m.shape = -3.7 * (S * phi.col(i));  // arbitrary test scaling and sign
    m.shape_std = shape_std;
    out.push_back(m);
  }
  return out;
}

ParameterPrior prior_of(const Eigen::VectorXd& mean, double rel_std) {
  ParameterPrior p;
  p.mean = mean;
  p.cov = (rel_std * mean).array().square().matrix().asDiagonal();
  p.lower = Eigen::VectorXd::Constant(mean.size(), -INFINITY);
  p.upper = Eigen::VectorXd::Constant(mean.size(), INFINITY);
  for (int j = 0; j < mean.size(); ++j) p.names.push_back("r" + std::to_string(j));
  return p;
}

}  // namespace

TEST_CASE("updating recovers hidden stiffness and mass parameters of a chain", "[estimator][updating]") {
  const Eigen::VectorXd truth = (Eigen::VectorXd(3) << 1.25, 0.8, 1.1).finished();
  const SparseMatrix S = sensors({0, 1, 2, 3, 5, 7});
  const auto test = measure(truth, S, 4, 0.1, 1e-3);
  const ParameterPrior prior = prior_of(Eigen::VectorXd::Ones(3), 0.5);
  OperatorModel model(chain, dense_solve, S, 8);
  const UpdateResult res = update(model, test, prior);
  std::string notes;
  for (const auto& note : res.notes) notes += note + "\n";
  CAPTURE(notes);
  REQUIRE(res.converged);
  REQUIRE(res.notes.empty());
  // Noise-free data, broad prior: the answer is the truth up to the prior's pull.
  for (int j = 0; j < 3; ++j) CHECK(res.r(j) == Approx(truth(j)).epsilon(2e-3));
  CHECK(res.history.front().freq_rms_pct > 2.0);
  CHECK(res.history.back().freq_rms_pct < 0.05);
  CHECK(res.history.back().pairs.size() == 4);
  CHECK(res.history.back().mean_mac > 0.9999);
  CHECK(res.identifiability.rank == 3);

  // Eq. (8) from central finite differences of u(r) at the answer: an independent
  // check of the eigen-sensitivities and the shape normalisation inside the loop.
  auto predict = [&](const Eigen::VectorXd& r) {
    const Operators ops = chain(r);
    auto [lambda, phi] = dense_solve(ops.K, ops.M, 8);
    std::vector<double> u;
    for (const auto& pr : res.history.back().pairs) {
      u.push_back(std::sqrt(lambda(pr.fem)) / (2 * M_PI));
      Eigen::VectorXd s = S * phi.col(pr.fem);
      s /= s.norm();
      if (s.dot(test[static_cast<std::size_t>(pr.test)].shape) < 0) s = -s;
      for (int k = 0; k < s.size(); ++k) u.push_back(s(k));
    }
    return Eigen::Map<Eigen::VectorXd>(u.data(), static_cast<Eigen::Index>(u.size())).eval();
  };
  const Eigen::VectorXd u0 = predict(res.r);
  Eigen::MatrixXd T(u0.size(), 3);
  for (int j = 0; j < 3; ++j) {
    const double h = 1e-6 * res.r(j);
    Eigen::VectorXd rp = res.r, rm = res.r;
    rp(j) += h;
    rm(j) -= h;
    T.col(j) = (predict(rp) - predict(rm)) / (2 * h);
  }
  Eigen::VectorXd w(u0.size());
  int row = 0;
  for (const auto& pr : res.history.back().pairs) {
    w(row++) = 1.0 / std::pow(test[static_cast<std::size_t>(pr.test)].frequency_std_hz, 2);
    for (int k = 0; k < S.rows(); ++k) w(row++) = 1.0 / (1e-3 * 1e-3);
  }
  const Eigen::MatrixXd H = Eigen::MatrixXd(prior.cov.inverse()) + T.transpose() * w.asDiagonal() * T;
  const Eigen::MatrixXd post = H.inverse();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      CHECK(res.posterior_cov(i, j) == Approx(post(i, j)).epsilon(1e-3).margin(1e-12));
}

TEST_CASE("frequencies only, modal-summation shapes and Taylor operators", "[estimator][updating]") {
  const Eigen::VectorXd truth = (Eigen::VectorXd(2) << 1.3, 0.9).finished();
  // Six sensors on eight DOFs: enough that the four lowest modes do not alias.
  const SparseMatrix S = sensors({0, 1, 3, 4, 6, 7});
  const Eigen::VectorXd r0 = Eigen::VectorXd::Ones(2);

  SECTION("frequencies alone identify two stiffness scales") {
    auto test = measure(truth, S, 4, 0.05, 0.0);
    for (auto& m : test) m.shape.resize(0);
    OperatorModel model(chain, dense_solve, S, 6);
    const auto res = update(model, test, prior_of(r0, 0.5));
    REQUIRE(res.converged);
    CHECK(res.r(0) == Approx(truth(0)).epsilon(1e-3));
    CHECK(res.r(1) == Approx(truth(1)).epsilon(1e-3));
  }
  SECTION("K linear in r: the Taylor model of imported operators is exact") {
    const auto test = measure(truth, S, 4, 0.1, 1e-3);
    OperatorModel exact(chain, dense_solve, S, 6);
    OperatorModel taylor(taylor_operators(chain(r0), r0), dense_solve, S, 6);
    const auto a = update(exact, test, prior_of(r0, 0.5));
    const auto b = update(taylor, test, prior_of(r0, 0.5));
    CHECK((a.r - b.r).norm() < 1e-10);
    CHECK(b.r(0) == Approx(truth(0)).epsilon(2e-3));
  }
  SECTION("the seed's modal-summation shape derivatives converge to the same answer") {
    const auto test = measure(truth, S, 4, 0.1, 1e-3);
    // With all 8 modes the modal sum is exact for this 8-DOF chain.
    OperatorModel model(chain, dense_solve, S, 8, ShapeDerivative::ModalSum);
    const auto res = update(model, test, prior_of(r0, 0.5));
    REQUIRE(res.converged);
    CHECK(res.r(0) == Approx(truth(0)).epsilon(2e-3));
    CHECK(res.r(1) == Approx(truth(1)).epsilon(2e-3));
  }
}

TEST_CASE("bounds are honoured and unpaired test modes reported", "[estimator][updating]") {
  const Eigen::VectorXd truth = (Eigen::VectorXd(2) << 1.3, 0.9).finished();
  const SparseMatrix S = sensors({0, 1, 3, 4, 6, 7});
  auto test = measure(truth, S, 3, 0.1, 1e-3);
  MeasuredMode stray;  // a test mode no analysis mode explains (a shape orthogonal to all computed)
  stray.id = 999;
  stray.frequency_hz = 1000.0;
  stray.frequency_std_hz = 1.0;
  stray.shape = Eigen::VectorXd::Zero(6);
  stray.shape(0) = 1;
  stray.shape_std = 1e-3;
  test.push_back(stray);
  ParameterPrior prior = prior_of(Eigen::VectorXd::Ones(2), 0.5);
  prior.upper(0) = 1.2;  // below the truth 1.3
  OperatorModel model(chain, dense_solve, S, 6);
  const auto res = update(model, test, prior);
  CHECK(res.r(0) <= 1.2);
  CHECK(res.r(0) == Approx(1.2));
  bool unpaired = false, bound = false;
  for (const auto& note : res.notes) {
    if (note.find("test mode 999 has no analysis partner") != std::string::npos) unpaired = true;
    if (note.find("bound") != std::string::npos) bound = true;
  }
  CHECK(unpaired);
  CHECK(bound);
  CHECK(res.history.back().pairs.size() == 3);
}

TEST_CASE("modes that swap order during the update stay with their test partner", "[estimator][updating]") {
  // Two nearly uncoupled oscillators: at the prior λ = (100, 150), at the truth
  // (200, 150) — the analysis modes change order on the way, and pairing by index
  // would exchange them. Tracking by shape must not.
  auto ops_of = [](const Eigen::VectorXd& r) {
    Operators ops;
    Eigen::MatrixXd K(2, 2), dK0 = Eigen::MatrixXd::Zero(2, 2), dK1 = Eigen::MatrixXd::Zero(2, 2);
    K << 100 * r(0) + 0.01, -0.01, -0.01, 150 * r(1) + 0.01;
    dK0(0, 0) = 100;
    dK1(1, 1) = 150;
    ops.K = K.sparseView();
    ops.M = Eigen::MatrixXd::Identity(2, 2).sparseView();
    ops.dK = {dK0.sparseView(), dK1.sparseView()};
    ops.dM = {SparseMatrix(2, 2), SparseMatrix(2, 2)};
    return ops;
  };
  SparseMatrix S(2, 2);
  S.setIdentity();
  std::vector<MeasuredMode> test(2);
  test[0].id = 1;
  test[0].frequency_hz = std::sqrt(150.0) / (2 * M_PI);
  test[0].shape = Eigen::Vector2d(0, 1);
  test[1].id = 2;
  test[1].frequency_hz = std::sqrt(200.0) / (2 * M_PI);
  test[1].shape = Eigen::Vector2d(1, 0);
  for (auto& t : test) {
    t.frequency_std_hz = 1e-3 * t.frequency_hz;
    t.shape_std = 1e-2;
  }
  OperatorModel model(ops_of, dense_solve, S, 2);
  UpdateOptions options;
  options.freq_tol_pct = 100;
  const auto res = update(model, test, prior_of(Eigen::VectorXd::Ones(2), 1.0), options);
  REQUIRE(res.converged);
  CHECK(res.r(0) == Approx(2.0).epsilon(1e-3));
  CHECK(res.r(1) == Approx(1.0).epsilon(1e-3));
  // Cycle 0: test mode 1 (150) ↔ analysis mode 2; at the end ↔ analysis mode 1.
  CHECK(res.history.front().pairs[0].fem == 1);
  CHECK(res.history.back().pairs[0].fem == 0);
  CHECK(res.history.back().pairs[1].fem == 1);
  CHECK(res.notes.empty());
}

TEST_CASE("a second configuration makes an unidentifiable parameter identifiable", "[estimator][updating]") {
  // r0 scales every spring, r1 every mass: bare-structure frequencies inform only
  // r0/r1. A known added mass (not scaled by r1) separates the two.
  auto make = [](double added) {
    return [added](const Eigen::VectorXd& r) {
      Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n, n), M0 = Eigen::MatrixXd::Zero(n, n);
      for (int i = 0; i < n; ++i) {
        const double k = 1000.0 * (1.0 + 0.1 * i);
        K(i, i) += k;
        if (i > 0) { K(i - 1, i - 1) += k; K(i - 1, i) -= k; K(i, i - 1) -= k; }
        M0(i, i) = 1.0 + 0.05 * i;
      }
      Eigen::MatrixXd Madd = Eigen::MatrixXd::Zero(n, n);
      Madd(n - 1, n - 1) = added;
      Operators ops;
      ops.K = (r(0) * K).sparseView();
      ops.M = (r(1) * M0 + Madd).sparseView();
      ops.dK = {K.sparseView(), SparseMatrix(n, n)};
      ops.dM = {SparseMatrix(n, n), M0.sparseView()};
      return ops;
    };
  };
  const Eigen::VectorXd truth = (Eigen::VectorXd(2) << 1.2, 0.9).finished();
  const SparseMatrix S = sensors({0, 1, 3, 4, 6, 7});
  auto frequencies_of = [&](double added) {
    const Operators ops = make(added)(truth);
    auto [lambda, phi] = dense_solve(ops.K, ops.M, 3);
    std::vector<MeasuredMode> test;
    for (int i = 0; i < 3; ++i) {
      MeasuredMode m;
      m.id = i + 1;
      m.frequency_hz = std::sqrt(lambda(i)) / (2 * M_PI);
      m.frequency_std_hz = 1e-3 * m.frequency_hz;
      test.push_back(m);
    }
    return test;
  };
  const ParameterPrior prior = prior_of(Eigen::VectorXd::Ones(2), 0.3);
  OperatorModel bare(make(0.0), dense_solve, S, 4), loaded(make(3.0), dense_solve, S, 4);
  const auto one = update(bare, frequencies_of(0.0), prior);
  CHECK(one.identifiability.rank == 1);
  CHECK(one.r(0) / one.r(1) == Approx(truth(0) / truth(1)).epsilon(1e-3));  // the ratio is found
  CHECK(one.identifiability.std_ratio.maxCoeff() > 0.5);  // but each alone stays near its prior

  const auto both = update({{"bare", &bare, frequencies_of(0.0)}, {"tip mass", &loaded, frequencies_of(3.0)}}, prior);
  REQUIRE(both.converged);
  CHECK(both.identifiability.rank == 2);
  CHECK(both.r(0) == Approx(truth(0)).epsilon(5e-3));
  CHECK(both.r(1) == Approx(truth(1)).epsilon(5e-3));
  CHECK(both.history.back().pairs.size() == 6);

  // Recursive: bare first, its posterior the prior of the loaded test, ends near the joint answer.
  const auto second = update(loaded, frequencies_of(3.0), posterior_as_prior(one, prior));
  CHECK(second.r(0) == Approx(both.r(0)).epsilon(1e-2));
  CHECK(second.r(1) == Approx(both.r(1)).epsilon(1e-2));
}

namespace {

/// A model whose solves fail (a NumericalError, as a non-converged eigen-solve
/// throws) from the `fail_from`-th on.
class FailingModel : public ModalModel {
 public:
  FailingModel(OperatorModel& inner, int fail_from) : m_inner(inner), m_fail_from(fail_from) {}
  int parameter_count() const override { return m_inner.parameter_count(); }
  ModalSolution solve(const Eigen::VectorXd& r) override {
    if (++m_solves >= m_fail_from) throw ssid::formats::NumericalError("eigen-solve did not converge");
    return m_inner.solve(r);
  }
  ModeSensitivity sensitivity(int i, bool shapes) override { return m_inner.sensitivity(i, shapes); }

 private:
  OperatorModel& m_inner;
  int m_fail_from = 0, m_solves = 0;
};

}  // namespace

TEST_CASE("an interruption returns the last accepted cycle, as the same run stopped there by its limit",
          "[estimator][updating][progress]") {
  const Eigen::VectorXd truth = (Eigen::VectorXd(3) << 1.25, 0.8, 1.1).finished();
  const SparseMatrix S = sensors({0, 1, 2, 3, 5, 7});
  const auto test = measure(truth, S, 4, 0.1, 1e-3);
  const ParameterPrior prior = prior_of(Eigen::VectorXd::Ones(3), 0.5);
  // Reference: two cycles after the start by the iteration limit (not converged).
  OperatorModel ref_model(chain, dense_solve, S, 8);
  UpdateOptions two;
  two.max_iterations = 2;
  const UpdateResult ref = update(ref_model, test, prior, two);
  REQUIRE(!ref.converged);
  REQUIRE(ref.history.size() == 3);
  REQUIRE(ref.stopped.empty());

  // Interrupted at the report of the third cycle done (it was accepted).
  OperatorModel model(chain, dense_solve, S, 8);
  std::vector<std::string> reports;
  const Progress stop_at_third = [&](const ProgressEvent& e) {
    CHECK(e.phase == "cycle");
    CHECK(e.total == 21);
    CHECK(e.total_is_bound);
    if (!e.tick) reports.push_back(e.text());
    if (!e.tick && e.done == 3) throw Interrupted("interrupted (test)");
  };
  const UpdateResult res = update(model, test, prior, {}, stop_at_third);
  CHECK(res.interrupted);
  CHECK(res.stopped == "interrupted (test)");
  CHECK(!res.converged);
  REQUIRE(res.history.size() == 3);
  CHECK(res.notes.back() == "stopped after 3 cycle(s): interrupted (test)");
  CHECK(res.r == ref.r);
  CHECK(res.r == res.history.back().r);
  CHECK(res.posterior_cov == ref.posterior_cov);
  CHECK(res.log_evidence == ref.log_evidence);
  REQUIRE(reports.size() >= 3);
  CHECK_THAT(reports.front(), Catch::StartsWith("cycle 1/21: J = "));

  // Interrupted before any cycle was accepted: nothing to return, the exception passes.
  OperatorModel model2(chain, dense_solve, S, 8);
  const Progress stop_at_once = [](const ProgressEvent&) { throw Interrupted("interrupted (test)"); };
  CHECK_THROWS_AS(update(model2, test, prior, {}, stop_at_once), Interrupted);
}

TEST_CASE("a numerical failure after the first cycle returns the last accepted one, marked stopped",
          "[estimator][updating]") {
  const Eigen::VectorXd truth = (Eigen::VectorXd(3) << 1.25, 0.8, 1.1).finished();
  const SparseMatrix S = sensors({0, 1, 2, 3, 5, 7});
  const auto test = measure(truth, S, 4, 0.1, 1e-3);
  const ParameterPrior prior = prior_of(Eigen::VectorXd::Ones(3), 0.5);
  OperatorModel inner(chain, dense_solve, S, 8);
  // Solves 1 and 2 (cycles 0 and 1) succeed; every later one fails, damped retries included.
  FailingModel model(inner, 3);
  const UpdateResult res = update(model, test, prior);
  CHECK(res.stopped == "eigen-solve did not converge");
  CHECK(!res.interrupted);
  CHECK(!res.converged);
  REQUIRE(res.history.size() == 2);
  CHECK(res.r == res.history.back().r);
  CHECK(res.posterior_std.size() == 3);
  // Failing in cycle 0 leaves nothing: the failure passes.
  FailingModel at_once(inner, 1);
  CHECK_THROWS_AS(update(at_once, test, prior), ssid::formats::NumericalError);
}

TEST_CASE("pair_for_update honours the analyst's pairs where MAC would pair differently", "[estimator][updating][pairs]") {
  // Two analysis modes; the test shape is analysis mode 2's, so MAC pairs it there.
  ModalSolution fem;
  fem.eigenvalues = Eigen::Vector2d(100.0, 400.0);
  fem.sensor_shapes.resize(3, 2);
  fem.sensor_shapes << 1, 0, 0, 1, 1, 0;
  MeasuredMode t;
  t.id = 7;
  t.frequency_hz = 3.0;  // analysis modes at 1.59 and 3.18 Hz
  t.frequency_std_hz = 0.03;
  t.shape = Eigen::Vector3d(0, 1, 0);
  t.shape_std = 0.01;
  UpdateOptions o;
  const auto by_mac = pair_for_update({t}, fem, o);
  REQUIRE(by_mac.size() == 1);
  CHECK(by_mac[0].fem == 1);
  t.fixed_partner = 0;  // the analyst says: analysis mode 1
  const auto fixed = pair_for_update({t}, fem, o);
  REQUIRE(fixed.size() == 1);
  CHECK(fixed[0].fem == 0);
  CHECK(fixed[0].mac == Approx(0.0).margin(1e-12));  // kept although MAC says no
  t.fixed_partner = 2;  // beyond the solved modes
  CHECK_THROWS_WITH(pair_for_update({t}, fem, o),
                    "test mode 7 is paired with analysis mode 3, but only 2 were solved");
}
