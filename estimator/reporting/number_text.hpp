#pragma once
/// \file number_text.hpp
/// Numbers as the reports print them: one pair of helpers for the estimator's
/// summaries, the diagnosis and the CLI.
#include <string>

namespace ssid::estimator {

/// `x` with `digits` decimals ("12.350" for 3).
std::string fixed(double x, int digits);
/// `x` with `digits` significant digits ("12.35", "0.001235", "1.235e+07"): for
/// quantities of any scale (kg, m⁴, J).
std::string significant(double x, int digits);

}  // namespace ssid::estimator
