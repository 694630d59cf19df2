#include "estimator/pretest/measurement_coordinates.hpp"

#include <Eigen/Dense>
#include <fmt/format.h>
#include <map>

#include "formats/parse_error.hpp"

namespace ssid::estimator::pretest {

Eigen::SparseMatrix<double> MeasurementCoordinates::congruent(const Eigen::SparseMatrix<double>& A) const {
  Eigen::SparseMatrix<double> out = T.transpose() * A * T;
  out.prune(0.0);
  return out;
}

Eigen::MatrixXd MeasurementCoordinates::displacements(const Eigen::Ref<const Eigen::MatrixXd>& U) const {
  return T_inv * U;
}

Eigen::MatrixXd MeasurementCoordinates::loads(const Eigen::Ref<const Eigen::MatrixXd>& F) const {
  return T.transpose() * F;
}

namespace {

/// The candidates of each grid, in a-set order, by grid id.
std::map<std::int64_t, std::vector<const CandidateDof*>> candidates_by_grid(const std::vector<CandidateDof>& candidates) {
  std::map<std::int64_t, std::vector<const CandidateDof*>> out;
  for (const auto& c : candidates) out[c.dof.point].push_back(&c);
  return out;
}

/// D_g (f x f): the given directions restricted to the grid's free translations,
/// then an orthonormal basis of the rest. Checks what the header promises.
Eigen::MatrixXd grid_block(std::int64_t grid, const std::vector<const CandidateDof*>& free,
                           const std::vector<Eigen::Vector3d>& dirs) {
  const auto f = static_cast<Eigen::Index>(free.size());
  const auto k = static_cast<Eigen::Index>(dirs.size());
  if (k > f)
    throw formats::InputError(fmt::format("sensor directions at grid {}: {} given, but the grid has {} free translation(s)",
                                          grid, k, f));
  Eigen::MatrixXd A(k, f);
  for (Eigen::Index i = 0; i < k; ++i) {
    for (Eigen::Index c = 0; c < f; ++c) A(i, c) = dirs[static_cast<std::size_t>(i)](free[static_cast<std::size_t>(c)]->dof.component - 1);
    if (A.row(i).norm() < 1e-3)
      throw formats::InputError(fmt::format(
          "sensor direction {} at grid {}: it measures only constrained translations (the grid's free translations are "
          "{} of 3)",
          i + 1, grid, f));
  }
  Eigen::MatrixXd unit = A;
  for (Eigen::Index i = 0; i < k; ++i) unit.row(i).normalize();
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(unit);
  if (svd.singularValues().minCoeff() < 1e-3)
    throw formats::InputError(fmt::format(
        "sensor directions at grid {}: the {} directions are linearly dependent (smallest singular value {:.3g}); a "
        "grid's sensors must measure independent directions",
        grid, k, svd.singularValues().minCoeff()));
  Eigen::MatrixXd D(f, f);
  D.topRows(k) = A;
  if (k < f) {
    // The last f − k columns of Q in Aᵀ = QR are orthonormal and orthogonal to A's rows.
    const Eigen::MatrixXd Q = Eigen::HouseholderQR<Eigen::MatrixXd>(A.transpose()).householderQ();
    D.bottomRows(f - k) = Q.rightCols(f - k).transpose();
  }
  return D;
}

}  // namespace

MeasurementCoordinates measurement_coordinates(const std::vector<translators::Dof>& a_set,
                                               const std::vector<CandidateDof>& candidates,
                                               const std::vector<SensorDirection>& directions) {
  const auto n = static_cast<Eigen::Index>(a_set.size());
  const auto by_grid = candidates_by_grid(candidates);
  std::map<std::int64_t, std::vector<Eigen::Vector3d>> dirs_of;
  for (const auto& s : directions) {
    if (!by_grid.count(s.grid))
      throw formats::InputError(fmt::format("sensor direction at grid {}: not a candidate grid (no such grid, no free "
                                            "translation, or left out of the candidate grids)",
                                            s.grid));
    if (!(s.direction.norm() > 0) || !s.direction.allFinite())
      throw formats::InputError(fmt::format("sensor direction at grid {}: expected a nonzero direction", s.grid));
    dirs_of[s.grid].push_back(s.direction.normalized());
  }

  MeasurementCoordinates mc;
  std::vector<Eigen::Triplet<double>> t, t_inv;
  std::vector<bool> done(static_cast<std::size_t>(n), false);
  for (const auto& [grid, dirs] : dirs_of) {
    const auto& free = by_grid.at(grid);
    const Eigen::MatrixXd D = grid_block(grid, free, dirs);
    const Eigen::MatrixXd D_inv = D.inverse();
    const auto f = static_cast<Eigen::Index>(free.size());
    for (Eigen::Index a = 0; a < f; ++a)
      for (Eigen::Index b = 0; b < f; ++b) {
        const Eigen::Index ra = free[static_cast<std::size_t>(a)]->row, rb = free[static_cast<std::size_t>(b)]->row;
        if (D(a, b) != 0) t_inv.emplace_back(ra, rb, D(a, b));
        if (D_inv(a, b) != 0) t.emplace_back(ra, rb, D_inv(a, b));
      }
    for (const auto* c : free) done[static_cast<std::size_t>(c->row)] = true;
  }
  for (Eigen::Index i = 0; i < n; ++i)
    if (!done[static_cast<std::size_t>(i)]) {
      t.emplace_back(i, i, 1.0);
      t_inv.emplace_back(i, i, 1.0);
    }
  mc.T.resize(n, n);
  mc.T.setFromTriplets(t.begin(), t.end());
  mc.T_inv.resize(n, n);
  mc.T_inv.setFromTriplets(t_inv.begin(), t_inv.end());

  // Candidates: unchanged, except a directed grid's, which become its directions
  // (placed where the grid's first candidate was, so the order stays by grid).
  for (const auto& c : candidates) {
    const auto it = dirs_of.find(c.dof.point);
    if (it == dirs_of.end()) {
      mc.candidates.push_back(c);
      continue;
    }
    const auto& free = by_grid.at(c.dof.point);
    if (free.front() != &c) continue;
    for (std::size_t i = 0; i < it->second.size(); ++i) {
      CandidateDof d;
      d.row = free[i]->row;
      d.dof = free[i]->dof;
      d.direction = it->second[i];
      d.directed = true;
      mc.candidates.push_back(d);
    }
  }
  return mc;
}

}  // namespace ssid::estimator::pretest
