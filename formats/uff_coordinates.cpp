/// \file uff_coordinates.cpp
/// Coordinate systems of universal files (datasets 18 and 2420) and their use on
/// node positions (definition system) and measured directions (displacement system).
#include <cmath>
#include <functional>
#include <set>

#include "formats/uff.hpp"

namespace ssid::formats::uff {

namespace {

using Vec = std::array<double, 3>;

constexpr double kDegree = M_PI / 180.0;

Vec sub(const Vec& a, const Vec& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
double dot(const Vec& a, const Vec& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Vec cross(const Vec& a, const Vec& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
Vec scaled(const Vec& a, double s) { return {a[0] * s, a[1] * s, a[2] * s}; }
double norm(const Vec& a) { return std::sqrt(dot(a, a)); }

/// Local curvilinear coordinates to local Cartesian.
Vec cartesian(int type, const Vec& p) {
  if (type == 1) return {p[0] * std::cos(p[1] * kDegree), p[0] * std::sin(p[1] * kDegree), p[2]};
  if (type == 2)
    return {p[0] * std::sin(p[1] * kDegree) * std::cos(p[2] * kDegree),
            p[0] * std::sin(p[1] * kDegree) * std::sin(p[2] * kDegree), p[0] * std::cos(p[1] * kDegree)};
  return p;
}

/// Local basis vector `k` (0..2) at local point p, in local Cartesian components.
Vec local_basis(int type, int k, const Vec& p) {
  if (type == 1) {
    const double t = p[1] * kDegree;
    if (k == 0) return {std::cos(t), std::sin(t), 0};
    if (k == 1) return {-std::sin(t), std::cos(t), 0};
    return {0, 0, 1};
  }
  if (type == 2) {
    const double t = p[1] * kDegree, f = p[2] * kDegree;
    if (k == 0) return {std::sin(t) * std::cos(f), std::sin(t) * std::sin(f), std::cos(t)};
    if (k == 1) return {std::cos(t) * std::cos(f), std::cos(t) * std::sin(f), -std::sin(t)};
    return {-std::sin(f), std::cos(f), 0};
  }
  Vec e{0, 0, 0};
  e[static_cast<std::size_t>(k)] = 1;
  return e;
}

Vec rotate(const CoordinateSystem& cs, const Vec& v) {
  Vec g{0, 0, 0};
  for (int i = 0; i < 3; ++i)
    for (int c = 0; c < 3; ++c) g[c] += v[i] * cs.axes[i][c];
  return g;
}

}  // namespace

std::array<double, 3> CoordinateSystem::to_global(const std::array<double, 3>& local) const {
  const Vec g = rotate(*this, cartesian(type, local));
  return {origin[0] + g[0], origin[1] + g[1], origin[2] + g[2]};
}

std::array<double, 3> CoordinateSystem::axis_at(int direction, const std::array<double, 3>& local) const {
  return rotate(*this, local_basis(type, direction - 1, local));
}

std::map<std::int64_t, CoordinateSystem> UffFile::coordinate_systems() const {
  std::map<std::int64_t, CoordinateSystem> out;
  std::map<std::int64_t, const Cs18*> by_points;
  for (const auto& d : datasets) {
    if (auto s = std::get_if<CoordinateSystems2420>(&d))
      for (const auto& c : s->systems) {
        CoordinateSystem cs;
        cs.id = c.id;
        cs.type = c.type;
        cs.axes = c.rows;
        cs.origin = c.origin;
        cs.name = c.name;
        out[c.id] = cs;
      }
    if (auto s = std::get_if<CoordinateSystems18>(&d))
      for (const auto& c : s->systems) by_points[c.id] = &c;
  }
  // Dataset 18 systems are given by points in a reference system, which may
  // itself be a dataset 18 system: resolve references first (depth first, cycles refused).
  std::set<std::int64_t> busy;
  std::function<void(std::int64_t)> resolve = [&](std::int64_t id) {
    if (out.count(id)) return;
    const Cs18& c = *by_points.at(id);
    if (!busy.insert(id).second)
      throw InputError("coordinate system " + std::to_string(id) + " (dataset 18) refers to itself through its reference systems");
    CoordinateSystem ref;  // 0: global
    if (c.reference != 0) {
      if (!by_points.count(c.reference) && !out.count(c.reference))
        throw InputError("coordinate system " + std::to_string(id) + " (dataset 18) refers to coordinate system " +
                         std::to_string(c.reference) + ", which the file does not define");
      if (by_points.count(c.reference)) resolve(c.reference);
      ref = out.at(c.reference);
    }
    if (c.method != 1 && c.method != 0)
      throw InputError("coordinate system " + std::to_string(id) + " (dataset 18): method of definition " +
                       std::to_string(c.method) + " is not read (1: origin, point on +X, point in the +XZ plane)");
    const Vec o = ref.to_global(c.origin), px = ref.to_global(c.x_point), pxz = ref.to_global(c.xz_point);
    const Vec ex = sub(px, o);
    const Vec ey0 = cross(sub(pxz, o), ex);  // z × x direction = y, from the xz-plane point
    const Vec ez0 = cross(ex, ey0);
    const double lx = norm(ex), ly = norm(ey0), lz = norm(ez0);
    if (lx == 0 || ly <= 1e-12 * lx * norm(sub(pxz, o)) || lz == 0)
      throw InputError("coordinate system " + std::to_string(id) +
                       " (dataset 18): its origin, point on +X and point in the +XZ plane span no plane");
    CoordinateSystem cs;
    cs.id = id;
    cs.type = c.type;
    cs.name = c.name;
    cs.origin = o;
    cs.axes = {scaled(ex, 1 / lx), scaled(ey0, 1 / ly), scaled(ez0, 1 / lz)};
    out[id] = cs;
    busy.erase(id);
  };
  for (const auto& [id, c] : by_points) resolve(id);
  return out;
}

namespace {

const CoordinateSystem* find_system(const std::map<std::int64_t, CoordinateSystem>& systems, const Node& n, int cs,
                                    const char* which) {
  if (cs == 0) return nullptr;
  auto it = systems.find(cs);
  if (it == systems.end())
    throw InputError("node " + std::to_string(n.id) + ": " + which + " coordinate system " + std::to_string(cs) +
                     " is not defined in the file (datasets 18, 2420)");
  return &it->second;
}

}  // namespace

std::vector<Node> UffFile::nodes_in_global() const {
  const auto systems = coordinate_systems();
  std::vector<Node> r = nodes();
  for (auto& n : r)
    if (const auto* cs = find_system(systems, n, n.definition_cs, "definition")) {
      n.xyz = cs->to_global(n.xyz);
      n.definition_cs = 0;
    }
  return r;
}

std::array<double, 3> UffFile::direction_in_global(const Node& node, int direction) const {
  if (direction == 0) return {0, 0, 0};
  const int axis = (std::abs(direction) - 1) % 3 + 1;
  const double sign = direction < 0 ? -1.0 : 1.0;
  const auto systems = coordinate_systems();
  const auto* cs = find_system(systems, node, node.displacement_cs, "displacement");
  if (!cs) {
    Vec e{0, 0, 0};
    e[static_cast<std::size_t>(axis - 1)] = sign;
    return e;
  }
  // A curvilinear system's basis depends on where the node is: its position in that system.
  Vec local{0, 0, 0};
  if (cs->type != 0) {
    Vec g = node.xyz;
    if (const auto* def = find_system(systems, node, node.definition_cs, "definition")) g = def->to_global(node.xyz);
    const Vec d = sub(g, cs->origin);
    const Vec p{dot(d, cs->axes[0]), dot(d, cs->axes[1]), dot(d, cs->axes[2])};
    const double rxy = std::hypot(p[0], p[1]);
    if (cs->type == 1) local = {rxy, std::atan2(p[1], p[0]) / kDegree, p[2]};
    else local = {norm(p), std::atan2(rxy, p[2]) / kDegree, std::atan2(p[1], p[0]) / kDegree};
  }
  return scaled(cs->axis_at(axis, local), sign);
}

}  // namespace ssid::formats::uff
