#pragma once
/// \file svg.hpp
/// The report's one plotting module (issue 24): charts with axes, ticks and
/// labels with units, a heat map with its colour scale and legend, and text
/// helpers. It draws; it computes no result. Every mark that stands for a
/// number carries that number in a `data-v` (or `data-x`/`data-y`) attribute,
/// written with `exact` so that it reads back bit for bit: the report's tests
/// compare those with the JSON of the same run (tests/cli/test_cli_report.cpp).
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace ssid::cli::report {

/// XML/HTML text escaped (&, <, >, ", ').
std::string esc(const std::string& s);
/// Shortest text that reads back as the same double ("%.17g"): data attributes.
std::string exact(double v);
/// A screen coordinate (pixels, one decimal).
std::string px(double v);
/// Colour of t in [0, 1] on a perceptually ordered scale (dark blue → yellow,
/// viridis-like); t outside is clamped.
std::string colour(double t);

/// Tick values covering [lo, hi] at a 1-2-5 step, about `target` of them.
std::vector<double> nice_ticks(double lo, double hi, int target = 6);

/// One axis: its data range and its label with unit ("frequency [Hz]").
struct Axis {
  double lo = 0, hi = 1;
  std::string label;
  bool log = false;  ///< logarithmic (lo > 0): ticks at 1, 2, 5 per decade
};

/// An axis range around values: [min, max] widened to the nice ticks, with
/// `pad` (fraction of the span) on both sides; a single value gets ±0.5 or ±10 %.
Axis axis_around(const std::vector<double>& values, const std::string& label, double pad = 0.05,
                 bool include_zero = false);
/// A logarithmic axis around the positive values (a factor 1.2 beyond them).
Axis log_axis_around(const std::vector<double>& values, const std::string& label);
/// The ticks of an axis: nice_ticks, or 1-2-5 per decade for a logarithmic one.
std::vector<double> axis_ticks(const Axis& a);

/// A 2-D chart: a plot area with its axes, ticks and labels; marks are added
/// in data coordinates through `x()` and `y()`.
class Chart {
 public:
  /// `width` × `height` pixels in all, axes and labels included.
  Chart(double width, double height, Axis x, Axis y);
  double x(double v) const;  ///< data → pixel
  double y(double v) const;
  double left() const { return m_left; }
  double right() const { return m_width - m_right_margin; }
  double top() const { return m_top; }
  double bottom() const { return m_height - m_bottom; }
  /// Adds SVG markup drawn inside the plot area (clipped to it).
  void add(const std::string& markup) { m_body += markup; }
  /// Category labels on the x axis instead of numeric ticks: (value, text).
  void set_x_categories(std::vector<std::pair<double, std::string>> c) { m_x_categories = std::move(c); }
  /// The whole chart as an <svg> element with `id`; `label` is its accessible name.
  std::string svg(const std::string& id, const std::string& label) const;

 private:
  double m_width, m_height;
  Axis m_x, m_y;
  double m_left = 64, m_right_margin = 16, m_top = 14, m_bottom = 46;
  std::vector<std::pair<double, std::string>> m_x_categories;
  std::string m_body;
};

/// A matrix as a heat map: one cell per value (class "cell", data-i, data-k,
/// data-v), the value printed in the cell when there is room, the cells of
/// `marked` outlined, row and column labels, axis titles and a colour bar from
/// `lo` to `hi` with its label.
struct HeatMap {
  std::vector<std::vector<double>> values;     ///< rows × columns
  std::vector<std::string> row_labels, col_labels;
  std::string row_title, col_title, value_label;
  std::set<std::pair<std::size_t, std::size_t>> marked;  ///< (row, column)
  double lo = 0, hi = 1;
  int digits = 2;  ///< decimals of the printed values
};
std::string heat_map_svg(const HeatMap& h, const std::string& id, const std::string& label);

}  // namespace ssid::cli::report
