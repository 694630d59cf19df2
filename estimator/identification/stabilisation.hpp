#pragma once
/// \file stabilisation.hpp
/// The stabilisation diagram and the choice of physical modes: poles identified at a
/// series of model orders are screened (unstable, over-damped, high MPD, low MPC),
/// compared with the previous order (frequency, damping and MAC stability), and the
/// stable ones clustered across orders into modes with the mean and standard deviation
/// of frequency, damping and shape. Every pole not in a mode keeps its reason.
/// Equations and defaults: docs/identification.md, "Stabilisation".
#include <Eigen/Core>
#include <string>
#include <vector>

#include "estimator/identification/era.hpp"

namespace ssid::estimator::identification {

/// The poles of one model order (any method; only lambda/hz/zeta/shape/mpc/mpd are used).
struct OrderPoles {
  Eigen::Index order = 0;
  std::vector<IdentifiedPole> poles;
};

struct StabilisationOptions {
  double freq_tol = 0.01;     ///< |f − f_prev|/f_prev ≤ this: stable in frequency (1 %)
  double damping_tol = 0.05;  ///< |ζ − ζ_prev|/ζ_prev ≤ this: stable in damping (5 %)
  double mac_min = 0.98;      ///< complex MAC with the previous order's pole ≥ this: stable in shape
  double zeta_max = 0.2;      ///< poles damped more than this are rejected (numerical)
  double mpc_min = 0.7;       ///< poles with MPC below this are rejected
  double mpd_max_deg = 30;    ///< poles with MPD above this (degrees) are rejected
  double hz_min = 0;          ///< poles outside [hz_min, hz_max] are rejected (band of interest)
  double hz_max = 1e300;
  /// A cluster becomes a mode when stable poles of at least this fraction of the orders
  /// that follow another order join it (and at least 2 poles); orders without any pole
  /// (ERA beyond the numerical rank of noise-free data) are not counted.
  double min_fraction = 0.5;
  /// Cluster membership: within cluster_freq_tol of the cluster's first pole in frequency
  /// and cluster_mac_min in complex MAC.
  double cluster_freq_tol = 0.01;
  double cluster_mac_min = 0.95;
  /// Hand selection, applied last. A mode within hand_tol (relative) of a frequency in
  /// `exclude_hz`, or whose index (0-based, by frequency) is in `exclude_index`, is
  /// rejected "excluded by hand"; with `keep_hz` not empty only modes near those stay.
  std::vector<double> exclude_hz;
  std::vector<std::size_t> exclude_index;
  std::vector<double> keep_hz;
  double hand_tol = 0.02;
};

/// The stability class of a pole against the previous order (the diagram's symbols).
enum class PoleClass {
  New,                     ///< "o": no pole within freq_tol at the previous order (or the first order)
  Frequency,               ///< "f": frequency stable only
  FrequencyDamping,        ///< "d": frequency and damping stable
  FrequencyShape,          ///< "v": frequency and shape stable
  Stable,                  ///< "s": frequency, damping and shape stable
  Rejected                 ///< screened out before comparison (see reason)
};

/// Why a pole is not part of any mode.
enum class RejectReason {
  None,
  Unstable,         ///< ζ ≤ 0 (growing or undamped)
  OverDamped,       ///< ζ > zeta_max
  OutOfBand,        ///< outside [hz_min, hz_max]
  HighMpd,          ///< MPD > mpd_max_deg
  LowMpc,           ///< MPC < mpc_min
  NotStable,        ///< not fully stable against the previous order
  NotRecurrent,     ///< stable, but its cluster recurs at too few orders
  ExcludedByHand    ///< its mode was excluded by the user's selection
};

/// The text of a reason, e.g. "high MPD" (for tables and JSON).
std::string reject_reason_text(RejectReason reason);
/// One-letter symbol of a class: o f d v s x.
char pole_class_symbol(PoleClass c);

/// One point of the diagram.
struct DiagramPole {
  Eigen::Index order = 0;
  std::size_t index = 0;  ///< into that order's poles
  double hz = 0, zeta = 0;
  PoleClass cls = PoleClass::New;
  RejectReason reason = RejectReason::None;
  int mode = -1;  ///< index into StabilisationResult::modes, −1 when none
};

/// A physical mode: the cluster's statistics (population standard deviations over its poles).
struct ClusteredMode {
  double hz = 0, hz_std = 0;      ///< Hz
  double zeta = 0, zeta_std = 0;  ///< dimensionless
  /// Mean shape over the poles, each scaled to unit norm and rotated onto the first
  /// pole's phase (φ_a = φ · (φ₁ᴴφ)* / |φ₁ᴴφ| / ‖φ‖); shape_std: per component, σ of |φ − mean|.
  Eigen::VectorXcd shape;
  Eigen::VectorXd shape_std;
  double mpc = 0;       ///< of the mean shape
  std::size_t poles = 0;  ///< how many orders contributed
};

struct StabilisationResult {
  std::vector<DiagramPole> diagram;   ///< every pole of every order
  std::vector<ClusteredMode> modes;   ///< by frequency
};

/// Classify, cluster and select. Orders must be listed in increasing order.
/// Throws formats::InputError for orders out of sequence or tolerances out of range.
StabilisationResult stabilise(const std::vector<OrderPoles>& orders, const StabilisationOptions& options = {});

/// The poles of each ERA result as OrderPoles.
std::vector<OrderPoles> order_poles(const std::vector<EraResult>& results);

}  // namespace ssid::estimator::identification
