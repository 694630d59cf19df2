#pragma once
/// \file rigid_body.hpp
/// Rigid-body checks for element matrices: an element's stiffness must do no
/// work in a rigid motion of its grids, K Φ = 0.
#include <Eigen/Core>
#include <vector>

namespace ssid::translators::elements {

/// Rigid-body modes (6 columns: translations x, y, z and rotations about x, y,
/// z through `reference`, all in basic) of a set of grids, each row block in
/// its grid's displacement frame: rows 6i..6i+5 = blockdiag(tᵢᵀ, tᵢᵀ)
/// [I −[xᵢ − x0]×; 0 I].
Eigen::MatrixXd rigid_body_modes(const std::vector<Eigen::Vector3d>& positions,
                                 const std::vector<Eigen::Matrix3d>& frames,
                                 const Eigen::Vector3d& reference = Eigen::Vector3d::Zero());

/// ‖K Φ‖_F / (‖K‖_F ‖Φ‖_F): zero (to rounding) for a stiffness that admits
/// the rigid-body motions Φ.
double rigid_body_residual(const Eigen::MatrixXd& K, const Eigen::MatrixXd& modes);

}  // namespace ssid::translators::elements
