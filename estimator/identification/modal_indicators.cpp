#include "estimator/identification/modal_indicators.hpp"

#include <cmath>
#include <fmt/format.h>

#include "formats/parse_error.hpp"

namespace ssid::estimator::identification {

using cd = std::complex<double>;

double modal_phase_collinearity(const Eigen::Ref<const Eigen::VectorXcd>& phi) {
  const double h = phi.squaredNorm();
  if (!(h > 0)) return 0.0;
  const cd t = (phi.transpose() * phi)(0, 0);
  return std::norm(t) / (h * h);
}

double principal_phase(const Eigen::Ref<const Eigen::VectorXcd>& phi) {
  const cd t = (phi.transpose() * phi)(0, 0);
  return 0.5 * std::arg(t);
}

double mean_phase_deviation(const Eigen::Ref<const Eigen::VectorXcd>& phi) {
  const double theta = principal_phase(phi);
  double num = 0, den = 0;
  for (Eigen::Index j = 0; j < phi.size(); ++j) {
    const double a = std::abs(phi(j));
    if (a == 0) continue;
    // Angle to the line (not the ray): fold into [0, π/2].
    double d = std::fmod(std::abs(std::arg(phi(j)) - theta), M_PI);
    if (d > M_PI / 2) d = M_PI - d;
    num += a * d;
    den += a;
  }
  return den > 0 ? num / den * 180.0 / M_PI : 0.0;
}

double complex_mac(const Eigen::Ref<const Eigen::VectorXcd>& a, const Eigen::Ref<const Eigen::VectorXcd>& b) {
  const double aa = a.squaredNorm(), bb = b.squaredNorm();
  if (!(aa > 0 && bb > 0)) return 0.0;
  return std::norm(a.dot(b)) / (aa * bb);
}

Eigen::VectorXcd rotate_to_real(const Eigen::Ref<const Eigen::VectorXcd>& phi) {
  Eigen::VectorXcd r = phi * std::polar(1.0, -principal_phase(phi));
  Eigen::Index big = 0;
  if (r.size() > 0) r.cwiseAbs().maxCoeff(&big);
  if (r.size() > 0 && r(big).real() < 0) r = -r;
  return r;
}

Eigen::VectorXd real_mode(const Eigen::Ref<const Eigen::VectorXcd>& phi) { return rotate_to_real(phi).real(); }

Eigen::VectorXcd unit_modal_mass_shape(const Eigen::Ref<const Eigen::VectorXcd>& residue_column, cd pole,
                                       Eigen::Index driving_point) {
  if (driving_point < 0 || driving_point >= residue_column.size())
    throw formats::InputError(fmt::format("modal scaling: driving point {} out of range (0 … {})", driving_point,
                                          residue_column.size() - 1));
  const cd two_i_wd(0.0, 2.0 * pole.imag());
  const cd phi_p = std::sqrt(two_i_wd * residue_column(driving_point));
  if (std::abs(phi_p) == 0)
    throw formats::InputError("modal scaling: zero residue at the driving point (the mode is not excited there)");
  Eigen::VectorXcd phi = two_i_wd * residue_column / phi_p;
  const Eigen::VectorXcd signed_shape = rotate_to_real(phi);
  // rotate_to_real may flip the sign only (θ₀ ≈ 0 or π for a near-real φ); keep the phase of φ otherwise.
  if ((signed_shape.dot(phi)).real() < 0) phi = -phi;
  return phi;
}

}  // namespace ssid::estimator::identification
