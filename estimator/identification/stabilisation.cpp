#include "estimator/identification/stabilisation.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "estimator/identification/modal_indicators.hpp"
#include "formats/parse_error.hpp"

namespace ssid::estimator::identification {

using formats::InputError;
using cd = std::complex<double>;

std::string reject_reason_text(RejectReason reason) {
  switch (reason) {
    case RejectReason::None: return "";
    case RejectReason::Unstable: return "unstable (damping ≤ 0)";
    case RejectReason::OverDamped: return "over-damped";
    case RejectReason::OutOfBand: return "out of band";
    case RejectReason::HighMpd: return "high MPD";
    case RejectReason::LowMpc: return "low MPC";
    case RejectReason::NotStable: return "not stable against the previous order";
    case RejectReason::NotRecurrent: return "not stable across enough orders";
    case RejectReason::ExcludedByHand: return "excluded by hand";
  }
  return "";
}

char pole_class_symbol(PoleClass c) {
  switch (c) {
    case PoleClass::New: return 'o';
    case PoleClass::Frequency: return 'f';
    case PoleClass::FrequencyDamping: return 'd';
    case PoleClass::FrequencyShape: return 'v';
    case PoleClass::Stable: return 's';
    case PoleClass::Rejected: return 'x';
  }
  return '?';
}

namespace {

void check_options(const StabilisationOptions& o) {
  auto positive = [](double v, const char* name) {
    if (!(v > 0)) throw InputError(fmt::format("stabilisation: {} = {} (expected > 0)", name, v));
  };
  auto unit = [](double v, const char* name) {
    if (!(v >= 0 && v <= 1)) throw InputError(fmt::format("stabilisation: {} = {} (expected in [0, 1])", name, v));
  };
  positive(o.freq_tol, "frequency tolerance");
  positive(o.damping_tol, "damping tolerance");
  positive(o.cluster_freq_tol, "cluster frequency tolerance");
  positive(o.hand_tol, "hand-selection tolerance");
  positive(o.zeta_max, "largest damping");
  unit(o.mac_min, "MAC threshold");
  unit(o.cluster_mac_min, "cluster MAC threshold");
  unit(o.mpc_min, "MPC threshold");
  unit(o.min_fraction, "recurrence fraction");
  if (!(o.hz_min <= o.hz_max))
    throw InputError(fmt::format("stabilisation: band {} … {} Hz (expected min ≤ max)", o.hz_min, o.hz_max));
}

RejectReason screen(const IdentifiedPole& p, const StabilisationOptions& o) {
  if (!(p.zeta > 0)) return RejectReason::Unstable;
  if (p.zeta > o.zeta_max) return RejectReason::OverDamped;
  if (p.hz < o.hz_min || p.hz > o.hz_max) return RejectReason::OutOfBand;
  if (p.mpd > o.mpd_max_deg) return RejectReason::HighMpd;
  if (p.mpc < o.mpc_min) return RejectReason::LowMpc;
  return RejectReason::None;
}

struct Cluster {
  std::vector<std::size_t> members;  // into the diagram
  double hz_sum = 0;
  Eigen::VectorXcd reference;  // the first member's shape
  Eigen::Index last_order = -1;
  double mean_hz() const { return hz_sum / static_cast<double>(members.size()); }
};

bool near_any(double hz, const std::vector<double>& list, double tol) {
  for (const double f : list)
    if (std::abs(hz - f) <= tol * std::abs(f)) return true;
  return false;
}

}  // namespace

StabilisationResult stabilise(const std::vector<OrderPoles>& orders, const StabilisationOptions& o) {
  check_options(o);
  for (std::size_t i = 1; i < orders.size(); ++i)
    if (orders[i].order <= orders[i - 1].order)
      throw InputError(fmt::format("stabilisation: order {} listed after order {} (expected increasing orders)",
                                   orders[i].order, orders[i - 1].order));
  StabilisationResult out;
  // Diagram positions of each order's poles, to look up the previous order.
  std::vector<std::vector<std::size_t>> at(orders.size());
  for (std::size_t i = 0; i < orders.size(); ++i) {
    const auto& cur = orders[i].poles;
    for (std::size_t j = 0; j < cur.size(); ++j) {
      const IdentifiedPole& p = cur[j];
      DiagramPole d;
      d.order = orders[i].order;
      d.index = j;
      d.hz = p.hz;
      d.zeta = p.zeta;
      d.reason = screen(p, o);
      if (d.reason != RejectReason::None) {
        d.cls = PoleClass::Rejected;
      } else if (i > 0) {
        // The nearest unscreened pole of the previous order, in frequency.
        const IdentifiedPole* best = nullptr;
        double best_df = 0;
        for (const std::size_t k : at[i - 1]) {
          if (out.diagram[k].reason != RejectReason::None &&
              out.diagram[k].reason != RejectReason::NotStable)
            continue;
          const IdentifiedPole& q = orders[i - 1].poles[out.diagram[k].index];
          const double df = std::abs(p.hz - q.hz) / q.hz;
          if (!best || df < best_df) {
            best = &q;
            best_df = df;
          }
        }
        if (best && best_df <= o.freq_tol) {
          const bool damp = std::abs(p.zeta - best->zeta) <= o.damping_tol * best->zeta;
          const bool shape = complex_mac(p.shape, best->shape) >= o.mac_min;
          d.cls = damp && shape ? PoleClass::Stable
                  : damp        ? PoleClass::FrequencyDamping
                  : shape       ? PoleClass::FrequencyShape
                                : PoleClass::Frequency;
        }
      }
      if (d.cls != PoleClass::Rejected && d.cls != PoleClass::Stable) d.reason = RejectReason::NotStable;
      at[i].push_back(out.diagram.size());
      out.diagram.push_back(d);
    }
  }

  // Cluster the stable poles, order by order: each joins the nearest cluster (in
  // frequency) that matches in frequency and shape and has no pole of this order yet.
  std::vector<Cluster> clusters;
  for (std::size_t i = 0; i < orders.size(); ++i)
    for (const std::size_t k : at[i]) {
      DiagramPole& d = out.diagram[k];
      if (d.cls != PoleClass::Stable) continue;
      const IdentifiedPole& p = orders[i].poles[d.index];
      Cluster* best = nullptr;
      double best_df = 0;
      for (Cluster& c : clusters) {
        if (c.last_order == d.order) continue;
        const double df = std::abs(p.hz - c.mean_hz()) / c.mean_hz();
        if (df > o.cluster_freq_tol || complex_mac(p.shape, c.reference) < o.cluster_mac_min) continue;
        if (!best || df < best_df) {
          best = &c;
          best_df = df;
        }
      }
      if (!best) {
        clusters.emplace_back();
        best = &clusters.back();
        best->reference = p.shape;
      }
      best->members.push_back(k);
      best->hz_sum += p.hz;
      best->last_order = d.order;
    }

  // Stable poles can exist from the second order on; an order that gave no pole at all
  // (e.g. ERA beyond the data's numerical rank) has nothing to recur in and is not counted.
  const auto realized = std::count_if(orders.begin(), orders.end(), [](const OrderPoles& op) { return !op.poles.empty(); });
  const double compared = realized > 1 ? static_cast<double>(realized - 1) : 1.0;
  const auto needed = std::max<std::size_t>(2, static_cast<std::size_t>(std::ceil(o.min_fraction * compared - 1e-9)));
  struct Built {
    ClusteredMode mode;
    std::vector<std::size_t> members;
  };
  std::vector<Built> built;
  for (const Cluster& c : clusters) {
    if (c.members.size() < needed) {
      for (const std::size_t k : c.members) out.diagram[k].reason = RejectReason::NotRecurrent;
      continue;
    }
    Built b;
    b.members = c.members;
    ClusteredMode& m = b.mode;
    const auto count = static_cast<double>(c.members.size());
    std::vector<Eigen::VectorXcd> aligned;
    for (const std::size_t k : c.members) {
      const DiagramPole& d = out.diagram[k];
      m.hz += d.hz / count;
      m.zeta += d.zeta / count;
      // Find the order's poles again by the diagram position.
      const auto oi = static_cast<std::size_t>(
          std::find_if(orders.begin(), orders.end(), [&](const OrderPoles& op) { return op.order == d.order; }) -
          orders.begin());
      const Eigen::VectorXcd& phi = orders[oi].poles[d.index].shape;
      const cd proj = c.reference.dot(phi);  // reference ᴴ φ
      const cd rot = std::abs(proj) > 0 ? std::conj(proj) / std::abs(proj) : cd(1, 0);
      aligned.push_back(phi * rot / phi.norm());
    }
    for (const std::size_t k : c.members) {
      const DiagramPole& d = out.diagram[k];
      m.hz_std += (d.hz - m.hz) * (d.hz - m.hz) / count;
      m.zeta_std += (d.zeta - m.zeta) * (d.zeta - m.zeta) / count;
    }
    m.hz_std = std::sqrt(m.hz_std);
    m.zeta_std = std::sqrt(m.zeta_std);
    m.shape = Eigen::VectorXcd::Zero(aligned.front().size());
    for (const auto& a : aligned) m.shape += a / count;
    m.shape_std = Eigen::VectorXd::Zero(m.shape.size());
    for (const auto& a : aligned) m.shape_std += (a - m.shape).cwiseAbs2() / count;
    m.shape_std = m.shape_std.cwiseSqrt();
    m.mpc = modal_phase_collinearity(m.shape);
    m.poles = c.members.size();
    built.push_back(std::move(b));
  }
  std::sort(built.begin(), built.end(), [](const Built& a, const Built& b) { return a.mode.hz < b.mode.hz; });

  // Hand selection.
  for (std::size_t idx = 0; idx < built.size(); ++idx) {
    const double hz = built[idx].mode.hz;
    const bool excluded = near_any(hz, o.exclude_hz, o.hand_tol) ||
                          std::find(o.exclude_index.begin(), o.exclude_index.end(), idx) != o.exclude_index.end() ||
                          (!o.keep_hz.empty() && !near_any(hz, o.keep_hz, o.hand_tol));
    if (excluded) {
      for (const std::size_t k : built[idx].members) out.diagram[k].reason = RejectReason::ExcludedByHand;
      continue;
    }
    for (const std::size_t k : built[idx].members) out.diagram[k].mode = static_cast<int>(out.modes.size());
    out.modes.push_back(built[idx].mode);
  }
  return out;
}

std::vector<OrderPoles> order_poles(const std::vector<EraResult>& results) {
  std::vector<OrderPoles> out;
  out.reserve(results.size());
  for (const EraResult& r : results) out.push_back(OrderPoles{r.order, r.poles});
  return out;
}

}  // namespace ssid::estimator::identification
