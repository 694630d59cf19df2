/// \file pretest_picture.cpp
#include "cli/report/pretest_picture.hpp"

#include <fmt/format.h>

#include <cmath>
#include <map>

#include "cli/report/report_data.hpp"
#include "cli/report/svg.hpp"
#include "formats/parse_error.hpp"

namespace ssid::cli::report {

namespace {

using json = nlohmann::json;

const char* kSensorColour = "#1f5fa8";
const char* kExciterColour = "#d62728";
const char* kGivenColour = "#f28e2b";

Eigen::Vector3d vec3(const json& a) { return {a[0].get<double>(), a[1].get<double>(), a[2].get<double>()}; }

/// An arrow from `p` (pixels) along the 3-D unit direction `d` projected by
/// `pl`, `length` pixels for a direction in the screen's plane (shorter as it
/// turns towards the viewer); end-on (within 15° of the view axis) a ringed dot.
std::string arrow(const Eigen::Vector2d& p, const Eigen::Vector3d& d, const Placement& pl, double length, double width,
                  const char* colour) {
  const Eigen::Vector2d s = pl.direction(d) / pl.scale;  // |s| = sine of the angle to the view axis
  if (s.norm() < std::sin(15.0 * M_PI / 180)) {
    return fmt::format("<circle cx=\"{0}\" cy=\"{1}\" r=\"4.5\" fill=\"none\" stroke=\"{2}\" stroke-width=\"{3}\"/><circle "
                       "cx=\"{0}\" cy=\"{1}\" r=\"1.6\" fill=\"{2}\"/>",
                       px(p.x()), px(p.y()), colour, px(width));
  }
  const Eigen::Vector2d q = p + length * s, u = s.normalized(), n(-u.y(), u.x());
  const double head = 3 + 2 * width;
  const Eigen::Vector2d b = q - head * u, l = b + 0.55 * head * n, r = b - 0.55 * head * n;
  return fmt::format("<line x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\" stroke=\"{}\" stroke-width=\"{}\"/><polygon points=\"{},{} "
                     "{},{} {},{}\" fill=\"{}\"/>",
                     px(p.x()), px(p.y()), px(b.x()), px(b.y()), colour, px(width), px(q.x()), px(q.y()), px(l.x()), px(l.y()),
                     px(r.x()), px(r.y()), colour);
}

std::string direction_text(const Eigen::Vector3d& d) {
  return fmt::format("({:.3f}, {:.3f}, {:.3f})", d.x(), d.y(), d.z());
}

/// The marks of one view.
std::string view_marks(const json& j, const Points& grids, const Lines& lines, const Lines& wire, const Placement& pl) {
  std::string s = fmt::format("<path class=\"structure\" d=\"{}\" fill=\"none\" stroke=\"#9a9a9a\" stroke-width=\"1\"/>\n",
                              lines_d(lines, grids, nullptr, 0, pl));
  if (!wire.empty())
    s += fmt::format("<path class=\"wire\" d=\"{}\" fill=\"none\" stroke=\"{}\" stroke-opacity=\"0.45\" stroke-width=\"1\" "
                     "stroke-dasharray=\"4 3\"/>\n",
                     lines_d(wire, grids, nullptr, 0, pl), kSensorColour);
  const bool triax = j.value("triax", false);
  // Sensors by grid, in the JSON's order of first appearance.
  std::vector<std::int64_t> order;
  std::map<std::int64_t, std::vector<const json*>> at;
  for (const auto& x : j["sensors"]) {
    const auto g = x["grid"].get<std::int64_t>();
    if (!at.count(g)) order.push_back(g);
    at[g].push_back(&x);
  }
  for (auto g : order) {
    if (!grids.count(g)) continue;
    const Eigen::Vector2d p = pl(grids.at(g));
    if (triax) {
      std::string arrows;
      for (const json* x : at[g]) arrows += arrow(p, vec3((*x)["direction_basic"]), pl, 13, 1.1, kSensorColour);
      s += fmt::format("<g class=\"triax\" data-grid=\"{}\">{}<rect x=\"{}\" y=\"{}\" width=\"8\" height=\"8\" fill=\"#fff\" "
                       "stroke=\"{}\" stroke-width=\"1.6\"/><title>triax at grid {}</title></g>\n",
                       g, arrows, px(p.x() - 4), px(p.y() - 4), kSensorColour, g);
      continue;
    }
    for (const json* x : at[g]) {
      const Eigen::Vector3d d = vec3((*x)["direction_basic"]);
      s += fmt::format("<g class=\"sensor\" data-grid=\"{}\" data-component=\"{}\">{}<circle cx=\"{}\" cy=\"{}\" r=\"2.2\" "
                       "fill=\"{}\"/><title>sensor at grid {}, {}, direction {} (basic)</title></g>\n",
                       g, sensor_component(*x), arrow(p, d, pl, 20, 1.6, kSensorColour), px(p.x()), px(p.y()),
                       kSensorColour, g, esc(sensor_label(*x)), direction_text(d));
    }
  }
  auto exciters = [&](const json& list, const char* cls, const char* colour, const char* letter, const std::string& name) {
    int k = 0;
    for (const auto& e : list) {
      ++k;
      const auto g = e["grid"].get<std::int64_t>();
      if (!grids.count(g)) continue;
      const Eigen::Vector2d p = pl(grids.at(g));
      const Eigen::Vector3d d = vec3(e["direction_basic"]), dc = vec3(e["direction"]);
      s += fmt::format("<g class=\"{}\" data-grid=\"{}\" data-direction=\"{},{},{}\">{}<circle cx=\"{}\" cy=\"{}\" r=\"4\" "
                       "fill=\"{}\"/><text x=\"{}\" y=\"{}\" font-size=\"11\" fill=\"{}\">{}{}</text><title>{} {} at grid {}, "
                       "direction cosines {} (grid's frame)</title></g>\n",
                       cls, g, exact(dc.x()), exact(dc.y()), exact(dc.z()), arrow(p, d, pl, 34, 2.6, colour), px(p.x()),
                       px(p.y()), colour, px(p.x() + 6), px(p.y() + 14), colour, letter, k,
                       name, k, g, direction_text(dc));
    }
  };
  exciters(j["exciters"], "exciter", kExciterColour, "E", "exciter");
  if (j.contains("given_exciters")) exciters(j["given_exciters"]["exciters"], "exciter-given", kGivenColour, "X", "given exciter");
  return s;
}

}  // namespace

std::string pretest_picture_svg(const json& j, const std::vector<View>& vs, const std::string& id) {
  if (!j.contains("geometry") || j["geometry"]["grids"].empty())
    throw formats::InputError("the pretest picture needs the deck's geometry (grids with positions)");
  const Points grids = read_points(j["geometry"]["grids"]);
  const Lines lines = read_lines(j["geometry"]["lines"]), wire = read_lines(j["geometry"]["test_lines"]);
  const double w = 720, h = 480, legend = 46;
  const bool triax = j.value("triax", false);
  std::string s = fmt::format(
      "<svg id=\"{0}\" class=\"chart pretest\" xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 {1} {2}\" width=\"{1}\" "
      "height=\"{2}\" role=\"img\" aria-label=\"the structure with the sensors and exciters\" font-family=\"sans-serif\">\n"
      "<rect x=\"0\" y=\"0\" width=\"{1}\" height=\"{2}\" fill=\"#fff\"/>\n",
      esc(id), px(w), px(h + legend));
  const std::size_t n_sensors = j["sensors"].size();
  for (std::size_t v = 0; v < vs.size(); ++v) {
    const Placement pl = place(vs[v], grids, w, h);
    s += fmt::format("<g class=\"view\" data-view=\"{}\"{}>\n<text x=\"10\" y=\"18\" font-size=\"13\">{} {}: {} {} — {} view</text>\n"
                     "<g class=\"marks\">\n{}</g>\n</g>\n",
                     vs[v].name, v ? " style=\"display:none\"" : "", esc(j.value("method", "")),
                     triax ? "triaxes" : "sensors", triax ? n_sensors / 3 : n_sensors,
                     triax ? "(3 DOFs each)" : "DOF(s)", esc(vs[v].label), view_marks(j, grids, lines, wire, pl));
  }
  // The legend: one sample glyph per kind of mark.
  double x = 12, y = h + 12;
  std::string items;
  auto item = [&](const std::string& glyph, const std::string& text) {
    const double needed = 34 + 6.2 * static_cast<double>(text.size());
    if (x + needed > w && x > 12) x = 12, y += 20;  // a second row
    items += fmt::format("<g transform=\"translate({} {})\">{}<text x=\"26\" y=\"4\" font-size=\"11\">{}</text></g>\n", px(x),
                         px(y), glyph, esc(text));
    x += needed;
  };
  item("<line x1=\"0\" y1=\"0\" x2=\"20\" y2=\"0\" stroke=\"#9a9a9a\"/>", "element");
  if (!wire.empty())
    item(fmt::format("<line x1=\"0\" y1=\"0\" x2=\"20\" y2=\"0\" stroke=\"{}\" stroke-opacity=\"0.45\" stroke-dasharray=\"4 3\"/>",
                     kSensorColour),
         "test wire frame");
  if (triax)
    item(fmt::format("<rect x=\"6\" y=\"-4\" width=\"8\" height=\"8\" fill=\"#fff\" stroke=\"{}\" stroke-width=\"1.6\"/>", kSensorColour),
         "triax (three translations)");
  else
    item(fmt::format("<line x1=\"0\" y1=\"0\" x2=\"14\" y2=\"0\" stroke=\"{0}\" stroke-width=\"1.6\"/><polygon points=\"20,0 "
                     "14,-3 14,3\" fill=\"{0}\"/>",
                     kSensorColour),
         "sensor (arrow: measured direction)");
  if (!j["exciters"].empty())
    item(fmt::format("<line x1=\"0\" y1=\"0\" x2=\"13\" y2=\"0\" stroke=\"{0}\" stroke-width=\"2.6\"/><polygon points=\"20,0 "
                     "12,-4 12,4\" fill=\"{0}\"/>",
                     kExciterColour),
         "exciter E (arrow: force direction)");
  if (j.contains("given_exciters"))
    item(fmt::format("<line x1=\"0\" y1=\"0\" x2=\"13\" y2=\"0\" stroke=\"{0}\" stroke-width=\"2.6\"/><polygon points=\"20,0 "
                     "12,-4 12,4\" fill=\"{0}\"/>",
                     kGivenColour),
         "given exciter X");
  item("<circle cx=\"10\" cy=\"0\" r=\"4.5\" fill=\"none\" stroke=\"#444\"/><circle cx=\"10\" cy=\"0\" r=\"1.6\" fill=\"#444\"/>",
       "along the view axis");
  s += "<g class=\"legend\">\n" + items + "</g>\n</svg>\n";
  return s;
}

std::string pretest_picture_file(const json& j, const View& v) {
  return "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n" + pretest_picture_svg(j, {v}, "pretest");
}

}  // namespace ssid::cli::report
