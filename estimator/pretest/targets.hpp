#pragma once
/// \file targets.hpp
/// Pretest planning, step 1: the target modes and the candidate sensor DOFs
/// (issue 23 item 1; seed report, pretest paper §3).
///
/// Works on an eigen-solution of the analysis set (estimator::EigenResult's
/// eigenvalues and modes) and the a-set's (grid, component) list, so it does
/// not depend on how the model was assembled.
#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "translators/dof_map.hpp"

namespace ssid::estimator::pretest {

/// Indices (columns of the eigen-solution) of the `count` lowest modes whose
/// frequency f = sqrt(λ)/2π is strictly above `min_hz` (Hz); rigid-body modes
/// fall below any positive `min_hz`. Throws formats::InputError when count < 1
/// or fewer than `count` such modes were solved for (saying how many there are).
std::vector<Eigen::Index> select_target_modes(const Eigen::Ref<const Eigen::VectorXd>& eigenvalues, int count,
                                              double min_hz);

/// A candidate sensor: one translational DOF of a grid, measured along the
/// grid's displacement frame (component 1, 2, 3 = T1, T2, T3 in CD), or, made
/// by measurement_coordinates (measurement_coordinates.hpp), along a given
/// direction (`directed`; its row is then a row of the measurement coordinates q).
struct CandidateDof {
  Eigen::Index row = 0;  ///< row of the a-set (of K, M and the modes)
  translators::Dof dof;  ///< grid and component (for a directed sensor: the a-set row's own)
  /// The measured direction, a unit vector in the grid's displacement frame:
  /// the component's axis, or the given direction of a directed sensor.
  Eigen::Vector3d direction = Eigen::Vector3d::Zero();
  bool directed = false;  ///< measures along a given direction, not along a component
};

/// How a sensor is named in reports: "T2", or the direction cosines "(0.6, 0.8, 0)".
std::string sensor_label(const CandidateDof& c);

/// The candidates: every translational DOF (components 1-3) of the a-set, or
/// only those of `grids` when it is not empty, in a-set order. Throws
/// formats::InputError for a listed grid that has no translational a-set DOF.
std::vector<CandidateDof> translational_candidates(const std::vector<translators::Dof>& a_set,
                                                   const std::vector<std::int64_t>& grids = {});

/// Groups of candidates on one grid (for triaxial placement): for each grid, in
/// order of first appearance, the positions in `candidates` of its DOFs.
std::vector<std::vector<Eigen::Index>> group_by_grid(const std::vector<CandidateDof>& candidates);

/// Rows `rows` of `A` (a dense gather).
Eigen::MatrixXd take_rows(const Eigen::Ref<const Eigen::MatrixXd>& A, const std::vector<Eigen::Index>& rows);

}  // namespace ssid::estimator::pretest
