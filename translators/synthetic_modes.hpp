#pragma once
/// \file synthetic_modes.hpp
/// The synthetic modal test: analysis modes sampled at chosen sensors, with
/// reproducible noise, as the measured data set a modal-test lab would hand over
/// (UFF nodes, dataset 2411, and real normal modes, dataset 55).
///
/// Sensors are grids; each sensor grid gives the translations along the global
/// (basic) axes X, Y, Z — what accelerometers measure — so a grid with a
/// displacement system (CD) is rotated to basic:
///   u_basic = R u_cd,   R = the CD frame's axes as columns in basic.
/// Rotations (components 4–6, about the basic axes) are written only on request.
///
/// Noise, per mode j (frequency f_j, sampled shape φ_j at the sensor DOFs):
///   f̃_j      = f_j (1 + p_f/100 · z),
///   φ̃_j(i)   = φ_j(i) + p_s/100 · max_k |φ_j(k)| · z_i,
/// with z, z_i independent standard normal deviates drawn in that order (the
/// frequency first, then the shape rows in sensor order) from a Mersenne twister
/// (std::mt19937_64, fully specified by the C++ standard) through an explicit
/// Box–Muller transform — std::normal_distribution is implementation-defined, so
/// a given seed gives the same data with every standard library.
#include <Eigen/Core>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "formats/uff.hpp"
#include "translators/constraints.hpp"
#include "translators/dof_map.hpp"
#include "translators/measurement/sensor_mapping.hpp"
#include "translators/measurement/mode_set.hpp"

namespace ssid::translators {

/// Standard normal deviates from std::mt19937_64 via Box–Muller, identical on
/// every platform for a given seed:
///   u₁ = (⌊x₁/2¹¹⌋ + 1)·2⁻⁵³ ∈ (0, 1],  u₂ = ⌊x₂/2¹¹⌋·2⁻⁵³ ∈ [0, 1),
///   z₁ = √(−2 ln u₁) cos 2πu₂,  z₂ = √(−2 ln u₁) sin 2πu₂  (returned in turn).
class NormalDeviates {
 public:
  explicit NormalDeviates(std::uint64_t seed) : m_engine(seed) {}
  double operator()();

 private:
  std::mt19937_64 m_engine;
  double m_spare = 0;
  bool m_has_spare = false;
};

struct SyntheticTestOptions {
  /// Sensor grids, in output order; empty: every grid of `grids`, in that order.
  std::vector<std::int64_t> sensors;
  bool rotations = false;      ///< also write components 4–6 (rotations about X, Y, Z)
  double noise_freq_pct = 0;   ///< p_f: standard deviation of the relative frequency error, %
  double noise_shape_pct = 0;  ///< p_s: standard deviation of shape noise, % of the mode's largest sensor value
  std::uint64_t seed = 1;
  std::string description = "ssid synthetic modal test";  ///< UFF 55 ID line 1
};

/// FE modes on the g-set, as an eigen-solve expanded them.
struct FeModeData {
  Eigen::MatrixXd shapes;             ///< g x m (mass-normalised, or any scaling)
  std::vector<double> frequency_hz;   ///< m
  std::vector<double> generalized_mass;  ///< m: φᵀMφ (1 for mass-normalised); empty: 1
};

struct SyntheticTest {
  ModeSet modes;                  ///< the (noisy) values at the sensor DOFs, node = grid id
  formats::uff::UffFile file;     ///< 2411 nodes of the sensors + one 55 per mode
};

/// Samples g-set modes at the sensors and adds noise. `gset` maps (grid,
/// component) to rows of `fe.shapes`; `grids` gives positions and CD frames.
/// Throws std::invalid_argument for a sensor that is not a grid of `grids`,
/// negative noise, or sizes that do not agree.
SyntheticTest synthetic_test(const FeModeData& fe, const DofMap& gset, const std::vector<GridPosition>& grids,
                             const SyntheticTestOptions& options = {});

/// The same from a-set modes (a x m), expanded through the reduction u_g = T u_a.
SyntheticTest synthetic_test(const FeModeData& a_modes, const Reduction& reduction, const DofMap& gset,
                             const std::vector<GridPosition>& grids, const SyntheticTestOptions& options = {});

/// Reads a sensor list: grid ids separated by blanks, commas or new lines;
/// "A:B" (or "A THRU B") is every grid of `grids` with id in [A, B]; '#' starts a
/// comment. Throws std::invalid_argument naming the token that is not an id.
std::vector<std::int64_t> parse_sensor_list(const std::string& text, const std::vector<GridPosition>& grids,
                                            const std::string& source = "sensor list");

}  // namespace ssid::translators
