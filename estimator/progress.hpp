#pragma once
/// \file progress.hpp
/// The library never prints: long computations report through this callback,
/// which the CLI turns into progress lines.
#include <functional>
#include <string>

namespace ssid::estimator {

/// Called with a short message and a fraction done in [0, 1] (or < 0 when unknown).
using Progress = std::function<void(const std::string& message, double fraction)>;

/// Calls `p` when set.
void report(const Progress& p, const std::string& message, double fraction = -1.0);

}  // namespace ssid::estimator
