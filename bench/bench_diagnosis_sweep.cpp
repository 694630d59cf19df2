// The diagnosis sweep of issue 26 ("Proof"): cases drawn at random from a seed,
// each a truth deck that refines the structure itself (never through the
// diagnosis's extension library), its modes from `ssid modes --uff`, noise
// added here, and `ssid diagnose` run on the nominal deck as a subprocess; one
// JSON line per case. `report` turns the lines into the tables of
// docs/diagnosis.md ("Sweep on cases it was not tuned on"). The driver is
// scripts/diagnosis-sweep.
//
//   bench_diagnosis_sweep run --ssid PATH --out DIR [--seed S] [--first I] [--count N]
//                             [--structures rod,frame,beam] [--null-fraction F] [--kinds K,...]
//                             [--case-timeout SECONDS] [--shape-noise rms|max] [--keep] [--skip-diagnose]
//   bench_diagnosis_sweep report RESULTS.jsonl [--docs FILE] [--command TEXT]
//
// Case i of seed S is drawn from std::mt19937_64 seeded with a mix of (S, i)
// (the engine is fully specified by the standard; the uniform and normal
// deviates are computed here and by translators::NormalDeviates, not by the
// implementation-defined std::*_distribution), so a case is the same on every
// platform and any case can be rerun alone (--first i --count 1 --keep).
//
// Why the truth decks are not the hypotheses' edits (docs/diagnosis.md):
//   local_stiffness: the whole strut gets its own, softer property (PROD A, or
//     every PBAR of the strut with A, I1, I2, J scaled) — the kind adds a
//     parallel CONROD;
//   missing_mass: a CONM2 with a CG offset of 2–8 cm — the kind adds a CONM2
//     at the grid;
//   support_dynamics: the generator's surge springs, 12-segment chains of
//     CELAS1 and CONM2 per spring — the kind uses 2k–m–2k;
//   local_modes: the rod becomes a tube of 4 CBARs, clamped at the balls, its
//     mass distributed — the kind uses two pinned CBARs and a middle CONM2;
//   joint_flexibility: 10 mm flexible stubs at every member end of one ball —
//     the kind uses CELAS1 springs in 4, 5, 6.
#include <sys/wait.h>

#include <algorithm>
#include <boost/math/special_functions/beta.hpp>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "formats/uff.hpp"
#include "tests/estimator/diagnosis/truss_cases.hpp"
#include "translators/measurement/mode_set.hpp"
#include "translators/synthetic_modes.hpp"
#include "translators/truss/configurations.hpp"

using namespace ssid;
using namespace ssid::test_support;
namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

// ------------------------------------------------------------------ drawing

std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

/// Uniform deviates from std::mt19937_64, computed here (the standard fixes the
/// engine's output, not std::uniform_real_distribution's).
class Draw {
 public:
  explicit Draw(std::uint64_t seed) : m_engine(seed) {}
  /// In [0, 1): the top 53 bits of one engine output.
  double uniform() { return static_cast<double>(m_engine() >> 11) * 0x1.0p-53; }
  double uniform(double a, double b) { return a + (b - a) * uniform(); }
  /// log-uniform in [a, b]: magnitudes spread evenly over decades.
  double log_uniform(double a, double b) { return a * std::pow(b / a, uniform()); }
  std::size_t index(std::size_t n) { return std::min(n - 1, static_cast<std::size_t>(uniform() * static_cast<double>(n))); }
  std::uint64_t bits() { return m_engine(); }
  /// k distinct elements of v, in drawn order.
  template <class T>
  std::vector<T> pick(std::vector<T> v, std::size_t k) {
    std::vector<T> out;
    while (out.size() < k && !v.empty()) {
      const std::size_t i = index(v.size());
      out.push_back(v[i]);
      v.erase(v.begin() + static_cast<std::ptrdiff_t>(i));
    }
    return out;
  }

 private:
  std::mt19937_64 m_engine;
};

// ---------------------------------------------------------------- structures

enum class Structure { Rod, Frame, Beam };

std::string name_of(Structure s) { return s == Structure::Rod ? "rod" : s == Structure::Frame ? "frame" : "beam"; }

/// What a structure's synthetic test looks like and which effects it can hide.
struct StructureInfo {
  double f_low = 2, f_high = 66;  ///< Hz: truth modes in this band are "measured"
  int nmodes = 80;                ///< modes `ssid modes` computes (covers the band with room)
  std::vector<std::string> kinds;
};

StructureInfo info_of(Structure s) {
  switch (s) {
    case Structure::Rod: return {2, 66, 80, {"local_stiffness", "missing_mass", "support_dynamics", "local_modes"}};
    case Structure::Frame: return {2, 120, 40, {"local_stiffness", "missing_mass", "joint_flexibility"}};
    case Structure::Beam: return {2, 58, 60, {"local_stiffness", "missing_mass", "support_dynamics"}};
  }
  return {};
}

/// A structure's cards and the cards the truth adds as text (CONM2 with offset).
struct Model {
  Case c;
  std::string extra;
};

Model build_structure(Structure s, const translators::truss::SuspensionDesign* surge) {
  Model m;
  if (s == Structure::Frame) {
    m.c = frame_case();
    return m;
  }
  m.c.t = tr::build_configured({});
  if (surge) tr::set_suspension(m.c.t, true, *surge);
  m.c.fe = tr::build_truss_cards(m.c.t, s == Structure::Rod ? tr::ModelForm::Rod : tr::ModelForm::Beam);
  fix_property_ids(m.c.fe);
  return m;
}

std::string deck_of(const Model& m) {
  std::string text = deck_text(m.c.t, m.c.fe);
  if (!m.extra.empty()) {
    const auto at = text.rfind("ENDDATA");
    if (at == std::string::npos) throw std::runtime_error("deck without ENDDATA");
    text.insert(at, m.extra);
  }
  return text;
}

/// Ball grids that can carry a sensor or a hidden mass (the frame's base is clamped).
std::vector<int> sensor_balls(Structure s, const Model& m) {
  if (s == Structure::Frame) return frame_sensors(m.c);
  std::vector<int> out;
  for (const auto& g : m.c.fe.grids)
    if (g.kind == "ball") out.push_back(g.id);
  return out;
}

std::vector<int> member_ids(Structure s, const Model& m) {
  std::set<int> ids;
  if (s == Structure::Rod)
    for (const auto& r : m.c.fe.rods) ids.insert(r.member);
  else
    for (const auto& b : m.c.fe.bars) ids.insert(b.member);
  return {ids.begin(), ids.end()};
}

std::string member_text(const Model& m, int member) {
  for (const auto& x : m.c.t.members)
    if (x.id == member) return x.group + " " + x.role + " strut " + std::to_string(member);
  return "member " + std::to_string(member);
}

// ------------------------------------------------------------------- effects

/// One hidden effect: what it is and which named locations count as right.
struct Effect {
  std::string kind, where, magnitude;
  double value = 0;               ///< the drawn magnitude in its unit (see `magnitude`)
  std::vector<int> elements;      ///< a cause naming any of these elements is at the right place
  std::vector<int> grids;         ///< ... or any of these grids
  bool any_location = false;      ///< the kind alone decides (support dynamics: all springs)
};

int next_property_id(const tr::TrussCards& fe) {
  int id = 90000;
  for (const auto& p : fe.rod_props) id = std::max(id, p.id);
  for (const auto& p : fe.bar_props) id = std::max(id, p.id);
  for (const auto& p : fe.spring_props) id = std::max(id, p.id);
  return id + 1;
}

/// Every element of `member` gets its own copy of its property with the
/// stiffness scaled by `factor` (PROD A; PBAR A, I1, I2, J). Returns their ids.
std::vector<int> soften_member(tr::TrussCards& fe, int member, double factor) {
  std::vector<int> elements;
  for (auto& r : fe.rods)
    if (r.member == member) {
      tr::FeRodProp p;
      for (const auto& q : fe.rod_props) if (q.id == r.pid) p = q;
      p.id = next_property_id(fe);
      p.A *= factor;
      p.kind = "softened";
      fe.rod_props.push_back(p);
      r.pid = p.id;
      elements.push_back(r.id);
    }
  for (auto& b : fe.bars)
    if (b.member == member) {
      tr::FeBarProp p;
      for (const auto& q : fe.bar_props) if (q.id == b.pid) p = q;
      p.id = next_property_id(fe);
      p.A *= factor;
      p.I1 *= factor;
      p.I2 *= factor;
      p.J *= factor;
      p.kind = "softened";
      fe.bar_props.push_back(p);
      b.pid = p.id;
      elements.push_back(b.id);
    }
  return elements;
}

Effect hide_local_stiffness(Structure s, Model& m, Draw& d) {
  const auto members = member_ids(s, m);
  const int member = members[d.index(members.size())];
  const double loss = d.log_uniform(0.03, 0.8);
  Effect e;
  e.kind = "local_stiffness";
  e.where = member_text(m, member);
  e.value = 1 - loss;
  char mag[64];
  std::snprintf(mag, sizeof mag, "stiffness x %.3f", 1 - loss);
  e.magnitude = mag;
  e.elements = soften_member(m.c.fe, member, 1 - loss);
  return e;
}

Effect hide_missing_mass(Structure s, Model& m, Draw& d) {
  const auto balls = sensor_balls(s, m);
  const int grid = balls[d.index(balls.size())];
  const double mass = s == Structure::Frame ? d.log_uniform(0.01, 1.0) : d.log_uniform(0.03, 3.0);
  // A CG offset of 2-8 cm in a random direction (uniform on the sphere).
  const double z = d.uniform(-1, 1), phi = d.uniform(0, 2 * M_PI), r = d.uniform(0.02, 0.08);
  const Eigen::Vector3d off = r * Eigen::Vector3d(std::sqrt(1 - z * z) * std::cos(phi), std::sqrt(1 - z * z) * std::sin(phi), z);
  char card[160];
  std::snprintf(card, sizeof card, "$ hidden mass (sweep truth): %.4g kg, CG offset %.3f m\nCONM2,%d,%d,0,%.6g,%.6g,%.6g,%.6g\n",
                mass, r, 99001, grid, mass, off.x(), off.y(), off.z());
  m.extra += card;
  Effect e;
  e.kind = "missing_mass";
  e.where = "grid " + std::to_string(grid);
  e.value = mass;
  char mag[64];
  std::snprintf(mag, sizeof mag, "%.3g kg, offset %.0f mm", mass, 1000 * r);
  e.magnitude = mag;
  e.grids = {grid};
  return e;
}

/// Structure-level: the surge frequencies of the three springs (drawn before the cards are built).
Effect draw_surge(Draw& d, tr::SuspensionDesign& sd) {
  const double f0 = d.log_uniform(25.0, 120.0);
  sd.surge_hz[0] = f0 * d.uniform(0.97, 1.03);
  sd.surge_hz[1] = f0 * d.uniform(0.97, 1.03);
  sd.surge_hz[2] = f0 * d.uniform(1.10, 1.25);
  Effect e;
  e.kind = "support_dynamics";
  e.where = "3 suspension springs";
  e.value = f0;
  char mag[64];
  std::snprintf(mag, sizeof mag, "surge %.1f/%.1f/%.1f Hz", sd.surge_hz[0], sd.surge_hz[1], sd.surge_hz[2]);
  e.magnitude = mag;
  e.any_location = true;
  return e;
}

Effect hide_local_modes(Model& m, Draw& d) {
  std::vector<int> rods;
  for (const auto& r : m.c.fe.rods) rods.push_back(r.id);
  const int rod = rods[d.index(rods.size())];
  const double f = d.log_uniform(10.0, 120.0);
  const auto& member = m.c.t.members.at(static_cast<std::size_t>(rod - 1));
  const double L = (m.c.fe.grid(member.b).x - m.c.fe.grid(member.a).x).norm();
  const double tube = m.c.t.tube_length(member) * m.c.t.hw.tube_mass_per_length();
  refine_rod(m.c, rod, clamped_tube_inertia(f, L, tube / L, m.c.fe.mat.E));
  Effect e;
  e.kind = "local_modes";
  e.where = member_text(m, rod);
  e.value = f;
  char mag[64];
  std::snprintf(mag, sizeof mag, "bending at %.1f Hz", f);
  e.magnitude = mag;
  e.elements = {rod};
  return e;
}

Effect hide_joint(Structure s, Model& m, Draw& d) {
  const auto balls = sensor_balls(s, m);
  const int ball = balls[d.index(balls.size())];
  const double k = d.log_uniform(1e3, 1e6);
  flexible_joint(m.c, ball, k);
  Effect e;
  e.kind = "joint_flexibility";
  e.where = "ball " + std::to_string(ball);
  e.value = k;
  char mag[64];
  std::snprintf(mag, sizeof mag, "k %.3g N m/rad", k);
  e.magnitude = mag;
  e.grids = {ball};
  return e;
}

// -------------------------------------------------------------------- cases

struct SweepOptions {
  std::string ssid, out;
  std::uint64_t seed = 1;
  int first = 0, count = 10;
  std::vector<Structure> structures = {Structure::Rod, Structure::Frame};
  double null_fraction = 0.5;
  std::vector<std::string> kinds;  ///< empty: every kind the structure has, and "two"
  int case_timeout = 900;
  bool keep = false;
  bool skip_diagnose = false;  ///< only the truth, its modes and the effect size (a check of the generator)
  /// Shape noise reference: "rms" (σ_s of the mode's RMS sensor component, as the
  /// tests) or "max" (of its largest component, as `ssid modes --noise-shape`:
  /// 2-3 times more noise on 240 DOFs).
  std::string shape_noise_of = "rms";
};

/// One drawn case: the three decks and what the test looks like.
struct DrawnCase {
  Structure structure = Structure::Rod;
  std::string truth_kind;  ///< "null", a kind, or "two"
  std::vector<Effect> effects;
  std::vector<std::pair<std::string, double>> parameter_factors;
  std::vector<int> candidates;  ///< every sensor-capable ball (clean modes are computed there)
  std::vector<int> sensors;     ///< the measured ones
  bool sparse = false;
  double sigma_f_pct = 0, sigma_s_pct = 0;
  std::uint64_t noise_seed = 0;
  std::string nominal, base, truth;  ///< deck texts
};

DrawnCase draw_case(const SweepOptions& o, int index) {
  Draw d(splitmix64(o.seed ^ splitmix64(static_cast<std::uint64_t>(index) + 0x51ed)));
  DrawnCase c;
  // Structure: the rod truss 3, the frame 2, the beam truss 1 (its diagnosis is slow).
  std::vector<Structure> pool;
  for (Structure s : o.structures)
    for (int w = 0; w < (s == Structure::Rod ? 3 : s == Structure::Frame ? 2 : 1); ++w) pool.push_back(s);
  c.structure = pool[d.index(pool.size())];
  const StructureInfo info = info_of(c.structure);
  std::vector<std::string> kinds;
  for (const auto& k : info.kinds)
    if (o.kinds.empty() || std::count(o.kinds.begin(), o.kinds.end(), k)) kinds.push_back(k);
  std::vector<std::string> menu = kinds;
  if (o.kinds.empty() || std::count(o.kinds.begin(), o.kinds.end(), "two")) menu.push_back("two");
  const bool null_case = d.uniform() < o.null_fraction || menu.empty() || (kinds.size() < 2 && menu == std::vector<std::string>{"two"});
  std::vector<std::string> effect_kinds;
  if (null_case) c.truth_kind = "null";
  else {
    c.truth_kind = menu[d.index(menu.size())];
    effect_kinds = c.truth_kind == "two" ? d.pick(kinds, 2) : std::vector<std::string>{c.truth_kind};
    if (effect_kinds.size() < 2 && c.truth_kind == "two") c.truth_kind = effect_kinds.front();
  }
  // Suspension dynamics changes the structure itself: drawn first.
  tr::SuspensionDesign sd;
  const bool surge = std::count(effect_kinds.begin(), effect_kinds.end(), "support_dynamics") > 0;
  Effect surge_effect;
  if (surge) surge_effect = draw_surge(d, sd);
  const Model nominal = build_structure(c.structure, nullptr);
  Model base = nominal;
  Model truth = build_structure(c.structure, surge ? &sd : nullptr);
  // Parameter errors: 1-3 DESVARs at once, each within +-15 %, in base and truth alike.
  std::vector<std::string> labels;
  for (const auto& v : nominal.c.fe.desvars) labels.push_back(v.label);
  for (const auto& label : d.pick(labels, 1 + d.index(3))) {
    const double factor = 1 + d.uniform(-0.15, 0.15);
    c.parameter_factors.emplace_back(label, factor);
    perturb(base.c.fe, label, factor);
    perturb(truth.c.fe, label, factor);
  }
  for (const auto& k : effect_kinds) {
    if (k == "support_dynamics") c.effects.push_back(surge_effect);
    else if (k == "local_stiffness") c.effects.push_back(hide_local_stiffness(c.structure, truth, d));
    else if (k == "missing_mass") c.effects.push_back(hide_missing_mass(c.structure, truth, d));
    else if (k == "local_modes") c.effects.push_back(hide_local_modes(truth, d));
    else if (k == "joint_flexibility") c.effects.push_back(hide_joint(c.structure, truth, d));
  }
  // The test: every ball, or a sparse set of 6-10 triaxial sensors (18-30 DOFs).
  c.candidates = sensor_balls(c.structure, nominal);
  c.sparse = d.uniform() < 0.5;
  c.sensors = c.candidates;
  if (c.sparse) {
    c.sensors = d.pick(c.candidates, 6 + d.index(5));
    std::sort(c.sensors.begin(), c.sensors.end());
  }
  c.sigma_f_pct = d.uniform(0.1, 0.5);
  c.sigma_s_pct = d.uniform(1.0, 4.0);
  c.noise_seed = d.bits();
  c.nominal = deck_of(nominal);
  c.base = deck_of(base);
  c.truth = deck_of(truth);
  return c;
}

// --------------------------------------------------------------- measuring

int run_command(const std::string& cmd) {
  const int status = std::system(cmd.c_str());
  if (status == -1) return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

void write_text(const fs::path& p, const std::string& text) {
  std::ofstream out(p, std::ios::binary);
  out << text;
  if (!out) throw std::runtime_error(p.string() + ": cannot write");
}

std::string join(const std::vector<int>& v, const char* sep = ",") {
  std::string s;
  for (int x : v) s += (s.empty() ? "" : sep) + std::to_string(x);
  return s;
}

/// Clean modes of a deck at the candidate balls, by `ssid modes --uff`.
translators::ModeSet clean_modes(const SweepOptions& o, const fs::path& dir, const std::string& name, int nmodes,
                                 const std::vector<int>& balls) {
  const fs::path deck = dir / (name + ".bdf"), unv = dir / (name + "_clean.unv");
  const std::string cmd = o.ssid + " modes " + deck.string() + " --nmodes " + std::to_string(nmodes) + " --uff " +
                          unv.string() + " --sensors " + join(balls) + " -q > " + (dir / (name + "_modes.log")).string() + " 2>&1";
  const int rc = run_command(cmd);
  if (rc != 0) throw std::runtime_error("ssid modes failed (" + std::to_string(rc) + "): " + cmd);
  return translators::modes_from_uff(formats::uff::read_uff(unv.string()));
}

double mac(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  const double ab = a.dot(b);
  return ab * ab / (a.squaredNorm() * b.squaredNorm());
}

/// How large the effect is, against the noise: truth modes in the band paired
/// with the truth-without-effect modes (same parameter errors) by MAC at every
/// candidate ball (greedy, highest first, MAC >= 0.5).
struct EffectSize {
  double shift_sigma = 0;   ///< max over pairs |f - f_base| / f_base / σ_f
  double max_shift_pct = 0;
  double shape_sigma = 0;   ///< max over pairs √n ‖φ̂ − φ̂_base‖ / σ_s at the measured DOFs (unit shapes)
  int new_modes = 0;        ///< truth modes seen in the band without a partner (surge, local modes)
  int lost_modes = 0;       ///< base modes in the band without a partner
};

std::vector<Eigen::Index> rows_of(const translators::ModeSet& set, const std::vector<int>& sensors) {
  std::vector<Eigen::Index> rows;
  const std::set<int> keep(sensors.begin(), sensors.end());
  for (std::size_t i = 0; i < set.dofs.size(); ++i)
    if (keep.count(static_cast<int>(set.dofs[i].node))) rows.push_back(static_cast<Eigen::Index>(i));
  return rows;
}

Eigen::VectorXd take(const Eigen::VectorXd& v, const std::vector<Eigen::Index>& rows) {
  Eigen::VectorXd out(static_cast<Eigen::Index>(rows.size()));
  for (std::size_t i = 0; i < rows.size(); ++i) out(static_cast<Eigen::Index>(i)) = v(rows[i]);
  return out;
}

std::vector<Eigen::Index> in_band(const translators::ModeSet& s, const StructureInfo& info) {
  std::vector<Eigen::Index> out;
  for (std::size_t j = 0; j < s.frequency_hz.size(); ++j)
    if (s.frequency_hz[j] >= info.f_low && s.frequency_hz[j] <= info.f_high) out.push_back(static_cast<Eigen::Index>(j));
  return out;
}

/// A mode is seen by the test when its mass-normalised shape moves the measured
/// sensors by at least kVisible times the median of the band's modes (RMS over
/// the sensors): a strut's local bending or a spring's surge that hardly moves
/// the balls stays below a lab's noise floor, as in a real test.
constexpr double kVisible = 0.1;

std::vector<Eigen::Index> visible_in_band(const translators::ModeSet& s, const StructureInfo& info,
                                          const std::vector<Eigen::Index>& rows) {
  const auto band = in_band(s, info);
  std::vector<double> rms;
  for (Eigen::Index j : band) rms.push_back(take(s.shapes.col(j), rows).norm());
  if (rms.empty()) return {};
  std::vector<double> sorted = rms;
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2), sorted.end());
  const double median = sorted[sorted.size() / 2];
  std::vector<Eigen::Index> out;
  for (std::size_t i = 0; i < band.size(); ++i)
    if (rms[i] >= kVisible * median) out.push_back(band[i]);
  return out;
}

EffectSize effect_size(const translators::ModeSet& truth, const translators::ModeSet& base, const StructureInfo& info,
                       const std::vector<int>& sensors, double sigma_f_pct, double sigma_s_pct) {
  EffectSize e;
  const auto tb = visible_in_band(truth, info, rows_of(truth, sensors)), bb = visible_in_band(base, info, rows_of(base, sensors));
  struct Cand { double mac; Eigen::Index t, b; };
  std::vector<Cand> cands;
  for (Eigen::Index t : tb)
    for (Eigen::Index b = 0; b < base.shapes.cols(); ++b) {
      const double fb = base.frequency_hz[static_cast<std::size_t>(b)];
      if (fb < 0.5 * info.f_low) continue;  // suspension modes
      const double m = mac(truth.shapes.col(t), base.shapes.col(b));
      if (m >= 0.5) cands.push_back({m, t, b});
    }
  std::sort(cands.begin(), cands.end(), [](const Cand& a, const Cand& b) { return a.mac > b.mac; });
  std::set<Eigen::Index> used_t, used_b;
  const auto rows = rows_of(truth, sensors);
  const double n = static_cast<double>(rows.size());
  for (const auto& c : cands) {
    if (used_t.count(c.t) || used_b.count(c.b)) continue;
    used_t.insert(c.t);
    used_b.insert(c.b);
    const double ft = truth.frequency_hz[static_cast<std::size_t>(c.t)], fb = base.frequency_hz[static_cast<std::size_t>(c.b)];
    const double shift = std::abs(ft - fb) / fb * 100;
    e.max_shift_pct = std::max(e.max_shift_pct, shift);
    e.shift_sigma = std::max(e.shift_sigma, shift / sigma_f_pct);
    Eigen::VectorXd a = take(truth.shapes.col(c.t), rows), b = take(base.shapes.col(c.b), rows);
    a.normalize();
    b.normalize();
    if (a.dot(b) < 0) b = -b;
    e.shape_sigma = std::max(e.shape_sigma, std::sqrt(n) * (a - b).norm() / (sigma_s_pct / 100));
  }
  for (Eigen::Index t : tb) e.new_modes += used_t.count(t) ? 0 : 1;
  for (Eigen::Index b : bb) e.lost_modes += used_b.count(b) ? 0 : 1;
  return e;
}

/// The measured set: the truth's modes seen in the band at the measured sensors, with
///   f̃ = f (1 + σ_f/100 · z),   φ̃_k = φ_k + σ_s/100 · rms(φ) · z_k,
/// z from translators::NormalDeviates(noise_seed) in that order, mode by mode.
translators::ModeSet measured_set(const translators::ModeSet& truth, const StructureInfo& info, const DrawnCase& c,
                                  const std::string& shape_noise_of) {
  const auto rows = rows_of(truth, c.sensors);
  const auto modes = visible_in_band(truth, info, rows);
  translators::ModeSet out;
  for (Eigen::Index r : rows) out.dofs.push_back(truth.dofs[static_cast<std::size_t>(r)]);
  out.shapes.resize(static_cast<Eigen::Index>(rows.size()), static_cast<Eigen::Index>(modes.size()));
  translators::NormalDeviates z(c.noise_seed);
  for (std::size_t j = 0; j < modes.size(); ++j) {
    const double f = truth.frequency_hz[static_cast<std::size_t>(modes[j])];
    out.frequency_hz.push_back(f * (1 + c.sigma_f_pct / 100 * z()));
    Eigen::VectorXd s = take(truth.shapes.col(modes[j]), rows);
    const double rms = shape_noise_of == "max" ? s.cwiseAbs().maxCoeff() : s.norm() / std::sqrt(static_cast<double>(s.size()));
    for (Eigen::Index k = 0; k < s.size(); ++k) s(k) += c.sigma_s_pct / 100 * rms * z();
    out.shapes.col(static_cast<Eigen::Index>(j)) = s;
    out.numbers.push_back(static_cast<int>(j) + 1);
    out.damping.push_back(0.0);
    out.modal_mass.push_back(0.0);
  }
  return out;
}

json fit_of(const json& f) {
  if (f.is_null()) return nullptr;
  return {{"freq_rms_pct", f.value("freq_rms_pct", -1.0)}, {"mean_mac", f.value("mean_mac", -1.0)}, {"paired", f.value("paired", -1)}};
}

bool contains_any(const json& list, const std::vector<int>& want) {
  if (!list.is_array()) return false;
  for (const auto& x : list)
    if (x.is_number_integer() && std::count(want.begin(), want.end(), x.get<int>())) return true;
  return false;
}

/// Runs one case end to end; the JSON line of the results file.
json run_case(const SweepOptions& o, int index) {
  const auto t0 = std::chrono::steady_clock::now();
  const DrawnCase c = draw_case(o, index);
  const StructureInfo info = info_of(c.structure);
  char name[32];
  std::snprintf(name, sizeof name, "case_%05d", index);
  const fs::path dir = fs::path(o.out) / "cases" / name;
  fs::create_directories(dir);
  write_text(dir / "nominal.bdf", c.nominal);
  write_text(dir / "base.bdf", c.base);
  write_text(dir / "truth.bdf", c.truth);
  const auto truth = clean_modes(o, dir, "truth", info.nmodes, c.candidates);
  const auto base = clean_modes(o, dir, "base", info.nmodes, c.candidates);
  const EffectSize size = effect_size(truth, base, info, c.sensors, c.sigma_f_pct, c.sigma_s_pct);
  const auto measured = measured_set(truth, info, c, o.shape_noise_of);
  formats::uff::write_uff(translators::mode_set_to_uff(measured), (dir / "measured.unv").string());
  const double t_setup = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  const fs::path diag = dir / "diagnose.json";
  const std::string cmd = "timeout " + std::to_string(o.case_timeout) + " " + o.ssid + " diagnose " + (dir / "nominal.bdf").string() +
                          " " + (dir / "measured.unv").string() + " --json " + diag.string() + " -q > " +
                          (dir / "diagnose.out").string() + " 2> " + (dir / "diagnose.err").string();
  const auto t1 = std::chrono::steady_clock::now();
  const int rc = o.skip_diagnose ? -2 : run_command(cmd);
  const double t_diag = std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();

  json r;
  r["index"] = index;
  r["seed"] = o.seed;
  r["structure"] = name_of(c.structure);
  r["truth_kind"] = c.truth_kind;
  r["effects"] = json::array();
  for (const auto& e : c.effects)
    r["effects"].push_back({{"kind", e.kind}, {"where", e.where}, {"magnitude", e.magnitude}, {"value", e.value},
                            {"elements", e.elements}, {"grids", e.grids}, {"any_location", e.any_location}});
  r["parameter_errors"] = json::object();
  for (const auto& [label, f] : c.parameter_factors) r["parameter_errors"][label] = f;
  r["sensors"] = c.sparse ? "sparse" : "all";
  r["measured_dofs"] = measured.dofs.size();
  r["measured_modes"] = measured.frequency_hz.size();
  r["sigma_f_pct"] = c.sigma_f_pct;
  r["sigma_s_pct"] = c.sigma_s_pct;
  r["shape_noise_of"] = o.shape_noise_of;
  r["noise_seed"] = c.noise_seed;
  r["effect"] = {{"shift_sigma", size.shift_sigma}, {"max_shift_pct", size.max_shift_pct}, {"shape_sigma", size.shape_sigma},
                 {"new_modes", size.new_modes}, {"lost_modes", size.lost_modes}};
  r["exit_code"] = rc;
  r["seconds_setup"] = t_setup;
  r["seconds_diagnose"] = t_diag;
  json d;
  bool have = false;
  if (fs::exists(diag)) {
    try {
      std::ifstream in(diag);
      d = json::parse(in);
      have = d.contains("cause") && d["cause"].is_object();
    } catch (const std::exception&) {
      have = false;
    }
  }
  if (!have) {
    r["named"] = nullptr;
    r["right_kind"] = false;
    r["right_location"] = false;
  } else {
    const json& cause = d["cause"];
    const std::string kind = cause.value("kind", "");
    const json loc = cause.value("location", json::object());
    r["named"] = {{"kind", kind},
                  {"location", loc.value("text", "")},
                  {"grids", loc.value("grids", json::array())},
                  {"elements", loc.value("elements", json::array())},
                  {"value", cause.value("value", json())},
                  {"std", cause.value("std", json())},
                  {"margin_nats", cause.value("margin_nats", 0.0)}};
    bool right_kind = false, right_location = false;
    if (c.effects.empty()) right_kind = right_location = kind == "parameter" || kind == "none";
    for (const auto& e : c.effects)
      if (e.kind == kind) {
        right_kind = true;
        right_location = right_location || e.any_location || contains_any(loc.value("elements", json()), e.elements) ||
                         contains_any(loc.value("grids", json()), e.grids);
      }
    r["right_kind"] = right_kind;
    r["right_location"] = right_location;
    json update = nullptr;
    for (const auto& h : d.value("ranking", json::array()))
      if (h.value("kind", "") == "parameter") update = h;
    r["fit"] = {{"deck", fit_of(d["gain"].value("before", json()))},
                {"update", fit_of(update)},
                {"cause", fit_of(d["gain"].value("after", json()))}};
    r["partial"] = d.value("partial", false);
  }
  if (!o.keep && rc == 0) fs::remove_all(dir);
  return r;
}

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  for (std::string x; std::getline(ss, x, sep);)
    if (!x.empty()) out.push_back(x);
  return out;
}

int run(const SweepOptions& o) {
  fs::create_directories(o.out);
  const fs::path results = fs::path(o.out) / "results.jsonl";
  std::set<int> done;  // resumable: a case already in the file is not rerun
  {
    std::ifstream in(results);
    for (std::string line; std::getline(in, line);)
      if (!line.empty()) done.insert(json::parse(line).at("index").get<int>());
  }
  std::ofstream out(results, std::ios::app);
  for (int i = o.first; i < o.first + o.count; ++i) {
    if (done.count(i)) continue;
    json r;
    try {
      r = run_case(o, i);
    } catch (const std::exception& e) {
      r = {{"index", i}, {"seed", o.seed}, {"error", e.what()}};
    }
    out << r.dump() << "\n";
    out.flush();
    std::fprintf(stderr, "case %d: %s %s -> %s (%s) %.1f s\n", i, r.value("structure", "?").c_str(),
                 r.value("truth_kind", "?").c_str(),
                 r.contains("named") && r["named"].is_object() ? r["named"].value("kind", "").c_str() : "-",
                 r.value("right_location", false) ? "right" : "wrong", r.value("seconds_diagnose", 0.0));
  }
  return 0;
}

// ------------------------------------------------------------------ report

/// Exact (Clopper–Pearson) two-sided 95 % interval of a binomial proportion k/n.
std::pair<double, double> clopper_pearson(int k, int n) {
  const double a = 0.05;
  const double lo = k == 0 ? 0.0 : boost::math::ibeta_inv(k, n - k + 1, a / 2);
  const double hi = k == n ? 1.0 : boost::math::ibeta_inv(k + 1, n - k, 1 - a / 2);
  return {lo, hi};
}

std::string pct(int k, int n) {
  if (n == 0) return "–";
  char b[48];
  std::snprintf(b, sizeof b, "%d/%d (%.0f %%)", k, n, 100.0 * k / n);
  return b;
}

/// Effect-size bin of a case: the largest frequency shift in σ of the frequency
/// noise; a new mode in the band (surge, local modes) is a bin of its own.
std::string bin_of(const json& r) {
  const json& e = r["effect"];
  if (e.value("new_modes", 0) > 0) return "new mode(s) in band";
  const double s = e.value("shift_sigma", 0.0);
  if (s < 1) return "< 1σ";
  if (s < 2) return "1–2σ";
  if (s < 5) return "2–5σ";
  if (s < 10) return "5–10σ";
  if (s < 30) return "10–30σ";
  return "≥ 30σ";
}

bool above_5_sigma(const json& r) {
  return r["effect"].value("new_modes", 0) > 0 || r["effect"].value("shift_sigma", 0.0) >= 5;
}

std::string report_text(const std::vector<json>& rows, const std::string& command) {
  std::ostringstream t;
  std::vector<json> ok;
  int errors = 0, partial = 0, timeouts = 0;
  double seconds = 0;
  std::map<std::string, int> per_structure;
  for (const auto& r : rows) {
    if (r.contains("error") || r["named"].is_null()) {
      ++errors;
      if (r.value("exit_code", 0) == 124) ++timeouts;
      continue;
    }
    if (r.value("partial", false)) ++partial;
    seconds += r.value("seconds_diagnose", 0.0);
    ++per_structure[r.value("structure", "")];
    ok.push_back(r);
  }
  t << "Generated by `" << command << "` from " << rows.size() << " cases (" << ok.size() << " diagnosed";
  for (const auto& [s, n] : per_structure) t << ", " << s << " " << n;
  t << "; " << errors << " without a diagnosis";
  if (timeouts) t << ", " << timeouts << " of them timed out";
  t << "; " << partial << " marked partial). Diagnosis time: mean "
    << (ok.empty() ? 0.0 : std::round(10 * seconds / static_cast<double>(ok.size())) / 10) << " s per case.\n\n";

  // False alarms.
  int nulls = 0, alarms = 0;
  std::map<std::string, int> alarm_kinds;
  for (const auto& r : ok)
    if (r["truth_kind"] == "null") {
      ++nulls;
      const std::string k = r["named"]["kind"];
      if (k != "parameter" && k != "none") {
        ++alarms;
        ++alarm_kinds[k];
      }
    }
  const auto [lo, hi] = clopper_pearson(alarms, std::max(nulls, 1));
  char line[256];
  std::snprintf(line, sizeof line, "**False alarms** (null cases: parameter errors only, 1–3 DESVARs within ±15 %%): %d of %d = %.1f %%, "
                "95 %% interval %.1f–%.1f %% (Clopper–Pearson). Target ≤ 1 %%: **%s**.",
                alarms, nulls, nulls ? 100.0 * alarms / nulls : 0.0, 100 * lo, 100 * hi,
                nulls == 0 ? "not measured" : (hi <= 0.01 ? "met" : (100.0 * alarms / nulls <= 1.0 ? "not shown (too few cases: the interval reaches above 1 %)" : "failed")));
  t << line;
  if (!alarm_kinds.empty()) {
    t << " Named instead:";
    for (const auto& [k, n] : alarm_kinds) t << " " << k << " " << n << ";";
  }
  t << "\n\n| null cases | every ball | sparse sensors |\n|---|---|---|\n";
  for (const std::string ref : {"rms", "max"})
  for (const std::string s : {"rod", "frame", "beam"}) {
    int n[2] = {0, 0}, k[2] = {0, 0};
    for (const auto& r : ok)
      if (r["truth_kind"] == "null" && r["structure"] == s && r.value("shape_noise_of", "rms") == ref) {
        const int j = r["sensors"] == "all" ? 0 : 1;
        ++n[j];
        const std::string named = r["named"]["kind"];
        k[j] += named != "parameter" && named != "none";
      }
    if (n[0] + n[1])
      t << "| " << s << (ref == "rms" ? "" : ", shape σ_s of the largest component") << ": false alarms | " << pct(k[0], n[0])
        << " | " << pct(k[1], n[1]) << " |\n";
  }
  t << "\n";

  // Confusion matrix of kinds.
  const std::vector<std::string> truths = {"null", "local_stiffness", "missing_mass", "support_dynamics", "local_modes",
                                           "joint_flexibility", "two"};
  std::set<std::string> named_set = {"none", "parameter"};
  for (const auto& r : ok) named_set.insert(r["named"]["kind"].get<std::string>());
  std::vector<std::string> named = {"none", "parameter"};
  for (const auto& k : named_set)
    if (k != "none" && k != "parameter") named.push_back(k);
  t << "Confusion matrix (rows: the hidden truth; columns: what `ssid diagnose` named; \"two\": two effects at once):\n\n";
  t << "| truth \\ named |";
  for (const auto& k : named) t << " " << k << " |";
  t << " cases |\n|---|";
  for (std::size_t i = 0; i < named.size(); ++i) t << "---|";
  t << "---|\n";
  for (const auto& tk : truths) {
    std::map<std::string, int> cnt;
    int n = 0;
    for (const auto& r : ok)
      if (r["truth_kind"] == tk) {
        ++cnt[r["named"]["kind"].get<std::string>()];
        ++n;
      }
    if (!n) continue;
    t << "| " << (tk == "null" ? "null (parameters only)" : tk) << " |";
    for (const auto& k : named) t << " " << (cnt[k] ? std::to_string(cnt[k]) : "·") << " |";
    t << " " << n << " |\n";
  }
  t << "\n";

  // Right kind and location against effect size (single effects).
  const std::vector<std::string> bins = {"< 1σ", "1–2σ", "2–5σ", "5–10σ", "10–30σ", "≥ 30σ", "new mode(s) in band"};
  t << "Single effects by effect size (the largest frequency shift the effect causes, truth with the effect against "
       "truth without it at the same parameter errors, in σ of the frequency noise; a truth mode in the band with no "
       "partner is its own bin). \"no cause\": named parameter or none.\n\n";
  t << "| effect size | cases | right kind | right kind and location | no cause | median shape effect [σ] |\n|---|---|---|---|---|---|\n";
  int big = 0, big_right = 0;
  for (const auto& b : bins) {
    int n = 0, rk = 0, rl = 0, none = 0;
    std::vector<double> shape;
    for (const auto& r : ok) {
      if (r["truth_kind"] == "null" || r["truth_kind"] == "two" || bin_of(r) != b) continue;
      ++n;
      rk += r.value("right_kind", false);
      rl += r.value("right_location", false);
      const std::string k = r["named"]["kind"];
      none += k == "parameter" || k == "none";
      shape.push_back(r["effect"].value("shape_sigma", 0.0));
      if (above_5_sigma(r)) {
        ++big;
        big_right += r.value("right_location", false);
      }
    }
    if (!n) continue;
    std::sort(shape.begin(), shape.end());
    char med[32];
    std::snprintf(med, sizeof med, "%.1f", shape[shape.size() / 2]);
    t << "| " << b << " | " << n << " | " << pct(rk, n) << " | " << pct(rl, n) << " | " << pct(none, n) << " | " << med << " |\n";
  }
  t << "\n";
  if (big) {
    const auto [blo, bhi] = clopper_pearson(big_right, big);
    std::snprintf(line, sizeof line, "**Right kind and location above 5σ** (single effects, a new mode counted above): %d of %d = %.0f %%, "
                  "95 %% interval %.0f–%.0f %%. Target ≥ 90 %%: **%s**.\n\n",
                  big_right, big, 100.0 * big_right / big, 100 * blo, 100 * bhi, 100.0 * big_right / big >= 90 ? "met" : "failed");
    t << line;
  }

  // Per kind above 5σ.
  t << "Single effects above 5σ by kind and structure:\n\n| structure | kind | cases | right kind | right kind and location |\n|---|---|---|---|---|\n";
  for (const std::string s : {"rod", "frame", "beam"})
    for (const auto& tk : truths) {
      int n = 0, rk = 0, rl = 0;
      for (const auto& r : ok)
        if (r["structure"] == s && r["truth_kind"] == tk && tk != "null" && tk != "two" && above_5_sigma(r)) {
          ++n;
          rk += r.value("right_kind", false);
          rl += r.value("right_location", false);
        }
      if (n) t << "| " << s << " | " << tk << " | " << n << " | " << pct(rk, n) << " | " << pct(rl, n) << " |\n";
    }
  t << "\n";

  // Two effects.
  int two = 0, two_one = 0, two_any_kind = 0;
  for (const auto& r : ok)
    if (r["truth_kind"] == "two") {
      ++two;
      two_any_kind += r.value("right_kind", false);
      two_one += r.value("right_location", false);
    }
  if (two) {
    t << "**Two effects at once** (" << two << " cases): one of the two named with the right kind in " << pct(two_any_kind, two)
      << ", with the right kind and location in " << pct(two_one, two)
      << " (the sweep reads the JSON's one `cause`: whether both were named is not measured).\n\n";
    t << "| structure | effects | sizes [σ; new modes] | named | right |\n|---|---|---|---|---|\n";
    for (const auto& r : ok)
      if (r["truth_kind"] == "two") {
        std::string eff;
        for (const auto& e : r["effects"]) eff += (eff.empty() ? "" : " + ") + e["kind"].get<std::string>() + " (" + e["where"].get<std::string>() + ", " + e["magnitude"].get<std::string>() + ")";
        char sz[64];
        std::snprintf(sz, sizeof sz, "%.1f; %d", r["effect"].value("shift_sigma", 0.0), r["effect"].value("new_modes", 0));
        t << "| " << r["structure"].get<std::string>() << " | " << eff << " | " << sz << " | " << r["named"]["kind"].get<std::string>()
          << " " << r["named"]["location"].get<std::string>() << " | " << (r.value("right_location", false) ? "yes" : "no") << " |\n";
      }
    t << "\n";
  }

  // A cause that fits worse than the ordinary update must never be named (issue 26).
  int worse = 0, named_causes = 0;
  for (const auto& r : ok) {
    const std::string k = r["named"]["kind"];
    if (k == "parameter" || k == "none" || !r["fit"]["update"].is_object() || !r["fit"]["cause"].is_object()) continue;
    ++named_causes;
    const json &c = r["fit"]["cause"], &u = r["fit"]["update"];
    worse += c.value("freq_rms_pct", 0.0) > u.value("freq_rms_pct", 0.0) && c.value("paired", 0) <= u.value("paired", 0);
  }
  t << "Named causes that fit worse than the ordinary update (a larger frequency RMS error with no more modes paired): "
    << worse << " of " << named_causes << ".\n";
  return t.str();
}

int report(const std::string& results, const std::string& docs, const std::string& command) {
  std::vector<json> rows;
  std::ifstream in(results);
  if (!in) {
    std::cerr << results << ": cannot open\n";
    return 2;
  }
  for (std::string line; std::getline(in, line);)
    if (!line.empty()) rows.push_back(json::parse(line));
  const std::string text = report_text(rows, command);
  if (docs.empty()) {
    std::cout << text;
    return 0;
  }
  const std::string begin = "<!-- diagnosis-sweep:begin (generated by scripts/diagnosis-sweep; do not edit) -->\n",
                    end = "<!-- diagnosis-sweep:end -->";
  std::ifstream d(docs, std::ios::binary);
  std::stringstream ss;
  ss << d.rdbuf();
  std::string doc = ss.str();
  const auto b = doc.find(begin), e = doc.find(end);
  if (b == std::string::npos || e == std::string::npos || e < b) {
    std::cerr << docs << ": no generated block (the markers " << begin.substr(0, begin.size() - 1) << " and " << end << ")\n";
    return 2;
  }
  doc.replace(b + begin.size(), e - b - begin.size(), text);
  write_text(docs, doc);
  return 0;
}

int usage() {
  std::cerr << "usage: bench_diagnosis_sweep run --ssid PATH --out DIR [--seed S] [--first I] [--count N]\n"
               "                             [--structures rod,frame,beam] [--null-fraction F] [--kinds K,...]\n"
               "                             [--case-timeout SECONDS] [--shape-noise rms|max] [--keep] [--skip-diagnose]\n"
               "       bench_diagnosis_sweep report RESULTS.jsonl [--docs FILE] [--command TEXT]\n";
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) return usage();
  const std::string what = argv[1];
  std::map<std::string, std::string> opt;
  std::vector<std::string> positional;
  for (int i = 2; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--keep" || a == "--skip-diagnose") opt[a] = "1";
    else if (a.rfind("--", 0) == 0 && i + 1 < argc) opt[a] = argv[++i];
    else if (a.rfind("--", 0) == 0) return usage();
    else positional.push_back(a);
  }
  try {
    if (what == "run") {
      SweepOptions o;
      if (!opt.count("--ssid") || !opt.count("--out")) return usage();
      o.ssid = opt["--ssid"];
      o.out = opt["--out"];
      if (opt.count("--seed")) o.seed = std::stoull(opt["--seed"]);
      if (opt.count("--first")) o.first = std::stoi(opt["--first"]);
      if (opt.count("--count")) o.count = std::stoi(opt["--count"]);
      if (opt.count("--null-fraction")) o.null_fraction = std::stod(opt["--null-fraction"]);
      if (opt.count("--case-timeout")) o.case_timeout = std::stoi(opt["--case-timeout"]);
      if (opt.count("--kinds")) o.kinds = split(opt["--kinds"], ',');
      if (opt.count("--shape-noise")) o.shape_noise_of = opt["--shape-noise"];
      if (o.shape_noise_of != "rms" && o.shape_noise_of != "max") {
        std::cerr << "--shape-noise: rms or max, not \"" << o.shape_noise_of << "\"\n";
        return 2;
      }
      o.keep = opt.count("--keep") > 0;
      o.skip_diagnose = opt.count("--skip-diagnose") > 0;
      if (opt.count("--structures")) {
        o.structures.clear();
        for (const auto& s : split(opt["--structures"], ',')) {
          if (s == "rod") o.structures.push_back(Structure::Rod);
          else if (s == "frame") o.structures.push_back(Structure::Frame);
          else if (s == "beam") o.structures.push_back(Structure::Beam);
          else {
            std::cerr << "--structures: unknown structure \"" << s << "\" (rod, frame, beam)\n";
            return 2;
          }
        }
      }
      return run(o);
    }
    if (what == "report" && positional.size() == 1)
      return report(positional[0], opt.count("--docs") ? opt["--docs"] : "",
                    opt.count("--command") ? opt["--command"] : "bench_diagnosis_sweep report " + positional[0]);
  } catch (const std::exception& e) {
    std::cerr << "bench_diagnosis_sweep: " << e.what() << "\n";
    return 1;
  }
  return usage();
}
