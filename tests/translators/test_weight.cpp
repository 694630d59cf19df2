#include <catch2/catch.hpp>

#include "translators/weight.hpp"

using namespace ssid::translators;

TEST_CASE("grid point weight of point masses: mass, CG and inertia by hand", "[weight]") {
  // Two lumped masses: 2 kg at (1,0,0) and 6 kg at (0,2,1); translational mass only.
  DofMap dofs;
  for (int g = 1; g <= 2; ++g)
    for (int c = 1; c <= 6; ++c) dofs.add({g, c});
  std::unordered_map<std::int64_t, Eigen::Vector3d> pos = {{1, {1, 0, 0}}, {2, {0, 2, 1}}};
  Eigen::SparseMatrix<double> M(12, 12);
  for (int c = 0; c < 3; ++c) {
    M.insert(c, c) = 2.0;
    M.insert(6 + c, 6 + c) = 6.0;
  }
  WeightSummary w = grid_point_weight(M, dofs, pos);
  CHECK(w.mass(0) == Approx(8.0));
  CHECK(w.mass(2) == Approx(8.0));
  const Eigen::Vector3d cg(2.0 / 8.0, 12.0 / 8.0, 6.0 / 8.0);
  CHECK((w.center - cg).norm() < 1e-12);
  // Inertia about the CG by direct summation: I = Σ m (|r|² I − r rᵀ).
  Eigen::Matrix3d I = Eigen::Matrix3d::Zero();
  for (auto [m, x] : {std::pair{2.0, Eigen::Vector3d(1, 0, 0)}, std::pair{6.0, Eigen::Vector3d(0, 2, 1)}}) {
    Eigen::Vector3d r = x - cg;
    I += m * (r.squaredNorm() * Eigen::Matrix3d::Identity() - r * r.transpose());
  }
  CHECK((w.inertia_cg - I).norm() < 1e-12);
  // The result does not depend on the reference point.
  WeightSummary w2 = grid_point_weight(M, dofs, pos, Eigen::Vector3d(5, -3, 2));
  CHECK((w2.center - cg).norm() < 1e-12);
  CHECK((w2.inertia_cg - I).norm() < 1e-11);
}
