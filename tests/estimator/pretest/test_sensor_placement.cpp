#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <random>

#include "estimator/pretest/sensor_placement.hpp"
#include "estimator/pretest/targets.hpp"
#include "formats/parse_error.hpp"

using namespace ssid::estimator::pretest;

namespace {

Eigen::MatrixXd random_modes(Eigen::Index r, Eigen::Index c, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> g;
  Eigen::MatrixXd A(r, c);
  for (Eigen::Index i = 0; i < A.size(); ++i) A(i) = g(rng);
  return A;
}

/// det(Φ_sᵀΦ_s) by a fresh dense factorisation: the brute-force reference.
double fisher_det(const Eigen::MatrixXd& Phi, const std::vector<Eigen::Index>& rows) {
  const Eigen::MatrixXd S = take_rows(Phi, rows);
  return (S.transpose() * S).determinant();
}

}  // namespace

TEST_CASE("pretest: each EI deletion is the brute-force best single deletion of the determinant", "[pretest][ei]") {
  const Eigen::MatrixXd Phi = random_modes(14, 4, 7);
  // EI(keep) must equal EI(keep+1) less the row whose removal leaves the largest det F,
  // found by recomputing the determinant for every candidate.
  std::vector<Eigen::Index> previous(14);
  for (Eigen::Index i = 0; i < 14; ++i) previous[static_cast<std::size_t>(i)] = i;
  for (int keep = 13; keep >= 4; --keep) {
    double best = -1;
    Eigen::Index best_row = -1;
    for (auto r : previous) {
      std::vector<Eigen::Index> rest;
      for (auto q : previous)
        if (q != r) rest.push_back(q);
      const double d = fisher_det(Phi, rest);
      if (d > best) best = d, best_row = r;
    }
    std::vector<Eigen::Index> expected;
    for (auto q : previous)
      if (q != best_row) expected.push_back(q);
    const Placement p = effective_independence(Phi, keep);
    INFO("keep " << keep);
    CHECK(p.selected == expected);
    CHECK(p.fisher.determinant == Approx(best).epsilon(1e-9));
    CHECK(p.fisher.log10_determinant == Approx(std::log10(best)).epsilon(1e-9));
    previous = expected;
  }
}

TEST_CASE("pretest: EI on a larger set matches the determinant-recomputing greedy search", "[pretest][ei]") {
  // 300 candidates: the Woodbury updates and the refreshes at each halving run many times.
  const Eigen::MatrixXd Phi = random_modes(300, 6, 11);
  std::vector<Eigen::Index> alive(300);
  for (Eigen::Index i = 0; i < 300; ++i) alive[static_cast<std::size_t>(i)] = i;
  while (alive.size() > 10) {
    double best = -1;
    std::size_t best_k = 0;
    for (std::size_t k = 0; k < alive.size(); ++k) {
      auto rest = alive;
      rest.erase(rest.begin() + static_cast<long>(k));
      const double d = fisher_det(Phi, rest);
      if (d > best) best = d, best_k = k;
    }
    alive.erase(alive.begin() + static_cast<long>(best_k));
  }
  CHECK(effective_independence(Phi, 10).selected == alive);
}

TEST_CASE("pretest: EI is invariant to the scaling of the modes", "[pretest][ei]") {
  const Eigen::MatrixXd Phi = random_modes(40, 5, 3);
  Eigen::VectorXd s(5);
  s << 1e3, 1e-2, 7.0, -3.0, 0.5;
  const Eigen::MatrixXd scaled = Phi * s.asDiagonal();
  const Placement a = effective_independence(Phi, 9), b = effective_independence(scaled, 9);
  CHECK(a.selected == b.selected);
  // The E values are a projector's diagonal: unchanged too.
  CHECK((a.score - b.score).cwiseAbs().maxCoeff() < 1e-10);
  // ... and sum to the number of modes.
  CHECK(a.score.sum() == Approx(5.0).epsilon(1e-12));
  // The determinant scales by Π s_j².
  CHECK(b.fisher.log10_determinant ==
        Approx(a.fisher.log10_determinant + 2 * s.cwiseAbs().array().log10().sum()).epsilon(1e-10));
}

TEST_CASE("pretest: triaxial EI keeps a grid holding a DOF with EI = 1", "[pretest][ei]") {
  // 4 modes, three grids of three DOFs. Grid 0 alone sees mode 4 (one DOF with E = 1,
  // summed E = 1); grids 1 and 2 both see modes 1-3 (E = 0.5 on each of their DOFs,
  // summed 1.5). Grid 0 has the smallest sum but is essential: grid 1 goes.
  Eigen::MatrixXd Phi = Eigen::MatrixXd::Zero(9, 4);
  Phi(0, 3) = 2.0;
  for (int g = 1; g <= 2; ++g)
    for (int k = 0; k < 3; ++k) Phi(3 * g + k, k) = 1.0;
  const std::vector<std::vector<Eigen::Index>> groups{{0, 1, 2}, {3, 4, 5}, {6, 7, 8}};
  const Placement p = effective_independence(Phi, 2, groups);
  CHECK(p.groups_kept == std::vector<Eigen::Index>{0, 2});
  CHECK(p.selected == std::vector<Eigen::Index>{0, 1, 2, 6, 7, 8});
  CHECK(p.protected_groups == 2);  // both remaining grids now hold an essential DOF
  // Asking for one grid is impossible: each is essential.
  CHECK_THROWS_AS(effective_independence(Phi, 1, groups), ssid::formats::InputError);
}

TEST_CASE("pretest: EI refuses fewer sensors than modes", "[pretest][ei]") {
  const Eigen::MatrixXd Phi = random_modes(10, 4, 1);
  CHECK_THROWS_WITH(effective_independence(Phi, 3),
                    "effective independence: 3 sensors cannot resolve 4 target modes (the Fisher information would "
                    "be singular)");
}

TEST_CASE("pretest: kinetic energy fractions with a lumped mass", "[pretest][ke]") {
  const Eigen::MatrixXd Phi = random_modes(6, 2, 5);
  Eigen::VectorXd m(6);
  m << 1, 2, 3, 4, 5, 6;
  Eigen::SparseMatrix<double> M(6, 6);
  for (int i = 0; i < 6; ++i) M.insert(i, i) = m(i);
  const std::vector<Eigen::Index> all{0, 1, 2, 3, 4, 5};
  const Eigen::MatrixXd ke = kinetic_energy_fractions(Phi, M, all);
  for (int j = 0; j < 2; ++j) {
    const double gm = (m.array() * Phi.col(j).array().square()).sum();
    for (int i = 0; i < 6; ++i) CHECK(ke(i, j) == Approx(m(i) * Phi(i, j) * Phi(i, j) / gm).epsilon(1e-12));
    CHECK(ke.col(j).sum() == Approx(1.0).epsilon(1e-12));
  }
  // KE ranks by the largest single-mode share, AKE by the mean.
  const Eigen::VectorXd kem = placement_metric(PlacementMethod::KineticEnergy, Phi, ke);
  const Eigen::VectorXd akem = placement_metric(PlacementMethod::AverageKineticEnergy, Phi, ke);
  for (int i = 0; i < 6; ++i) {
    CHECK(kem(i) == Approx(std::max(ke(i, 0), ke(i, 1))));
    CHECK(akem(i) == Approx(0.5 * (ke(i, 0) + ke(i, 1))));
  }
}

TEST_CASE("pretest: EVP and its absolute sum rank by the product and the scaled sum", "[pretest][evp]") {
  Eigen::MatrixXd Phi(4, 2);
  Phi << 1.0, -2.0,   // product 2, scaled sum 1/2 + 2/4 = 1.0
      0.5, 4.0,       // product 2, scaled sum 0.25 + 1 = 1.25
      2.0, 0.0,       // product 0 (a node of mode 2), scaled sum 1
      -1.5, -3.0;     // product 4.5, scaled sum 0.75 + 0.75 = 1.5
  const Eigen::MatrixXd none(4, 2);
  const Placement evp = rank_placement(PlacementMethod::EigenvectorProduct, Phi,
                                       placement_metric(PlacementMethod::EigenvectorProduct, Phi, none), 2);
  CHECK(evp.selected == std::vector<Eigen::Index>{0, 3});  // 4.5, then 2 (tie: lower index)
  const Placement sum = rank_placement(PlacementMethod::EigenvectorSum, Phi,
                                       placement_metric(PlacementMethod::EigenvectorSum, Phi, none), 2);
  CHECK(sum.selected == std::vector<Eigen::Index>{1, 3});
  // Grouped: rows {0,1} sum 4, rows {2,3} sum 4.5 for EVP.
  const Placement g = rank_placement(PlacementMethod::EigenvectorProduct, Phi,
                                     placement_metric(PlacementMethod::EigenvectorProduct, Phi, none), 1,
                                     {{0, 1}, {2, 3}});
  CHECK(g.selected == std::vector<Eigen::Index>{2, 3});
  CHECK(g.fisher.determinant == Approx((take_rows(Phi, {2, 3}).transpose() * take_rows(Phi, {2, 3})).determinant()));
}

TEST_CASE("pretest: target modes above a frequency and translational candidates", "[pretest]") {
  Eigen::VectorXd lam(5);
  const double w = 2 * M_PI;
  lam << 0.0, 1e-9, w * w * 4, w * w * 9, w * w * 16;  // 0, 0, 2, 3, 4 Hz
  CHECK(select_target_modes(lam, 2, 0.01) == std::vector<Eigen::Index>{2, 3});
  CHECK(select_target_modes(lam, 2, 2.5) == std::vector<Eigen::Index>{3, 4});
  CHECK_THROWS_WITH(select_target_modes(lam, 3, 2.5),
                    "target modes: 3 asked above 2.500000 Hz, but the model's solved modes hold only 2");
  const std::vector<ssid::translators::Dof> aset{{1, 1}, {1, 2}, {1, 4}, {2, 3}, {3, 1}, {3, 6}};
  const auto c = translational_candidates(aset);
  REQUIRE(c.size() == 4);
  CHECK(c[2].row == 3);
  CHECK(c[2].dof.point == 2);
  CHECK(group_by_grid(c) == std::vector<std::vector<Eigen::Index>>{{0, 1}, {2}, {3}});
  CHECK(translational_candidates(aset, {3}).size() == 1);
  CHECK_THROWS_WITH(translational_candidates(aset, {9}),
                    "candidate grid 9: no translational DOF in the analysis set (no such grid, or all its "
                    "translations constrained)");
}
