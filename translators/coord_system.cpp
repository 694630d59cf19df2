#include "translators/coord_system.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <set>
#include <stdexcept>

namespace ssid::translators {

namespace {
constexpr double kDeg = M_PI / 180.0;

std::string name_of(const CoordDefinition& d) {
  if (!d.source.empty()) return d.source;
  static const char* names[] = {"CORD2R", "CORD2C", "CORD2S"};
  return std::string(names[static_cast<int>(d.type)]) + " " + std::to_string(d.cid);
}

/// Local rectangular coordinates of system `s` from its own coordinates.
Eigen::Vector3d local_rect(CoordType type, const Eigen::Vector3d& c) {
  switch (type) {
    case CoordType::Rectangular: return c;
    case CoordType::Cylindrical:
      return {c(0) * std::cos(c(1) * kDeg), c(0) * std::sin(c(1) * kDeg), c(2)};
    case CoordType::Spherical: {
      const double st = std::sin(c(1) * kDeg), ct = std::cos(c(1) * kDeg);
      return {c(0) * st * std::cos(c(2) * kDeg), c(0) * st * std::sin(c(2) * kDeg), c(0) * ct};
    }
  }
  return c;
}
}  // namespace

Eigen::Vector3d CoordSystem::to_basic(const Eigen::Vector3d& coords) const {
  return origin + axes * local_rect(type, coords);
}

Eigen::Vector3d CoordSystem::from_basic(const Eigen::Vector3d& x_basic) const {
  const Eigen::Vector3d p = axes.transpose() * (x_basic - origin);
  switch (type) {
    case CoordType::Rectangular: return p;
    case CoordType::Cylindrical:
      return {std::hypot(p(0), p(1)), std::atan2(p(1), p(0)) / kDeg, p(2)};
    case CoordType::Spherical: {
      const double r = p.norm();
      const double rho = std::hypot(p(0), p(1));
      return {r, std::atan2(rho, p(2)) / kDeg, std::atan2(p(1), p(0)) / kDeg};
    }
  }
  return p;
}

Eigen::Matrix3d CoordSystem::displacement_frame(const Eigen::Vector3d& x_basic) const {
  if (type == CoordType::Rectangular) return axes;
  const Eigen::Vector3d p = axes.transpose() * (x_basic - origin);
  // Azimuth measured in the local X-Y plane; on the axis atan2(0,0) = 0 gives
  // the θ = 0 (φ = 0) limit documented in the header.
  const double az = std::atan2(p(1), p(0));
  const double ca = std::cos(az), sa = std::sin(az);
  Eigen::Matrix3d local;
  if (type == CoordType::Cylindrical) {
    local.col(0) << ca, sa, 0;   // u_r
    local.col(1) << -sa, ca, 0;  // u_θ
    local.col(2) << 0, 0, 1;     // u_z
  } else {
    const double polar = std::atan2(std::hypot(p(0), p(1)), p(2));
    const double st = std::sin(polar), ct = std::cos(polar);
    local.col(0) << st * ca, st * sa, ct;    // u_r
    local.col(1) << ct * ca, ct * sa, -st;   // u_θ (increasing polar angle)
    local.col(2) << -sa, ca, 0;              // u_φ
  }
  return axes * local;
}

CoordSystem make_coord_system(const CoordDefinition& def, const CoordSystem& reference) {
  const Eigen::Vector3d a = reference.to_basic(def.a);
  const Eigen::Vector3d b = reference.to_basic(def.b);
  const Eigen::Vector3d c = reference.to_basic(def.c);
  const double scale = std::max({(b - a).norm(), (c - a).norm(), 1e-300});
  const Eigen::Vector3d ab = b - a, ac = c - a;
  if (ab.norm() <= 1e-12 * scale || ac.norm() <= 1e-12 * scale)
    throw std::invalid_argument(name_of(def) + ": points A, B and C must be distinct");
  const Eigen::Vector3d ez = ab.normalized();
  const Eigen::Vector3d xdir = ac - ez * ez.dot(ac);
  if (xdir.norm() <= 1e-10 * ac.norm())
    throw std::invalid_argument(name_of(def) + ": points A, B and C are collinear");
  CoordSystem s;
  s.cid = def.cid;
  s.type = def.type;
  s.origin = a;
  s.axes.col(0) = xdir.normalized();
  s.axes.col(2) = ez;
  s.axes.col(1) = ez.cross(s.axes.col(0));
  return s;
}

CoordSystems::CoordSystems() { m_systems[0] = CoordSystem{}; }

CoordSystems::CoordSystems(const std::vector<CoordDefinition>& defs) : CoordSystems() {
  std::map<long, const CoordDefinition*> pending;
  for (const auto& d : defs) {
    if (d.cid <= 0) throw std::invalid_argument(name_of(d) + ": CID must be > 0");
    if (!pending.emplace(d.cid, &d).second)
      throw std::invalid_argument(name_of(d) + ": coordinate system " + std::to_string(d.cid) +
                                  " is defined twice");
  }
  // Resolve by repeated passes: each pass resolves every definition whose
  // reference is known. A pass that makes no progress means an undefined RID
  // or a cycle.
  while (!pending.empty()) {
    bool progress = false;
    for (auto it = pending.begin(); it != pending.end();) {
      const CoordDefinition& d = *it->second;
      auto ref = m_systems.find(d.rid);
      if (ref != m_systems.end()) {
        m_systems[d.cid] = make_coord_system(d, ref->second);
        it = pending.erase(it);
        progress = true;
      } else {
        ++it;
      }
    }
    if (!progress) {
      for (const auto& [cid, d] : pending)
        if (!pending.count(d->rid))
          throw std::invalid_argument(name_of(*d) + ": reference system RID " + std::to_string(d->rid) +
                                      " is not defined");
      std::string names;
      for (const auto& [cid, d] : pending) names += (names.empty() ? "" : ", ") + name_of(*d);
      throw std::invalid_argument("coordinate systems reference each other in a cycle: " + names);
    }
  }
}

const CoordSystem& CoordSystems::get(long cid) const {
  auto it = m_systems.find(cid);
  if (it == m_systems.end())
    throw std::out_of_range("coordinate system " + std::to_string(cid) + " is not defined");
  return it->second;
}

Eigen::Matrix<double, 6, 6> dof_transform(const Eigen::Matrix3d& T) {
  Eigen::Matrix<double, 6, 6> R = Eigen::Matrix<double, 6, 6>::Zero();
  R.topLeftCorner<3, 3>() = T;
  R.bottomRightCorner<3, 3>() = T;
  return R;
}

}  // namespace ssid::translators
