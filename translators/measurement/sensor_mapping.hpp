#pragma once
/// \file sensor_mapping.hpp
/// Test nodes to FE grids, and measured test DOFs to FE DOFs.
///
/// Works on plain data (ids, positions in the basic system, the grid's
/// displacement frame) so it does not depend on how grid cards are typed.
/// A test node maps to the grid with the same id, or to the nearest grid within
/// a tolerance; nodes that map nowhere are reported, never dropped silently.
/// A measured DOF is a node and a signed direction (UFF 58 convention: ±1, ±2,
/// ±3 = ±X, ±Y, ±Z translations, ±4..±6 rotations about them), in the global
/// (basic) system. The FE components of a grid are in its displacement frame
/// (NASTRAN's CD), so a measured direction is in general a combination of the
/// grid's three components: the observation row
///   z = s · e_aᵀ R u_cd = Σ_c s R(a, c) u_cd(c),
/// with s the sign, a the axis and R the frame's axes as columns in basic.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "translators/dof_map.hpp"

namespace ssid::translators {

/// A grid on plain data.
struct GridPosition {
  std::int64_t id = 0;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  ///< in the basic system
  /// Axes of the grid's displacement system (CD) as columns, in basic; identity for CD = 0.
  Eigen::Matrix3d frame = Eigen::Matrix3d::Identity();
};

/// A test node on plain data (from UFF 15/2411).
struct TestNode {
  std::int64_t id = 0;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  ///< global (test) system
  int displacement_cs = 0;  ///< 0: directions are global; otherwise a local system ssid does not apply
};

enum class MapBy {
  Id,            ///< grid with the same id
  Position,      ///< nearest grid within the tolerance
  IdThenPosition ///< same id when such a grid exists, else nearest within the tolerance
};

struct NodeMapOptions {
  MapBy by = MapBy::Id;
  double tolerance = 0;  ///< distance, in model units; needed (> 0) for position matching
};

struct NodeMatch {
  std::int64_t test_node = 0;
  std::int64_t grid = 0;
  double distance = 0;  ///< test node to grid (0 when matched by id without positions)
  bool by_position = false;
};

struct NodeMapping {
  std::vector<NodeMatch> matches;
  std::vector<std::int64_t> unmapped;  ///< test nodes with no grid
  /// Why each unmapped node maps nowhere, e.g. "no grid with this id".
  std::map<std::int64_t, std::string> why_unmapped;
  std::vector<std::string> problems;   ///< why nodes are unmapped, shared grids, local systems

  /// The grid a test node maps to.
  std::optional<std::int64_t> grid_of(std::int64_t test_node) const;
};

/// Maps test nodes to grids. Throws std::invalid_argument when position matching
/// is asked without a positive tolerance.
NodeMapping map_test_nodes(const std::vector<TestNode>& nodes, const std::vector<GridPosition>& grids,
                           const NodeMapOptions& options);

/// A measured DOF: test node and signed direction (±1..±6).
struct MeasuredDof {
  std::int64_t node = 0;
  int direction = 1;
  bool operator==(const MeasuredDof& o) const { return node == o.node && direction == o.direction; }
};

/// Refuses measured DOFs on test nodes that map to no grid: a sensor the model
/// cannot see, which left out would estimate or correlate on part of the data
/// (and, with a misnumbered test, on the wrong data) without a word. Throws
/// formats::InputError naming each such node and why, `model` saying where the
/// grids come from (e.g. "the deck rod.bdf"), `test` (the measured file) leading:
///   "test.unv: test node 5: no grid with this id in the deck rod.bdf"
/// or, for several, "test.unv: 3 measured test nodes map to no grid of the deck
/// rod.bdf:" and one "  test node 5: no grid with this id" a line (ten at most).
/// Test nodes with no measured DOF (geometry only) are not checked.
void require_mapped(const std::vector<MeasuredDof>& measured, const NodeMapping& mapping, const std::string& test,
                    const std::string& model);

/// One measured DOF in terms of FE DOFs: value = Σ coefficient · u(dof).
struct ObservationRow {
  MeasuredDof measured;
  std::vector<std::pair<Dof, double>> terms;
};

struct Observation {
  std::vector<ObservationRow> rows;          ///< one per mapped measured DOF, in the order given
  std::vector<MeasuredDof> unmapped;         ///< measured DOFs whose node maps to no grid
};

/// Builds the observation rows of measured DOFs through a node mapping.
/// Throws std::invalid_argument for a direction outside ±1..±6.
Observation observe(const std::vector<MeasuredDof>& measured, const NodeMapping& mapping,
                    const std::vector<GridPosition>& grids);

/// The observation as a sparse matrix C (rows: measured DOFs, columns: the DOFs of
/// `dofs`) so that test shapes ≈ C Φ. A term on a DOF the map does not hold
/// (constrained, hence zero) is dropped.
Eigen::SparseMatrix<double> observation_matrix(const Observation& obs, const DofMap& dofs);

}  // namespace ssid::translators
