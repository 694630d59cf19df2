#pragma once
/// \file projection.hpp
/// The structure drawn from the deck's geometry (docs/report.md): grids and
/// element lines as the JSON's "geometry" holds them (report_data.hpp
/// geometry_json), a view direction, and the parallel projection of 3-D points
/// onto a panel. Used by the report's mode shapes and cause picture and by
/// `ssid pretest --svg` (pretest_picture.hpp). It draws; it computes no result.
#include <Eigen/Core>
#include <cstdint>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

namespace ssid::cli::report {

/// Grid id → position (basic system).
using Points = std::map<std::int64_t, Eigen::Vector3d>;
/// Element lines as (grid, grid).
using Lines = std::vector<std::pair<std::int64_t, std::int64_t>>;

/// Points of JSON rows [[id, x, y, z], ...].
Points read_points(const nlohmann::json& rows);
/// Lines of JSON rows [[g1, g2], ...].
Lines read_lines(const nlohmann::json& rows);

/// A view direction: the screen's right and up axes in basic.
struct View {
  const char* name;   ///< "iso", "front", "side", "top"
  const char* label;  ///< for a menu: "isometric", "front (from −Y)", ...
  Eigen::Vector3d toward;  ///< unit vector from the structure towards the viewer
  Eigen::Vector3d right = Eigen::Vector3d::Zero(), up = Eigen::Vector3d::Zero();
};

/// The four views, isometric first: iso (from +X −Y +Z), front (from −Y),
/// side (from +X), top (from +Z); Z is up on the screen where it can be.
std::vector<View> views();

/// The view of a `--view` word: iso, x (= side, from +X), y (= front, from −Y),
/// z (= top, from +Z), or one of the names of views(). Throws
/// formats::InputError naming `option` for any other word.
View view_named(const std::string& word, const std::string& option);

/// Screen placement of one view in a panel: pixel = (ox + s x·right, oy − s x·up).
struct Placement {
  Eigen::Vector3d right, up;
  double scale = 1, ox = 0, oy = 0;
  Eigen::Vector2d operator()(const Eigen::Vector3d& x) const { return {ox + scale * x.dot(right), oy - scale * x.dot(up)}; }
  /// A direction (no offset) on the screen, pixels per unit length.
  Eigen::Vector2d direction(const Eigen::Vector3d& d) const { return {scale * d.dot(right), -scale * d.dot(up)}; }
};

/// The placement fitting `grids` into `w` × `h` pixels (14 % margins, 24 px
/// kept free at the top for a title).
Placement place(const View& v, const Points& grids, double w, double h);

/// SVG path data of `lines` with the grids moved by `amp` × shape (grids absent
/// from `shape` stay; `shape` null: undeformed).
std::string lines_d(const Lines& lines, const Points& grids, const Points* shape, double amp, const Placement& pl);

}  // namespace ssid::cli::report
