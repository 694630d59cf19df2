#pragma once
/// \file lattice.hpp
/// The benchmarks' model: a free-free cubic lattice of N³ nodes 1 m apart, every
/// lattice edge a 3D Euler–Bernoulli frame element (6 DOF per node), lumped
/// translational mass (rotations massless, as NASTRAN lumps CBAR mass), and the
/// small timing helpers the benchmarks share. A private copy of the frame element:
/// the element library lives in translators/, and the benchmark must not move when
/// that changes.
#include <sys/resource.h>

#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <chrono>
#include <utility>
#include <vector>

namespace bench {

using SpMat = Eigen::SparseMatrix<double>;
using Mat12 = Eigen::Matrix<double, 12, 12>;

inline double cpu_s() {
  struct rusage ru {};
  getrusage(RUSAGE_SELF, &ru);
  return static_cast<double>(ru.ru_utime.tv_sec + ru.ru_stime.tv_sec) +
         1e-6 * static_cast<double>(ru.ru_utime.tv_usec + ru.ru_stime.tv_usec);
}

inline long peak_rss_mib() {
  struct rusage ru {};
  getrusage(RUSAGE_SELF, &ru);
  return ru.ru_maxrss / 1024;
}

inline double now_s() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

struct Section {
  double E = 2.1e11, G = 8.1e10, rho = 7850.0;
  double A = 1.0e-3, Iy = 1.0e-6, Iz = 1.0e-6, J = 2.0e-6;
};

/// Euler–Bernoulli 3D frame element stiffness in global axes, DOFs
/// (u, v, w, θx, θy, θz) at end a then end b. Local x runs a → b; local y is
/// the component of `ref` normal to x. K = Tᵀ K_local T, T = diag(R, R, R, R).
/// A private copy for the benchmark (the element library lives in translators/).
inline Mat12 frame_stiffness(const Eigen::Vector3d& xa, const Eigen::Vector3d& xb, const Eigen::Vector3d& ref,
                      const Section& s) {
  const Eigen::Vector3d d = xb - xa;
  const double L = d.norm(), L2 = L * L, L3 = L2 * L;
  const Eigen::Vector3d ex = d / L;
  const Eigen::Vector3d ey = (ref - ref.dot(ex) * ex).normalized();
  const Eigen::Vector3d ez = ex.cross(ey);
  Mat12 k = Mat12::Zero();
  const double ea = s.E * s.A / L, gj = s.G * s.J / L;
  k(0, 0) = k(6, 6) = ea;
  k(0, 6) = -ea;
  k(3, 3) = k(9, 9) = gj;
  k(3, 9) = -gj;
  // Bending in the local x-y plane (v, θz), inertia Iz.
  const double z = s.E * s.Iz;
  k(1, 1) = k(7, 7) = 12 * z / L3;
  k(1, 7) = -12 * z / L3;
  k(1, 5) = k(1, 11) = 6 * z / L2;
  k(5, 7) = k(7, 11) = -6 * z / L2;
  k(5, 5) = k(11, 11) = 4 * z / L;
  k(5, 11) = 2 * z / L;
  // Bending in the local x-z plane (w, θy), inertia Iy (signs: θy = −dw/dx).
  const double y = s.E * s.Iy;
  k(2, 2) = k(8, 8) = 12 * y / L3;
  k(2, 8) = -12 * y / L3;
  k(2, 4) = k(2, 10) = -6 * y / L2;
  k(4, 8) = k(8, 10) = 6 * y / L2;
  k(4, 4) = k(10, 10) = 4 * y / L;
  k(4, 10) = 2 * y / L;
  k = k.selfadjointView<Eigen::Upper>();
  Eigen::Matrix3d R;
  R.row(0) = ex;
  R.row(1) = ey;
  R.row(2) = ez;
  Mat12 T = Mat12::Zero();
  for (int b = 0; b < 4; ++b) T.block<3, 3>(3 * b, 3 * b) = R;
  return T.transpose() * k * T;
}

struct Model {
  SpMat K, M;
  long nodes = 0, elements = 0;
  int n = 0;  // nodes per edge
};

/// The six rigid-body modes of the lattice (translations, then rotations about
/// the origin: u = e × x, θ = e), its near-null space for the multilevel method.
inline Eigen::MatrixXd rigid_body_modes(const Model& m) {
  Eigen::MatrixXd B = Eigen::MatrixXd::Zero(6 * m.nodes, 6);
  const int n = m.n;
  for (long a = 0; a < m.nodes; ++a) {
    const Eigen::Vector3d x(static_cast<double>(a % n), static_cast<double>((a / n) % n), static_cast<double>(a / n / n));
    for (int c = 0; c < 3; ++c) {
      B(6 * a + c, c) = 1.0;
      const Eigen::Vector3d u = Eigen::Vector3d::Unit(c).cross(x);
      for (int d = 0; d < 3; ++d) B(6 * a + d, 3 + c) = u(d);
      B(6 * a + 3 + c, 3 + c) = 1.0;
    }
  }
  return B;
}

/// The six constant-strain fields u = E (x − x̄) of the lattice (rotations zero), the
/// same fields translators::a_set_strain_fields builds from a deck: the multilevel
/// method's coarse space takes them beside the rigid-body modes.
inline Eigen::MatrixXd strain_fields(const Model& m) {
  Eigen::MatrixXd F = Eigen::MatrixXd::Zero(6 * m.nodes, 6);
  const int n = m.n;
  const double c = 0.5 * (n - 1);
  for (long a = 0; a < m.nodes; ++a) {
    const Eigen::Vector3d x(a % n - c, (a / n) % n - c, a / n / n - c);
    int col = 0;
    for (int p = 0; p < 3; ++p)
      for (int q = p; q < 3; ++q, ++col) {
        F(6 * a + p, col) += 0.5 * x(q);
        F(6 * a + q, col) += 0.5 * x(p);
      }
  }
  return F;
}

inline Model lattice(int n, const Section& s) {
  Model m;
  m.n = n;
  auto id = [n](int i, int j, int k) { return (static_cast<long>(k) * n + j) * n + i; };
  m.nodes = static_cast<long>(n) * n * n;
  const long ndof = 6 * m.nodes;
  std::vector<Eigen::Triplet<double>> tk, tm;
  tk.reserve(static_cast<size_t>(3 * m.nodes) * 64);
  std::vector<double> mass(static_cast<size_t>(m.nodes), 0.0);
  // Elements along x, y, z from every node.
  const Eigen::Vector3d ref_for_x(0, 1, 0), ref_for_yz(1, 0, 0);
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        for (int dir = 0; dir < 3; ++dir) {
          const int i2 = i + (dir == 0), j2 = j + (dir == 1), k2 = k + (dir == 2);
          if (i2 >= n || j2 >= n || k2 >= n) continue;
          const long a = id(i, j, k), b = id(i2, j2, k2);
          const Eigen::Vector3d xa(i, j, k), xb(i2, j2, k2);
          const Mat12 ke = frame_stiffness(xa, xb, dir == 0 ? ref_for_x : ref_for_yz, s);
          const long dofs[2] = {6 * a, 6 * b};
          for (int r = 0; r < 12; ++r)
            for (int c = 0; c < 12; ++c)
              if (ke(r, c) != 0.0)
                tk.emplace_back(static_cast<int>(dofs[r / 6] + r % 6), static_cast<int>(dofs[c / 6] + c % 6), ke(r, c));
          const double half = 0.5 * s.rho * s.A * (xb - xa).norm();
          mass[static_cast<size_t>(a)] += half;
          mass[static_cast<size_t>(b)] += half;
          ++m.elements;
        }
  m.K.resize(ndof, ndof);
  m.K.setFromTriplets(tk.begin(), tk.end());
  m.K.makeCompressed();
  std::vector<Eigen::Triplet<double>>().swap(tk);
  tm.reserve(static_cast<size_t>(ndof));
  for (long a = 0; a < m.nodes; ++a)
    for (int c = 0; c < 6; ++c) tm.emplace_back(static_cast<int>(6 * a + c), static_cast<int>(6 * a + c),
                                                 c < 3 ? mass[static_cast<size_t>(a)] : 0.0);
  m.M.resize(ndof, ndof);
  m.M.setFromTriplets(tm.begin(), tm.end());
  m.M.makeCompressed();
  return m;
}

/// Wall and CPU seconds of one call.
template <class F>
std::pair<double, double> timed(F&& f) {
  const double w = now_s(), c = cpu_s();
  f();
  return {now_s() - w, cpu_s() - c};
}

}  // namespace bench
