/// \file svg.cpp
#include "cli/report/svg.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "estimator/reporting/number_text.hpp"

namespace ssid::cli::report {

std::string esc(const std::string& s) {
  std::string o;
  o.reserve(s.size());
  for (char c : s) {
    switch (c) {
      case '&': o += "&amp;"; break;
      case '<': o += "&lt;"; break;
      case '>': o += "&gt;"; break;
      case '"': o += "&quot;"; break;
      case '\'': o += "&#39;"; break;
      default: o += c;
    }
  }
  return o;
}

std::string exact(double v) { return fmt::format("{}", v); }  // fmt's shortest round-trip form

std::string px(double v) { return fmt::format("{:.1f}", v); }

std::string colour(double t) {
  // Viridis at eight stops, linearly interpolated: ordered in lightness, readable
  // in grey print, safe for the common colour-vision deficiencies.
  static const std::array<std::array<double, 3>, 8> stops = {{{68, 1, 84},
                                                             {70, 50, 127},
                                                             {54, 92, 141},
                                                             {39, 127, 142},
                                                             {31, 161, 135},
                                                             {74, 194, 109},
                                                             {159, 218, 58},
                                                             {253, 231, 37}}};
  t = std::clamp(std::isfinite(t) ? t : 0.0, 0.0, 1.0) * (stops.size() - 1);
  const std::size_t i = std::min<std::size_t>(static_cast<std::size_t>(t), stops.size() - 2);
  const double f = t - static_cast<double>(i);
  std::array<int, 3> c{};
  for (int k = 0; k < 3; ++k)
    c[k] = static_cast<int>(std::lround(stops[i][k] + f * (stops[i + 1][k] - stops[i][k])));
  return fmt::format("#{:02x}{:02x}{:02x}", c[0], c[1], c[2]);
}

std::vector<double> nice_ticks(double lo, double hi, int target) {
  if (!(hi > lo)) return {lo};
  const double raw = (hi - lo) / std::max(target, 1);
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  double step = mag;
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (raw <= m * mag * 1.0000001) {
      step = m * mag;
      break;
    }
  std::vector<double> t;
  for (double v = std::ceil(lo / step - 1e-9) * step; v <= hi + step * 1e-9; v += step)
    t.push_back(std::abs(v) < step * 1e-9 ? 0.0 : v);
  return t;
}

Axis axis_around(const std::vector<double>& values, const std::string& label, double pad, bool include_zero) {
  double lo = INFINITY, hi = -INFINITY;
  for (double v : values)
    if (std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v);
  if (include_zero) lo = std::min(lo, 0.0), hi = std::max(hi, 0.0);
  if (!std::isfinite(lo)) lo = 0, hi = 1;
  if (hi - lo <= 0) {
    const double d = lo == 0 ? 0.5 : std::abs(lo) * 0.1;
    lo -= d, hi += d;
  }
  const double span = hi - lo;
  return {lo - pad * span, hi + pad * span, label};
}

Axis log_axis_around(const std::vector<double>& values, const std::string& label) {
  double lo = INFINITY, hi = 0;
  for (double v : values)
    if (std::isfinite(v) && v > 0) lo = std::min(lo, v), hi = std::max(hi, v);
  if (!std::isfinite(lo)) lo = 1, hi = 10;
  return {lo / 1.2, hi * 1.2, label, true};
}

std::vector<double> axis_ticks(const Axis& a) {
  if (!a.log) return nice_ticks(a.lo, a.hi);
  std::vector<double> t;
  const int k0 = static_cast<int>(std::floor(std::log10(a.lo))), k1 = static_cast<int>(std::ceil(std::log10(a.hi)));
  const bool sparse = k1 - k0 > 3;  // many decades: their starts only
  for (int k = k0; k <= k1; ++k)
    for (double m : {1.0, 2.0, 5.0}) {
      if (sparse && m != 1.0) continue;
      const double v = m * std::pow(10.0, k);
      if (v >= a.lo && v <= a.hi) t.push_back(v);
    }
  return t;
}

Chart::Chart(double width, double height, Axis x, Axis y) : m_width(width), m_height(height), m_x(std::move(x)), m_y(std::move(y)) {}

namespace {
/// Where v lies along the axis, 0 at lo and 1 at hi.
double fraction(const Axis& a, double v) {
  if (a.log) return (std::log10(std::max(v, 1e-300)) - std::log10(a.lo)) / (std::log10(a.hi) - std::log10(a.lo));
  return (v - a.lo) / (a.hi - a.lo);
}
}  // namespace

double Chart::x(double v) const { return m_left + fraction(m_x, v) * (right() - m_left); }
double Chart::y(double v) const { return bottom() - fraction(m_y, v) * (bottom() - m_top); }

std::string Chart::svg(const std::string& id, const std::string& label) const {
  std::string s = fmt::format(
      "<svg id=\"{}\" class=\"chart\" xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 {} {}\" width=\"{}\" "
      "height=\"{}\" role=\"img\" aria-label=\"{}\">\n",
      esc(id), px(m_width), px(m_height), px(m_width), px(m_height), esc(label));
  s += fmt::format("<defs><clipPath id=\"{}-clip\"><rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\"/></clipPath></defs>\n",
                   esc(id), px(m_left), px(m_top), px(right() - m_left), px(bottom() - m_top));
  // Grid lines and ticks.
  s += "<g class=\"axes\">\n";
  if (m_x_categories.empty()) {
    for (double t : axis_ticks(m_x))
      s += fmt::format("<line class=\"grid\" x1=\"{0}\" x2=\"{0}\" y1=\"{1}\" y2=\"{2}\"/><text class=\"tick\" x=\"{0}\" "
                       "y=\"{3}\" text-anchor=\"middle\">{4}</text>\n",
                       px(x(t)), px(m_top), px(bottom()), px(bottom() + 14), esc(estimator::significant(t, 4)));
  } else {
    for (const auto& [v, text] : m_x_categories)
      s += fmt::format("<text class=\"tick\" x=\"{}\" y=\"{}\" text-anchor=\"middle\">{}</text>\n", px(x(v)),
                       px(bottom() + 14), esc(text));
  }
  for (double t : axis_ticks(m_y))
    s += fmt::format("<line class=\"grid\" x1=\"{0}\" x2=\"{1}\" y1=\"{2}\" y2=\"{2}\"/><text class=\"tick\" x=\"{3}\" "
                     "y=\"{4}\" text-anchor=\"end\">{5}</text>\n",
                     px(m_left), px(right()), px(y(t)), px(m_left - 5), px(y(t) + 4), esc(estimator::significant(t, 4)));
  s += fmt::format("<rect class=\"frame\" x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\"/>\n", px(m_left), px(m_top),
                   px(right() - m_left), px(bottom() - m_top));
  s += fmt::format("<text class=\"label\" x=\"{}\" y=\"{}\" text-anchor=\"middle\">{}</text>\n", px((m_left + right()) / 2),
                   px(m_height - 8), esc(m_x.label));
  s += fmt::format("<text class=\"label\" transform=\"translate(14 {}) rotate(-90)\" text-anchor=\"middle\">{}</text>\n",
                   px((m_top + bottom()) / 2), esc(m_y.label));
  s += "</g>\n";
  s += fmt::format("<g class=\"marks\" clip-path=\"url(#{}-clip)\">\n", esc(id)) + m_body + "</g>\n</svg>\n";
  return s;
}

std::string heat_map_svg(const HeatMap& h, const std::string& id, const std::string& label) {
  const std::size_t rows = h.values.size(), cols = rows ? h.values.front().size() : 0;
  const double cell = std::clamp(560.0 / std::max<std::size_t>({rows, cols, 1}), 12.0, 40.0);
  const double left = 70, top = 16, legend = 90;
  std::size_t widest_col = 0;
  for (const auto& l : h.col_labels) widest_col = std::max(widest_col, l.size());
  const double below = widest_col * 7.5 > cell ? 36 + widest_col * 5.5 : 56;  // room for slanted labels
  const double width = left + cols * cell + legend, height = top + std::max(rows * cell, 120.0) + below;
  std::string s = fmt::format(
      "<svg id=\"{}\" class=\"chart heatmap\" xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 {} {}\" width=\"{}\" "
      "height=\"{}\" role=\"img\" aria-label=\"{}\">\n",
      esc(id), px(width), px(height), px(width), px(height), esc(label));
  const bool print_values = cell >= 22;
  for (std::size_t i = 0; i < rows; ++i)
    for (std::size_t k = 0; k < cols; ++k) {
      const double v = h.values[i][k];
      const double t = (v - h.lo) / (h.hi - h.lo);
      const double cx = left + k * cell, cy = top + i * cell;
      s += fmt::format(
          "<rect class=\"cell\" data-i=\"{}\" data-k=\"{}\" data-v=\"{}\" x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" "
          "fill=\"{}\"><title>{} {}, {} {}: {} {}</title></rect>\n",
          i, k, exact(v), px(cx), px(cy), px(cell), px(cell), colour(t), esc(h.row_title), esc(h.row_labels[i]),
          esc(h.col_title), esc(h.col_labels[k]), esc(h.value_label), estimator::fixed(v, 4));
      if (print_values)
        s += fmt::format("<text class=\"cellv\" x=\"{}\" y=\"{}\" text-anchor=\"middle\" fill=\"{}\">{}</text>\n",
                         px(cx + cell / 2), px(cy + cell / 2 + 4), t > 0.6 ? "#000" : "#fff", estimator::fixed(v, h.digits));
    }
  for (const auto& [i, k] : h.marked)
    s += fmt::format("<rect class=\"pair\" data-i=\"{}\" data-k=\"{}\" x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\"/>\n", i, k,
                     px(left + k * cell + 1), px(top + i * cell + 1), px(cell - 2), px(cell - 2));
  const std::size_t label_every = cell >= 14 ? 1 : 2;
  for (std::size_t i = 0; i < rows; i += label_every)
    s += fmt::format("<text class=\"tick\" x=\"{}\" y=\"{}\" text-anchor=\"end\">{}</text>\n", px(left - 4),
                     px(top + i * cell + cell / 2 + 4), esc(h.row_labels[i]));
  // Column labels wider than a cell are written at 45 degrees.
  std::size_t widest = 0;
  for (const auto& l : h.col_labels) widest = std::max(widest, l.size());
  const bool slant = widest * 7.5 > cell;
  for (std::size_t k = 0; k < cols; k += label_every) {
    const double x = left + k * cell + cell / 2, y = top + rows * cell + 14;
    if (slant)
      s += fmt::format("<text class=\"tick\" transform=\"translate({} {}) rotate(-45)\" text-anchor=\"end\">{}</text>\n",
                       px(x + 3), px(y - 4), esc(h.col_labels[k]));
    else
      s += fmt::format("<text class=\"tick\" x=\"{}\" y=\"{}\" text-anchor=\"middle\">{}</text>\n", px(x), px(y),
                       esc(h.col_labels[k]));
  }
  s += fmt::format("<text class=\"label\" x=\"{}\" y=\"{}\" text-anchor=\"middle\">{}</text>\n", px(left + cols * cell / 2),
                   px(height - 10), esc(h.col_title));
  s += fmt::format("<text class=\"label\" transform=\"translate(14 {}) rotate(-90)\" text-anchor=\"middle\">{}</text>\n",
                   px(top + rows * cell / 2), esc(h.row_title));
  // The colour bar: 20 steps from lo (bottom) to hi (top), ticks at the nice values.
  const double bx = left + cols * cell + 18, bh = std::max(rows * cell, 120.0), bw = 14;
  for (int n = 0; n < 20; ++n)
    s += fmt::format("<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"{}\"/>\n", px(bx),
                     px(top + bh - (n + 1) * bh / 20), px(bw), px(bh / 20 + 0.5), colour((n + 0.5) / 20));
  s += fmt::format("<rect class=\"frame\" x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\"/>\n", px(bx), px(top), px(bw), px(bh));
  for (double t : nice_ticks(h.lo, h.hi, 5))
    s += fmt::format("<text class=\"tick\" x=\"{}\" y=\"{}\">{}</text>\n", px(bx + bw + 4),
                     px(top + bh - (t - h.lo) / (h.hi - h.lo) * bh + 4), esc(estimator::significant(t, 3)));
  s += fmt::format("<text class=\"label\" transform=\"translate({} {}) rotate(-90)\" text-anchor=\"middle\">{}</text>\n",
                   px(bx + bw + 52), px(top + bh / 2), esc(h.value_label));
  s += "</svg>\n";
  return s;
}

}  // namespace ssid::cli::report
