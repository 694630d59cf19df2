#include "estimator/eigen/method_choice.hpp"

#include <fmt/format.h>

namespace ssid::estimator {

namespace {

// Rates of a 2-core AMD EPYC (docs/performance.md, "Auto: the method by cost"):
// the 94k lattice's factor, 1.74e11 flops, in 5.7 s; its 330 solved columns with
// nnz(L) 6.6e7 in 4.7 s; the rest of block Lanczos 3.2 s (10k: 0.3 s).
constexpr double kDirectFixedSeconds = 0.15;     // t₀: CHOLMOD's set-up, small supernodes
constexpr double kFactorFlopRate = 30e9;         // r_f, flop/s
constexpr double kSolveFlopRate = 18e9;          // r_s, flop/s (4 nnz(L) a column)
constexpr double kLanczosSecondsPerEntry = 1e-7; // t_b, per DOF and solved column
constexpr double kColumnsPerMode = 8.0;          // block Lanczos with refinement
// The multilevel method: 10k 0.9-1.0 s, 94k 4.5-5.8 s, 1M 67-75 s for 41 modes.
constexpr double kMultilevelFixedSeconds = 0.35;  // t₀
constexpr double kMultilevelSecondsPerEntry = 1.1e-6;  // t_m, per DOF and block column
constexpr int kMultilevelGuardColumns = 10;

}  // namespace

double predicted_direct_seconds(long n, int modes, const FactorForecast& factor) {
  const double columns = kColumnsPerMode * modes;
  return kDirectFixedSeconds + factor.flops / kFactorFlopRate +
         columns * (4.0 * factor.nnz / kSolveFlopRate + static_cast<double>(n) * kLanczosSecondsPerEntry);
}

double predicted_multilevel_seconds(long n, int modes) {
  return kMultilevelFixedSeconds +
         kMultilevelSecondsPerEntry * static_cast<double>(n) * static_cast<double>(modes + kMultilevelGuardColumns);
}

MethodChoice choose_method(long n, int modes, const FactorForecast& factor, double memory_limit) {
  MethodChoice c;
  c.direct_seconds = predicted_direct_seconds(n, modes, factor);
  c.multilevel_seconds = predicted_multilevel_seconds(n, modes);
  c.factor_fits = memory_limit <= 0.0 || factor.bytes <= memory_limit;
  c.multilevel = !c.factor_fits || c.multilevel_seconds < c.direct_seconds;
  const std::string figures = fmt::format("factor {:.3g} flops, nnz(L) {:.3g}, {:.2f} GiB", factor.flops, factor.nnz,
                                          factor.bytes / 1073741824.0);
  if (!c.factor_fits)
    c.reason = fmt::format("multilevel: the factor would not fit ({}; limit {:.2f} GiB)", figures,
                           memory_limit / 1073741824.0);
  else if (c.multilevel)
    c.reason = fmt::format("multilevel: predicted {:.2g} s against {:.2g} s for the direct method ({})",
                           c.multilevel_seconds, c.direct_seconds, figures);
  else
    c.reason = fmt::format("direct: predicted {:.2g} s against {:.2g} s for the multilevel method ({})",
                           c.direct_seconds, c.multilevel_seconds, figures);
  return c;
}

}  // namespace ssid::estimator
