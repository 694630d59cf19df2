/// \file projection.cpp
#include "cli/report/projection.hpp"

#include <fmt/format.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "formats/parse_error.hpp"

namespace ssid::cli::report {

Points read_points(const nlohmann::json& rows) {
  Points p;
  for (const auto& r : rows) p[r[0].get<std::int64_t>()] = {r[1].get<double>(), r[2].get<double>(), r[3].get<double>()};
  return p;
}

Lines read_lines(const nlohmann::json& rows) {
  Lines l;
  for (const auto& r : rows) l.push_back({r[0].get<std::int64_t>(), r[1].get<std::int64_t>()});
  return l;
}

std::vector<View> views() {
  std::vector<View> v = {{"iso", "isometric", {1, -1, 1}},
                         {"front", "front (from −Y)", {0, -1, 0}},
                         {"side", "side (from +X)", {1, 0, 0}},
                         {"top", "top (from +Z)", {0, 0, 1}}};
  for (auto& w : v) {
    w.toward.normalize();
    const Eigen::Vector3d z = Eigen::Vector3d::UnitZ();
    w.right = z.cross(w.toward).norm() > 1e-9 ? z.cross(w.toward).normalized() : Eigen::Vector3d::UnitX();
    w.up = w.toward.cross(w.right);
  }
  return v;
}

View view_named(const std::string& word, const std::string& option) {
  const std::string name = word == "x" ? "side" : word == "y" ? "front" : word == "z" ? "top" : word;
  for (const auto& v : views())
    if (name == v.name) return v;
  throw formats::InputError(option + ": expected iso, x, y or z, got \"" + word + "\"");
}

Placement place(const View& v, const Points& grids, double w, double h) {
  double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
  for (const auto& [id, p] : grids) {
    x0 = std::min(x0, p.dot(v.right)), x1 = std::max(x1, p.dot(v.right));
    y0 = std::min(y0, p.dot(v.up)), y1 = std::max(y1, p.dot(v.up));
  }
  Placement pl{v.right, v.up};
  const double m = 0.14, dx = std::max(x1 - x0, 1e-12), dy = std::max(y1 - y0, 1e-12);
  pl.scale = std::min(w * (1 - 2 * m) / dx, (h - 24) * (1 - 2 * m) / dy);
  pl.ox = w / 2 - pl.scale * (x0 + x1) / 2;
  pl.oy = 24 + (h - 24) / 2 + pl.scale * (y0 + y1) / 2;
  return pl;
}

std::string lines_d(const Lines& lines, const Points& grids, const Points* shape, double amp, const Placement& pl) {
  std::string d;
  auto at = [&](std::int64_t id) {
    Eigen::Vector3d x = grids.at(id);
    if (shape) {
      auto it = shape->find(id);
      if (it != shape->end()) x += amp * it->second;
    }
    return pl(x);
  };
  for (const auto& [a, b] : lines) {
    if (!grids.count(a) || !grids.count(b)) continue;
    const auto p = at(a), q = at(b);
    d += fmt::format("M{:.0f} {:.0f}L{:.0f} {:.0f}", p.x(), p.y(), q.x(), q.y());
  }
  return d;
}

}  // namespace ssid::cli::report
