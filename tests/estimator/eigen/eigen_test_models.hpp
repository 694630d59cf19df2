#pragma once
// Small models with known spectra for the eigen-solver tests.
#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <random>
#include <vector>

namespace ssid::test {

using SpMat = Eigen::SparseMatrix<double>;
using Triplets = std::vector<Eigen::Triplet<double>>;

/// Spring k between DOFs a and b (b < 0: grounded).
inline void add_spring(Triplets& t, int a, int b, double k) {
  t.emplace_back(a, a, k);
  if (b >= 0) {
    t.emplace_back(b, b, k);
    t.emplace_back(a, b, -k);
    t.emplace_back(b, a, -k);
  }
}

inline SpMat from_triplets(int n, const Triplets& t) {
  SpMat A(n, n);
  A.setFromTriplets(t.begin(), t.end());
  A.makeCompressed();
  return A;
}

/// Chain of n masses m joined by n − 1 springs k; `grounded_ends`: springs to
/// ground at both ends too (fixed-fixed). Closed form:
///   fixed-fixed λ_j = 4k/m sin²(jπ / (2(n+1))), j = 1..n
///   free-free   λ_j = 4k/m sin²(jπ / (2n)),     j = 0..n−1 (one zero mode)
inline SpMat chain_stiffness(int n, double k, bool grounded_ends) {
  Triplets t;
  for (int i = 0; i + 1 < n; ++i) add_spring(t, i, i + 1, k);
  if (grounded_ends) {
    add_spring(t, 0, -1, k);
    add_spring(t, n - 1, -1, k);
  }
  return from_triplets(n, t);
}

inline SpMat diagonal(const Eigen::VectorXd& d) {
  Triplets t;
  for (int i = 0; i < d.size(); ++i) t.emplace_back(i, i, d(i));
  return from_triplets(static_cast<int>(d.size()), t);
}

/// Random sparse SPD pencil (K, M) with fixed seed: K = BᵀB + shift I from a
/// sparse random B, M = CᵀC + I (consistent, not diagonal).
inline std::pair<SpMat, SpMat> random_pencil(int n, unsigned seed, double density = 0.15) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0), p(0.0, 1.0);
  auto random_sparse = [&](double dens) {
    Triplets t;
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j)
        if (i == j || p(rng) < dens) t.emplace_back(i, j, u(rng));
    return from_triplets(n, t);
  };
  const SpMat B = random_sparse(density), C = random_sparse(density / 2);
  SpMat I(n, n);
  I.setIdentity();
  SpMat K = SpMat(B.transpose() * B) + 0.1 * I;
  SpMat M = SpMat(C.transpose() * C) * 0.1 + I;
  K.makeCompressed();
  M.makeCompressed();
  return {K, M};
}

/// A free 3D pin-jointed truss: all pairs of the 8 corners of a box joined by
/// rods (axial stiffness EA/L along the rod), 3 DOF per node, unit lumped mass.
/// The complete graph is rigid, so it has exactly six zero eigenvalues.
inline std::pair<SpMat, SpMat> free_box_truss() {
  std::vector<Eigen::Vector3d> x;
  for (int i = 0; i < 8; ++i) x.emplace_back(1.0 * (i & 1), 1.5 * ((i >> 1) & 1), 2.0 * ((i >> 2) & 1));
  Triplets t;
  for (int a = 0; a < 8; ++a)
    for (int b = a + 1; b < 8; ++b) {
      const Eigen::Vector3d d = x[b] - x[a];
      const double L = d.norm();
      const Eigen::Vector3d e = d / L;
      const Eigen::Matrix3d k = (1000.0 / L) * e * e.transpose();
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) {
          t.emplace_back(3 * a + r, 3 * a + c, k(r, c));
          t.emplace_back(3 * b + r, 3 * b + c, k(r, c));
          t.emplace_back(3 * a + r, 3 * b + c, -k(r, c));
          t.emplace_back(3 * b + r, 3 * a + c, -k(r, c));
        }
    }
  return {from_triplets(24, t), diagonal(Eigen::VectorXd::Constant(24, 2.0))};
}

/// A free 3D pin-jointed lattice truss: nodes on an n x n x n grid 1 m apart,
/// each unit cube's 8 corners joined pairwise by rods (EA/L = 1000/L), so the
/// lattice is rigid: exactly six zero eigenvalues. 3 DOF per node, lumped mass
/// 2 per DOF. DOF (node a, component c) is row perm[3a + c] when `perm` is
/// given (a scrambled numbering), 3a + c otherwise.
inline std::pair<SpMat, SpMat> free_lattice_truss(int n, const std::vector<int>& perm = {}) {
  auto node = [n](int i, int j, int k) { return (k * n + j) * n + i; };
  const int nn = n * n * n;
  auto dof = [&perm](int a, int c) { return perm.empty() ? 3 * a + c : perm[static_cast<size_t>(3 * a + c)]; };
  Triplets t;
  for (int k = 0; k + 1 < n; ++k)
    for (int j = 0; j + 1 < n; ++j)
      for (int i = 0; i + 1 < n; ++i)
        for (int p = 0; p < 8; ++p)
          for (int q = p + 1; q < 8; ++q) {
            const Eigen::Vector3d xp(i + (p & 1), j + ((p >> 1) & 1), k + ((p >> 2) & 1));
            const Eigen::Vector3d xq(i + (q & 1), j + ((q >> 1) & 1), k + ((q >> 2) & 1));
            const int a = node(i + (p & 1), j + ((p >> 1) & 1), k + ((p >> 2) & 1));
            const int b = node(i + (q & 1), j + ((q >> 1) & 1), k + ((q >> 2) & 1));
            const Eigen::Vector3d d = xq - xp;
            const double L = d.norm();
            const Eigen::Matrix3d ke = (1000.0 / L) * (d / L) * (d / L).transpose();
            for (int r = 0; r < 3; ++r)
              for (int c = 0; c < 3; ++c) {
                t.emplace_back(dof(a, r), dof(a, c), ke(r, c));
                t.emplace_back(dof(b, r), dof(b, c), ke(r, c));
                t.emplace_back(dof(a, r), dof(b, c), -ke(r, c));
                t.emplace_back(dof(b, r), dof(a, c), -ke(r, c));
              }
          }
  return {from_triplets(3 * nn, t), diagonal(Eigen::VectorXd::Constant(3 * nn, 2.0))};
}

}  // namespace ssid::test
