#pragma once
/// \file rigid_modes.hpp
/// The low-energy displacement fields of a model's analysis set that the
/// multilevel eigen-solver builds its coarse space from
/// (estimator/eigen/multilevel/aggregation_amg.hpp): the six rigid-body motions, and the
/// six constant-strain fields.
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

/// a x 6: the constant-strain fields u = E (x − x̄), E the symmetric unit tensors
/// (e_x e_xᵀ, sym(e_x e_yᵀ), sym(e_x e_zᵀ), e_y e_yᵀ, sym(e_y e_zᵀ), e_z e_zᵀ; sym(A) =
/// (A + Aᵀ)/2) in basic axes, x̄ the mean position of the model's grids, rotation
/// components zero (the curl of a symmetric gradient vanishes), each a-set DOF in
/// its grid's displacement frame (CD); scalar points get zero rows.
///
/// Why: with the rigid-body modes, they make the coarse space of the multilevel
/// solver linear in each aggregate rather than piecewise rigid. A piecewise-rigid
/// space bends too stiffly: the 94k-DOF benchmark lattice's coarse model put its
/// first elastic eigenvalue 2.8x too high (frequency 1.7x); with these fields 1.15x
/// (frequency 1.07x, and with a prolongator smoothed once instead of twice), and
/// LOBPCG took 17 iterations instead of 25 (docs/performance.md).
Eigen::MatrixXd a_set_strain_fields(const FeModel& model);

}  // namespace ssid::translators
