#include <catch2/catch.hpp>

#include <Eigen/Geometry>
#include <cmath>
#include <random>

#include "translators/synthetic_modes.hpp"

using namespace ssid::translators;
namespace uff = ssid::formats::uff;

namespace {

/// Three grids (ids 1, 2, 7), 6 DOFs each, grid 7 with a displacement frame
/// rotated 30° about Z; two random modes on the 18 g-set DOFs.
struct Fixture {
  DofMap gset;
  std::vector<GridPosition> grids;
  FeModeData fe;
  Fixture() {
    const Eigen::Matrix3d rz = Eigen::AngleAxisd(M_PI / 6, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    grids = {GridPosition{1, {0, 0, 0}, Eigen::Matrix3d::Identity()},
             GridPosition{2, {1, 0, 0}, Eigen::Matrix3d::Identity()}, GridPosition{7, {2, 0.5, 0}, rz}};
    for (const auto& g : grids)
      for (int c = 1; c <= 6; ++c) gset.add({g.id, c});
    std::mt19937 gen(3);
    std::uniform_real_distribution<double> u(-1, 1);
    fe.shapes.resize(18, 2);
    for (Eigen::Index i = 0; i < 18; ++i)
      for (Eigen::Index j = 0; j < 2; ++j) fe.shapes(i, j) = u(gen);
    fe.frequency_hz = {3.5, 12.25};
    fe.generalized_mass = {1.0, 1.0};
  }
};

}  // namespace

TEST_CASE("Normal deviates: explicit Box-Muller over mt19937_64, mean 0 and variance 1", "[synthetic]") {
  NormalDeviates z(42);
  std::mt19937_64 e(42);
  const double u1 = (static_cast<double>(e() >> 11) + 1.0) / 9007199254740992.0;
  const double u2 = static_cast<double>(e() >> 11) / 9007199254740992.0;
  const double r = std::sqrt(-2 * std::log(u1));
  CHECK(z() == r * std::cos(2 * M_PI * u2));
  CHECK(z() == r * std::sin(2 * M_PI * u2));

  const int n = 200000;
  double s = 0, s2 = 0, s4 = 0;
  int beyond2 = 0;
  for (int i = 0; i < n; ++i) {
    const double v = z();
    s += v;
    s2 += v * v;
    s4 += v * v * v * v;
    beyond2 += std::abs(v) > 2;
  }
  // Standard errors: mean 1/sqrt(n) = 0.0022, variance sqrt(2/n) = 0.0032.
  CHECK(std::abs(s / n) < 0.01);
  CHECK(std::abs(s2 / n - 1) < 0.015);
  CHECK(std::abs(s4 / n - 3) < 0.06);                  // Gaussian kurtosis
  CHECK(std::abs(double(beyond2) / n - 0.0455) < 0.002);  // P(|z| > 2)
}

TEST_CASE("Synthetic test without noise: translations in basic at every grid", "[synthetic]") {
  Fixture f;
  auto t = synthetic_test(f.fe, f.gset, f.grids);
  REQUIRE(t.modes.dofs.size() == 9);
  CHECK(t.modes.frequency_hz == f.fe.frequency_hz);
  // Grid 2 (basic frame): rows 3..5 are its components 1..3.
  for (int a = 0; a < 3; ++a) CHECK(t.modes.shapes(3 + a, 1) == f.fe.shapes(6 + a, 1));
  // Grid 7 (rotated CD): the sampled vector is R u_cd.
  Eigen::Vector3d ucd = f.fe.shapes.block(12, 0, 3, 1);
  Eigen::Vector3d ub = f.grids[2].frame * ucd;
  for (int a = 0; a < 3; ++a) CHECK(t.modes.shapes(6 + a, 0) == Approx(ub(a)).margin(1e-15));
  CHECK(t.modes.dofs[6].node == 7);
  CHECK(t.modes.dofs[8].direction == 3);

  // The file: nodes 2411 at basic positions, one 55 per mode; read back exactly in Extended precision.
  const std::string text = uff::format_uff(t.file, uff::Precision::Extended);
  auto back = uff::parse_uff(text, "synthetic.unv");
  auto nodes = back.nodes();
  REQUIRE(nodes.size() == 3);
  CHECK(nodes[2].xyz[1] == 0.5);
  auto read = modes_from_uff(back);
  REQUIRE(read.shapes.cols() == 2);
  CHECK(read.frequency_hz == t.modes.frequency_hz);
  CHECK(read.shapes == t.modes.shapes);
  CHECK(read.modal_mass == std::vector<double>{1.0, 1.0});
}

TEST_CASE("Synthetic test: chosen sensors, rotations, a-set expansion", "[synthetic]") {
  Fixture f;
  SyntheticTestOptions o;
  o.sensors = {7, 1};
  o.rotations = true;
  auto t = synthetic_test(f.fe, f.gset, f.grids, o);
  REQUIRE(t.modes.dofs.size() == 12);
  CHECK(t.modes.dofs[0].node == 7);
  CHECK(t.modes.dofs[6].node == 1);
  Eigen::Vector3d rcd = f.fe.shapes.block(15, 1, 3, 1);
  CHECK(t.modes.shapes(4, 1) == Approx((f.grids[2].frame * rcd)(1)).margin(1e-15));

  // a-set: grid 1 fixed (its DOFs removed); expansion through T gives zeros there.
  Reduction red;
  red.T.resize(18, 12);
  std::vector<Eigen::Triplet<double>> trip;
  for (int i = 0; i < 12; ++i) trip.emplace_back(6 + i, i, 1.0);
  red.T.setFromTriplets(trip.begin(), trip.end());
  FeModeData a = f.fe;
  a.shapes = f.fe.shapes.bottomRows(12);
  auto ta = synthetic_test(a, red, f.gset, f.grids, o);
  CHECK(ta.modes.shapes.topRows(6) == t.modes.shapes.topRows(6));
  CHECK(ta.modes.shapes.bottomRows(6).isZero(0));

  o.sensors = {5};
  CHECK_THROWS_WITH(synthetic_test(f.fe, f.gset, f.grids, o), Catch::Contains("sensor grid 5 is not a grid"));
  o.sensors = {};
  o.noise_freq_pct = -1;
  CHECK_THROWS(synthetic_test(f.fe, f.gset, f.grids, o));
}

TEST_CASE("Synthetic noise: reproducible by seed, sized as asked", "[synthetic]") {
  Fixture f;
  // Many modes of equal shape so the noise statistics can be checked.
  const int nm = 400;
  FeModeData fe;
  fe.shapes = f.fe.shapes.col(0).replicate(1, nm);
  fe.frequency_hz.assign(nm, 10.0);
  SyntheticTestOptions o;
  o.noise_freq_pct = 2;
  o.noise_shape_pct = 5;
  o.seed = 7;
  auto a = synthetic_test(fe, f.gset, f.grids, o);
  auto b = synthetic_test(fe, f.gset, f.grids, o);
  CHECK(a.modes.shapes == b.modes.shapes);
  CHECK(a.modes.frequency_hz == b.modes.frequency_hz);
  o.seed = 8;
  auto c = synthetic_test(fe, f.gset, f.grids, o);
  CHECK(a.modes.frequency_hz != c.modes.frequency_hz);

  auto clean = synthetic_test(fe, f.gset, f.grids, {});
  const double max0 = clean.modes.shapes.col(0).cwiseAbs().maxCoeff();
  // Relative frequency error: std 2 %; shape error: std 5 % of the max.
  double s2f = 0, s2s = 0;
  for (int j = 0; j < nm; ++j) {
    const double e = a.modes.frequency_hz[j] / 10.0 - 1;
    s2f += e * e;
    s2s += (a.modes.shapes.col(j) - clean.modes.shapes.col(j)).squaredNorm() / (max0 * max0);
  }
  const double sf = std::sqrt(s2f / nm), ss = std::sqrt(s2s / (nm * 9.0));
  CHECK(sf == Approx(0.02).epsilon(0.1));   // 400 samples: relative standard error 3.5 %
  CHECK(ss == Approx(0.05).epsilon(0.05));  // 3600 samples: 1.2 %
  // The noise description is carried in the file.
  const auto* m = a.file.nodal_data().front();
  CHECK_THAT(m->id_lines[1], Catch::Contains("seed 7"));
}

TEST_CASE("Sensor lists: ids, ranges, comments", "[synthetic]") {
  Fixture f;
  CHECK(parse_sensor_list("7, 1\n# comment\n2", f.grids) == std::vector<std::int64_t>{7, 1, 2});
  CHECK(parse_sensor_list("1:5", f.grids) == std::vector<std::int64_t>{1, 2});
  CHECK(parse_sensor_list("2 THRU 7", f.grids) == std::vector<std::int64_t>{2, 7});
  CHECK_THROWS_WITH(parse_sensor_list("1 x2", f.grids, "s.txt"), Catch::Contains("s.txt: expected a grid id") &&
                                                                       Catch::Contains("\"x2\""));
}
