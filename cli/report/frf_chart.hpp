#pragma once
/// \file frf_chart.hpp
/// FRF overlays (the seed report's Figures 4 and 6–9): magnitude on a logarithmic
/// axis and phase, of several curves over frequency, stacked. Drawn by `ssid frf
/// --svg` (analysis against measured) and by `ssid identify modes --report`
/// (measured against the identified modal model). Part of the report's plotting
/// module (svg.hpp): it draws, it computes nothing.
#include <complex>
#include <string>
#include <vector>

namespace ssid::cli::report {

/// One curve: its CSS class, stroke colour, legend text, and the FRF at frequencies f (Hz).
struct FrfCurve {
  std::string cls, colour, name;
  std::vector<double> f;
  std::vector<std::complex<double>> h;
  std::string dash;  ///< SVG stroke-dasharray ("" solid): a curve drawn over another stays visible
};

/// The magnitude (logarithmic, unit `unit`) and phase charts of `curves`, stacked under
/// `title` and a legend, as an SVG group (`<g>`) placed `height` pixels down; adds its
/// own height to `height`. The charts' ids are `id`-mag and `id`-phase; each curve is a
/// `<polyline class="cls">` with one point per frequency (the magnitude chart leaves
/// out zeros, which a logarithmic axis cannot show).
std::string frf_overlay_charts(const std::vector<FrfCurve>& curves, const std::string& title, const std::string& unit,
                               const std::string& id, double& height);

/// The same as one standalone `<svg>` element (720 px wide) with `id`.
std::string frf_overlay_svg(const std::vector<FrfCurve>& curves, const std::string& title, const std::string& unit,
                            const std::string& id);

}  // namespace ssid::cli::report
