// Model-form diagnosis on the MPI truss rod model: an effect is hidden in a
// truth deck, its modes (from the generator's own reference assembler) are
// "measured" at the ball grids with noise (frequencies 0.2 %, shapes 2 % of the
// RMS component), and ssid is given the nominal deck. It must name the right
// kind and location and show a gain; with parameter errors only it must not
// invent a cause.
#include <catch2/catch.hpp>

#include "estimator/diagnosis/diagnosis.hpp"
#include "tests/estimator/diagnosis/diagnosis_report.hpp"
#include "tests/estimator/diagnosis/truss_cases.hpp"
#include "translators/truss/configurations.hpp"

using namespace ssid;
using namespace ssid::test_support;
namespace dx = ssid::estimator::diagnosis;

namespace {

dx::Diagnosis run(const Case& nominal, const translators::ModeSet& measured, dx::DiagnosisOptions opt = {}) {
  return dx::diagnose({{"mpi_rod.bdf", deck_text(nominal.t, nominal.fe), measured}}, opt);
}

const dx::Hypothesis& cause(const dx::Diagnosis& d) { return d.ranking.at(static_cast<std::size_t>(d.cause)); }

bool has(const std::vector<std::int64_t>& v, std::int64_t x) { return std::find(v.begin(), v.end(), x) != v.end(); }

}  // namespace

TEST_CASE("diagnosis finds a missing mass on the rod truss", "[estimator][diagnosis][rod][slow]") {
  const Case nominal = rod_case();
  Case truth = rod_case();
  perturb(truth.fe, "STRUTA", 1.05);  // plus an ordinary parameter error
  const int grid = 29;                // optics boom tip ball
  const double mass = 2.0;            // kg (about 1 % of the truss)
  truth.fe.masses.push_back({9001, grid, mass, 0.0, "hidden"});
  TestSpec spec;
  spec.seed = 11;
  const dx::Diagnosis d = run(nominal, synthetic_test(truth.fe, spec));
  CAPTURE(ranking(d));
  REQUIRE(d.cause_kind == "missing_mass");
  CHECK(has(cause(d).location.grids, grid));
  const auto& h = cause(d);
  const double est = h.estimate(h.estimate.size() - 1), sd = h.posterior_std(h.estimate.size() - 1);
  CHECK(std::abs(est - mass) < std::max(3 * sd, 0.1 * mass));
  CHECK(h.after.freq_rms_pct < 0.5 * h.before.freq_rms_pct);
  CHECK(d.margin >= 3.0);
  // The written deck is the extended model at the estimate: it has the new DESVAR at its value.
  CHECK(d.updated_deck.find("XM29") != std::string::npos);
}

TEST_CASE("diagnosis finds a softened strut on the rod truss", "[estimator][diagnosis][rod][slow]") {
  const Case nominal = rod_case();
  Case truth = rod_case();
  perturb(truth.fe, "JOINTM", 0.95);
  // A tower longeron at the base (carries the tower's bending) loses 50 % of its axial stiffness.
  int member = 0;
  for (const auto& m : truth.t.members)
    if (m.group == "tower" && m.role == "longeron") { member = m.id; break; }
  REQUIRE(member > 0);
  tr::FeRod* rod = nullptr;
  for (auto& r : truth.fe.rods) if (r.id == member) rod = &r;
  REQUIRE(rod);
  tr::FeRodProp p;
  for (const auto& q : truth.fe.rod_props) if (q.id == rod->pid) p = q;
  p.id = 9999;
  p.A *= 0.5;
  truth.fe.rod_props.push_back(p);
  rod->pid = p.id;
  TestSpec spec;
  spec.seed = 12;
  const dx::Diagnosis d = run(nominal, synthetic_test(truth.fe, spec));
  CAPTURE(member, ranking(d));
  REQUIRE(d.cause_kind == "local_stiffness");
  CHECK(has(cause(d).location.elements, member));
  const auto& h = cause(d);
  // dA ≈ −A/2.
  const double est = h.estimate(h.estimate.size() - 1);
  CHECK(est == Approx(-0.5 * p.A * 2).epsilon(0.3));
  CHECK(h.after.freq_rms_pct < h.before.freq_rms_pct);
}

TEST_CASE("diagnosis finds suspension springs with mass (surge modes)", "[estimator][diagnosis][rod][slow]") {
  const Case nominal = rod_case();
  Case truth;
  truth.t = tr::build_configured({});
  tr::set_suspension(truth.t, true);
  truth.fe = tr::build_truss_cards(truth.t, tr::ModelForm::Rod);
  fix_property_ids(truth.fe);
  TestSpec spec;
  spec.seed = 13;
  const auto measured = synthetic_test(truth.fe, spec);
  // The analyst's prior: 30 % of XINIT on every DESVAR. With the default prior
  // from the DESVAR bounds (half the room to the nearer bound: 45 % here), the
  // same cause is named at the same place, but the third surge mode (56.85 Hz,
  // spring 7303) stays unpaired: the suspension stiffness KSUSP, weakly held,
  // rises 13 % in the joint estimate and carries the spring's new mode to
  // 60.2 Hz, where test mode 14 already claims it, and an unpaired mode exerts
  // no pull (docs/diagnosis.md, "Limits").
  dx::DiagnosisOptions opt;
  opt.study.prior_std_pct = 30.0;
  const dx::Diagnosis d = run(nominal, measured, opt);
  CAPTURE(ranking(d));
  CHECK(!d.evidence.unpaired_test.empty());
  REQUIRE(d.cause_kind == "support_dynamics");
  const auto& h = cause(d);
  // The three surge modes (48, 48, 57 Hz) all gain a partner.
  CHECK(h.after.paired >= d.nominal.before.paired + 3);
  CHECK(h.after.paired == h.after.measured);
  CHECK(h.after.freq_rms_pct < 0.5);
}

TEST_CASE("diagnosis with parameter errors only names no model-form cause", "[estimator][diagnosis][rod][slow]") {
  const Case nominal = rod_case();
  Case truth = rod_case();
  perturb(truth.fe, "STRUTA", 1.08);
  perturb(truth.fe, "JOINTM", 0.9);
  TestSpec spec;
  spec.seed = 14;
  const dx::Diagnosis d = run(nominal, synthetic_test(truth.fe, spec));
  CAPTURE(ranking(d));
  CHECK(d.cause_kind == "parameter");
  CHECK(cause(d).after.freq_rms_pct < cause(d).before.freq_rms_pct);
}

TEST_CASE("a wrongly assumed noise level raises no false alarm and the implied noise is reported",
          "[estimator][diagnosis][rod][calibration][slow]") {
  // Parameter errors only (three DESVARs at once); the test's noise is 0.2 % in
  // the frequencies and 2 % of the RMS component in the shapes, and the
  // diagnosis assumes 0.3 × or 3 × that. The noise is estimated: the answer
  // must be "parameter" both times, with the implied noise near the real one:
  // shapes (ν ≈ 2900 degrees of freedom, 99 % of ŝ within ± 3.4 %) within
  // ± 5 %; frequencies (12 modes, ν ≈ 8 after the fit: 99 % of √(χ²_8 / 8)
  // between 0.41 and 1.66) within 0.41–1.66 × 0.2 %.
  const Case nominal = rod_case();
  Case truth = rod_case();
  perturb(truth.fe, "STRUTA", 1.06);
  perturb(truth.fe, "JOINTM", 0.93);
  perturb(truth.fe, "BNUTA", 1.10);
  TestSpec spec;
  spec.seed = 15;
  const auto measured = synthetic_test(truth.fe, spec);
  for (const double factor : {0.3, 3.0}) {
    dx::DiagnosisOptions opt;
    opt.study.frequency_std_pct = factor * spec.freq_noise_pct;
    opt.study.shape_std_pct = factor * spec.shape_noise_pct;
    const dx::Diagnosis d = run(nominal, measured, opt);
    CAPTURE(factor, ranking(d), d.residual.text, d.noise.frequency_pct, d.noise.shape_pct);
    CHECK(d.cause_kind == "parameter");
    CHECK(d.residual.consistent);
    CHECK(d.noise.shape_pct > 0.95 * spec.shape_noise_pct);
    CHECK(d.noise.shape_pct < 1.05 * spec.shape_noise_pct);
    CHECK(d.noise.frequency_pct > 0.41 * spec.freq_noise_pct);
    CHECK(d.noise.frequency_pct < 1.66 * spec.freq_noise_pct);
  }
}

TEST_CASE("two hidden masses: the second is found with the first in the null", "[estimator][diagnosis][rod][calibration]") {
  // 2 kg at ball 29 (optics boom tip) and 1 kg at ball 63 (the other boom):
  // after the first is named, the screening at its model finds the second,
  // and the diagnosis names both.
  const Case nominal = rod_case();
  Case truth = rod_case();
  perturb(truth.fe, "STRUTA", 1.04);
  truth.fe.masses.push_back({9001, 29, 2.0, 0.0, "hidden"});
  truth.fe.masses.push_back({9002, 63, 1.0, 0.0, "hidden"});
  TestSpec spec;
  spec.seed = 16;
  dx::DiagnosisOptions opt;
  opt.kinds = {"missing_mass", "local_stiffness"};
  const dx::Diagnosis d = run(nominal, synthetic_test(truth.fe, spec), opt);
  CAPTURE(ranking(d), d.second.text);
  REQUIRE(d.second.tested);
  CHECK(d.second.named);
  REQUIRE(d.cause_kind == "missing_mass + missing_mass");
  const auto& h = cause(d);
  CHECK(has(h.location.grids, 29));
  CHECK(has(h.location.grids, 63));
  CHECK(h.false_alarm <= 0.01);
  // Both masses within 3σ of the truth (the new parameters are the last two, in order).
  const auto n = h.estimate.size();
  CHECK(std::abs(h.estimate(n - 2) - 2.0) < 3 * h.posterior_std(n - 2));
  CHECK(std::abs(h.estimate(n - 1) - 1.0) < 3 * h.posterior_std(n - 1));
}

TEST_CASE("diagnosis from two configurations sharing parameters", "[estimator][diagnosis][rod]") {
  // Bare and with 24 kg at the metrology tip; the same hidden mass in both.
  const int grid = 40;
  const double mass = 1.0;
  std::vector<dx::ConfigurationInput> configs;
  unsigned seed = 21;
  for (const std::vector<std::string>& names : {std::vector<std::string>{}, std::vector<std::string>{"metrology_tip_mass"}}) {
    const Case nominal = rod_case(names);
    Case truth = rod_case(names);
    perturb(truth.fe, "STRUTA", 1.04);
    truth.fe.masses.push_back({9001, grid, mass, 0.0, "hidden"});
    TestSpec spec;
    spec.seed = seed++;
    configs.push_back({names.empty() ? "bare.bdf" : "tip.bdf", deck_text(nominal.t, nominal.fe), synthetic_test(truth.fe, spec)});
  }
  dx::DiagnosisOptions opt;
  opt.kinds = {"missing_mass", "local_stiffness"};
  const dx::Diagnosis d = dx::diagnose(configs, opt);
  CAPTURE(ranking(d));
  REQUIRE(d.cause_kind == "missing_mass");
  CHECK(has(cause(d).location.grids, grid));
  const auto& h = cause(d);
  // Both configurations' modes are in the estimate.
  CHECK(h.after.measured == static_cast<int>(configs[0].measured.frequency_hz.size() + configs[1].measured.frequency_hz.size()));
  CHECK(std::abs(h.estimate(h.estimate.size() - 1) - mass) < std::max(3 * h.posterior_std(h.estimate.size() - 1), 0.15));
}

TEST_CASE("the cause predicts held-back modes better than the ordinary update", "[estimator][diagnosis][rod]") {
  const Case nominal = rod_case();
  Case truth = rod_case();
  truth.fe.masses.push_back({9001, 29, 2.0, 0.0, "hidden"});
  TestSpec spec;
  spec.seed = 31;
  dx::DiagnosisOptions opt;
  opt.kinds = {"missing_mass", "local_stiffness"};
  opt.hold_back = 3;
  const dx::Diagnosis d = run(nominal, synthetic_test(truth.fe, spec), opt);
  CAPTURE(ranking(d));
  REQUIRE(d.cause_kind == "missing_mass");
  const dx::Hypothesis* param = nullptr;
  for (const auto& h : d.ranking) if (h.kind == "parameter") param = &h;
  REQUIRE(param);
  CHECK(cause(d).predicted == 3);
  CHECK(cause(d).prediction_rms_pct >= 0);
  CHECK(cause(d).prediction_rms_pct < param->prediction_rms_pct);
}

TEST_CASE("diagnosis finds local strut modes the rod model lacks", "[estimator][diagnosis][rod][slow]") {
  // Strut 101 (a metrology-boom section diagonal, balls 49-51, 0.96 m) is a tube whose first bending
  // mode (clamped-clamped) sits at 45.5 Hz, next to the global mode at 44.4 Hz:
  // the test shows three modes where the rod model has one.
  const Case nominal = rod_case();
  Case truth = rod_case();
  perturb(truth.fe, "STRUTA", 1.03);
  const int rod = 101;
  const auto& member = truth.t.members.at(rod - 1);
  const double L = (truth.fe.grid(member.b).x - truth.fe.grid(member.a).x).norm();
  const double tube_mass = truth.t.tube_length(member) * truth.t.hw.tube_mass_per_length();
  refine_rod(truth, rod, clamped_tube_inertia(45.5, L, tube_mass / L, truth.fe.mat.E));
  TestSpec spec;
  spec.seed = 41;
  const auto measured = synthetic_test(truth.fe, spec, 80);
  const dx::Diagnosis d = run(nominal, measured);
  CAPTURE(ranking(d));
  CHECK(!d.evidence.unpaired_test.empty());
  REQUIRE(d.cause_kind == "local_modes");
  const auto& h = cause(d);
  CHECK(has(h.location.elements, rod));
  CHECK(h.after.paired > d.nominal.before.paired);
  CHECK(h.after.freq_rms_pct < d.nominal.before.freq_rms_pct);
  CHECK(d.margin >= 3.0);
}
