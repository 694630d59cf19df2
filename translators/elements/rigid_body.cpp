#include "translators/elements/rigid_body.hpp"

#include <stdexcept>

#include "translators/elements/transform.hpp"

namespace ssid::translators::elements {

Eigen::MatrixXd rigid_body_modes(const std::vector<Eigen::Vector3d>& positions,
                                 const std::vector<Eigen::Matrix3d>& frames, const Eigen::Vector3d& reference) {
  if (positions.size() != frames.size())
    throw std::invalid_argument("rigid_body_modes: one displacement frame per position is required");
  Eigen::MatrixXd phi(6 * positions.size(), 6);
  for (std::size_t i = 0; i < positions.size(); ++i)
    phi.block<6, 6>(6 * i, 0) =
        detail::dof6(frames[i]).transpose() * detail::rigid_offset(positions[i] - reference);
  return phi;
}

double rigid_body_residual(const Eigen::MatrixXd& K, const Eigen::MatrixXd& modes) {
  const double scale = K.norm() * modes.norm();
  return scale > 0 ? (K * modes).norm() / scale : 0.0;
}

}  // namespace ssid::translators::elements
