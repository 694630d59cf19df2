#pragma once
/// \file rigid_modes.hpp
/// The six rigid-body motions of a model's analysis set: the near-null space the
/// multilevel eigen-solver builds its coarse space from
/// (estimator/multilevel/aggregation_amg.hpp).
#include <Eigen/Core>

#include "translators/assembly/fe_model.hpp"

namespace ssid::translators {

/// a x 6: columns are unit translations along basic x, y, z and unit rotations
/// about basic axes through the origin (u = θ × x, rotation components θ), each
/// a-set DOF given in its grid's displacement frame (CD); scalar points get zero
/// rows. A rigid element or an SPC does not change these rows: the a-set DOFs are
/// independent ones, and a constrained model's rigid motions are still its
/// lowest-energy shapes locally.
Eigen::MatrixXd a_set_rigid_body_modes(const FeModel& model);

}  // namespace ssid::translators
