// Joint flexibility, hidden and found: a frame tower in the MPI truss's beam
// form (balls, RBE2 spiders, one CBAR per member, no diagonals — see
// frame_case in truss_cases.hpp) whose joints at one ball are rotationally
// flexible in the truth (short soft stubs between the ball and every member
// end, a different form from the CELAS1 springs the joint_flexibility kind
// tries). The truth's modes come from the generator's reference assembler,
// "measured" at the balls above the clamped base with the tests' noise
// (frequency 0.2 %, shapes 2 % of the RMS component); ssid gets the nominal deck.
#include <catch2/catch.hpp>

#include "estimator/diagnosis/diagnosis.hpp"
#include "tests/estimator/diagnosis/diagnosis_report.hpp"
#include "tests/estimator/diagnosis/truss_cases.hpp"

using namespace ssid;
using namespace ssid::test_support;
namespace dx = ssid::estimator::diagnosis;

namespace {

translators::ModeSet measure(const Case& truth, const Case& nominal, unsigned seed) {
  TestSpec spec;
  spec.f_low = 2.0;
  spec.f_high = 120.0;  // the 16 lateral/torsion modes; axial modes start above 200 Hz
  spec.seed = seed;
  spec.sensor_grids = frame_sensors(nominal);
  return synthetic_test(truth.fe, spec, 40);
}

}  // namespace

TEST_CASE("diagnosis finds rotationally flexible joints at one ball of a frame", "[estimator][diagnosis][frame][slow]") {
  const Case nominal = frame_case();
  Case truth = frame_case();
  perturb(truth.fe, "TUBEI", 1.05);
  const int ball = 10;              // second level, corner 1
  flexible_joint(truth, ball, 2000.0);  // N m/rad: a fifth of the members' 4EI/L
  const auto measured = measure(truth, nominal, 51);
  REQUIRE(measured.frequency_hz.size() == 16);
  const dx::Diagnosis d = dx::diagnose({{"frame.bdf", deck_text(nominal.t, nominal.fe), measured}}, {});
  CAPTURE(ranking(d));
  REQUIRE(d.cause_kind == "joint_flexibility");
  const auto& h = d.ranking.at(static_cast<std::size_t>(d.cause));
  CHECK(h.location.text.find("grid " + std::to_string(ball) + " ") != std::string::npos);
  CHECK(h.after.freq_rms_pct < 0.5 * d.nominal.before.freq_rms_pct);
  CHECK(h.after.freq_rms_pct < 0.5);
  CHECK(d.margin >= 3.0);
  // The springs stand for the stubs (rate 2000 N m/rad under a pure moment; the
  // stubs also twist at 0.75 of it and shear): the same order, not the same number.
  const double k = h.estimate(h.estimate.size() - 1);
  CHECK(k > 0.7 * 2000.0);
  CHECK(k < 1.5 * 2000.0);
  // The written deck has the springs' DESVAR.
  CHECK(d.updated_deck.find("XJ" + std::to_string(ball)) != std::string::npos);
}

TEST_CASE("diagnosis of the frame with parameter errors only invents no joint", "[estimator][diagnosis][frame][slow]") {
  const Case nominal = frame_case();
  Case truth = frame_case();
  perturb(truth.fe, "TUBEI", 0.92);
  perturb(truth.fe, "BALLM", 1.06);
  const dx::Diagnosis d = dx::diagnose({{"frame.bdf", deck_text(nominal.t, nominal.fe), measure(truth, nominal, 52)}}, {});
  CAPTURE(ranking(d));
  CHECK(d.cause_kind == "parameter");
}
