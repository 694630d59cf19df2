#include "translators/elements/point.hpp"

#include <Eigen/Geometry>
#include <stdexcept>

#include "translators/elements/transform.hpp"

namespace ssid::translators::elements {

Matrix6d conm2_matrix(const Conm2& c) {
  Eigen::Matrix3d I;
  I << c.i11, -c.i21, -c.i31, -c.i21, c.i22, -c.i32, -c.i31, -c.i32, c.i33;
  Matrix6d mcg = Matrix6d::Zero();
  mcg.topLeftCorner<3, 3>() = c.mass * Eigen::Matrix3d::Identity();
  mcg.bottomRightCorner<3, 3>() = c.inertia_frame * I * c.inertia_frame.transpose();
  const Matrix6d S = detail::rigid_offset(c.offset) * detail::dof6(c.t);
  return S.transpose() * mcg * S;
}

Matrix6d conm2_derivative(const Conm2& c, Conm2Param which) {
  Conm2 u = c;
  u.mass = u.i11 = u.i21 = u.i22 = u.i31 = u.i32 = u.i33 = 0;
  switch (which) {
    case Conm2Param::Mass: u.mass = 1; break;
    case Conm2Param::I11: u.i11 = 1; break;
    case Conm2Param::I21: u.i21 = 1; break;
    case Conm2Param::I22: u.i22 = 1; break;
    case Conm2Param::I31: u.i31 = 1; break;
    case Conm2Param::I32: u.i32 = 1; break;
    case Conm2Param::I33: u.i33 = 1; break;
  }
  return conm2_matrix(u);
}

Eigen::MatrixXd scalar_element_matrix(double value, bool grounded) {
  if (grounded) return Eigen::MatrixXd::Constant(1, 1, value);
  Eigen::MatrixXd m(2, 2);
  m << value, -value, -value, value;
  return m;
}

Eigen::Matrix3d bush_axes_from_vector(const Eigen::Vector3d& xa, const Eigen::Vector3d& xb,
                                      const Eigen::Vector3d& v) {
  const Eigen::Vector3d d = xb - xa;
  if (!(d.norm() > 0))
    throw std::invalid_argument("CBUSH: GA and GB coincide, so the element axes need CID");
  const Eigen::Vector3d x = d.normalized();
  const Eigen::Vector3d z = x.cross(v);
  if (!(z.norm() > 1e-9 * v.norm()))
    throw std::invalid_argument("CBUSH: orientation vector v is zero or parallel to GA-GB");
  Eigen::Matrix3d R;
  R.row(0) = x;
  R.row(2) = z.normalized();
  R.row(1) = R.row(2).cross(R.row(0));
  return R;
}

Eigen::MatrixXd bush_stiffness(const BushGeometry& g, const Eigen::Matrix<double, 6, 1>& k) {
  const Matrix6d E = detail::dof6(g.axes);
  const Matrix6d kd = k.asDiagonal();
  if (g.grounded) {
    const Matrix6d S = E * detail::dof6(g.grids.ta);
    return S.transpose() * kd * S;
  }
  const Eigen::Vector3d p = g.grids.xa + g.s * (g.grids.xb - g.grids.xa);
  Eigen::Matrix<double, 6, 12> D;
  D.leftCols<6>() = -E * detail::rigid_offset(p - g.grids.xa) * detail::dof6(g.grids.ta);
  D.rightCols<6>() = E * detail::rigid_offset(p - g.grids.xb) * detail::dof6(g.grids.tb);
  return D.transpose() * kd * D;
}

Eigen::MatrixXd bush_derivative(const BushGeometry& g, int i) {
  if (i < 1 || i > 6) throw std::invalid_argument("CBUSH stiffness index must be 1-6");
  Eigen::Matrix<double, 6, 1> k = Eigen::Matrix<double, 6, 1>::Zero();
  k(i - 1) = 1;
  return bush_stiffness(g, k);
}

}  // namespace ssid::translators::elements
