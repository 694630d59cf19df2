#pragma once
// Helpers for the element tests: random frames, a small dense assembler and
// a dense generalised eigen-solve (Eigen's GeneralizedSelfAdjointEigenSolver).
#include <Eigen/Dense>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <random>
#include <vector>

namespace element_test {

inline Eigen::Matrix3d random_rotation(std::mt19937& rng) {
  std::normal_distribution<double> n(0, 1);
  Eigen::Quaterniond q(n(rng), n(rng), n(rng), n(rng));
  return q.normalized().toRotationMatrix();
}

inline Eigen::Vector3d random_vector(std::mt19937& rng, double scale = 1.0) {
  std::uniform_real_distribution<double> u(-scale, scale);
  return {u(rng), u(rng), u(rng)};
}

/// Dense g-set of n grids with 6 DOFs each.
struct Dense {
  Eigen::MatrixXd K, M;
  explicit Dense(int grids) : K(Eigen::MatrixXd::Zero(6 * grids, 6 * grids)), M(K) {}
  template <class Mat>
  void add(const Mat& k, const Mat& m, int ga, int gb) {
    const int idx[2] = {6 * ga, 6 * gb};
    for (int p = 0; p < 2; ++p)
      for (int q = 0; q < 2; ++q) {
        K.block(idx[p], idx[q], 6, 6) += k.block(6 * p, 6 * q, 6, 6);
        M.block(idx[p], idx[q], 6, 6) += m.block(6 * p, 6 * q, 6, 6);
      }
  }
  /// Sorted eigenvalues ω² with the listed DOFs removed.
  Eigen::VectorXd eigenvalues(const std::vector<int>& fixed) const {
    std::vector<int> keep;
    for (int i = 0; i < K.rows(); ++i)
      if (std::find(fixed.begin(), fixed.end(), i) == fixed.end()) keep.push_back(i);
    const int n = static_cast<int>(keep.size());
    Eigen::MatrixXd k(n, n), m(n, n);
    for (int a = 0; a < n; ++a)
      for (int b = 0; b < n; ++b) k(a, b) = K(keep[a], keep[b]), m(a, b) = M(keep[a], keep[b]);
    Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(k, m);
    return es.eigenvalues();
  }
};

/// Every DOF of grid g, or the listed components (1-6) of it.
inline std::vector<int> dofs_of(int g, std::initializer_list<int> comps = {1, 2, 3, 4, 5, 6}) {
  std::vector<int> out;
  for (int c : comps) out.push_back(6 * g + c - 1);
  return out;
}

inline double rel_err(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  const double s = std::max(a.norm(), b.norm());
  return s > 0 ? (a - b).norm() / s : 0.0;
}

/// Index of the eigenvalue nearest to `target`.
inline double nearest(const Eigen::VectorXd& ev, double target) {
  double best = ev(0);
  for (int i = 0; i < ev.size(); ++i)
    if (std::abs(ev(i) - target) < std::abs(best - target)) best = ev(i);
  return best;
}

}  // namespace element_test

namespace element_test {

/// Sorted eigenvalues of (k, m) after statically condensing the DOFs that
/// carry no mass (exact for massless DOFs; needed for lumped mass without
/// rotational inertia, whose M is singular).
inline Eigen::VectorXd eig_condensed(const Eigen::MatrixXd& k, const Eigen::MatrixXd& m) {
  std::vector<int> r, c;
  for (int i = 0; i < k.rows(); ++i) (m.row(i).cwiseAbs().maxCoeff() > 0 ? r : c).push_back(i);
  auto sub = [](const Eigen::MatrixXd& a, const std::vector<int>& rows, const std::vector<int>& cols) {
    Eigen::MatrixXd s(rows.size(), cols.size());
    for (std::size_t i = 0; i < rows.size(); ++i)
      for (std::size_t j = 0; j < cols.size(); ++j) s(i, j) = a(rows[i], cols[j]);
    return s;
  };
  Eigen::MatrixXd kr = sub(k, r, r);
  if (!c.empty()) kr -= sub(k, r, c) * sub(k, c, c).ldlt().solve(sub(k, c, r));
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(kr, sub(m, r, r));
  return es.eigenvalues();
}

/// Columns selecting, for each listed grid, the given basic direction of its
/// translation (rot = false) or rotation (rot = true).
inline void add_projection(Eigen::MatrixXd& P, int& col, int grid, const Eigen::Vector3d& dir, bool rot) {
  P.block<3, 1>(6 * grid + (rot ? 3 : 0), col++) = dir;
}

}  // namespace element_test
