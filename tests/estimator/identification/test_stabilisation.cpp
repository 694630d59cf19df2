// Stabilisation diagram and mode selection (estimator/identification/stabilisation.hpp):
// ERA over model orders on the noisy 3-DOF chain finds its three modes and rejects the rest.
#include <catch2/catch.hpp>

#include <cmath>
#include <map>

#include "chain_model.hpp"
#include "estimator/identification/modal_indicators.hpp"
#include "estimator/identification/stabilisation.hpp"
#include "formats/parse_error.hpp"

using namespace ssid::estimator::identification;
using ident_test::cd;

namespace {

std::vector<OrderPoles> chain_diagram_input(std::vector<cd>& poles, std::vector<Eigen::VectorXcd>& shapes) {
  const auto model = ident_test::chain_model(false, {0, 2});
  model.exact(poles, shapes);
  const double dt = 0.004;
  const auto Y = ident_test::with_noise(model.markov(dt, 1000), 0.02, 5);
  EraOptions o;
  o.dt = dt;
  std::vector<Eigen::Index> orders;
  for (Eigen::Index n = 4; n <= 30; n += 2) orders.push_back(n);
  return order_poles(era_orders(Y, o, orders));
}

}  // namespace

TEST_CASE("stabilisation of ERA over orders 4…30 finds the chain's three modes (2 % noise)",
          "[identification][stabilisation]") {
  std::vector<cd> poles;
  std::vector<Eigen::VectorXcd> shapes;
  const auto input = chain_diagram_input(poles, shapes);
  const StabilisationResult r = stabilise(input);
  REQUIRE(r.modes.size() == 3);
  double worst_f = 0, worst_z = 0, worst_mac = 1;
  for (std::size_t m = 0; m < 3; ++m) {
    const double f = std::abs(poles[m]) / (2 * M_PI);
    const double z = -poles[m].real() / std::abs(poles[m]);
    worst_f = std::max(worst_f, std::abs(r.modes[m].hz - f) / f);
    worst_z = std::max(worst_z, std::abs(r.modes[m].zeta - z) / z);
    worst_mac = std::min(worst_mac, complex_mac(r.modes[m].shape, shapes[m]));
    CHECK(r.modes[m].poles >= 7);
    CHECK(r.modes[m].hz_std > 0);
    CHECK(r.modes[m].hz_std < 1e-3 * r.modes[m].hz);
    CHECK(r.modes[m].zeta_std < 0.1 * r.modes[m].zeta);
    CHECK(r.modes[m].shape_std.size() == 3);
  }
  // Every pole is either in a mode or rejected with a reason; spurious poles exist and are rejected.
  std::map<RejectReason, int> reasons;
  for (const DiagramPole& d : r.diagram) {
    CHECK((d.mode >= 0) == (d.reason == RejectReason::None));
    if (d.mode >= 0) CHECK(d.cls == PoleClass::Stable);
    ++reasons[d.reason];
  }
  std::string summary;
  for (const auto& [reason, count] : reasons) summary += reject_reason_text(reason) + ": " + std::to_string(count) + "; ";
  INFO("modes vs exact: max relative frequency error " << worst_f << ", damping " << worst_z << ", min MAC "
                                                       << worst_mac << "; poles: " << summary);
  CHECK(worst_f < 1e-3);
  CHECK(worst_z < 0.05);
  CHECK(worst_mac > 0.999);
  CHECK(r.diagram.size() > 3 * input.size());  // spurious poles were identified ...
  CHECK(reasons[RejectReason::None] + reasons[RejectReason::NotStable] < static_cast<int>(r.diagram.size()));
  CHECK(reasons[RejectReason::None] <= static_cast<int>(3 * input.size()));  // ... and none of them kept
}

TEST_CASE("modes are kept or excluded by hand, by frequency or index", "[identification][stabilisation]") {
  std::vector<cd> poles;
  std::vector<Eigen::VectorXcd> shapes;
  const auto input = chain_diagram_input(poles, shapes);
  const StabilisationResult all = stabilise(input);
  REQUIRE(all.modes.size() == 3);

  StabilisationOptions o;
  o.exclude_hz = {all.modes[1].hz * 1.005};
  const StabilisationResult without = stabilise(input, o);
  REQUIRE(without.modes.size() == 2);
  CHECK(without.modes[0].hz == all.modes[0].hz);
  CHECK(without.modes[1].hz == all.modes[2].hz);
  int excluded = 0;
  for (const DiagramPole& d : without.diagram) excluded += d.reason == RejectReason::ExcludedByHand;
  CHECK(excluded == static_cast<int>(all.modes[1].poles));

  StabilisationOptions k;
  k.keep_hz = {all.modes[2].hz};
  const StabilisationResult kept = stabilise(input, k);
  REQUIRE(kept.modes.size() == 1);
  CHECK(kept.modes[0].hz == all.modes[2].hz);

  StabilisationOptions i;
  i.exclude_index = {0};
  const StabilisationResult by_index = stabilise(input, i);
  REQUIRE(by_index.modes.size() == 2);
  CHECK(by_index.modes[0].hz == all.modes[1].hz);
}

TEST_CASE("stabilisation classes and rejections on hand-made poles", "[identification][stabilisation]") {
  auto pole = [](double hz, double zeta, Eigen::Vector2cd shape) {
    IdentifiedPole p;
    p.hz = hz;
    p.zeta = zeta;
    p.shape = shape;
    p.mpc = modal_phase_collinearity(shape);
    p.mpd = mean_phase_deviation(shape);
    return p;
  };
  const Eigen::Vector2cd a(1, 2), b(2, -1), c(cd(1, 0), std::polar(1.0, 55 * M_PI / 180));
  std::vector<OrderPoles> in(3);
  for (std::size_t i = 0; i < 3; ++i) {
    in[i].order = static_cast<Eigen::Index>(2 * i + 2);
    in[i].poles.push_back(pole(10.0 * (1 + 0.001 * static_cast<double>(i)), 0.02, a));  // stable
    in[i].poles.push_back(pole(20.0, 0.02 * (1 + 0.5 * static_cast<double>(i)), b));   // damping jumps: 'v'
    in[i].poles.push_back(pole(30.0, 0.01, c));                                         // MPD 27.5°, MPC cos²55°: low MPC
    in[i].poles.push_back(pole(40.0, -0.01, a));                                        // unstable
  }
  const StabilisationResult r = stabilise(in);
  REQUIRE(r.modes.size() == 1);
  CHECK(r.modes[0].hz == Approx(10.015));  // orders 4 and 6 (order 2 has nothing to be stable against)
  CHECK(r.modes[0].poles == 2);
  for (const DiagramPole& d : r.diagram) {
    if (d.order == 2) {
      CHECK(d.cls == (d.hz > 25 ? PoleClass::Rejected : PoleClass::New));
    } else if (d.hz < 15) {
      CHECK(d.cls == PoleClass::Stable);
      CHECK(pole_class_symbol(d.cls) == 's');
    } else if (d.hz < 25) {
      CHECK(d.cls == PoleClass::FrequencyShape);
      CHECK(reject_reason_text(d.reason) == "not stable against the previous order");
    } else if (d.hz < 35) {
      CHECK(d.reason == RejectReason::LowMpc);
    } else {
      CHECK(reject_reason_text(d.reason) == "unstable (damping ≤ 0)");
    }
  }
  StabilisationOptions bad;
  bad.mac_min = 1.5;
  CHECK_THROWS_WITH(stabilise(in, bad), "stabilisation: MAC threshold = 1.5 (expected in [0, 1])");
  std::swap(in[0], in[2]);
  CHECK_THROWS_WITH(stabilise(in), "stabilisation: order 4 listed after order 6 (expected increasing orders)");
}
