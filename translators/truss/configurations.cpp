/// \file configurations.cpp
#include "translators/truss/configurations.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "formats/parse_error.hpp"

namespace ssid::translators::truss {

namespace {

constexpr double kG = 9.80665;

double sig(double v, int digits = 4) {
  if (v == 0) return 0;
  const double p = std::pow(10.0, digits - 1 - static_cast<int>(std::floor(std::log10(std::fabs(v)))));
  return std::round(v * p) / p;
}

/// The ball nearest to x (the structure's balls are at least 0.7 m apart).
int ball_at(const TrussModel& t, const Eigen::Vector3d& x) {
  int best = 0;
  double d = 1e300;
  for (const auto& b : t.balls)
    if ((b.x - x).norm() < d) {
      d = (b.x - x).norm();
      best = b.id;
    }
  if (d > 1e-3) throw std::logic_error("no ball at the requested corner");
  return best;
}

/// Adds the second diagonal (an X) to the lowest tower bay face whose existing
/// diagonal satisfies `in_face`.
template <class Pred>
void add_tower_cross(TrussModel& t, Pred in_face) {
  const Member* diag = nullptr;
  double zmin = 1e300;
  for (const auto& m : t.members) {
    if (m.role != "tower_diagonal" || !in_face(t.ball(m.a).x, t.ball(m.b).x)) continue;
    const double z = std::min(t.ball(m.a).x.z(), t.ball(m.b).x.z());
    if (z < zmin) {
      zmin = z;
      diag = &m;
    }
  }
  if (!diag) throw std::logic_error("tower face not found");
  const Eigen::Vector3d xa = t.ball(diag->a).x, xb = t.ball(diag->b).x;
  const int p = ball_at(t, {xa.x(), xa.y(), xb.z()}), q = ball_at(t, {xb.x(), xb.y(), xa.z()});
  Member m;
  m.id = static_cast<int>(t.members.size()) + 1;
  m.a = std::min(p, q);
  m.b = std::max(p, q);
  m.group = "tower";
  m.role = "extra_diagonal";
  t.members.push_back(m);
}

TrussModel component_chain(const std::string& name, const std::vector<double>& spans, double end_mass, bool long_bnut) {
  TrussModel t;
  t.name = name;
  t.hw = mpi_hardware();
  double x = 0;
  for (std::size_t i = 0; i <= spans.size(); ++i) {
    Ball b;
    b.id = static_cast<int>(i) + 1;
    b.x = Eigen::Vector3d(x, 0, 0);
    b.group = "component";
    b.label = "C" + std::to_string(i);
    if (end_mass > 0 && (i == 0 || i == spans.size())) b.added_mass = end_mass;
    t.balls.push_back(b);
    if (i < spans.size()) x += spans[i];
  }
  for (std::size_t i = 0; i < spans.size(); ++i) {
    Member m;
    m.id = static_cast<int>(i) + 1;
    m.a = static_cast<int>(i) + 1;
    m.b = static_cast<int>(i) + 2;
    m.group = "component";
    m.role = "strut";
    m.long_bnut = long_bnut;
    t.members.push_back(m);
  }
  return t;
}

}  // namespace

const std::vector<ConfigInfo>& list_configs() {
  static const std::vector<ConfigInfo> list = {
      {"bare", "the primary test configuration: bare truss on three massless suspension springs", false},
      {"metrology_tip_mass", "24 kg at the metrology boom tip: 6 kg on each of its four end balls", false},
      {"optics_tip_mass", "16 kg at the optics boom tip: 4 kg on each of its four end balls", false},
      {"tower_diagonal_1", "one extra diagonal strut in the tower (an X in the lowest bay's y = 0 face)", false},
      {"tower_diagonal_2", "two extra tower diagonals (an X in the lowest bay's y = 0 face and in its face towards x = 0)", false},
      {"strut_mass", "240 g at the mid-span of the longest strut", false},
      {"long_bnut", "three long (3.1 in) B-nut struts: the three longest struts, long B-nuts at both ends", false},
      {"massless_springs", "suspension by three massless springs (the report's suspension model; default)", false},
      {"surge_springs", "suspension springs with distributed mass: surge modes near 48, 48 and 57 Hz", false},
      {"free", "no suspension: free-free (six rigid-body modes at 0 Hz)", false},
      {"component1", "ball-strut-ball-strut-ball, two 1.35 m struts (Table 1 config 1: 12.26 Hz bending, 826.3 Hz axial)", true},
      {"component2", "ball-strut-ball-strut-ball, two 1.2 m struts (config 2: 15.91 / 942.2 Hz)", true},
      {"component3", "ball-strut-ball-strut-ball, 1.35 m and 1.0 m struts (config 3: 13.95 / 1013.2 Hz)", true},
      {"component4", "short 0.5 m long-B-nut strut between two 10 kg masses (config 4; Table 3: 6.21, 9.04, 115.2 Hz)", true},
      {"component5", "ball-strut-ball-strut-ball-strut-ball, three 1.0 m struts (config 5: 12.09 / 825.5 Hz)", true},
      {"component6", "ball-strut-ball, one 1.0 m strut (config 6: 133.56 / 1202.3 Hz)", true},
      {"component7", "ball-strut-ball, one 0.8 m strut (config 7: 165.5 / 1518.5 Hz)", true},
  };
  return list;
}

double surge_spring_mass(double k, double f_hz, int segments) {
  const double N = segments;
  const double r = N * std::sin(M_PI / (2.0 * N)) / (M_PI * f_hz);
  return k * r * r;
}

void set_suspension(TrussModel& t, bool surge, const SuspensionDesign& d) {
  if (t.suspension.size() != 3) throw std::invalid_argument("the MPI hangs from exactly three suspension points");
  // Static load shares: sum F = W, sum F x = W x_cg, sum F y = W y_cg.
  Eigen::Matrix3d A;
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector3d x = t.ball(t.suspension[static_cast<std::size_t>(i)].ball).x;
    A(0, i) = 1.0;
    A(1, i) = x.x();
    A(2, i) = x.y();
  }
  const double W = t.total_mass() * kG;
  const Eigen::Vector3d cg = t.center_of_gravity();
  const Eigen::Vector3d F = A.fullPivLu().solve(Eigen::Vector3d(W, W * cg.x(), W * cg.y()));
  for (int i = 0; i < 3; ++i) {
    if (F(i) <= 0) throw std::invalid_argument("centre of gravity outside the suspension triangle");
    Suspension& s = t.suspension[static_cast<std::size_t>(i)];
    s.k_vertical = d.k_vertical;
    s.k_lateral = sig(F(i) / d.cable_length);  // pendulum: restoring force m g x / L
    s.spring_mass = surge ? sig(surge_spring_mass(d.k_vertical, d.surge_hz[i], d.segments)) : 0.0;
    s.segments = surge ? d.segments : 0;
  }
}

void apply_config(TrussModel& t, const std::string& name) {
  const auto& all = list_configs();
  auto it = std::find_if(all.begin(), all.end(), [&](const ConfigInfo& c) { return c.name == name; });
  if (it == all.end()) throw formats::InputError("unknown configuration '" + name + "' (ssid truss list-configs)");
  if (it->component) throw formats::InputError("'" + name + "' is a component assembly and cannot be combined");
  if (name == "bare") {
  } else if (name == "metrology_tip_mass") {
    for (int id : metrology_tip_balls(t)) t.balls[static_cast<std::size_t>(id - 1)].added_mass += 6.0;
  } else if (name == "optics_tip_mass") {
    for (int id : optics_tip_balls(t)) t.balls[static_cast<std::size_t>(id - 1)].added_mass += 4.0;
  } else if (name == "tower_diagonal_1" || name == "tower_diagonal_2") {
    const double y0 = 0.0;  // the tower's faces lie at y = 0, y = 0.9 m, x = 3 m and x = 4 m
    add_tower_cross(t, [&](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
      return std::fabs(a.y() - y0) < 1e-6 && std::fabs(b.y() - y0) < 1e-6;
    });
    if (name == "tower_diagonal_2") {
      double x0 = 1e300;  // the tower's face towards the optics boom's x = 0 end
      for (const auto& b : t.balls)
        if (b.group == "tower") x0 = std::min(x0, b.x.x());
      add_tower_cross(t, [x0](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
        return std::fabs(a.x() - x0) < 1e-6 && std::fabs(b.x() - x0) < 1e-6;
      });
    }
  } else if (name == "strut_mass") {
    t.members[static_cast<std::size_t>(longest_member(t) - 1)].mid_mass += 0.240;
  } else if (name == "long_bnut") {
    std::vector<int> ids;
    for (const auto& m : t.members) ids.push_back(m.id);
    std::stable_sort(ids.begin(), ids.end(), [&](int a, int b) {
      return t.length(t.members[static_cast<std::size_t>(a - 1)]) > t.length(t.members[static_cast<std::size_t>(b - 1)]) + 1e-9;
    });
    for (int k = 0; k < 3; ++k) t.members[static_cast<std::size_t>(ids[static_cast<std::size_t>(k)] - 1)].long_bnut = true;
  } else if (name == "massless_springs") {
    set_suspension(t, false);
  } else if (name == "surge_springs") {
    set_suspension(t, true);
  } else if (name == "free") {
    t.suspension.clear();
  }
  t.configs.push_back(name);
}

TrussModel build_component(int n) {
  switch (n) {
    case 1: return component_chain("component1", {1.35, 1.35}, 0.0, false);
    case 2: return component_chain("component2", {1.2, 1.2}, 0.0, false);
    case 3: return component_chain("component3", {1.35, 1.0}, 0.0, false);
    case 4: return component_chain("component4", {0.5}, 10.0, true);
    case 5: return component_chain("component5", {1.0, 1.0, 1.0}, 0.0, false);
    case 6: return component_chain("component6", {1.0}, 0.0, false);
    case 7: return component_chain("component7", {0.8}, 0.0, false);
    default: throw formats::InputError("component configurations are numbered 1 to 7");
  }
}

TrussModel build_configured(const std::vector<std::string>& names) {
  for (const auto& n : names)
    if (n.rfind("component", 0) == 0) {
      if (names.size() != 1) throw formats::InputError("a component configuration cannot be combined with others");
      const std::string num = n.substr(9);
      if (num.size() != 1 || num[0] < '1' || num[0] > '7') throw formats::InputError("unknown configuration '" + n + "'");
      TrussModel t = build_component(num[0] - '0');
      t.configs.push_back(n);
      return t;
    }
  TrussModel t = build_mpi();
  for (const auto& n : names) apply_config(t, n);
  // Masses change the load shares: re-derive the suspension unless the model is free.
  if (!t.suspension.empty()) {
    const bool surge = t.suspension.front().spring_mass > 0;
    set_suspension(t, surge);
  }
  return t;
}

}  // namespace ssid::translators::truss
