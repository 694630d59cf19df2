#pragma once
/// \file pretest_picture.hpp
/// The pretest picture (issue 23 item 7, docs/pretest.md "The picture"): the
/// structure from the deck's geometry (elements as grey lines, the sensors'
/// wire frame dashed), each sensor as an arrow along its measured direction,
/// each triax as a square with its three short arrows, each exciter as a red
/// arrow along its force direction (given exciters in orange), and a legend.
/// Drawn from a pretest JSON ("geometry", "sensors" with "direction_basic",
/// "triax", "exciters" and "given_exciters" with "direction_basic") and nothing
/// else, by `ssid pretest --svg` and by the pretest report.
///
/// Marks (inside `<g class="marks">` of each view): `<g class="sensor"
/// data-grid data-component>` per sensor DOF (without --triax), `<g
/// class="triax" data-grid>` per triax, `<g class="exciter" data-grid
/// data-direction>` per exciter and `<g class="exciter-given" ...>` per given one.
/// A direction within 15° of the view axis is drawn end-on (a ringed dot).
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli/report/projection.hpp"

namespace ssid::cli::report {

/// The picture as one <svg> element with `id`: a `<g class="view"
/// data-view="NAME">` per view of `vs` (all but the first hidden; the report's
/// menu switches them) and the legend. Throws formats::InputError when `j`
/// has no geometry with grids.
std::string pretest_picture_svg(const nlohmann::json& j, const std::vector<View>& vs, const std::string& id);

/// A standalone SVG file's text (XML declaration, one view).
std::string pretest_picture_file(const nlohmann::json& j, const View& v);

}  // namespace ssid::cli::report
