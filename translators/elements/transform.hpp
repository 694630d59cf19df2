#pragma once
/// \file transform.hpp
/// Internal helpers shared by the element routines (namespace detail).
#include <Eigen/Core>

#include "translators/elements/element_types.hpp"

namespace ssid::translators::elements::detail {

/// Skew matrix: skew(w) * v = w × v.
inline Eigen::Matrix3d skew(const Eigen::Vector3d& w) {
  Eigen::Matrix3d s;
  s << 0, -w(2), w(1), w(2), 0, -w(0), -w(1), w(0), 0;
  return s;
}

/// blockdiag(ta, ta, tb, tb): grid displacement frames to basic for a
/// two-grid element (u_basic = T u_global).
inline Matrix12d grid_frames(const Eigen::Matrix3d& ta, const Eigen::Matrix3d& tb) {
  Matrix12d T = Matrix12d::Zero();
  T.block<3, 3>(0, 0) = ta;
  T.block<3, 3>(3, 3) = ta;
  T.block<3, 3>(6, 6) = tb;
  T.block<3, 3>(9, 9) = tb;
  return T;
}

/// Rigid offset: motion (basic) of the point x_grid + w from the grid's
/// motion (basic): u_p = u + θ × w, θ_p = θ.
inline Matrix6d rigid_offset(const Eigen::Vector3d& w) {
  Matrix6d S = Matrix6d::Identity();
  S.block<3, 3>(0, 3) = -skew(w);
  return S;
}

}  // namespace ssid::translators::elements::detail

namespace ssid::translators::elements::detail {
/// blockdiag(t, t) for one grid.
inline Matrix6d dof6(const Eigen::Matrix3d& t) {
  Matrix6d T = Matrix6d::Zero();
  T.topLeftCorner<3, 3>() = t;
  T.bottomRightCorner<3, 3>() = t;
  return T;
}
}  // namespace ssid::translators::elements::detail
