#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <cmath>
#include <random>

#include "estimator/updating/bayes.hpp"

using namespace ssid::estimator;

namespace {
struct Linear {
  Eigen::MatrixXd A;
  Eigen::VectorXd z, r0, sig;
  Eigen::MatrixXd P;
  Linear() {
    std::mt19937 rng(11);
    std::normal_distribution<double> g;
    A.resize(8, 3);
    for (int i = 0; i < 8; ++i)
      for (int j = 0; j < 3; ++j) A(i, j) = g(rng);
    z.resize(8);
    for (int i = 0; i < 8; ++i) z(i) = g(rng);
    r0 = Eigen::Vector3d(0.5, -0.2, 1.0);
    sig = Eigen::VectorXd::Constant(8, 0.3);
    sig(2) = 0.1;
    Eigen::MatrixXd B = Eigen::MatrixXd::Random(3, 3);
    P = B * B.transpose() + Eigen::MatrixXd::Identity(3, 3);
  }
};
}  // namespace

TEST_CASE("for a linear model one step of Eq. (7) reaches the closed-form posterior", "[bayes]") {
  Linear L;
  const Eigen::MatrixXd W = L.sig.array().square().inverse().matrix().asDiagonal();
  const Eigen::MatrixXd Pinv = L.P.inverse();
  const Eigen::MatrixXd H = Pinv + L.A.transpose() * W * L.A;
  const Eigen::VectorXd mean = H.ldlt().solve(Pinv * L.r0 + L.A.transpose() * W * L.z);
  const Eigen::Vector3d start(3.0, 2.0, -1.0);
  const Eigen::VectorXd inf = Eigen::VectorXd::Constant(3, INFINITY);
  BayesStep s = bayes_step(start, L.r0, L.P, L.z, L.A * start, L.A, L.sig, -inf, inf);
  CHECK((s.r_next - mean).norm() < 1e-12);
  CHECK((s.posterior_cov - H.inverse()).norm() < 1e-12);
  CHECK_FALSE(s.clipped);
  // A second step does not move (the fixed point is the posterior mode).
  BayesStep s2 = bayes_step(s.r_next, L.r0, L.P, L.z, L.A * s.r_next, L.A, L.sig, -inf, inf);
  CHECK((s2.r_next - s.r_next).norm() < 1e-12);
  // Bounds clip the step.
  Eigen::VectorXd hi = inf;
  hi(0) = mean(0) - 0.1;
  BayesStep s3 = bayes_step(start, L.r0, L.P, L.z, L.A * start, L.A, L.sig, -inf, hi);
  CHECK(s3.clipped);
  CHECK(s3.r_next(0) == hi(0));
}

TEST_CASE("Laplace evidence is exact for a linear-Gaussian model", "[bayes]") {
  Linear L;
  const Eigen::VectorXd inf = Eigen::VectorXd::Constant(3, INFINITY);
  BayesStep s = bayes_step(L.r0, L.r0, L.P, L.z, L.A * L.r0, L.A, L.sig, -inf, inf);
  // Objective at the mode.
  BayesStep at = bayes_step(s.r_next, L.r0, L.P, L.z, L.A * s.r_next, L.A, L.sig, -inf, inf);
  const double laplace = laplace_log_evidence(at.objective, L.sig, L.P, at.posterior_cov);
  // Exact: z ~ N(A r0, S_ee + A P A^T).
  const Eigen::MatrixXd C = Eigen::MatrixXd(L.sig.array().square().matrix().asDiagonal()) + L.A * L.P * L.A.transpose();
  const Eigen::VectorXd d = L.z - L.A * L.r0;
  Eigen::LLT<Eigen::MatrixXd> cl(C);
  const double exact = -0.5 * d.dot(cl.solve(d)) - cl.matrixLLT().diagonal().array().log().sum() -
                       0.5 * static_cast<double>(d.size()) * std::log(2 * M_PI);
  CHECK(laplace == Approx(exact).epsilon(1e-10));
}

TEST_CASE("identifiability flags a parameter the data do not inform", "[bayes]") {
  Eigen::MatrixXd T(4, 2);
  T << 1, 0, 2, 0, -1, 0, 0.5, 0;  // the second parameter has no effect
  Eigen::VectorXd sig = Eigen::VectorXd::Constant(4, 0.1);
  Eigen::MatrixXd P = Eigen::MatrixXd::Identity(2, 2);
  Eigen::MatrixXd H = P.inverse() + T.transpose() * (sig.array().square().inverse().matrix().asDiagonal()) * T;
  Identifiability id = identifiability(T, sig, P, H.inverse());
  CHECK(id.rank == 1);
  CHECK(id.std_ratio(1) == Approx(1.0));
  CHECK(id.std_ratio(0) < 0.1);
}
