#include "estimator/identification/data_checks.hpp"

#include <cmath>
#include <fmt/format.h>
#include <limits>

#include "estimator/identification/era.hpp"
#include "estimator/identification/frf_synthesis.hpp"
#include "formats/parse_error.hpp"

namespace ssid::estimator::identification {

using formats::InputError;

FrfDifference compare_frfs(const Eigen::Ref<const Eigen::VectorXd>& f, const Eigen::Ref<const Eigen::VectorXcd>& a,
                           const Eigen::Ref<const Eigen::VectorXcd>& b) {
  if (a.size() != f.size() || b.size() != f.size() || f.size() == 0)
    throw InputError(fmt::format("FRF comparison: {} lines, FRFs of {} and {} values (expected one per line)",
                                 f.size(), a.size(), b.size()));
  FrfDifference d;
  const double na = a.norm(), nb = b.norm();
  d.error = na > 0 && nb > 0 ? (a - b).norm() / std::sqrt(na * nb) : std::numeric_limits<double>::quiet_NaN();
  d.frac = frf_assurance(a, b);
  Eigen::Index ka = 0, kb = 0;
  a.cwiseAbs().maxCoeff(&ka);
  b.cwiseAbs().maxCoeff(&kb);
  d.peak_hz_a = f(ka);
  d.peak_hz_b = f(kb);
  return d;
}

std::vector<LowCoherenceBand> low_coherence_bands(const Eigen::Ref<const Eigen::VectorXd>& f,
                                                  const Eigen::Ref<const Eigen::VectorXd>& coherence, double threshold) {
  if (coherence.size() != f.size())
    throw InputError(fmt::format("coherence: {} lines, {} values (expected one per line)", f.size(), coherence.size()));
  std::vector<LowCoherenceBand> out;
  for (Eigen::Index k = 0; k < f.size(); ++k) {
    const double c = coherence(k);
    if (c >= threshold) continue;  // NaN falls through: below
    const double v = std::isnan(c) ? 0.0 : c;
    if (k > 0 && !out.empty() && out.back().hi_hz == f(k - 1)) {  // continues the band of line k − 1
      out.back().hi_hz = f(k);
      out.back().min = std::min(out.back().min, v);
      ++out.back().lines;
    } else {
      out.push_back({f(k), f(k), v, 1});
    }
  }
  return out;
}

std::vector<PeakResolution> peak_resolution(const Eigen::Ref<const Eigen::VectorXd>& f,
                                            const Eigen::Ref<const Eigen::VectorXd>& magnitude,
                                            const std::vector<std::pair<double, double>>& identified, double tol,
                                            double min_fraction) {
  const Eigen::Index n = f.size();
  if (n < 3 || magnitude.size() != n)
    throw InputError(fmt::format("peak resolution: {} lines and {} magnitudes (expected at least 3, one per line)", n,
                                 magnitude.size()));
  const double df = f(1) - f(0);
  for (Eigen::Index k = 1; k < n; ++k)
    if (!(std::abs(f(k) - f(k - 1) - df) <= 1e-6 * df))
      throw InputError(fmt::format("peak resolution: uneven lines at {} Hz (expected every {} Hz)", f(k), df));
  const double top = magnitude.maxCoeff();
  std::vector<PeakResolution> out;
  for (Eigen::Index k = 1; k + 1 < n; ++k) {
    const double p = magnitude(k);
    if (!(p > magnitude(k - 1) && p >= magnitude(k + 1) && p >= min_fraction * top)) continue;
    const double half = p / std::sqrt(2.0);
    // Walk to the half-power crossing on each side; a higher value first: not isolated.
    const auto crossing = [&](int dir, double& at) {
      for (Eigen::Index j = k + dir; j >= 0 && j < n; j += dir) {
        if (magnitude(j) > p) return false;
        if (magnitude(j) < half) {
          const Eigen::Index i = j - dir;  // the last line at or above half power
          const double t = (magnitude(i) - half) / (magnitude(i) - magnitude(j));
          at = f(i) + t * (f(j) - f(i));
          return true;
        }
      }
      return false;
    };
    double lo = 0, hi = 0;
    if (!crossing(-1, lo) || !crossing(+1, hi)) continue;
    PeakResolution r;
    r.hz = f(k);
    r.half_power_hz = hi - lo;
    double nearest = std::numeric_limits<double>::infinity();
    for (const auto& [hz, zeta] : identified)
      if (std::abs(hz - r.hz) <= tol * hz && std::abs(hz - r.hz) < nearest) {
        nearest = std::abs(hz - r.hz);
        r.half_power_hz = 2 * zeta * hz;
        r.from_identified = true;
      }
    r.zeta = r.half_power_hz / (2 * r.hz);
    r.lines = r.half_power_hz / df;
    out.push_back(r);
  }
  return out;
}

std::vector<DecaySegment> decay_segments(const Eigen::Ref<const Eigen::MatrixXd>& records, double dt,
                                         Eigen::Index segment, Eigen::Index step, Eigen::Index order) {
  if (!(dt > 0)) throw InputError(fmt::format("decay segments: sample interval {} s (expected > 0)", dt));
  if (step < 1 || segment < 4 || records.rows() < segment || records.cols() < 1)
    throw InputError(fmt::format("decay segments: {} samples of {} channel(s), segments of {} every {} (expected at "
                                 "least one segment of 4 or more samples and a step ≥ 1)",
                                 records.rows(), records.cols(), segment, step));
  std::vector<DecaySegment> out;
  EraOptions eo;
  eo.order = order;
  eo.dt = dt;
  for (Eigen::Index start = 0; start + segment <= records.rows(); start += step) {
    const auto block = records.middleRows(start, segment);
    DecaySegment d;
    d.start_s = static_cast<double>(start) * dt;
    d.rms = std::sqrt(block.squaredNorm() / static_cast<double>(block.size()));
    d.hz = d.zeta = std::numeric_limits<double>::quiet_NaN();
    // Orders 2, 4, … up to `order`, and the highest the data carry: beyond the numerical
    // rank (noise-free data of few modes) the realization is round-off.
    std::vector<Eigen::Index> orders;
    for (Eigen::Index o = 2; o <= order; o += 2) orders.push_back(o);
    const std::vector<EraResult> rs = era_orders(markov_from_records(block), eo, orders);
    std::size_t use = 0;
    for (std::size_t i = 0; i < rs.size(); ++i) {
      const Eigen::VectorXd& sv = rs[i].singular_values;
      if (sv.size() >= rs[i].order && sv(rs[i].order - 1) > 1e-9 * sv(0)) use = i;
    }
    const EraResult& r = rs[use];
    double best = -1;
    for (const IdentifiedPole& p : r.poles)
      if (p.lambda.imag() > 0 && p.zeta > 0 && p.zeta < 0.2 && p.msv > best) {
        best = p.msv;
        d.hz = p.hz;
        d.zeta = p.zeta;
      }
    out.push_back(d);
  }
  return out;
}

}  // namespace ssid::estimator::identification
