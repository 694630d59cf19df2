#pragma once
/// \file mode_set.hpp
/// Mode sets at measured DOFs: what correlation and estimation compare.
/// Built from UFF 55 real normal modes (test, or FE modes written at sensors),
/// or later from an eigen-solve through an observation matrix (C Φ).
#include <Eigen/Core>
#include <string>
#include <vector>

#include "formats/uff.hpp"
#include "translators/measurement/sensor_mapping.hpp"

namespace ssid::translators {

/// Modes sampled at a list of measured DOFs (rows) — one column per mode.
struct ModeSet {
  std::vector<MeasuredDof> dofs;
  Eigen::MatrixXd shapes;           ///< dofs x modes
  std::vector<double> frequency_hz;
  std::vector<int> numbers;         ///< mode numbers as labelled in the source
  std::vector<double> damping;      ///< viscous damping ratio (0 when not given)
  std::vector<double> modal_mass;   ///< as given (0 when not given)
  /// Per mode, the identification's σ of the frequency [Hz] and of each component
  /// of the unit-normalised shape (`ssid identify modes --json`: "hz_std",
  /// "shape_std"); empty when the source gives none (UFF 55), NaN for a mode without.
  std::vector<double> frequency_std_hz;
  std::vector<double> shape_std;
};

/// What became of the 55 datasets of a file.
struct ModeSetReport {
  std::size_t complex_modes = 0;  ///< complex-mode datasets (reported, not used)
  std::size_t other = 0;          ///< 55 datasets of other analysis types
  std::vector<std::string> problems;
};

/// The real normal modes (analysis type 2) of a universal file. Rows are every
/// (node, component) present in every mode: components 1..NDV (at most 6) in the
/// global directions; a DOF that some mode lacks is dropped and reported. Modes
/// keep file order.
ModeSet modes_from_uff(const formats::uff::UffFile& file, ModeSetReport* report = nullptr);

/// A mode set as UFF 55 real normal modes (one dataset per mode, analysis type 2),
/// preceded by `nodes` as dataset 2411 when given. Nodes appear in the order of
/// their first DOF; NDV is 6 when any rotation is present, else 3. Components the
/// set does not hold are written as 0 — UFF 55 cannot mark a component unmeasured,
/// so keep the measured DOF list beside the file (or use 58 records) when it matters.
/// A negative direction is written as the negated value on the positive axis.
formats::uff::UffFile mode_set_to_uff(const ModeSet& set, const std::vector<formats::uff::Node>& nodes = {});

/// The nodes of a universal file (datasets 15 and 2411) as the mapping takes them.
std::vector<TestNode> test_nodes(const formats::uff::UffFile& file);

/// Segments between two nodes, (smaller id, larger id), each once, sorted.
using NodeSegments = std::vector<std::pair<std::int64_t, std::int64_t>>;

/// The test geometry's trace lines (dataset 82; node 0 lifts the pen) as segments.
NodeSegments trace_segments(const formats::uff::UffFile& file);

/// `segments` between test nodes as segments between the grids they map to: those whose
/// two nodes map to two different grids.
NodeSegments segments_in_grids(const NodeSegments& segments, const NodeMapping& mapping);

/// The measured DOFs named by the 58 functions of a file (response node and
/// signed direction), each once, in file order: the sensors of an FRF test.
std::vector<MeasuredDof> measured_dofs(const formats::uff::UffFile& file);

/// `set` restricted to the rows whose DOF is in `keep`, in the order of `keep`
/// (DOFs of `keep` the set lacks are skipped).
ModeSet restrict_to(const ModeSet& set, const std::vector<MeasuredDof>& keep);

/// The DOFs both sets hold, in the order of `a`.
std::vector<MeasuredDof> common_dofs(const ModeSet& a, const ModeSet& b);

/// Renames the nodes of a set's DOFs through a node mapping (test node → grid)
/// so it can be compared with a set labelled by grid ids; DOFs of unmapped nodes
/// are dropped.
ModeSet relabel(const ModeSet& set, const NodeMapping& mapping);

}  // namespace ssid::translators
