#pragma once
/// \file html_report.hpp
/// `--report FILE.html` (issue 24, docs/report.md): one self-contained HTML
/// page (inline SVG and CSS, one small inline script, nothing fetched) drawn
/// from a command's JSON result and nothing else. The sections present depend
/// on the keys the JSON holds:
///   - "run": command, inputs with SHA-256, ssid version, date;
///   - correlate: "mac" with "fe_modes"/"test_modes" (heat map, pairs marked),
///     "pairs" (frequency comparison, error per pair);
///   - estimate: "correlation" of the first configuration, "pairs" and
///     "initial_pairs" (before and after the update), "parameters" (prior and
///     posterior mean ± σ in prior σ), "identifiability.posterior_correlation",
///     "iterations" (convergence per cycle);
///   - identify: "stabilisation" (the diagram) and "modes" (their table);
///   - diagnose: "evidence" (residuals by mode and by grid), "ranking",
///     "cause" (and where it sits on "geometry"), "gain";
///   - pretest: the sensors and exciters on "geometry" (pretest_picture.hpp),
///     "methods" (Fisher determinant and condition per method), "tam" (the
///     target modes' cross-orthogonality per TAM), "exciters"/"given_exciters"
///     (MIF drop-offs, the GA per generation), "evaluation", "model_error";
///   - "geometry" and "shapes": mode shapes of each pair, analysis and test side
///     by side, in four view directions, animated by the inline script, static in print.
/// Marks carry the JSON's values in data attributes (svg.hpp), so a test can
/// check the picture against the numbers.
#include <nlohmann/json.hpp>
#include <string>

namespace ssid::cli::report {

/// The report page of a command's JSON (with its "run" object).
std::string html_report(const nlohmann::json& j);

/// `ssid identify modes`' stabilisation diagram (issue 22 item 8) from its JSON
/// ("stabilisation", "modes"): frequency on x, model order on y, one symbol per
/// pole and stability class, the chosen modes as vertical lines, the sum of the FRF
/// magnitudes (log scale, fitted to the order range) behind. `standalone`: an SVG
/// file of its own (with its fonts and legend inline), else for the report page.
std::string stabilisation_svg(const nlohmann::json& j, bool standalone);

}  // namespace ssid::cli::report
