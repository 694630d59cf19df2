// The multistage ARMAX identification and its model-order rule against the
// simulated systems of the seed's ARMAX paper (seed report, Appendix A, "ARMAX
// Identification of Vibrating Structures", Tables 1–9). The tests simulate the
// records themselves and check against the continuous systems' exact modes,
// computed here by Eigen independently of the estimator.
#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <unsupported/Eigen/MatrixFunctions>
#include <cmath>
#include <complex>
#include <cstdint>
#include <random>
#include <vector>

#include "estimator/identification/armax.hpp"
#include "estimator/identification/armax_order.hpp"
#include "estimator/identification/armax_paper.hpp"
#include "formats/parse_error.hpp"

using namespace ssid::estimator::identification;
using Eigen::MatrixXd;
using Eigen::VectorXd;
using namespace armax_test;

namespace {

/// Complex MAC of an identified shape against a real one.
double complex_mac(const Eigen::VectorXcd& a, const VectorXd& e) {
  const std::complex<double> dot = a.dot(e.cast<std::complex<double>>());
  return std::norm(dot) / (a.squaredNorm() * e.squaredNorm());
}

/// One of the paper's cases: the system, its sampling, the orders for p = 2, the
/// exact values it tabulates (to check the inferred m, k, c) and its shapes.
struct PaperCase {
  const char* name;
  Lumped system;
  double dt;
  std::vector<int> outputs;  ///< the two measured masses, 0-based
  int s, m;                  ///< ARMAX and prior ARX orders for p = 2
  std::vector<double> table_hz, table_zeta, table_ratio;  ///< the paper's "Exact" columns
};

/// Checks the order rule's result on one case against the exact modes: the order
/// found, every run's frequency within 0.05 % and damping within 5 % (the paper's
/// accuracy), the shapes' ratio within 0.03 of the exact one and MAC ≥ 0.999.
/// (The paper's one realisation has shape errors up to 0.016, Table 9's
/// −0.988 − 0.011i; over these eight realisations the worst is 0.029, the
/// aperiodic case's sixth mode at seed 6: 0.03 is the bound that holds, not the
/// paper's figure. docs/identification.md ("Multistage ARMAX") lists the spread.)
void check_case(const PaperCase& c, std::uint64_t seed) {
  const auto exact = exact_modes(c.system, c.outputs[0], c.outputs[1]);
  const Records rec = simulate(c.system, c.dt, c.outputs, seed);
  ArmaxOptions both;
  both.ar_order = c.s;
  both.arx_order = c.m;
  const auto result = armax_model_order(rec.response, rec.force, c.dt, single_output_runs(2, both), {});

  INFO(c.name << ", seed " << seed);
  REQUIRE(result.modes.size() == exact.size());
  for (const auto& model : result.models) CHECK(model.converged);
  for (std::size_t i = 0; i < exact.size(); ++i) {
    const auto& mode = result.modes[i];
    INFO("exact mode " << exact[i].hz << " Hz, zeta " << exact[i].zeta);
    for (std::size_t r = 0; r < result.models.size(); ++r) {
      const ArmaxPole& pole = result.models[r].poles[mode.pole[r]];
      INFO("run " << r + 1 << ": " << pole.hz << " Hz, zeta " << pole.zeta);
      CHECK(std::abs(pole.hz - exact[i].hz) <= 5e-4 * exact[i].hz);
      CHECK(std::abs(pole.zeta - exact[i].zeta) <= 0.05 * exact[i].zeta);
    }
    CHECK(mode.hz_std < 5e-4 * exact[i].hz);
    const std::complex<double> ratio = mode.shape(0) / mode.shape(1);
    INFO("shape ratio " << ratio << ", exact " << exact[i].ratio);
    CHECK(std::abs(ratio - exact[i].ratio) <= 0.03);
    CHECK(complex_mac(mode.shape, VectorXd{{exact[i].ratio, 1.0}}) >= 0.999);
  }
  CHECK_FALSE(result.rejected.empty());
}

PaperCase two_dof() {
  return {"2-DOF", lumped_system(2, kGround, false, false), 1.476649e-4, {0, 1}, 6, 45,
          {977.47, 1693.02}, {1.031e-2, 5.950e-3}, {1.0, -1.0}};
}

PaperCase aperiodic_six_dof() {
  return {"aperiodic 6-DOF", lumped_system(6, kCoupling, true, false), 1.51224e-4, {2, 3}, 9, 65,
          {1021.50, 1135.82, 1283.14, 1428.98, 1548.67, 1626.34},
          {9.861e-3, 8.868e-3, 7.850e-3, 7.049e-3, 6.504e-3, 6.194e-3},
          {1.0, -1.0, 1.0, -1.0, 1.0, -1.0}};
}

PaperCase periodic_six_dof() {
  return {"periodic 6-DOF", lumped_system(6, kCoupling, false, true), 1.51224e-4, {2, 3}, 6, 65,
          {977.47, 1183.15, 1512.82, 1653.18}, {1.03e-2, 8.51e-3, 6.66e-3, 6.09e-3},
          {1.0, 0.5, -0.5, -1.0}};
}

/// A pole as the paper tabulates it (frequency in Hz, damping ratio) at sampling dt.
ArmaxPole tabulated_pole(double hz, double zeta, double dt) {
  ArmaxPole p;
  const double w = 2 * kPi * hz;
  p.real = zeta >= 1;
  const std::complex<double> lambda(-zeta * w, p.real ? 0.0 : w * std::sqrt(1 - zeta * zeta));
  p.z = std::exp(lambda * dt);
  p.hz = hz;
  p.zeta = zeta;
  p.shape = Eigen::VectorXcd::Ones(1);
  return p;
}

ArmaxModel tabulated_run(const std::vector<std::pair<double, double>>& table, double dt) {
  ArmaxModel model;
  for (const auto& [hz, zeta] : table) model.poles.push_back(tabulated_pole(hz, zeta, dt));
  return model;
}

}  // namespace

TEST_CASE("ARMAX test systems reproduce the paper's exact columns (Tables 1-9)", "[armax]") {
  // The inferred m, k, c (see Lumped) against every "Exact" entry, to the digits printed.
  for (const PaperCase& c : {two_dof(), aperiodic_six_dof(), periodic_six_dof()}) {
    INFO(c.name);
    const auto exact = exact_modes(c.system, c.outputs[0], c.outputs[1]);
    REQUIRE(exact.size() == c.table_hz.size());
    for (std::size_t i = 0; i < exact.size(); ++i) {
      CHECK(exact[i].hz == Approx(c.table_hz[i]).margin(0.006));
      CHECK(exact[i].zeta == Approx(c.table_zeta[i]).epsilon(1e-3));  // 3-4 digits printed
      CHECK(exact[i].ratio == Approx(c.table_ratio[i]).margin(1e-9));
    }
  }
  // The periodic case's second and third frequencies are double (paper, Tables 7-9).
  const auto periodic = exact_modes(periodic_six_dof().system, 2, 3);
  CHECK(periodic[0].multiplicity == 1);
  CHECK(periodic[1].multiplicity == 2);
  CHECK(periodic[2].multiplicity == 2);
  CHECK(periodic[3].multiplicity == 1);
}

TEST_CASE("ARMAX 2-DOF case: two modes, the paper's accuracy (Tables 1-3)", "[armax]") {
  for (std::uint64_t seed = 1; seed <= 8; ++seed) check_case(two_dof(), seed);
}

TEST_CASE("ARMAX aperiodic 6-DOF case: six modes, the paper's accuracy (Tables 4-6)", "[armax]") {
  for (std::uint64_t seed = 1; seed <= 8; ++seed) check_case(aperiodic_six_dof(), seed);
}

TEST_CASE("ARMAX periodic 6-DOF case: the repeated pairs found once each (Tables 7-9)", "[armax]") {
  // One force excites one combination of each double mode, so the records hold four
  // distinct frequencies; 1183.15 and 1512.82 Hz are the repeated pairs.
  for (std::uint64_t seed = 1; seed <= 8; ++seed) check_case(periodic_six_dof(), seed);
}

TEST_CASE("ARMAX order rule on the paper's own Tables 4-5 gives its classification", "[armax]") {
  const double dt = 1.51224e-4;
  const std::vector<ArmaxModel> runs = {
      tabulated_run({{74.29, 1.0}, {423.88, 1.0}, {1021.48, 9.899e-3}, {1135.70, 8.897e-3}, {1283.14, 7.869e-3},
                     {1428.99, 7.062e-3}, {1548.60, 6.552e-3}, {1626.29, 6.248e-3}, {3011.31, 1.175e-3},
                     {3082.46, 5.494e-2}},
                    dt),
      tabulated_run({{56.43, 1.0}, {1021.50, 9.970e-3}, {1135.58, 8.930e-3}, {1283.18, 7.921e-3},
                     {1428.97, 7.089e-3}, {1548.68, 6.460e-3}, {1626.38, 6.298e-3}, {2652.43, 2.726e-2},
                     {3111.02, 2.476e-4}, {3312.30, 5.991e-2}},
                    dt),
      tabulated_run({{50.62, 0.189}, {1021.48, 9.882e-3}, {1135.72, 8.932e-3}, {1283.12, 7.842e-3},
                     {1428.98, 7.069e-3}, {1548.53, 6.532e-3}, {1626.27, 6.211e-3}, {2859.51, 7.438e-3},
                     {3016.43, 1.760e-2}},
                    dt)};
  std::vector<RejectedPole> rejected;
  const auto modes = recurring_modes(runs, {{2, 3}, {2}, {3}}, {}, rejected);
  const std::vector<double> system = {1021.50, 1135.82, 1283.14, 1428.98, 1548.67, 1626.34};
  REQUIRE(modes.size() == system.size());
  for (std::size_t i = 0; i < system.size(); ++i) {
    CHECK(std::abs(modes[i].hz_mean - system[i]) < 0.2);
    CHECK(modes[i].hz_std > 0);
    CHECK(modes[i].outputs == std::vector<int>{2, 3});
  }
  // Mean and sample standard deviation over the three runs, by hand:
  // 1021.48, 1021.50, 1021.48 Hz and 9.899e-3, 9.970e-3, 9.882e-3.
  CHECK(modes[0].hz_mean == Approx(3064.46 / 3).epsilon(1e-12));
  CHECK(modes[0].hz_std == Approx(0.02 / std::sqrt(3.0)).epsilon(1e-8));  // two equal, one 0.02 off
  CHECK(modes[0].zeta_mean == Approx(29.751e-3 / 3).epsilon(1e-12));
  // 29 poles, 18 in modes: the paper's 11 noise entries, each with its reason.
  REQUIRE(rejected.size() == 11);
  int real = 0, nyquist = 0, unmatched = 0;
  for (const auto& r : rejected) {
    if (r.reason == "real root") ++real;
    if (r.reason == "at the Nyquist frequency") ++nyquist;
    if (r.reason.rfind("not ", 0) == 0) ++unmatched;
  }
  CHECK(real == 3);
  CHECK(nyquist == 1);  // 3312.30 Hz lies above the 3306.4 Hz Nyquist frequency
  CHECK(unmatched == 7);
  // 3011.31 Hz (p = 2) and 3016.43 Hz (record 4) are 0.17 % apart: the paper tells
  // them apart by damping, 1.175e-3 against 1.760e-2.
  bool close_pair_rejected = false;
  for (const auto& r : rejected)
    if (r.run == 0 && std::abs(r.pole.hz - 3011.31) < 1e-9) {
      close_pair_rejected = true;
      CHECK(r.reason == "not found in run 2 (outputs 3)");
    }
  CHECK(close_pair_rejected);
}

TEST_CASE("ARMAX recovers a noise-free system's poles exactly", "[armax]") {
  // Without noise the records obey the ARMA model of Eq. 3 exactly (s = 2N/p), so
  // every step returns the roots of the 2-DOF system sampled at Δt: e^{λΔt}, λ
  // from Eigen's continuous eigenproblem.
  const PaperCase c = two_dof();
  const Records rec = simulate(c.system, c.dt, {0, 1}, 7, false);
  ArmaxOptions o;
  o.ar_order = 2;  // s = 2N/p: the exact order
  o.arx_order = 20;
  const ArmaxModel model = identify_armax(rec.response, rec.force, c.dt, o);
  const auto exact = exact_modes(c.system, 0, 1);
  REQUIRE(model.poles.size() == 2);
  for (std::size_t i = 0; i < 2; ++i) {
    CHECK(model.poles[i].hz == Approx(exact[i].hz).epsilon(1e-7));
    CHECK(model.poles[i].zeta == Approx(exact[i].zeta).epsilon(1e-5));
    CHECK(std::abs(model.poles[i].shape(0) / model.poles[i].shape(1) - exact[i].ratio) < 1e-6);
  }
}

TEST_CASE("ARMAX with two force records recovers a noise-free system's poles exactly", "[armax]") {
  // The MIMO form (q = 2 inputs): independent forces on both masses of the 2-DOF
  // system; B_l is then 2 × 2.
  const PaperCase c = two_dof();
  const Records rec = simulate(c.system, c.dt, {0, 1}, 11, false, 2);
  ArmaxOptions o;
  o.ar_order = 2;
  o.arx_order = 20;
  const ArmaxModel model = identify_armax(rec.response, rec.force, c.dt, o);
  const auto exact = exact_modes(c.system, 0, 1);
  REQUIRE(model.poles.size() == 2);
  REQUIRE(model.exo.size() == 2);
  CHECK(model.exo[0].cols() == 2);
  for (std::size_t i = 0; i < 2; ++i) {
    CHECK(model.poles[i].hz == Approx(exact[i].hz).epsilon(1e-7));
    CHECK(model.poles[i].zeta == Approx(exact[i].zeta).epsilon(1e-5));
    CHECK(std::abs(model.poles[i].shape(0) / model.poles[i].shape(1) - exact[i].ratio) < 1e-6);
  }
}

TEST_CASE("ARMAX rejects records and orders it cannot use", "[armax]") {
  const MatrixXd y = MatrixXd::Random(100, 2), f = MatrixXd::Random(99, 1);
  ArmaxOptions o;
  o.ar_order = 2;
  o.arx_order = 10;
  try {
    identify_armax(y, f, 1e-3, o);
    FAIL("no error");
  } catch (const ssid::formats::InputError& e) {
    CHECK(std::string(e.what()) ==
          "ARMAX: 100 response samples but 99 force samples; the records must have the same length");
  }
  const MatrixXd f100 = MatrixXd::Random(100, 1);
  o.arx_order = 30;
  try {
    identify_armax(y, f100, 1e-3, o);
    FAIL("no error");
  } catch (const ssid::formats::InputError& e) {
    CHECK(std::string(e.what()) ==
          "ARMAX: 100 samples are too few for a prior ARX model of order 30 (91 unknowns per output; at least "
          "twice as many equations are required)");
  }
  o.arx_order = 1;
  CHECK_THROWS_AS(identify_armax(y, f100, 1e-3, o), ssid::formats::InputError);
  o.arx_order = 10;
  CHECK_THROWS_AS(identify_armax(y, f100, 0.0, o), ssid::formats::InputError);
  CHECK_THROWS_AS(identify_armax(y, MatrixXd::Zero(100, 1), 1e-3, o), ssid::formats::InputError);
  std::vector<ArmaxRun> runs = single_output_runs(2, o);
  runs[1].outputs = {5};
  try {
    armax_model_order(y, f100, 1e-3, runs, {});
    FAIL("no error");
  } catch (const ssid::formats::InputError& e) {
    CHECK(std::string(e.what()) == "ARMAX order rule: run 2 names response record 6 of 2");
  }
  CHECK_THROWS_AS(armax_model_order(y, f100, 1e-3, {runs[0]}, {}), ssid::formats::InputError);
}
