// Diagnosis benchmark: (1) a sweep on the MPI truss rod model — effects of
// every kind hidden at several locations and magnitudes, with realistic noise;
// found/missed per case (the table in docs/diagnosis.md); (2) the time of a
// whole diagnosis on the beam model (docs/performance.md).
//   bench_diagnosis sweep [KIND]  the sweep (about 15 minutes; KIND: only the rows of one hidden kind)
//   bench_diagnosis beam          one beam-model diagnosis, timed
//   bench_diagnosis sample F.unv  writes samples/mpi_rod_hidden_mass.unv (docs/diagnosis.md)
#include <chrono>
#include <ctime>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <cstdio>
#include <iostream>
#include <string>

#include "estimator/diagnosis/diagnosis.hpp"
#include "formats/uff.hpp"
#include "tests/estimator/diagnosis/truss_cases.hpp"
#include "translators/truss/configurations.hpp"

using namespace ssid;
using namespace ssid::test_support;
namespace dx = ssid::estimator::diagnosis;

namespace {

struct Row {
  std::string kind, where, magnitude, found, location_ok;
  double margin = 0, rms_before = 0, rms_after = 0, seconds = 0;
};

Row diagnose_case(const std::string& nominal_deck, const translators::ModeSet& measured, const std::string& kind,
                  const std::string& where, const std::string& magnitude,
                  const std::function<bool(const dx::Hypothesis&)>& right_place) {
  const auto t0 = std::chrono::steady_clock::now();
  const dx::Diagnosis d = dx::diagnose({{"model.bdf", nominal_deck, measured}}, {});
  Row r;
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.kind = kind;
  r.where = where;
  r.magnitude = magnitude;
  r.found = d.cause_kind;
  const dx::Hypothesis& h = d.cause >= 0 ? d.ranking[static_cast<std::size_t>(d.cause)] : d.nominal;
  r.location_ok = d.cause_kind == kind ? (right_place(h) ? "yes" : "no (" + h.location.text + ")") : "-";
  r.margin = d.margin;
  r.rms_before = d.nominal.before.freq_rms_pct;  // the deck as given
  r.rms_after = h.after.freq_rms_pct;
  std::printf("| %s | %s | %s | %s | %s | %.1f | %.2f -> %.2f | %.1f |\n", r.kind.c_str(), r.where.c_str(),
              r.magnitude.c_str(), r.found.c_str(), r.location_ok.c_str(), r.margin, r.rms_before, r.rms_after, r.seconds);
  std::fflush(stdout);
  return r;
}

/// A rod-model case: the truth's elastic modes 2-66 Hz at every ball.
Row diagnose_case(const Case& nominal, const tr::TrussCards& truth, const std::string& kind, const std::string& where,
                  const std::string& magnitude, const std::function<bool(const dx::Hypothesis&)>& right_place,
                  unsigned seed) {
  TestSpec spec;
  spec.seed = seed;
  return diagnose_case(deck_text(nominal.t, nominal.fe), synthetic_test(truth, spec, 80), kind, where, magnitude,
                       right_place);
}

bool has(const std::vector<std::int64_t>& v, std::int64_t x) { return std::find(v.begin(), v.end(), x) != v.end(); }

void sweep(const std::string& only) {
  const Case nominal = rod_case();
  std::printf("| hidden kind | where | magnitude | diagnosed | right location | margin [nats] | freq RMS %% before -> after | time [s] |\n");
  std::printf("|---|---|---|---|---|---|---|---|\n");
  unsigned seed = 100;
  auto run = [&](const std::string& kind) { return only.empty() || only == kind; };
  // Parameter errors only.
  for (int k = 0; k < 3 && run("parameter"); ++k) {
    Case truth = rod_case();
    perturb(truth.fe, "STRUTA", 1.0 + 0.04 * (k + 1));
    perturb(truth.fe, "JOINTM", 1.0 - 0.05 * (k + 1));
    diagnose_case(nominal, truth.fe, "parameter", "STRUTA, JOINTM", "+" + std::to_string(4 * (k + 1)) + " %, -" +
                  std::to_string(5 * (k + 1)) + " %", [](const dx::Hypothesis&) { return true; }, seed++);
  }
  // Missing masses.
  for (int grid : {29, 63, 40, 10})
    for (double m : {0.5, 2.0}) {
      if (!run("missing_mass")) break;
      Case truth = rod_case();
      perturb(truth.fe, "STRUTA", 1.03);
      truth.fe.masses.push_back({9001, grid, m, 0.0, "hidden"});
      char mag[32];
      std::snprintf(mag, sizeof mag, "%.1f kg", m);
      diagnose_case(nominal, truth.fe, "missing_mass", "grid " + std::to_string(grid), mag,
                    [grid](const dx::Hypothesis& h) { return has(h.location.grids, grid); }, seed++);
    }
  // Local stiffness: one member of each role/group, two magnitudes.
  std::vector<std::pair<std::string, std::string>> picks = {
      {"tower", "longeron"}, {"optics_boom", "longeron"}, {"metrology_boom", "longeron"}, {"tower", "batten"},
      {"optics_boom", "diagonal"}};
  for (const auto& [group, role] : picks)
    for (double factor : {0.5, 0.8}) {
      if (!run("local_stiffness")) break;
      Case truth = rod_case();
      perturb(truth.fe, "JOINTM", 0.97);
      int member = 0;
      for (const auto& m : truth.t.members)
        if (m.group == group && m.role == role) { member = m.id; break; }
      if (!member) continue;
      for (auto& r : truth.fe.rods)
        if (r.id == member) {
          tr::FeRodProp p;
          for (const auto& q : truth.fe.rod_props) if (q.id == r.pid) p = q;
          p.id = 9999;
          p.A *= factor;
          truth.fe.rod_props.push_back(p);
          r.pid = p.id;
        }
      char mag[32];
      std::snprintf(mag, sizeof mag, "EA x %.1f", factor);
      diagnose_case(nominal, truth.fe, "local_stiffness", group + " " + role + " CROD " + std::to_string(member), mag,
                    [member](const dx::Hypothesis& h) { return has(h.location.elements, member); }, seed++);
    }
  // Suspension springs with mass.
  for (double f : {48.0, 35.0, 60.0}) {
    if (!run("support_dynamics")) break;
    Case truth;
    truth.t = tr::build_configured({});
    tr::SuspensionDesign sd;
    sd.surge_hz[0] = sd.surge_hz[1] = f;
    sd.surge_hz[2] = f * 57.0 / 48.0;
    tr::set_suspension(truth.t, true, sd);
    truth.fe = tr::build_truss_cards(truth.t, tr::ModelForm::Rod);
    fix_property_ids(truth.fe);
    char mag[48];
    std::snprintf(mag, sizeof mag, "surge %.0f/%.0f/%.0f Hz", f, f, f * 57.0 / 48.0);
    diagnose_case(nominal, truth.fe, "support_dynamics", "3 suspension springs", mag,
                  [](const dx::Hypothesis&) { return true; }, seed++);
  }
  // Local strut modes: one strut's tube bends at f (clamped-clamped), near or
  // between global modes (44.4, 49.9, 14.2, 12.4 Hz).
  const std::vector<std::pair<int, double>> struts = {{101, 45.5}, {101, 47.5}, {109, 51.0}, {90, 14.6}, {184, 13.0}, {6, 30.0}};
  for (const auto& [rod, f] : struts) {
    if (!run("local_modes")) break;
    Case truth = rod_case();
    perturb(truth.fe, "STRUTA", 1.03);
    const auto& m = truth.t.members.at(static_cast<std::size_t>(rod - 1));
    const double L = (truth.fe.grid(m.b).x - truth.fe.grid(m.a).x).norm();
    const double tube = truth.t.tube_length(m) * truth.t.hw.tube_mass_per_length();
    refine_rod(truth, rod, clamped_tube_inertia(f, L, tube / L, truth.fe.mat.E));
    char mag[48];
    std::snprintf(mag, sizeof mag, "bending at %.1f Hz", f);
    diagnose_case(nominal, truth.fe, "local_modes", m.group + " " + m.role + " CROD " + std::to_string(rod), mag,
                  [rod = rod](const dx::Hypothesis& h) { return has(h.location.elements, rod); }, seed++);
  }
  // Joint flexibility on the beam-form frame tower (tests/.../test_diagnosis_frame.cpp).
  const Case frame = frame_case();
  for (const auto& [ball, k] : std::vector<std::pair<int, double>>{{10, 2000.0}, {10, 5000.0}, {15, 2000.0}, {19, 2000.0}, {7, 5000.0}, {7, 20000.0}, {7, 50000.0}, {10, 100000.0}}) {
    if (!run("joint_flexibility")) break;
    Case truth = frame_case();
    perturb(truth.fe, "TUBEI", 1.05);
    flexible_joint(truth, ball, k);
    TestSpec spec;
    spec.f_high = 120.0;
    spec.seed = seed++;
    spec.sensor_grids = frame_sensors(frame);
    char mag[48];
    std::snprintf(mag, sizeof mag, "k %.0f N m/rad", k);
    diagnose_case(deck_text(frame.t, frame.fe), synthetic_test(truth.fe, spec, 40), "joint_flexibility",
                  "frame ball " + std::to_string(ball), mag,
                  [ball = ball](const dx::Hypothesis& h) {
                    return h.location.text.find("grid " + std::to_string(ball) + " ") != std::string::npos;
                  });
  }
}

void beam() {
  Case nominal{tr::build_configured({}), {}};
  nominal.fe = tr::build_truss_cards(nominal.t, tr::ModelForm::Beam);
  fix_property_ids(nominal.fe);
  tr::TrussCards truth = nominal.fe;
  perturb(truth, "STRUTA", 1.04);
  truth.masses.push_back({99001, 29, 2.0, 0.0, "hidden"});
  TestSpec spec;
  spec.seed = 5;
  spec.f_high = 58.0;  // the global modes: strut-local modes start near 62 Hz in the beam form
  const auto measured = synthetic_test(truth, spec, 80);
  dx::DiagnosisOptions opt;
  opt.study.analysis_band_factor = 1.05;
  if (const char* k = std::getenv("SSID_BENCH_KINDS")) {  // e.g. "missing_mass": a shorter run
    std::stringstream ss(k);
    for (std::string x; std::getline(ss, x, ',');) opt.kinds.push_back(x);
  }
  const auto t0 = std::chrono::steady_clock::now();
  const std::clock_t c0 = std::clock();
  opt.progress = [&](const ssid::estimator::ProgressEvent& e) {
    std::fprintf(stderr, "  [wall %7.1f s, CPU %7.1f s] %s\n",
                 std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(),
                 static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC, e.text().c_str());
  };
  // Shape sensitivities by modal summation instead of Nelson's method (the study's "sensitivity").
  if (std::getenv("SSID_BENCH_MODAL_SUM")) opt.study.shape_derivative = ssid::estimator::ShapeDerivative::ModalSum;
  if (std::getenv("SSID_BENCH_CYCLES")) opt.update_progress = opt.progress;  // every solve of every estimate
  const dx::Diagnosis d = dx::diagnose({{"mpi_beam.bdf", deck_text(nominal.t, nominal.fe), measured}}, opt);
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const double cpu = static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC;
  for (const auto& h : d.ranking)
    std::printf("  %-18s %-40s score %.1f, freq RMS %.3f %%, paired %d\n", h.kind.c_str(), h.location.text.c_str(), h.score,
                h.after.freq_rms_pct, h.after.paired);
  for (const auto& n : d.notes) std::printf("  note: %s\n", n.c_str());
  std::printf("beam model: %zu measured modes, %zu hypotheses re-estimated; cause %s (%s); wall %.1f s, CPU %.1f s\n",
              measured.frequency_hz.size(), d.ranking.size(), d.cause_kind.c_str(), d.summary.c_str(), s, cpu);
}

}  // namespace

/// The measured file of the docs' example: the rod truss with 2 kg hidden at
/// ball 29 and STRUTA 5 % high, elastic modes 2–66 Hz at every ball, noise as the tests'.
void sample(const std::string& path) {
  Case truth = rod_case();
  perturb(truth.fe, "STRUTA", 1.05);
  truth.fe.masses.push_back({9001, 29, 2.0, 0.0, "hidden"});
  TestSpec spec;
  spec.seed = 7;
  formats::uff::write_uff(translators::mode_set_to_uff(synthetic_test(truth.fe, spec)), path);
}

/// The nominal rod deck as the generator writes it (property ids fixed as in the tests).
void nominal_deck(const std::string& path) {
  const Case c = rod_case();
  std::ofstream(path) << deck_text(c.t, c.fe);
}

int main(int argc, char** argv) {
  const std::string what = argc > 1 ? argv[1] : "sweep";
  if (what == "sample" && argc > 2) {
    sample(argv[2]);
    if (argc > 3) nominal_deck(argv[3]);
  }
  else if (what == "sweep") sweep(argc > 2 ? argv[2] : "");
  else if (what == "beam") beam();
  else {
    std::cerr << "usage: bench_diagnosis sweep [KIND]|beam|sample OUT.unv\n";
    return 2;
  }
  return 0;
}
