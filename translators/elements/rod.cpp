#include "translators/elements/rod.hpp"

#include <stdexcept>

#include "translators/elements/complex_step.hpp"
#include "translators/elements/transform.hpp"

namespace ssid::translators::elements {

namespace {
using detail::Complex;

/// K, M in basic (before the CD frames) for scalar T.
template <class T>
void rod_basic(const GridPair& g, const T& a, const T& j, const T& nsm, const T& e, const T& gm, const T& rho,
               MassKind mass, Eigen::Matrix<T, 12, 12>& k, Eigen::Matrix<T, 12, 12>& m) {
  const Eigen::Vector3d d = g.xb - g.xa;
  const double L = d.norm();
  if (!(L > 0)) throw std::invalid_argument("rod: grids GA and GB coincide");
  const Eigen::Matrix3d ee = (d / L) * (d / L).transpose();
  const Eigen::Matrix<T, 3, 3> eeT = ee.cast<T>();
  const T ka = e * a / L, kt = gm * j / L;
  k.setZero();
  m.setZero();
  for (int p = 0; p < 2; ++p)
    for (int q = 0; q < 2; ++q) {
      const double s = p == q ? 1.0 : -1.0;
      k.template block<3, 3>(6 * p, 6 * q) = eeT * (ka * s);
      k.template block<3, 3>(6 * p + 3, 6 * q + 3) = eeT * (kt * s);
    }
  const T mu = rho * a + nsm;
  const Eigen::Matrix<T, 3, 3> I3 = Eigen::Matrix<T, 3, 3>::Identity();
  if (mass == MassKind::Lumped) {
    m.template block<3, 3>(0, 0) = I3 * (mu * L / 2.0);
    m.template block<3, 3>(6, 6) = I3 * (mu * L / 2.0);
  } else {
    for (int p = 0; p < 2; ++p)
      for (int q = 0; q < 2; ++q) m.template block<3, 3>(6 * p, 6 * q) = I3 * (mu * L / 6.0 * (p == q ? 2.0 : 1.0));
  }
}

ElementMatrices eval_raw(const GridPair& g, const RodSection& s, const Material& mat, MassKind mass,
                         const RodSection& ds, const Material& dmat, bool derivative) {
  const Matrix12d T = detail::grid_frames(g.ta, g.tb);
  ElementMatrices out;
  if (!derivative) {
    Matrix12d k, m;
    rod_basic<double>(g, s.a, s.j, s.nsm, mat.e, mat.g, mat.rho, mass, k, m);
    out.k = T.transpose() * k * T;
    out.m = T.transpose() * m * T;
    return out;
  }
  const Complex h(0.0, detail::kComplexStep);
  Eigen::Matrix<Complex, 12, 12> k, m;
  rod_basic<Complex>(g, s.a + h * ds.a, s.j + h * ds.j, s.nsm + h * ds.nsm, mat.e + h * dmat.e, mat.g + h * dmat.g,
                     mat.rho + h * dmat.rho, mass, k, m);
  out.k = T.transpose() * (k.imag() / detail::kComplexStep) * T;
  out.m = T.transpose() * (m.imag() / detail::kComplexStep) * T;
  return out;
}

ElementMatrices eval(const GridPair& g, const RodSection& s, const Material& mat, MassKind mass,
                     const RodSection& ds, const Material& dmat, bool derivative) {
  ElementMatrices out = eval_raw(g, s, mat, mass, ds, dmat, derivative);
  // Exact symmetry (Tᵀ K T is symmetric only to rounding).
  out.k = (0.5 * (out.k + out.k.transpose())).eval();
  out.m = (0.5 * (out.m + out.m.transpose())).eval();
  return out;
}
}  // namespace

ElementMatrices rod_matrices(const GridPair& g, const RodSection& s, const Material& mat, MassKind mass) {
  return eval(g, s, mat, mass, {}, {}, false);
}

ElementMatrices rod_directional_derivative(const GridPair& g, const RodSection& s, const Material& mat,
                                           MassKind mass, const RodSection& ds, const Material& dmat) {
  return eval(g, s, mat, mass, ds, dmat, true);
}

ElementMatrices rod_derivative(const GridPair& g, const RodSection& s, const Material& mat, MassKind mass,
                               RodParam which) {
  RodSection ds;
  Material dm;
  switch (which) {
    case RodParam::A: ds.a = 1; break;
    case RodParam::J: ds.j = 1; break;
    case RodParam::Nsm: ds.nsm = 1; break;
    case RodParam::E: dm.e = 1; break;
    case RodParam::G: dm.g = 1; break;
    case RodParam::Rho: dm.rho = 1; break;
  }
  return rod_directional_derivative(g, s, mat, mass, ds, dm);
}

}  // namespace ssid::translators::elements
