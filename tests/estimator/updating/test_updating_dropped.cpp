// A test mode whose analysis partner is lost during the iterations leaves the
// update, is reported (notes and UpdateResult::dropped), and the estimate goes
// on with the modes that keep their partners.
#include <catch2/catch.hpp>
#include <cmath>

#include "estimator/updating/updating.hpp"

using namespace ssid::estimator;

namespace {

/// Three modes with λ_i = (2π f_i)² r. At the nominal r = 1 the modes are the
/// sensor unit vectors e0, e1, e2; at any other r the third mode has turned into
/// e3, which the third test shape does not contain (its partner is "lost").
class TurningModel : public ModalModel {
 public:
  int parameter_count() const override { return 1; }
  ModalSolution solve(const Eigen::VectorXd& r) override {
    m_r = r(0);
    ModalSolution s;
    s.eigenvalues.resize(3);
    for (int i = 0; i < 3; ++i) s.eigenvalues(i) = std::pow(2 * M_PI * f[i], 2) * m_r;
    s.sensor_shapes = Eigen::MatrixXd::Zero(4, 3);
    s.sensor_shapes(0, 0) = s.sensor_shapes(1, 1) = 1;
    s.sensor_shapes(m_r == 1.0 ? 2 : 3, 2) = 1;
    s.tracking_shapes = s.sensor_shapes;
    ++solves;
    return s;
  }
  ModeSensitivity sensitivity(int i, bool shapes) override {
    ModeSensitivity s;
    s.d_eigenvalue = Eigen::VectorXd::Constant(1, std::pow(2 * M_PI * f[i], 2));
    if (shapes) s.d_sensor_shape = Eigen::MatrixXd::Zero(4, 1);
    return s;
  }
  double f[3] = {10, 20, 30};
  double m_r = 1;
  int solves = 0;
};

}  // namespace

TEST_CASE("a test mode that loses its analysis partner leaves the update and is reported", "[estimator][updating]") {
  TurningModel model;
  std::vector<MeasuredMode> test;
  for (int i = 0; i < 3; ++i) {
    MeasuredMode m;
    m.id = 101 + i;
    m.frequency_hz = model.f[i] * std::sqrt(1.1);  // truth r = 1.1
    m.frequency_std_hz = 1e-4 * m.frequency_hz;
    m.shape = Eigen::VectorXd::Zero(4);
    m.shape(i) = -2.0;
    m.shape_std = 1e-3;
    test.push_back(m);
  }
  ParameterPrior prior;
  prior.names = {"r"};
  prior.mean = Eigen::VectorXd::Ones(1);
  prior.cov = Eigen::MatrixXd::Constant(1, 1, 0.25);
  prior.lower = Eigen::VectorXd::Constant(1, 0.1);
  prior.upper = Eigen::VectorXd::Constant(1, 10.0);
  const UpdateResult r = update(model, test, prior);
  REQUIRE(r.converged);
  REQUIRE(r.dropped.size() == 1);
  CHECK(r.dropped[0].test == 2);
  CHECK(r.dropped[0].cycle == 1);
  CHECK_THAT(r.dropped[0].why, Catch::Contains("could not be followed") || Catch::Contains("no longer matches"));
  bool noted = false;
  for (const auto& n : r.notes) noted = noted || n.find("test mode 103 left the update") != std::string::npos;
  CHECK(noted);
  CHECK(r.history.front().pairs.size() == 3);
  CHECK(r.history.back().pairs.size() == 2);
  // From the two modes that kept their partners (the prior pulls by ~1e-6 at these weights).
  CHECK(r.r(0) == Approx(1.1).epsilon(1e-5));
}
