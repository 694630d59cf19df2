#pragma once
/// \file method_choice.hpp
/// EigenMethod::Auto's choice between the direct method (a Cholesky factor of
/// K − σM and block Lanczos) and the multilevel method (LOBPCG with an aggregation
/// preconditioner, no factor of the full model), by predicted cost.
///
/// Why a cost model rather than a size threshold: the direct method's cost is its
/// factor's, which the symbolic analysis gives exactly (flops, nnz(L)) before any
/// numeric work, and which grows as n² on 3D solid-like meshes but almost
/// linearly on thin shells or long beams; the multilevel method's cost grows as
/// n × modes. A DOF threshold is right for one family of models only.
///
/// The rates below were measured on the benchmark lattices (bench_eigen,
/// docs/performance.md "Auto: the method by cost") on a 2-core machine; both
/// predictions scale alike with the machine's speed, so their ratio, which
/// decides, holds better than either figure. A prediction is a guide: within a
/// factor of 1.5 either way on the lattices of 10k-1M DOFs.
#include <string>

namespace ssid::estimator {

/// What the symbolic analysis of K − σM says about its factor.
struct FactorForecast {
  double flops = 0;  ///< the numeric factorisation's flops
  double nnz = 0;    ///< entries of L
  double bytes = 0;  ///< memory of the factorisation (CholmodFactor::factor_bytes)
};

/// The choice and why.
struct MethodChoice {
  bool multilevel = false;
  double direct_seconds = 0;      ///< predicted, factor and Lanczos (the analysis is already done)
  double multilevel_seconds = 0;  ///< predicted, setup and LOBPCG
  bool factor_fits = true;        ///< bytes within memory_limit (0: no limit)
  /// One line: the method, and the figures it was chosen by, e.g. "multilevel:
  /// predicted 5.7 s against 13.8 s for the direct method (factor 1.74e+11 flops,
  /// nnz(L) 6.61e+07, 0.76 GiB)".
  std::string reason;
};

/// Predicted seconds of the direct method for the lowest `modes` modes of an
/// n-DOF model: t = t₀ + F / r_f + c (4 nnz(L) / r_s + n t_b), F the factor's
/// flops, c ≈ 8 × modes the columns block Lanczos solves (16-column blocks;
/// measured 330 for 41 modes), r_f and r_s the factorisation's and the solves'
/// rates and t_b the Lanczos bookkeeping per DOF and column.
double predicted_direct_seconds(long n, int modes, const FactorForecast& factor);
/// Predicted seconds of the multilevel method: t = t₀ + t_m n (modes + 10), the
/// preconditioned LOBPCG's work per DOF and column (45 columns for 35 modes)
/// times its ~17-23 iterations, folded into t_m.
double predicted_multilevel_seconds(long n, int modes);

/// The direct method when its factor fits in `memory_limit` bytes (0: no limit)
/// and is predicted faster, the multilevel method otherwise.
MethodChoice choose_method(long n, int modes, const FactorForecast& factor, double memory_limit);

}  // namespace ssid::estimator
