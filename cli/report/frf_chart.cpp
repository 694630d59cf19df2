#include "cli/report/frf_chart.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "cli/report/svg.hpp"

namespace ssid::cli::report {

std::string frf_overlay_charts(const std::vector<FrfCurve>& curves, const std::string& title, const std::string& unit,
                           const std::string& id, double& height) {
  std::vector<double> fs, mags;
  for (const auto& c : curves)
    for (std::size_t k = 0; k < c.f.size(); ++k) {
      fs.push_back(c.f[k]);
      if (std::abs(c.h[k]) > 0) mags.push_back(std::abs(c.h[k]));
    }
  if (mags.empty()) mags.push_back(1.0);  // all zero: any axis will do
  Axis fx{*std::min_element(fs.begin(), fs.end()), *std::max_element(fs.begin(), fs.end()), "frequency [Hz]"};
  if (!(fx.hi > fx.lo)) fx.hi = fx.lo + 1;
  Chart mag(720, 300, fx, log_axis_around(mags, "|H| [" + unit + "]"));
  Chart ph(720, 220, fx, Axis{-180, 180, "phase [deg]"});
  for (const auto& c : curves) {
    std::string pm, pp;
    for (std::size_t k = 0; k < c.f.size(); ++k) {
      const double a = std::abs(c.h[k]);
      if (a > 0) pm += px(mag.x(c.f[k])) + "," + px(mag.y(a)) + " ";
      pp += px(ph.x(c.f[k])) + "," + px(ph.y(std::arg(c.h[k]) * 180 / M_PI)) + " ";
    }
    const std::string dash = c.dash.empty() ? std::string() : " stroke-dasharray=\"" + c.dash + "\"";
    mag.add(fmt::format("<polyline class=\"{}\" points=\"{}\" fill=\"none\" stroke=\"{}\" stroke-width=\"1.3\"{}><title>{}</title></polyline>\n",
                        c.cls, pm, c.colour, dash, esc(c.name)));
    ph.add(fmt::format("<polyline class=\"{}\" points=\"{}\" fill=\"none\" stroke=\"{}\" stroke-width=\"1\"{}><title>{}</title></polyline>\n",
                       c.cls, pp, c.colour, dash, esc(c.name)));
  }
  std::string legend;
  double lx = 80;
  for (const auto& c : curves) {
    legend += fmt::format("<line x1=\"{0}\" x2=\"{1}\" y1=\"20\" y2=\"20\" stroke=\"{2}\" stroke-width=\"2\"{5}/><text x=\"{3}\" "
                          "y=\"24\" font-size=\"12\">{4}</text>\n",
                          px(lx), px(lx + 24), c.colour, px(lx + 30), esc(c.name),
                          c.dash.empty() ? std::string() : " stroke-dasharray=\"" + c.dash + "\"");
    lx += 40 + 7.0 * static_cast<double>(c.name.size());
  }
  std::string s = fmt::format("<g transform=\"translate(0 {})\">\n<text x=\"10\" y=\"4\" font-size=\"13\" "
                              "font-weight=\"bold\">{}</text>\n{}<g transform=\"translate(0 30)\">{}</g>\n"
                              "<g transform=\"translate(0 330)\">{}</g>\n</g>\n",
                              px(height + 14), esc(title), legend, mag.svg(id + "-mag", title + ": magnitude"),
                              ph.svg(id + "-phase", title + ": phase"));
  height += 14 + 330 + 220 + 20;
  return s;
}


std::string frf_overlay_svg(const std::vector<FrfCurve>& curves, const std::string& title, const std::string& unit,
                            const std::string& id) {
  double height = 0;
  const std::string body = frf_overlay_charts(curves, title, unit, id, height);
  return fmt::format("<svg id=\"{0}\" xmlns=\"http://www.w3.org/2000/svg\" width=\"720\" height=\"{1}\" viewBox=\"0 0 720 {1}\" "
                     "role=\"img\" aria-label=\"{2}\">\n{3}</svg>\n",
                     esc(id), px(height + 10), esc(title), body);
}

}  // namespace ssid::cli::report
