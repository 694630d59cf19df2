/// \file truss_cards.cpp
/// Turns the truss inventory into the rod or beam model form.
#include "translators/truss/truss_cards.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

namespace ssid::translators::truss {

namespace {

/// Significant-digit rounding so values print exactly in 8 columns.
double sig(double v, int digits = 4) {
  if (v == 0) return 0;
  const double p = std::pow(10.0, digits - 1 - static_cast<int>(std::floor(std::log10(std::fabs(v)))));
  return std::round(v * p) / p;
}
Eigen::Vector3d round_x(const Eigen::Vector3d& x) {
  return {std::round(x.x() * 1e5) / 1e5, std::round(x.y() * 1e5) / 1e5, std::round(x.z() * 1e5) / 1e5};
}

// Id blocks (documented in docs/truss.md).
constexpr int kStrutGridBase = 100000;   // strut grids: 100000 + 100 * member + k
constexpr int kSpringGridBase = 900000;  // surge chain grids: 900000 + 100 * point + k
constexpr int kBarBase = 100000;         // CBAR: 100000 + 100 * member + k
constexpr int kJointMassBase = 1000;     // CONM2 ball/joint: 1000 + ball
constexpr int kStrutMassBase = 2000;     // CONM2 rod form, half tubes: 2000 + ball
constexpr int kAddedMassBase = 3000;     // CONM2 added (configuration) mass: 3000 + ball
constexpr int kMidMassBase = 4000;       // CONM2 mid-span mass: 4000 + member
constexpr int kSpringMassBase = 5000;    // CONM2 surge chain: 5000 + 100 * point + k
constexpr int kRigidBase = 6000;         // RBE2: 6000 + ball
constexpr int kSpringBase = 7000;        // CELAS1: 7000 + 100 * point + k
// PROD ids start above the PELAS ids (11-15): NASTRAN property ids share one
// number space, so a PROD 11 next to a PELAS 11 is a duplicate.
constexpr int kRodPropBase = 100;        // PROD rod form: 101, 102, ...

// Property ids.
constexpr int kPbarTube = 1, kPbarEndcap = 2, kPbarBnut = 3, kPbarLongBnut = 4;
constexpr int kPelasVertical = 11, kPelasChain = 12, kPelasLateral = 13;  // lateral: 13, 14, 15 per point

void add_desvar(TrussCards& fe, int id, const std::string& label, double init, const std::string& what) {
  fe.desvars.push_back({id, label, init, sig(init / 10.0), sig(init * 10.0), what});
}
void add_dvprel(TrussCards& fe, const std::string& type, int pid, const std::string& pname, int dvid, double coef) {
  fe.dvprels.push_back({static_cast<int>(fe.dvprels.size()) + 1, type, pid, pname, dvid, coef, {}});
}

Eigen::Vector3d orientation(const Eigen::Vector3d& axis) {
  return std::fabs(axis.normalized().z()) > 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitZ();
}

void add_suspension(const TrussModel& t, TrussCards& fe, bool massless_only_vertical_prop) {
  if (t.suspension.empty()) return;
  const double kv = t.suspension.front().k_vertical;
  fe.spring_props.push_back({kPelasVertical, kv, "suspension"});
  bool any_chain = false;
  for (std::size_t p = 0; p < t.suspension.size(); ++p) {
    const Suspension& s = t.suspension[p];
    if (std::fabs(s.k_vertical - kv) > 1e-12) throw std::invalid_argument("suspension springs must share one stiffness");
    const int pid_lat = kPelasLateral + static_cast<int>(p);
    fe.spring_props.push_back({pid_lat, s.k_lateral, "pendulum"});
    const int base = kSpringBase + 100 * static_cast<int>(p + 1);
    fe.springs.push_back({base + 1, pid_lat, s.ball, 1, 0, 0});
    fe.springs.push_back({base + 2, pid_lat, s.ball, 2, 0, 0});
    if (s.spring_mass <= 0) {
      fe.springs.push_back({base + 3, kPelasVertical, s.ball, 3, 0, 0});
      continue;
    }
    // Coil spring with distributed mass: a chain of `segments` springs of N k,
    // interior grids carrying m_s / N, the half segments at the ends lumped to the
    // ball and to ground. Fixed-fixed surge of the discrete chain:
    // f_n = (N / pi) sqrt(k / m_s) sin(n pi / 2N).
    any_chain = true;
    const int N = s.segments;
    const double seg_len = 0.3 / N;  // 0.3 m coil above the ball
    const Eigen::Vector3d x0 = t.ball(s.ball).x;
    int prev = s.ball;
    const int gbase = kSpringGridBase + 100 * static_cast<int>(p + 1);
    const int mbase = kSpringMassBase + 100 * static_cast<int>(p + 1);
    fe.masses.push_back({mbase, s.ball, s.spring_mass / (2.0 * N), 0.0, "spring"});
    for (int k = 1; k < N; ++k) {
      const int g = gbase + k;
      fe.grids.push_back({g, round_x(x0 + Eigen::Vector3d(0, 0, k * seg_len)), "12456", "spring"});
      fe.masses.push_back({mbase + k, g, s.spring_mass / N, 0.0, "spring"});
      fe.springs.push_back({base + 10 + k, kPelasChain, prev, 3, g, 3});
      prev = g;
    }
    fe.springs.push_back({base + 10 + N, kPelasChain, prev, 3, 0, 0});
  }
  if (any_chain) {
    const int N = t.suspension.front().segments;
    fe.spring_props.push_back({kPelasChain, kv * N, "suspension_chain"});
  }
  (void)massless_only_vertical_prop;
}

}  // namespace

double equivalent_axial_area(const TrussModel& t, const Member& m) {
  const Hardware& h = t.hw;
  const FittingSection& bn = t.bnut_of(m);
  const double compliance =
      t.tube_length(m) / h.tube_area + 2.0 * h.endcap.length / h.endcap.area + 2.0 * bn.length / bn.area;
  return t.length(m) / compliance;
}

Eigen::Vector3d equivalent_area_gradient(const TrussModel& t, const Member& m) {
  const Hardware& h = t.hw;
  const FittingSection& bn = t.bnut_of(m);
  const double A = equivalent_axial_area(t, m), L = t.length(m);
  const double c = A * A / L;
  return {c * t.tube_length(m) / (h.tube_area * h.tube_area), c * 2.0 * h.endcap.length / (h.endcap.area * h.endcap.area),
          c * 2.0 * bn.length / (bn.area * bn.area)};
}

int tube_segments(const TrussModel& t, const Member& m) { return t.tube_length(m) > 1.0 ? 4 : 2; }

std::size_t TrussCards::dof_count() const {
  std::size_t n = 0;
  for (const auto& g : grids) n += 6 - g.ps.size();
  return n;
}

const FeGrid& TrussCards::grid(int id) const {
  for (const auto& g : grids)
    if (g.id == id) return g;
  throw std::out_of_range("no grid " + std::to_string(id));
}

double TrussCards::total_mass() const {
  std::map<int, const FeGrid*> gmap;
  for (const auto& g : grids) gmap[g.id] = &g;
  double s = 0;
  for (const auto& m : masses) s += m.m;
  std::map<int, double> rod_mpl, bar_mpl;
  for (const auto& p : rod_props) rod_mpl[p.id] = mat.rho * p.A + p.nsm;
  for (const auto& p : bar_props) bar_mpl[p.id] = mat.rho * p.A + p.nsm;
  for (const auto& r : rods) s += rod_mpl.at(r.pid) * (gmap.at(r.g2)->x - gmap.at(r.g1)->x).norm();
  for (const auto& b : bars) s += bar_mpl.at(b.pid) * (gmap.at(b.g2)->x - gmap.at(b.g1)->x).norm();
  return s;
}

TrussCards build_truss_cards(const TrussModel& t, ModelForm form) {
  TrussCards fe;
  fe.form = form;
  fe.title = t.name + (form == ModelForm::Rod ? " rod model" : " beam model");
  const Hardware& h = t.hw;
  // Structural material carries no density: mass enters through CONM2 and NSM,
  // decoupled from the stiffness parameters as in the report's model form.
  fe.mat = {1, h.E, h.nu, 0.0};

  for (const auto& b : t.balls) fe.grids.push_back({b.id, b.x, form == ModelForm::Rod ? "456" : "", "ball"});

  // Joint mass, added mass.
  std::vector<double> fittings(t.balls.size() + 1, 0.0), half_tubes(t.balls.size() + 1, 0.0);
  for (const auto& m : t.members) {
    const double fit = h.endcap.mass + t.bnut_of(m).mass;
    const double half = 0.5 * (t.tube_length(m) * h.tube_mass_per_length() + m.mid_mass);
    fittings[m.a] += fit;
    fittings[m.b] += fit;
    half_tubes[m.a] += half;
    half_tubes[m.b] += half;
  }

  if (form == ModelForm::Rod) {
    // One PROD per strut length (and B-nut kind): its series-equivalent area, and a
    // DVPREL1 expressing it through the component areas (exact at the nominal point).
    std::map<std::pair<long long, bool>, int> pid_of;
    std::vector<Eigen::Vector3d> grads;
    for (const auto& m : t.members) {
      auto key = std::make_pair(std::llround(t.length(m) * 1e6), m.long_bnut);
      if (!pid_of.count(key)) {
        const int pid = kRodPropBase + static_cast<int>(pid_of.size()) + 1;
        pid_of[key] = pid;
        fe.rod_props.push_back({pid, equivalent_axial_area(t, m), 0.0, 0.0, m.long_bnut ? "long_bnut_strut" : "strut"});
        grads.push_back(equivalent_area_gradient(t, m));
      }
      fe.rods.push_back({m.id, pid_of[key], m.a, m.b, m.id});
    }
    for (const auto& b : t.balls) {
      fe.masses.push_back({kJointMassBase + b.id, b.id, h.ball_mass + fittings[b.id], 0.0, "joint"});
      fe.masses.push_back({kStrutMassBase + b.id, b.id, half_tubes[b.id], 0.0, "strut"});
      if (b.added_mass > 0) fe.masses.push_back({kAddedMassBase + b.id, b.id, b.added_mass, 0.0, "added"});
    }
    add_suspension(t, fe, true);
    const bool any_long = std::any_of(t.members.begin(), t.members.end(), [](const Member& m) { return m.long_bnut; });
    add_desvar(fe, 1, "STRUTA", h.tube_area, "strut tube area A_strut, m^2 (enters PROD A through the series-equivalent area)");
    add_desvar(fe, 2, "BNUTA", h.bnut.area, "B-nut area A_bnut, m^2 (through the series-equivalent area)");
    if (any_long) add_desvar(fe, 10, "LBNUTA", h.long_bnut.area, "long B-nut area, m^2 (through the series-equivalent area)");
    add_desvar(fe, 9, "ECAPA", h.endcap.area, "end-cap area, m^2 (through the series-equivalent area)");
    for (std::size_t k = 0; k < fe.rod_props.size(); ++k) {
      const bool lb = fe.rod_props[k].kind == "long_bnut_strut";
      FeDvprel r{static_cast<int>(fe.dvprels.size()) + 1, "PROD", fe.rod_props[k].id, "A", 1, grads[k](0), {}};
      r.more = {{lb ? 10 : 2, grads[k](2)}, {9, grads[k](1)}};
      fe.dvprels.push_back(r);
    }
    add_desvar(fe, 7, "JOINTM", 1.0, "joint mass scale (ball + B-nuts + end caps, CONM2 M)");
    for (const auto& c : fe.masses)
      if (c.kind == "joint") add_dvprel(fe, "CONM2", c.id, "M", 7, c.m);
  } else {
    const FittingSection& bn = h.bnut;
    const FittingSection& lb = h.long_bnut;
    const FittingSection& ec = h.endcap;
    fe.bar_props.push_back({kPbarTube, h.tube_area, h.tube_inertia, h.tube_inertia, 2 * h.tube_inertia,
                            sig(h.tube_mass_per_length()), "tube"});
    fe.bar_props.push_back({kPbarEndcap, ec.area, ec.inertia, ec.inertia, 2 * ec.inertia, sig(ec.mass / ec.length), "endcap"});
    fe.bar_props.push_back({kPbarBnut, bn.area, bn.inertia, bn.inertia, 2 * bn.inertia, sig(bn.mass / bn.length), "bnut"});
    fe.bar_props.push_back({kPbarLongBnut, lb.area, lb.inertia, lb.inertia, 2 * lb.inertia, sig(lb.mass / lb.length), "long_bnut"});

    std::vector<std::vector<int>> surface(t.balls.size() + 1);
    for (const auto& m : t.members) {
      const Eigen::Vector3d xa = t.ball(m.a).x, xb = t.ball(m.b).x;
      const double L = (xb - xa).norm();
      const Eigen::Vector3d n = (xb - xa) / L;
      const FittingSection& b = t.bnut_of(m);
      const int nseg = tube_segments(t, m);
      const double s_tube0 = h.ball_radius + b.length + ec.length, s_tube1 = L - s_tube0;
      // Stations along the strut and the property of the element that ends at each.
      std::vector<double> s = {h.ball_radius, h.ball_radius + b.length, s_tube0};
      std::vector<int> pid = {m.long_bnut ? kPbarLongBnut : kPbarBnut, kPbarEndcap};
      for (int k = 1; k <= nseg; ++k) {
        s.push_back(s_tube0 + (s_tube1 - s_tube0) * k / nseg);
        pid.push_back(kPbarTube);
      }
      s.push_back(L - h.ball_radius - b.length);
      pid.push_back(kPbarEndcap);
      s.push_back(L - h.ball_radius);
      pid.push_back(m.long_bnut ? kPbarLongBnut : kPbarBnut);
      std::vector<int> g;
      for (std::size_t k = 0; k < s.size(); ++k) {
        const int id = kStrutGridBase + 100 * m.id + static_cast<int>(k) + 1;
        const bool surf = k == 0 || k + 1 == s.size();
        fe.grids.push_back({id, round_x(xa + s[k] * n), "", surf ? "ball_surface" : "strut"});
        g.push_back(id);
      }
      surface[m.a].push_back(g.front());
      surface[m.b].push_back(g.back());
      const Eigen::Vector3d v = orientation(n);
      for (std::size_t k = 0; k + 1 < g.size(); ++k)
        fe.bars.push_back({kBarBase + 100 * m.id + static_cast<int>(k) + 1, pid[k], g[k], g[k + 1], v, m.id});
      if (m.mid_mass > 0) {
        const int mid = g[2 + static_cast<std::size_t>(nseg) / 2];  // tube station at half length
        fe.masses.push_back({kMidMassBase + m.id, mid, m.mid_mass, 0.0, "mid_span"});
      }
    }
    for (const auto& b : t.balls) {
      // Solid sphere inertia 2/5 m r^2: the ball's rotary inertia matters for joint rotation.
      fe.masses.push_back({kJointMassBase + b.id, b.id, h.ball_mass, sig(0.4 * h.ball_mass * h.ball_radius * h.ball_radius), "ball"});
      if (b.added_mass > 0) fe.masses.push_back({kAddedMassBase + b.id, b.id, b.added_mass, 0.0, "added"});
      if (!surface[b.id].empty()) fe.rigids.push_back({kRigidBase + b.id, b.id, surface[b.id]});
    }
    add_suspension(t, fe, false);

    add_desvar(fe, 1, "STRUTA", h.tube_area, "strut tube area A_strut, m^2");
    add_dvprel(fe, "PBAR", kPbarTube, "A", 1, 1.0);
    add_desvar(fe, 2, "BNUTA", bn.area, "B-nut area A_bnut, m^2");
    add_dvprel(fe, "PBAR", kPbarBnut, "A", 2, 1.0);
    add_desvar(fe, 3, "BNUTI", bn.inertia, "B-nut bending inertia I_bnut, m^4 (I1 = I2, J = 2I)");
    for (auto [f, c] : {std::pair<const char*, double>{"I1", 1.0}, {"I2", 1.0}, {"J", 2.0}}) add_dvprel(fe, "PBAR", kPbarBnut, f, 3, c);
    add_desvar(fe, 4, "ECAPI", ec.inertia, "end-cap bending inertia I_endcap, m^4");
    for (auto [f, c] : {std::pair<const char*, double>{"I1", 1.0}, {"I2", 1.0}, {"J", 2.0}}) add_dvprel(fe, "PBAR", kPbarEndcap, f, 4, c);
    add_desvar(fe, 5, "LBNUTI", lb.inertia, "long B-nut bending inertia I_longbnut, m^4");
    for (auto [f, c] : {std::pair<const char*, double>{"I1", 1.0}, {"I2", 1.0}, {"J", 2.0}}) add_dvprel(fe, "PBAR", kPbarLongBnut, f, 5, c);
    add_desvar(fe, 7, "BALLM", h.ball_mass, "node ball mass, kg (CONM2 M)");
    for (const auto& c : fe.masses)
      if (c.kind == "ball") add_dvprel(fe, "CONM2", c.id, "M", 7, 1.0);
    add_desvar(fe, 8, "STRUTI", h.tube_inertia, "strut tube bending inertia, m^4");
    for (auto [f, c] : {std::pair<const char*, double>{"I1", 1.0}, {"I2", 1.0}, {"J", 2.0}}) add_dvprel(fe, "PBAR", kPbarTube, f, 8, c);
    add_desvar(fe, 9, "ECAPA", ec.area, "end-cap area, m^2");
    add_dvprel(fe, "PBAR", kPbarEndcap, "A", 9, 1.0);
    add_desvar(fe, 10, "LBNUTA", lb.area, "long B-nut area, m^2");
    add_dvprel(fe, "PBAR", kPbarLongBnut, "A", 10, 1.0);
  }
  if (!t.suspension.empty()) {
    add_desvar(fe, 6, "KSUSP", t.suspension.front().k_vertical, "suspension spring stiffness, N/m (PELAS K)");
    add_dvprel(fe, "PELAS", kPelasVertical, "K1", 6, 1.0);
    for (const auto& p : fe.spring_props)
      if (p.kind == "suspension_chain") add_dvprel(fe, "PELAS", p.id, "K1", 6, p.k / t.suspension.front().k_vertical);
  }
  return fe;
}

}  // namespace ssid::translators::truss
