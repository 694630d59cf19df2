// Closed-form checks of the truss generator's reference assembler: the physics
// its frequency claims rest on.
#include <catch2/catch.hpp>

#include <cmath>

#include "translators/truss/configurations.hpp"
#include "translators/truss/reference_modes.hpp"

using namespace ssid::translators::truss;

namespace {
TrussCards empty_model() {
  TrussCards fe;
  fe.mat = {1, 70e9, 0.3, 0.0};
  return fe;
}
}  // namespace

TEST_CASE("reference assembler: rod between two masses vibrates at sqrt(2k/m)", "[truss][assembler]") {
  TrussCards fe = empty_model();
  fe.grids = {{1, {0, 0, 0}, "456", "ball"}, {2, {0.6, 0.8, 0}, "456", "ball"}};  // skewed axis, L = 1
  fe.rod_props = {{1, 2e-4, 0, 0, "strut"}};
  fe.rods = {{1, 1, 1, 2, 1}};
  fe.masses = {{1, 1, 2.0, 0, "joint"}, {2, 2, 2.0, 0, "joint"}};
  const ReferenceModes m = reference_modes(fe, 6);
  REQUIRE(m.frequency_hz.size() == 6);
  for (int j = 0; j < 5; ++j) CHECK(std::fabs(m.frequency_hz[j]) < 1e-3);  // 3 translations, 2 transverse relative motions
  const double k = 70e9 * 2e-4 / 1.0;
  CHECK(m.frequency_hz[5] == Approx(std::sqrt(2 * k / 2.0) / (2 * M_PI)).epsilon(1e-9));
}

TEST_CASE("reference assembler: free-free tube of 80 CBARs matches Euler-Bernoulli bending and axial", "[truss][assembler]") {
  TrussCards fe = empty_model();
  const double L = 2.0, A = 2e-4, I = 2e-8, mpl = 0.55;
  const int n = 80;
  Eigen::Vector3d axis = Eigen::Vector3d(1, 2, 2).normalized();  // an oblique axis exercises the rotation
  for (int k = 0; k <= n; ++k) fe.grids.push_back({k + 1, axis * (L * k / n), "", "strut"});
  fe.bar_props = {{1, A, I, I, 2 * I, mpl, "tube"}};
  for (int k = 0; k < n; ++k) fe.bars.push_back({k + 1, 1, k + 1, k + 2, Eigen::Vector3d::UnitZ(), 1});
  const Assembled asm_ = assemble_reference(fe);
  const ReferenceModes m = reference_modes(fe, 14);
  // Lumped mass has no rotary inertia: spinning about the axis carries no kinetic
  // energy, so there are five rigid-body modes with mass, then the bending pair.
  for (int j = 0; j < 5; ++j) CHECK(std::fabs(m.frequency_hz[j]) < 1e-2);
  const double bend = 4.730040745 * 4.730040745 / (2 * M_PI * L * L) * std::sqrt(70e9 * I / mpl);
  CHECK(m.frequency_hz[5] == Approx(bend).epsilon(1e-3));
  CHECK(m.frequency_hz[6] == Approx(bend).epsilon(1e-3));  // the orthogonal plane (I1 = I2)
  // The axial mode: translations along the axis carry (almost) all its kinetic energy.
  const ReferenceModes many = reference_modes(fe, 60);
  double axial = 0;
  for (std::size_t j = 5; j < many.frequency_hz.size() && axial == 0; ++j) {
    double along = 0, total = 0;
    for (int g = 0; g <= n; ++g) {
      const Eigen::Vector3d u = many.shapes.block(6 * g, static_cast<Eigen::Index>(j), 3, 1);
      const double mg = asm_.M.coeff(6 * g, 6 * g);
      along += mg * std::pow(u.dot(axis), 2);
      total += mg * u.squaredNorm();
    }
    if (along > 0.99 * total) axial = many.frequency_hz[j];
  }
  CHECK(axial == Approx(std::sqrt(70e9 * A / mpl) / (2 * L)).epsilon(1e-3));
}

TEST_CASE("reference assembler: RBE2 offset couples translation and rotation rigidly", "[truss][assembler]") {
  // A mass m with rotary inertia J at grid 1, a rigid arm of length r to grid 2,
  // a grounded spring k in y at grid 2: omega^2 = k (1/m + r^2/J).
  TrussCards fe = empty_model();
  const double m = 3.0, J = 0.02, r = 0.25, k = 5000.0;
  fe.grids = {{1, {0, 0, 0}, "", "ball"}, {2, {r, 0, 0}, "", "ball_surface"}};
  fe.masses = {{1, 1, m, J, "ball"}};
  fe.rigids = {{1, 1, {2}}};
  fe.spring_props = {{1, k, "suspension"}};
  fe.springs = {{1, 1, 2, 2, 0, 0}};
  const ReferenceModes modes = reference_modes(fe, 6);
  REQUIRE(modes.a_set_size == 6);
  CHECK(modes.frequency_hz.back() == Approx(std::sqrt(k * (1 / m + r * r / J)) / (2 * M_PI)).epsilon(1e-9));
  CHECK(std::fabs(modes.frequency_hz[4]) < 1e-3);
}

TEST_CASE("surge chain: fixed-fixed spring of N segments surges at the design frequency", "[truss][assembler]") {
  const double k = 600.0, f = 48.0;
  const int N = 12;
  const double ms = surge_spring_mass(k, f, N);
  TrussCards fe = empty_model();
  fe.spring_props = {{1, N * k, "suspension_chain"}};
  for (int i = 1; i < N; ++i) {
    fe.grids.push_back({i, {0, 0, 0.01 * i}, "12456", "spring"});
    fe.masses.push_back({i, i, ms / N, 0, "spring"});
  }
  for (int i = 1; i <= N; ++i) {
    // Ends grounded: the first and last segments tie to ground.
    if (i == 1) fe.springs.push_back({i, 1, 1, 3, 0, 0});
    else if (i == N) fe.springs.push_back({i, 1, N - 1, 3, 0, 0});
    else fe.springs.push_back({i, 1, i - 1, 3, i, 3});
  }
  const ReferenceModes m = reference_modes(fe, 3);
  CHECK(m.frequency_hz[0] == Approx(f).epsilon(1e-9));
  // Continuous spring: f = (1/2) sqrt(k/m); the 12-segment chain is within 0.3 %.
  CHECK(m.frequency_hz[0] == Approx(0.5 * std::sqrt(k / ms)).epsilon(3e-3));
}
