#include "translators/elements/bar.hpp"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <stdexcept>
#include <vector>

#include "translators/elements/complex_step.hpp"
#include "translators/elements/transform.hpp"

namespace ssid::translators::elements {

namespace {
using detail::Complex;
using detail::real_part;
template <class T>
using Mat12 = Eigen::Matrix<T, 12, 12>;
template <class T>
using Mat4 = Eigen::Matrix<T, 4, 4>;
template <class T>
using MatX = Eigen::Matrix<T, Eigen::Dynamic, Eigen::Dynamic>;

template <class T>
struct Props {
  T a, i1, i2, i12, j, nsm, k1, k2, e, g, rho;
};

template <class T>
Props<T> combine(const BarSection& s, const Material& m, const BarSection& ds, const Material& dm, const T& h) {
  return {s.a + h * ds.a,     s.i1 + h * ds.i1, s.i2 + h * ds.i2,  s.i12 + h * ds.i12,
          s.j + h * ds.j,     s.nsm + h * ds.nsm, s.k1 + h * ds.k1, s.k2 + h * ds.k2,
          m.e + h * dm.e,     m.g + h * dm.g,   m.rho + h * dm.rho};
}

/// Timoshenko bending matrix for E I = 1 in (v_a, θ_a, v_b, θ_b), θ = v'.
template <class T>
Mat4<T> bending(double L, const T& phi) {
  const double L2 = L * L;
  Mat4<T> k;
  k << T(12), T(6 * L), T(-12), T(6 * L),  //
      T(6 * L), (4.0 + phi) * L2, T(-6 * L), (2.0 - phi) * L2,  //
      T(-12), T(-6 * L), T(12), T(-6 * L),  //
      T(6 * L), (2.0 - phi) * L2, T(-6 * L), (4.0 + phi) * L2;
  return k / ((1.0 + phi) * L * L2);
}

/// Consistent Hermite mass for μ = 1 in the same DOFs.
Eigen::Matrix4d hermite_mass(double L) {
  Eigen::Matrix4d m;
  m << 156, 22 * L, 54, -13 * L,  //
      22 * L, 4 * L * L, 13 * L, -3 * L * L,  //
      54, 13 * L, 156, -22 * L,  //
      -13 * L, -3 * L * L, -22 * L, 4 * L * L;
  return m * (L / 420.0);
}

/// Scatter a 4x4 plane matrix into 12x12 between planes p and q.
/// Plane 1: (v_a, θz_a, v_b, θz_b); plane 2: (w_a, −θy_a, w_b, −θy_b).
template <class T, class M4>
void add_planes(Mat12<T>& K, const M4& kb, int p, int q, const T& factor) {
  static const int idx[2][4] = {{1, 5, 7, 11}, {2, 4, 8, 10}};
  static const double sgn[2][4] = {{1, 1, 1, 1}, {1, -1, 1, -1}};
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) K(idx[p][r], idx[q][c]) += factor * sgn[p][r] * sgn[q][c] * T(kb(r, c));
}

template <class T>
void add_pair(Mat12<T>& K, int i, int j, const T& v, const T& off) {
  K(i, i) += v, K(j, j) += v, K(i, j) += off, K(j, i) += off;
}

std::vector<int> released_dofs(int pa, int pb) {
  std::vector<int> out;
  for (int end = 0; end < 2; ++end) {
    int p = end == 0 ? pa : pb;
    if (p < 0) throw std::invalid_argument("pin flags must be digits 1-6, got " + std::to_string(p));
    for (; p > 0; p /= 10) {
      const int d = p % 10;
      if (d < 1 || d > 6)
        throw std::invalid_argument("pin flag " + std::to_string(end == 0 ? pa : pb) + " has digit " +
                                    std::to_string(d) + " (expected 1-6)");
      const int i = 6 * end + d - 1;
      bool seen = false;
      for (int x : out) seen |= x == i;
      if (!seen) out.push_back(i);
    }
  }
  return out;
}

/// Local (element-frame) K and M.
template <class T>
void local_matrices(double L, const Props<T>& p, MassKind mass, bool torsion_lumped, const std::vector<int>& released,
                    Mat12<T>& K, Mat12<T>& M) {
  K.setZero();
  M.setZero();
  add_pair<T>(K, 0, 6, p.e * p.a / L, -p.e * p.a / L);
  add_pair<T>(K, 3, 9, p.g * p.j / L, -p.g * p.j / L);
  // PBAR remark 4: K1, K2 are ignored when I12 is not zero.
  const bool shear = real_part(p.i12) == 0.0;
  const T zero(0);
  const T phi1 = shear && real_part(p.k1) > 0 ? 12.0 * p.e * p.i1 / (p.k1 * p.a * p.g * L * L) : zero;
  const T phi2 = shear && real_part(p.k2) > 0 ? 12.0 * p.e * p.i2 / (p.k2 * p.a * p.g * L * L) : zero;
  add_planes<T>(K, bending<T>(L, phi1), 0, 0, p.e * p.i1);
  add_planes<T>(K, bending<T>(L, phi2), 1, 1, p.e * p.i2);
  const Mat4<T> kb0 = bending<T>(L, zero);
  add_planes<T>(K, kb0, 0, 1, p.e * p.i12);
  add_planes<T>(K, kb0, 1, 0, p.e * p.i12);

  const T mu = p.rho * p.a + p.nsm;
  const T polar = p.rho * (p.i1 + p.i2);
  if (mass == MassKind::Lumped) {
    for (int i : {0, 1, 2, 6, 7, 8}) M(i, i) = mu * L / 2.0;
    if (torsion_lumped) M(3, 3) = M(9, 9) = polar * L / 2.0;
  } else {
    add_pair<T>(M, 0, 6, mu * L / 3.0, mu * L / 6.0);
    add_pair<T>(M, 3, 9, polar * L / 3.0, polar * L / 6.0);
    const Eigen::Matrix4d mh = hermite_mass(L);
    add_planes<T>(M, mh, 0, 0, mu);
    add_planes<T>(M, mh, 1, 1, mu);
  }
  if (released.empty()) return;

  // Static condensation of the released DOFs (kept r, released c).
  std::vector<int> kept;
  for (int i = 0; i < 12; ++i) {
    bool rel = false;
    for (int x : released) rel |= x == i;
    if (!rel) kept.push_back(i);
  }
  const int nr = static_cast<int>(kept.size()), nc = static_cast<int>(released.size());
  MatX<T> Kcc(nc, nc), Kcr(nc, nr);
  for (int a = 0; a < nc; ++a) {
    for (int b = 0; b < nc; ++b) Kcc(a, b) = K(released[a], released[b]);
    for (int b = 0; b < nr; ++b) Kcr(a, b) = K(released[a], kept[b]);
  }
  Eigen::FullPivLU<MatX<T>> lu(Kcc);
  if (!lu.isInvertible())
    throw std::invalid_argument("pin flags release DOFs that have no stiffness of their own (a mechanism)");
  const MatX<T> X = lu.solve(Kcr);  // u_c = −X u_r
  MatX<T> G = MatX<T>::Zero(12, nr);  // u = G u_r
  for (int b = 0; b < nr; ++b) G(kept[b], b) = T(1);
  for (int a = 0; a < nc; ++a)
    for (int b = 0; b < nr; ++b) G(released[a], b) = -X(a, b);
  const MatX<T> Kr = G.transpose() * K * G;
  const MatX<T> Mr = G.transpose() * M * G;
  K.setZero();
  if (mass == MassKind::Coupled) M.setZero();
  for (int a = 0; a < nr; ++a)
    for (int b = 0; b < nr; ++b) {
      K(kept[a], kept[b]) = Kr(a, b);
      if (mass == MassKind::Coupled) M(kept[a], kept[b]) = Mr(a, b);
    }
}

/// Local element DOFs from global grid DOFs: u_local = T u_global.
Matrix12d global_to_local(const BarGeometry& g, const Eigen::Matrix3d& R) {
  Matrix12d T = Matrix12d::Zero();
  Matrix6d RR = Matrix6d::Zero();
  RR.topLeftCorner<3, 3>() = R;
  RR.bottomRightCorner<3, 3>() = R;
  const Matrix6d ta = detail::dof6(g.grids.ta), tb = detail::dof6(g.grids.tb);
  T.topLeftCorner<6, 6>() = RR * detail::rigid_offset(g.wa) * ta;
  T.bottomRightCorner<6, 6>() = RR * detail::rigid_offset(g.wb) * tb;
  return T;
}

ElementMatrices eval(const BarGeometry& g, const BarSection& s, const Material& mat, MassKind mass, bool torsion,
                     const BarSection* ds, const Material* dm) {
  const Eigen::Matrix3d R = bar_element_axes(g);
  const double L = ((g.grids.xb + g.wb) - (g.grids.xa + g.wa)).norm();
  const std::vector<int> released = released_dofs(g.pa, g.pb);
  const Matrix12d T = global_to_local(g, R);
  ElementMatrices out;
  if (!ds) {
    Mat12<double> K, M;
    local_matrices<double>(L, combine<double>(s, mat, {}, {}, 0.0), mass, torsion, released, K, M);
    out.k = T.transpose() * K * T;
    out.m = T.transpose() * M * T;
  } else {
    Mat12<Complex> K, M;
    const Complex h(0.0, detail::kComplexStep);
    local_matrices<Complex>(L, combine<Complex>(s, mat, *ds, *dm, h), mass, torsion, released, K, M);
    out.k = T.transpose() * (K.imag() / detail::kComplexStep) * T;
    out.m = T.transpose() * (M.imag() / detail::kComplexStep) * T;
  }
  // Exact symmetry (the products above are symmetric only to rounding).
  out.k = (0.5 * (out.k + out.k.transpose())).eval();
  out.m = (0.5 * (out.m + out.m.transpose())).eval();
  return out;
}

void unit(BarParam which, BarSection& ds, Material& dm) {
  switch (which) {
    case BarParam::A: ds.a = 1; break;
    case BarParam::I1: ds.i1 = 1; break;
    case BarParam::I2: ds.i2 = 1; break;
    case BarParam::I12: ds.i12 = 1; break;
    case BarParam::J: ds.j = 1; break;
    case BarParam::Nsm: ds.nsm = 1; break;
    case BarParam::K1: ds.k1 = 1; break;
    case BarParam::K2: ds.k2 = 1; break;
    case BarParam::E: dm.e = 1; break;
    case BarParam::G: dm.g = 1; break;
    case BarParam::Rho: dm.rho = 1; break;
  }
}
}  // namespace

Eigen::Matrix3d bar_element_axes(const BarGeometry& g) {
  const Eigen::Vector3d d = (g.grids.xb + g.wb) - (g.grids.xa + g.wa);
  const double L = d.norm();
  if (!(L > 0)) throw std::invalid_argument("CBAR/CBEAM: ends A and B (grids plus offsets) coincide");
  const Eigen::Vector3d x = d / L;
  const Eigen::Vector3d z = x.cross(g.v);
  if (!(z.norm() > 1e-9 * g.v.norm()))
    throw std::invalid_argument("CBAR/CBEAM: orientation vector v is zero or parallel to the element axis");
  Eigen::Matrix3d R;
  R.row(0) = x;
  R.row(2) = z.normalized();
  R.row(1) = R.row(2).cross(R.row(0));
  return R;
}

ElementMatrices bar_matrices(const BarGeometry& g, const BarSection& s, const Material& mat, MassKind mass,
                             bool barmass) {
  return eval(g, s, mat, mass, barmass, nullptr, nullptr);
}
ElementMatrices bar_directional_derivative(const BarGeometry& g, const BarSection& s, const Material& mat,
                                           MassKind mass, const BarSection& ds, const Material& dmat, bool barmass) {
  return eval(g, s, mat, mass, barmass, &ds, &dmat);
}
ElementMatrices bar_derivative(const BarGeometry& g, const BarSection& s, const Material& mat, MassKind mass,
                               BarParam which, bool barmass) {
  BarSection ds;
  Material dm;
  unit(which, ds, dm);
  return eval(g, s, mat, mass, barmass, &ds, &dm);
}

ElementMatrices beam_matrices(const BarGeometry& g, const BarSection& s, const Material& mat, MassKind mass) {
  return eval(g, s, mat, mass, true, nullptr, nullptr);
}
ElementMatrices beam_directional_derivative(const BarGeometry& g, const BarSection& s, const Material& mat,
                                            MassKind mass, const BarSection& ds, const Material& dmat) {
  return eval(g, s, mat, mass, true, &ds, &dmat);
}
ElementMatrices beam_derivative(const BarGeometry& g, const BarSection& s, const Material& mat, MassKind mass,
                                BarParam which) {
  BarSection ds;
  Material dm;
  unit(which, ds, dm);
  return eval(g, s, mat, mass, true, &ds, &dm);
}

}  // namespace ssid::translators::elements
