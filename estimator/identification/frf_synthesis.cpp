#include "estimator/identification/frf_synthesis.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <fmt/format.h>
#include <limits>

#include "formats/parse_error.hpp"

namespace ssid::estimator::identification {

using formats::InputError;
using cd = std::complex<double>;

const char* quantity_name(FrfQuantity q) {
  return q == FrfQuantity::Displacement ? "displacement" : q == FrfQuantity::Velocity ? "velocity" : "acceleration";
}

const char* quantity_unit(FrfQuantity q) {
  return q == FrfQuantity::Displacement ? "length/force" : q == FrfQuantity::Velocity ? "length/s/force" : "length/s²/force";
}

int quantity_data_type(FrfQuantity q) { return q == FrfQuantity::Displacement ? 8 : q == FrfQuantity::Velocity ? 11 : 12; }

std::optional<FrfQuantity> quantity_of_data_type(int data_type) {
  switch (data_type) {
    case 8: return FrfQuantity::Displacement;
    case 11: return FrfQuantity::Velocity;
    case 12: return FrfQuantity::Acceleration;
    default: return std::nullopt;
  }
}

Eigen::MatrixXcd synthesize_frf(const Eigen::Ref<const Eigen::VectorXd>& frequency_hz, const ModalFrfModel& modes,
                                FrfQuantity quantity) {
  const Eigen::Index nm = modes.eigenvalue.size(), no = modes.response.rows();
  if (modes.zeta.size() != nm || modes.drive.size() != nm || modes.response.cols() != nm)
    throw InputError(fmt::format("FRF synthesis: {} eigenvalues, {} damping ratios, {} drive values and {} response "
                                 "columns (expected one per mode)",
                                 nm, modes.zeta.size(), modes.drive.size(), modes.response.cols()));
  for (Eigen::Index r = 0; r < nm; ++r)
    if (!(modes.zeta(r) >= 0))
      throw InputError(fmt::format("FRF synthesis: mode {} has damping ratio {} (expected ≥ 0)", r + 1, modes.zeta(r)));
  const int power = quantity == FrfQuantity::Displacement ? 0 : quantity == FrfQuantity::Velocity ? 1 : 2;

  // A rigid-body mode's ω_r² is round-off around 0 (either sign): take it as 0.
  Eigen::VectorXd w2 = modes.eigenvalue.cwiseMax(0.0);
  const Eigen::VectorXd wr = w2.cwiseSqrt();
  // Participation of each mode in each response: φ_kr φ_dr.
  const Eigen::MatrixXd part = modes.response * modes.drive.asDiagonal();

  Eigen::MatrixXcd h(frequency_hz.size(), no);
  Eigen::VectorXcd modal(nm);
  for (Eigen::Index k = 0; k < frequency_hz.size(); ++k) {
    const double w = 2 * M_PI * frequency_hz(k);
    for (Eigen::Index r = 0; r < nm; ++r) {
      const cd den(w2(r) - w * w, 2 * modes.zeta(r) * wr(r) * w);
      if (den == cd(0, 0))
        throw InputError(fmt::format("FRF synthesis: the line at {} Hz meets mode {} ({} Hz) with zero damping or as "
                                     "a rigid-body mode at 0 Hz: the FRF is infinite there (start the band above "
                                     "it or give damping)",
                                     frequency_hz(k), r + 1, wr(r) / (2 * M_PI)));
      modal(r) = 1.0 / den;
    }
    cd factor(1, 0);
    for (int p = 0; p < power; ++p) factor *= cd(0, w);
    h.row(k) = (factor * (part * modal)).transpose();
  }
  return h;
}

double frf_assurance(const Eigen::Ref<const Eigen::VectorXcd>& a, const Eigen::Ref<const Eigen::VectorXcd>& b) {
  if (a.size() != b.size())
    throw InputError(fmt::format("FRAC: FRFs of {} and {} lines (expected the same lines)", a.size(), b.size()));
  const double na = a.squaredNorm(), nb = b.squaredNorm();
  if (!(na > 0) || !(nb > 0)) return std::numeric_limits<double>::quiet_NaN();
  return std::norm(a.dot(b)) / (na * nb);
}

std::vector<std::optional<std::size_t>> damping_partners(const Eigen::Ref<const Eigen::VectorXd>& analysis_hz,
                                                         const std::vector<double>& measured_hz, double tolerance) {
  struct Candidate {
    double rel;
    Eigen::Index r;
    std::size_t t;
  };
  std::vector<Candidate> cands;
  for (Eigen::Index r = 0; r < analysis_hz.size(); ++r)
    for (std::size_t t = 0; t < measured_hz.size(); ++t) {
      const double rel = std::abs(analysis_hz(r) - measured_hz[t]) / measured_hz[t];
      if (rel <= tolerance) cands.push_back({rel, r, t});
    }
  // Stable: equal distances keep the lower analysis mode first, then the lower measured one.
  std::stable_sort(cands.begin(), cands.end(), [](const Candidate& a, const Candidate& b) { return a.rel < b.rel; });
  std::vector<std::optional<std::size_t>> out(static_cast<std::size_t>(analysis_hz.size()));
  std::vector<bool> used(measured_hz.size());
  for (const Candidate& c : cands) {
    auto& slot = out[static_cast<std::size_t>(c.r)];
    if (slot || used[c.t]) continue;
    slot = c.t;
    used[c.t] = true;
  }
  return out;
}

}  // namespace ssid::estimator::identification
