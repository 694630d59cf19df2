// The helpers the extension kinds share (extension_util.hpp), against values
// worked by hand.
#include <Eigen/Dense>
#include <catch2/catch.hpp>
#include <cmath>

#include "estimator/diagnosis/hypotheses/extension_util.hpp"

namespace ext = ssid::estimator::diagnosis::hypotheses;

TEST_CASE("explained_share: the MAC for one column, 1 inside the span, 0 across it", "[estimator][extensions]") {
  Eigen::VectorXd t(3);
  t << 1, 2, 2;  // |t|² = 9
  Eigen::MatrixXd a(3, 1);
  a << 1, 0, 0;
  CHECK(ext::detail::explained_share(a, t) == Approx(1.0 / 9.0));  // (a·t)²/(|a|²|t|²)
  Eigen::MatrixXd b(3, 2);
  b << 1, 0, 0, 1, 0, 1;  // spans (1,0,0) and (0,1,1): t = 1·(1,0,0) + 2·(0,1,1)
  CHECK(ext::detail::explained_share(b, t) == Approx(1.0));
  Eigen::MatrixXd c(3, 2);
  c << 0, 0, 1, 0, -1, 0;  // (0,1,−1) ⟂ t, and a zero column
  CHECK(ext::detail::explained_share(c, t) == Approx(0.0).margin(1e-15));
  CHECK(ext::detail::explained_share(Eigen::MatrixXd::Zero(3, 2), t) == 0.0);
  CHECK(ext::detail::explained_share(a, Eigen::VectorXd::Zero(3)) == 0.0);
}

TEST_CASE("response_at_sensors: the modal sum of the forced answer, worked by hand", "[estimator][extensions]") {
  // Two modes, λ = (2π·10)², (2π·20)², seen at two sensors as (1, 0) and (1, 1);
  // a force with modal components (3, −1) answered at 15 Hz:
  // u = 3·(1,0)/(λ₁ − ω²) − 1·(1,1)/(λ₂ − ω²).
  ext::UnexplainedModes x;
  const double w = 2 * M_PI;
  x.eigenvalues = Eigen::Vector2d(std::pow(10 * w, 2), std::pow(20 * w, 2));
  x.sensor_shapes.resize(2, 2);
  x.sensor_shapes << 1, 1, 0, 1;
  const double lam = std::pow(15 * w, 2), d1 = x.eigenvalues(0) - lam, d2 = x.eigenvalues(1) - lam;
  const Eigen::VectorXd u = ext::detail::response_at_sensors(x, 15.0, Eigen::Vector2d(3, -1));
  REQUIRE(u.size() == 2);
  CHECK(u(0) == Approx(3 / d1 - 1 / d2));
  CHECK(u(1) == Approx(-1 / d2));
  // Exactly at a mode its term stays finite and dominates, with the sign of the side it is taken from.
  const Eigen::VectorXd at = ext::detail::response_at_sensors(x, 10.0, Eigen::Vector2d(1, 1));
  CHECK(std::isfinite(at(0)));
  CHECK(std::abs(at(0)) > 1e6 * std::abs(at(1)));
}
