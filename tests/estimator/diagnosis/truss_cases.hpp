#pragma once
// Synthetic tests for the diagnosis: an MPI truss model form with an effect
// hidden in it (the truth), its modes from the generator's own reference
// assembler (independent of ssid's deck assembly) sampled at ball grids with
// noise, and the nominal deck text that ssid is given.
#include <algorithm>
#include <map>
#include <stdexcept>
#include <random>
#include <set>
#include <string>

#include "formats/deck_writer.hpp"
#include "translators/measurement/mode_set.hpp"
#include "translators/truss/configurations.hpp"
#include "translators/truss/reference_modes.hpp"
#include "translators/truss/truss_deck.hpp"

namespace ssid::test_support {

namespace tr = translators::truss;

/// Property ids of the rod form's PROD cards collide with the suspension PELAS
/// (fixed on main: PROD ids move to 101-142, DVPREL1 of PELAS names K). Until
/// that is merged, the same renumbering is done here on the plain model, not
/// in the generator. Does nothing when there is no collision.
inline void fix_property_ids(tr::TrussCards& fe) {
  std::set<int> springs;
  for (const auto& p : fe.spring_props) springs.insert(p.id);
  bool clash = false;
  for (const auto& p : fe.rod_props) clash = clash || springs.count(p.id);
  if (clash) {
    std::map<int, int> moved;
    for (auto& p : fe.rod_props) { moved[p.id] = p.id + 100; p.id += 100; }
    for (auto& r : fe.rods) r.pid = moved.count(r.pid) ? moved[r.pid] : r.pid;
    for (auto& d : fe.dvprels)
      if (d.type == "PROD" && moved.count(d.pid)) d.pid = moved[d.pid];
  }
  for (auto& d : fe.dvprels)
    if (d.type == "PELAS" && d.pname == "K1") d.pname = "K";
}

inline std::string deck_text(const tr::TrussModel& t, const tr::TrussCards& fe) {
  return formats::render_file(tr::to_deck(t, fe, "diagnosis test"), 0);
}

/// Noise and band of a synthetic modal test.
struct TestSpec {
  double f_low = 2.0, f_high = 66.0;  ///< Hz: elastic modes in this band are "measured"
  double freq_noise_pct = 0.2;        ///< σ of the frequency noise, % of it
  double shape_noise_pct = 2.0;       ///< σ of each component, % of the shape's RMS component
  unsigned seed = 1;
  std::vector<int> sensor_grids;      ///< empty: every ball grid (kind "ball")
};

/// The truth's modes at the sensors (x, y, z of each sensor grid), with noise.
inline translators::ModeSet synthetic_test(const tr::TrussCards& truth, const TestSpec& spec, int count = 60) {
  const tr::ReferenceModes rm = tr::reference_modes(truth, count);
  std::vector<int> sensors = spec.sensor_grids;
  if (sensors.empty())
    for (const auto& g : truth.grids)
      if (g.kind == "ball") sensors.push_back(g.id);
  std::map<int, std::size_t> index;
  for (std::size_t i = 0; i < rm.grid_ids.size(); ++i) index[rm.grid_ids[i]] = i;
  translators::ModeSet set;
  for (int g : sensors)
    for (int c = 1; c <= 3; ++c) set.dofs.push_back({g, c});
  std::mt19937 rng(spec.seed);
  std::normal_distribution<double> n01(0.0, 1.0);
  std::vector<Eigen::VectorXd> cols;
  for (std::size_t j = 0; j < rm.frequency_hz.size(); ++j) {
    const double f = rm.frequency_hz[j];
    if (f < spec.f_low || f > spec.f_high) continue;
    Eigen::VectorXd s(static_cast<Eigen::Index>(set.dofs.size()));
    for (std::size_t k = 0; k < set.dofs.size(); ++k)
      s(static_cast<Eigen::Index>(k)) =
          rm.shapes(static_cast<Eigen::Index>(6 * index.at(static_cast<int>(set.dofs[k].node)) + set.dofs[k].direction - 1),
                    static_cast<Eigen::Index>(j));
    const double rms = s.norm() / std::sqrt(static_cast<double>(s.size()));
    for (Eigen::Index k = 0; k < s.size(); ++k) s(k) += spec.shape_noise_pct / 100.0 * rms * n01(rng);
    cols.push_back(s);
    set.frequency_hz.push_back(f * (1.0 + spec.freq_noise_pct / 100.0 * n01(rng)));
    set.numbers.push_back(static_cast<int>(set.numbers.size()) + 1);
    set.damping.push_back(0.0);
    set.modal_mass.push_back(0.0);
  }
  set.shapes.resize(static_cast<Eigen::Index>(set.dofs.size()), static_cast<Eigen::Index>(cols.size()));
  for (std::size_t j = 0; j < cols.size(); ++j) set.shapes.col(static_cast<Eigen::Index>(j)) = cols[j];
  return set;
}

/// The rod-form truss and its plain model (ids fixed).
struct Case {
  tr::TrussModel t;
  tr::TrussCards fe;
};
inline Case rod_case(const std::vector<std::string>& configs = {}) {
  Case c{tr::build_configured(configs), {}};
  c.fe = tr::build_truss_cards(c.t, tr::ModelForm::Rod);
  fix_property_ids(c.fe);
  return c;
}

/// Sets a DESVAR's value in the truth: the designed fields follow through the
/// DVPREL1 relations of the plain model (coefficient × value, summed).
inline void perturb(tr::TrussCards& fe, const std::string& label, double factor) {
  int dv = 0;
  for (auto& d : fe.desvars)
    if (d.label == label) { dv = d.id; d.init *= factor; }
  std::map<int, double> value_of;
  for (const auto& d : fe.desvars) value_of[d.id] = d.init;
  for (const auto& r : fe.dvprels) {
    bool uses = r.dvid == dv;
    for (const auto& [id, c] : r.more) uses = uses || id == dv;
    if (!uses) continue;
    double v = r.coef * value_of[r.dvid];
    for (const auto& [id, c] : r.more) v += c * value_of[id];
    if (r.type == "PROD")
      for (auto& p : fe.rod_props) if (p.id == r.pid && r.pname == "A") p.A = v;
    if (r.type == "CONM2")
      for (auto& m : fe.masses) if (m.id == r.pid && r.pname == "M") m.m = v;
    if (r.type == "PELAS")
      for (auto& s : fe.spring_props) if (s.id == r.pid) s.k = v;
    if (r.type == "PBAR")
      for (auto& p : fe.bar_props)
        if (p.id == r.pid) {
          if (r.pname == "A") p.A = v;
          if (r.pname == "I1") p.I1 = v;
          if (r.pname == "I2") p.I2 = v;
          if (r.pname == "J") p.J = v;
        }
  }
}

/// Hides local strut modes: rod `rod_id` of the rod form becomes a tube of
/// `segments` CBARs through new interior grids (kind "strut": not sensors) with
/// the rod's area (axial rate kept), bending inertia I = `inertia` [m⁴], J = 2I,
/// and the tube's mass — lumped at the two balls in the rod form — moved onto
/// the bars as NSM. The ball grids keep their rotations held (GRID PS 456), so
/// the tube is clamped at both ends. A finer model than the two-bar refinement
/// the local_modes kind tries.
inline void refine_rod(Case& c, int rod_id, double inertia, int segments = 4) {
  tr::TrussCards& fe = c.fe;
  auto it = std::find_if(fe.rods.begin(), fe.rods.end(), [&](const tr::FeRod& r) { return r.id == rod_id; });
  if (it == fe.rods.end()) throw std::invalid_argument("refine_rod: no rod " + std::to_string(rod_id));
  const tr::FeRod rod = *it;
  fe.rods.erase(it);
  const tr::Member& member = c.t.members.at(static_cast<std::size_t>(rod_id - 1));
  const double tube_mass = c.t.tube_length(member) * c.t.hw.tube_mass_per_length();
  for (auto& m : fe.masses)
    if (m.kind == "strut" && (m.grid == rod.g1 || m.grid == rod.g2)) m.m -= tube_mass / 2;
  const tr::FeRodProp* rp = nullptr;
  for (const auto& p : fe.rod_props) if (p.id == rod.pid) rp = &p;
  const Eigen::Vector3d a = fe.grid(rod.g1).x, b = fe.grid(rod.g2).x;
  tr::FeBarProp bp;
  for (const auto& p : fe.bar_props) bp.id = std::max(bp.id, p.id);
  for (const auto& p : fe.rod_props) bp.id = std::max(bp.id, p.id);
  bp.id += 1;
  bp.A = rp->A;
  bp.nsm = tube_mass / (b - a).norm();
  bp.I1 = bp.I2 = inertia;
  bp.J = 2 * inertia;
  bp.kind = "tube";
  fe.bar_props.push_back(bp);
  int next_grid = 0, next_bar = 0;
  for (const auto& g : fe.grids) next_grid = std::max(next_grid, g.id);
  for (const auto& x : fe.bars) next_bar = std::max(next_bar, x.id);
  for (const auto& r : fe.rods) next_bar = std::max(next_bar, r.id);
  next_bar = std::max(next_bar, rod_id);
  const Eigen::Vector3d axis = (b - a).normalized();
  Eigen::Index k = 0;
  axis.cwiseAbs().minCoeff(&k);
  const Eigen::Vector3d v = Eigen::Vector3d::Unit(k);
  int prev = rod.g1;
  for (int s = 1; s <= segments; ++s) {
    int g = rod.g2;
    if (s < segments) {
      tr::FeGrid ng;
      ng.id = ++next_grid;
      ng.x = a + (b - a) * (static_cast<double>(s) / segments);
      ng.kind = "strut";
      fe.grids.push_back(ng);
      g = ng.id;
    }
    fe.bars.push_back({++next_bar, bp.id, prev, g, v, rod.member});
    prev = g;
  }
}

/// Bending inertia [m⁴] that puts the first clamped–clamped bending mode of a
/// uniform tube (length L, mass per length μ, modulus E) at f:
/// ω = (4.730)² √(EI/(μL⁴)).
inline double clamped_tube_inertia(double f_hz, double L, double mu, double E) {
  const double w = 2 * M_PI * f_hz, b = 4.730040745 * 4.730040745;
  return std::pow(w * L * L / b, 2) * mu / E;
}

/// A frame tower in the beam form of the MPI truss: 4 × 0.6 m storeys of a
/// 0.6 × 0.5 m rectangle, legs and battens of the MPI strut tube, no
/// diagonals — its lateral stiffness is all frame action, so the joints'
/// rotational stiffness shows in the global modes. Balls (CONM2 with inertia)
/// are joined by RBE2 spiders (123456) to grids on their surface where one CBAR
/// per member starts (no strut-interior grids: no local modes); the base balls
/// are clamped (GRID PS). Parameters: TUBEI (tube I1 = I2, J = 2·TUBEI) and
/// BALLM (every ball's CONM2 M).
inline Case frame_case() {
  Case c;
  tr::TrussCards& fe = c.fe;
  fe.form = tr::ModelForm::Beam;
  fe.title = "frame tower (beam form)";
  fe.mat = {1, 6.89e10, 0.33, 0.0};
  const double ax = 0.6, ay = 0.5, h = 0.6, r = 0.03, A = 2.0e-4, I = 2.2e-8, ball = 1.2;
  const int levels = 5;
  auto ball_id = [](int level, int corner) { return 1 + 4 * level + corner; };
  const double cx[4] = {0, ax, ax, 0}, cy[4] = {0, 0, ay, ay};
  for (int l = 0; l < levels; ++l)
    for (int k = 0; k < 4; ++k)
      fe.grids.push_back({ball_id(l, k), Eigen::Vector3d(cx[k], cy[k], l * h), l == 0 ? "123456" : "", "ball"});
  fe.bar_props.push_back({1, A, I, I, 2 * I, 0.5, "tube"});
  std::vector<std::pair<int, int>> members;
  for (int l = 0; l + 1 < levels; ++l)
    for (int k = 0; k < 4; ++k) members.push_back({ball_id(l, k), ball_id(l + 1, k)});
  for (int l = 1; l < levels; ++l)
    for (int k = 0; k < 4; ++k) members.push_back({ball_id(l, k), ball_id(l, (k + 1) % 4)});
  std::map<int, std::vector<int>> spider;
  int m = 0;
  for (const auto& [a, b] : members) {
    ++m;
    const Eigen::Vector3d xa = fe.grid(a).x, xb = fe.grid(b).x, e = (xb - xa).normalized();
    const int sa = 100000 + 100 * m + 1, sb = sa + 1;
    fe.grids.push_back({sa, xa + r * e, "", "ball_surface"});
    fe.grids.push_back({sb, xb - r * e, "", "ball_surface"});
    Eigen::Index k = 0;
    e.cwiseAbs().minCoeff(&k);
    fe.bars.push_back({100000 + 100 * m + 1, 1, sa, sb, Eigen::Vector3d::Unit(k), m});
    spider[a].push_back(sa);
    spider[b].push_back(sb);
  }
  for (const auto& [b, gm] : spider) fe.rigids.push_back({200000 + b, b, gm});
  for (const auto& g : std::vector<tr::FeGrid>(fe.grids))
    if (g.kind == "ball") fe.masses.push_back({1000 + g.id, g.id, ball, 0.4 * ball * r * r, "ball"});
  fe.desvars.push_back({1, "TUBEI", I, 0.1 * I, 10 * I, "tube bending inertia, m^4 (PBAR I1 = I2, J = 2 TUBEI)"});
  fe.desvars.push_back({2, "BALLM", ball, 0.1 * ball, 10 * ball, "ball mass, kg (CONM2 M)"});
  fe.dvprels.push_back({1, "PBAR", 1, "I1", 1, 1.0, {}});
  fe.dvprels.push_back({2, "PBAR", 1, "I2", 1, 1.0, {}});
  fe.dvprels.push_back({3, "PBAR", 1, "J", 1, 2.0, {}});
  int id = 4;
  for (const auto& x : fe.masses) fe.dvprels.push_back({id++, "CONM2", x.id, "M", 2, 1.0, {}});
  fe.eigrl_nd = 30;
  fe.eigrl_v2 = 1000.0;
  return c;
}

/// The ball grids of a frame_case above its clamped base (the sensors).
inline std::vector<int> frame_sensors(const Case& c) {
  std::vector<int> out;
  for (const auto& g : c.fe.grids)
    if (g.kind == "ball" && g.ps.empty()) out.push_back(g.id);
  return out;
}

/// Hides rotationally flexible joints at one ball of a frame_case: every member
/// end there starts after a short stub (10 mm CBAR, the tube's area, bending
/// inertia k_θ·l/E so its rate under a pure moment is k_θ [N·m/rad], J = 2I)
/// instead of at the ball's surface grid. A different form from the
/// joint_flexibility kind's CELAS1 springs (the stub also bends in shear and
/// twists at 2G/E·k_θ).
inline void flexible_joint(Case& c, int ball, double k_theta) {
  tr::TrussCards& fe = c.fe;
  const double ls = 0.01, Is = k_theta * ls / fe.mat.E;
  tr::FeBarProp stub;
  for (const auto& p : fe.bar_props) stub.id = std::max(stub.id, p.id);
  stub.id += 1;
  stub.A = fe.bar_props.front().A;
  stub.I1 = stub.I2 = Is;
  stub.J = 2 * Is;
  stub.kind = "joint_stub";
  fe.bar_props.push_back(stub);
  const tr::FeRigid* spider = nullptr;
  for (const auto& r : fe.rigids) if (r.gn == ball) spider = &r;
  if (!spider) throw std::invalid_argument("flexible_joint: no spider at ball " + std::to_string(ball));
  int next_grid = 0, next_bar = 0;
  for (const auto& g : fe.grids) next_grid = std::max(next_grid, g.id);
  for (const auto& b : fe.bars) next_bar = std::max(next_bar, b.id);
  const std::vector<int> ends = spider->gm;
  for (int s : ends)
    for (auto& b : fe.bars) {
      if (b.g1 != s && b.g2 != s) continue;
      const int other = b.g1 == s ? b.g2 : b.g1;
      const Eigen::Vector3d xs = fe.grid(s).x, e = (fe.grid(other).x - xs).normalized();
      tr::FeGrid g{++next_grid, xs + ls * e, "", "strut"};
      (b.g1 == s ? b.g1 : b.g2) = g.id;
      const tr::FeBar stub_bar{++next_bar, stub.id, s, g.id, b.v, b.member};
      fe.grids.push_back(g);
      fe.bars.push_back(stub_bar);
      break;
    }
}

}  // namespace ssid::test_support
