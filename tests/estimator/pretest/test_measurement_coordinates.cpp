#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>
#include <Eigen/SparseCore>
#include <cmath>
#include <random>
#include <set>

#include "estimator/correlation/measures.hpp"
#include "estimator/pretest/measurement_coordinates.hpp"
#include "estimator/pretest/sensor_placement.hpp"
#include "estimator/pretest/targets.hpp"
#include "formats/parse_error.hpp"

using namespace ssid::estimator::pretest;
using ssid::translators::Dof;

namespace {

std::mt19937 rng(2026);

Eigen::Vector3d random_unit() {
  std::normal_distribution<double> g;
  return Eigen::Vector3d(g(rng), g(rng), g(rng)).normalized();
}

/// A random symmetric positive definite n x n matrix, well conditioned.
Eigen::MatrixXd random_spd(Eigen::Index n) {
  std::normal_distribution<double> g;
  Eigen::MatrixXd A(n, n);
  for (Eigen::Index i = 0; i < A.size(); ++i) A(i) = g(rng);
  return A * A.transpose() + static_cast<double>(n) * Eigen::MatrixXd::Identity(n, n);
}

/// The a-set of `grids` grids with all six components.
std::vector<Dof> six_dof_grids(int grids) {
  std::vector<Dof> a;
  for (int g = 1; g <= grids; ++g)
    for (int c = 1; c <= 6; ++c) a.push_back({g, c});
  return a;
}

/// Rows `grid`'s T1-T3 of `U` (six DOFs per grid, grids numbered from 1).
Eigen::MatrixXd translations(const Eigen::MatrixXd& U, int grid) { return U.middleRows(6 * (grid - 1), 3); }

}  // namespace

TEST_CASE("pretest: a directed sensor's coordinate is d·u, and the model in q keeps eigenvalues and mass",
          "[pretest][directions]") {
  const auto a_set = six_dof_grids(3);
  const Eigen::Index n = 18;
  const Eigen::MatrixXd K = random_spd(n), M = random_spd(n);
  const auto cand = translational_candidates(a_set);
  // Grid 1: one direction; grid 2: two directions 30° apart (not orthogonal); grid 3: T1-T3.
  const Eigen::Vector3d d1 = random_unit();
  const Eigen::Vector3d e1 = random_unit();
  const Eigen::Vector3d e2 = (std::cos(M_PI / 6) * e1 + std::sin(M_PI / 6) * e1.unitOrthogonal()).normalized();
  const MeasurementCoordinates mc = measurement_coordinates(a_set, cand, {{1, 2.5 * d1}, {2, e1}, {2, e2}});

  REQUIRE(mc.candidates.size() == 6);  // 1 + 2 + 3
  CHECK(mc.candidates[0].directed);
  CHECK(mc.candidates[0].dof.point == 1);
  CHECK((mc.candidates[0].direction - d1).norm() < 1e-15);  // normalised
  CHECK(mc.candidates[1].dof.point == 2);
  CHECK(mc.candidates[2].dof.point == 2);
  CHECK(!mc.candidates[3].directed);
  CHECK(mc.candidates[3].row == 12);
  CHECK(sensor_label(mc.candidates[3]) == "T1");

  // Coordinates: Φ_q at a directed candidate is the direction's dot product with
  // the grid's translations, computed directly; elsewhere Φ_q = Φ.
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(K, M);
  const Eigen::MatrixXd Phi = es.eigenvectors();
  const Eigen::MatrixXd Phi_q = mc.displacements(Phi);
  CHECK((Phi_q.row(mc.candidates[0].row) - d1.transpose() * translations(Phi, 1)).norm() < 1e-12);
  CHECK((Phi_q.row(mc.candidates[1].row) - e1.transpose() * translations(Phi, 2)).norm() < 1e-12);
  CHECK((Phi_q.row(mc.candidates[2].row) - e2.transpose() * translations(Phi, 2)).norm() < 1e-12);
  CHECK((Phi_q.bottomRows(6) - Phi.bottomRows(6)).norm() < 1e-12);
  CHECK((Phi_q.middleRows(3, 3) - Phi.middleRows(3, 3)).norm() < 1e-12);  // grid 1's rotations

  // The congruence keeps the eigenvalues (against a dense solve of the original),
  // mass-normalisation and the work of a load.
  const Eigen::SparseMatrix<double> Kq = mc.congruent(K.sparseView()), Mq = mc.congruent(M.sparseView());
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> esq{Eigen::MatrixXd(Kq), Eigen::MatrixXd(Mq)};
  CHECK((esq.eigenvalues() - es.eigenvalues()).cwiseAbs().maxCoeff() < 1e-9 * es.eigenvalues().maxCoeff());
  CHECK((Phi_q.transpose() * Eigen::MatrixXd(Mq) * Phi_q - Eigen::MatrixXd::Identity(n, n)).norm() < 1e-10);
  CHECK((Eigen::MatrixXd(Kq) * Phi_q - Eigen::MatrixXd(Mq) * Phi_q * es.eigenvalues().asDiagonal()).norm() <
        1e-9 * es.eigenvalues().maxCoeff());
  const Eigen::VectorXd f = Eigen::VectorXd::LinSpaced(n, -1, 2);
  CHECK((Phi_q.transpose() * mc.loads(f) - Phi.transpose() * f).norm() < 1e-11);
}

TEST_CASE("pretest: Guyan onto given directions equals the closed-form static condensation", "[pretest][directions]") {
  // One grid, K and M on its three translations. Condensing onto the measured
  // y = D u (D: k x 3) keeps the static shapes u = K⁻¹Dᵀ(D K⁻¹ Dᵀ)⁻¹ y, so
  //   K_G = (D K⁻¹ Dᵀ)⁻¹,   M_G = Ψᵀ M Ψ,   Ψ = K⁻¹Dᵀ K_G,
  // whatever coordinates complete D: the closed form the reduction must give.
  const std::vector<Dof> a_set{{7, 1}, {7, 2}, {7, 3}};
  const auto cand = translational_candidates(a_set);
  for (int k = 1; k <= 3; ++k) {
    const Eigen::MatrixXd K = random_spd(3), M = random_spd(3);
    std::vector<SensorDirection> dirs;
    Eigen::MatrixXd D(k, 3);
    for (int i = 0; i < k; ++i) {
      const Eigen::Vector3d d = random_unit();
      dirs.push_back({7, d});
      D.row(i) = d.transpose();
    }
    const MeasurementCoordinates mc = measurement_coordinates(a_set, cand, dirs);
    std::vector<Eigen::Index> rows;
    for (const auto& c : mc.candidates) rows.push_back(c.row);
    REQUIRE(static_cast<int>(rows.size()) == k);
    const auto g = ssid::estimator::guyan_reduce(mc.congruent(K.sparseView()), mc.congruent(M.sparseView()), rows);
    REQUIRE(g.status == ssid::estimator::ReductionStatus::Ok);
    const Eigen::MatrixXd Kg = (D * K.inverse() * D.transpose()).inverse();
    const Eigen::MatrixXd Psi = K.inverse() * D.transpose() * Kg;
    const Eigen::MatrixXd Mg = Psi.transpose() * M * Psi;
    INFO("directions: " << k);
    CHECK((g.K - Kg).norm() < 1e-10 * Kg.norm());
    CHECK((g.M - Mg).norm() < 1e-10 * Mg.norm());
  }
}

TEST_CASE("pretest: a direction at a grid with a constrained translation measures its free part",
          "[pretest][directions]") {
  // Grid 5 has T1, T2 free (T3 constrained): d = (1, 1, 1)/√3 measures (u1 + u2)/√3.
  const std::vector<Dof> a_set{{4, 1}, {5, 1}, {5, 2}, {5, 6}};
  const auto cand = translational_candidates(a_set);
  const Eigen::Vector3d d = Eigen::Vector3d::Ones().normalized();
  const MeasurementCoordinates mc = measurement_coordinates(a_set, cand, {{5, d}});
  REQUIRE(mc.candidates.size() == 2);
  const Eigen::MatrixXd U = Eigen::MatrixXd::Random(4, 3);
  const Eigen::MatrixXd Uq = mc.displacements(U);
  CHECK((Uq.row(mc.candidates[1].row) - (U.row(1) + U.row(2)) / std::sqrt(3.0)).norm() < 1e-14);
  CHECK((mc.T * Uq - U).norm() < 1e-13);

  CHECK_THROWS_WITH(measurement_coordinates(a_set, cand, {{5, Eigen::Vector3d::UnitZ()}}),
                    Catch::Contains("sensor direction 1 at grid 5: it measures only constrained translations"));
  CHECK_THROWS_WITH(measurement_coordinates(a_set, cand, {{4, Eigen::Vector3d::UnitX()}, {4, Eigen::Vector3d::UnitY()}}),
                    Catch::Contains("sensor directions at grid 4: 2 given, but the grid has 1 free translation(s)"));
  CHECK_THROWS_WITH(measurement_coordinates(a_set, cand, {{9, Eigen::Vector3d::UnitX()}}),
                    Catch::Contains("sensor direction at grid 9: not a candidate grid"));
  CHECK_THROWS_WITH(measurement_coordinates(a_set, cand, {{5, Eigen::Vector3d::Zero()}}),
                    Catch::Contains("expected a nonzero direction"));
  const Eigen::Vector3d x = Eigen::Vector3d::UnitX(), almost_x = Eigen::Vector3d(1, 1e-5, 0).normalized();
  CHECK_THROWS_WITH(measurement_coordinates(a_set, cand, {{5, x}, {5, almost_x}}),
                    Catch::Contains("the 2 directions are linearly dependent"));
}

TEST_CASE("pretest: triaxial EI is invariant to the orientation of each triax", "[pretest][directions][ei]") {
  // A triax's EI is the trace of its 3 x 3 block of the projection Φ(ΦᵀΦ)⁻¹Φᵀ,
  // unchanged by rotating the triax; so rotating every triax by its own
  // random rotation must select the same grids with the same Fisher determinant.
  const int grids = 20;
  const auto a_set = six_dof_grids(grids);
  const auto cand = translational_candidates(a_set);
  std::normal_distribution<double> g;
  Eigen::MatrixXd Phi(6 * grids, 8);
  for (Eigen::Index i = 0; i < Phi.size(); ++i) Phi(i) = g(rng);
  std::vector<SensorDirection> dirs;
  for (int gr = 1; gr <= grids; ++gr) {
    const Eigen::Matrix3d Q = Eigen::HouseholderQR<Eigen::Matrix3d>(Eigen::Matrix3d::Random()).householderQ();
    for (int c = 0; c < 3; ++c) dirs.push_back({gr, Q.col(c)});
  }
  const MeasurementCoordinates mc = measurement_coordinates(a_set, cand, dirs);
  auto place = [&](const std::vector<CandidateDof>& cs, const Eigen::MatrixXd& P) {
    std::vector<Eigen::Index> rows;
    for (const auto& c : cs) rows.push_back(c.row);
    return effective_independence(take_rows(P, rows), 5, group_by_grid(cs));
  };
  const Placement nominal = place(cand, Phi), rotated = place(mc.candidates, mc.displacements(Phi));
  auto grids_of = [](const std::vector<CandidateDof>& cs, const Placement& p) {
    std::set<std::int64_t> s;
    for (auto i : p.selected) s.insert(cs[static_cast<std::size_t>(i)].dof.point);
    return s;
  };
  CHECK(grids_of(cand, nominal) == grids_of(mc.candidates, rotated));
  CHECK(rotated.fisher.determinant == Approx(nominal.fisher.determinant).epsilon(1e-9));
  // Single DOFs are not invariant: EI along rotated axes chooses other channels,
  // and its determinant is the brute-force det((CΦ)ᵀ(CΦ)) of the rows it chose.
  std::vector<Eigen::Index> rows;
  for (const auto& c : mc.candidates) rows.push_back(c.row);
  const Eigen::MatrixXd Pq = take_rows(mc.displacements(Phi), rows);
  const Placement single = effective_independence(Pq, 10);
  Eigen::MatrixXd C(10, Phi.rows());
  C.setZero();
  for (int i = 0; i < 10; ++i) {
    const auto& c = mc.candidates[static_cast<std::size_t>(single.selected[static_cast<std::size_t>(i)])];
    for (int k = 0; k < 3; ++k) C(i, 6 * (c.dof.point - 1) + k) = c.direction(k);
  }
  const Eigen::MatrixXd S = C * Phi;
  CHECK(single.fisher.determinant == Approx((S.transpose() * S).determinant()).epsilon(1e-9));
}
