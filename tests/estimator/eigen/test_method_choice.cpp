// EigenMethod::Auto's choice by predicted cost (method_choice.hpp): the predictions
// against the formulas worked by hand, the choice on the benchmark lattices' own
// factor figures (docs/performance.md), the memory limit, and the reason's text.
#include <catch2/catch.hpp>

#include "estimator/eigen/method_choice.hpp"

using namespace ssid::estimator;

TEST_CASE("method choice: the predictions are the documented formulas", "[method_choice]") {
  // t_d = 0.15 + F / 30e9 + 8 ND (4 nnz(L) / 18e9 + n 1e-7)
  const FactorForecast f{3.0e10, 9.0e6, 1.0e8};
  const double columns = 8.0 * 41;
  CHECK(predicted_direct_seconds(50000, 41, f) ==
        Approx(0.15 + 1.0 + columns * (4.0 * 9.0e6 / 18e9 + 50000 * 1e-7)).epsilon(1e-12));
  // t_m = 0.35 + 1.1e-6 n (ND + 10)
  CHECK(predicted_multilevel_seconds(50000, 41) == Approx(0.35 + 1.1e-6 * 50000 * 51).epsilon(1e-12));
}

TEST_CASE("method choice: the benchmark lattices", "[method_choice]") {
  // The symbolic analyses' figures (bench_eigen N --analyze-only, grid-point ordering).
  const FactorForecast lattice10k{1.11e9, 2.15e6, 2.2e7}, lattice94k{1.74e11, 6.61e7, 0.76 * 1073741824.0},
      lattice1m{2.67e13, 2.08e9, 22.4 * 1073741824.0};
  const double limit = 18.8 * 1073741824.0;  // 80 % of this machine's memory
  const MethodChoice small = choose_method(10368, 41, lattice10k, limit);
  CHECK_FALSE(small.multilevel);
  CHECK(small.factor_fits);
  CHECK(small.reason ==
        "direct: predicted 0.68 s against 0.93 s for the multilevel method (factor 1.11e+09 flops, nnz(L) 2.15e+06, "
        "0.02 GiB)");
  const MethodChoice medium = choose_method(93750, 41, lattice94k, limit);
  CHECK(medium.multilevel);
  CHECK(medium.reason ==
        "multilevel: predicted 5.6 s against 14 s for the direct method (factor 1.74e+11 flops, nnz(L) 6.61e+07, "
        "0.76 GiB)");
  const MethodChoice large = choose_method(998250, 41, lattice1m, limit);
  CHECK(large.multilevel);
  CHECK_FALSE(large.factor_fits);
  CHECK(large.reason == "multilevel: the factor would not fit (factor 2.67e+13 flops, nnz(L) 2.08e+09, 22.40 GiB; "
                        "limit 18.80 GiB)");
  // No limit: the 1M factor "fits", and the multilevel method still wins on cost.
  const MethodChoice unlimited = choose_method(998250, 41, lattice1m, 0.0);
  CHECK(unlimited.factor_fits);
  CHECK(unlimited.multilevel);
  CHECK(unlimited.direct_seconds > 10 * unlimited.multilevel_seconds);
}

TEST_CASE("method choice: a factor that does not fit decides, whatever the cost", "[method_choice]") {
  // A tiny model whose direct solve is predicted far cheaper, but with a memory limit below its factor.
  const FactorForecast f{1.0e6, 1.0e4, 2.0e5};
  CHECK_FALSE(choose_method(600, 6, f, 1.0e6).multilevel);
  const MethodChoice c = choose_method(600, 6, f, 1.0e5);
  CHECK(c.multilevel);
  CHECK_FALSE(c.factor_fits);
  CHECK(c.direct_seconds < c.multilevel_seconds);
}
