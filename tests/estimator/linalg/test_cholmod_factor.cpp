#include "estimator/linalg/cholmod_factor.hpp"

#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <algorithm>
#include <random>
#include <vector>

#include "tests/estimator/eigen/eigen_test_models.hpp"

using namespace ssid::estimator;
using namespace ssid::test;

TEST_CASE("CholmodFactor solves against a dense Cholesky, one and many right-hand sides", "[cholmod]") {
  for (int n : {5, 40, 200}) {
    const auto [K, M] = random_pencil(n, 7u + static_cast<unsigned>(n));
    for (FactorKind kind : {FactorKind::Supernodal, FactorKind::Simplicial, FactorKind::Auto}) {
      CholmodFactor f(kind);
      const FactorStatus st = f.factorize(K);  // full storage: the wrapper takes tril
      REQUIRE(st.ok());
      REQUIRE(st.rcond > 0.0);
      const Eigen::MatrixXd Kd = Eigen::MatrixXd(K);
      const Eigen::MatrixXd B = Eigen::MatrixXd::Random(n, 3);
      const Eigen::MatrixXd X = f.solve(B);
      const Eigen::MatrixXd Xd = Kd.llt().solve(B);
      CHECK((X - Xd).norm() <= 1e-10 * Xd.norm());
      Eigen::VectorXd x(n);
      const Eigen::VectorXd b = B.col(1);
      f.solve(b.data(), x.data(), 1);
      CHECK((x - Xd.col(1)).norm() <= 1e-10 * Xd.col(1).norm());
      CHECK(f.solve_count() == 4);
      if (kind == FactorKind::Supernodal) CHECK(f.supernodal());
    }
  }
}

TEST_CASE("CholmodFactor analyses once per pattern and refactors when only values change", "[cholmod]") {
  const SpMat K = chain_stiffness(60, 5.0, true);  // tridiagonal: (0, 59) is outside the pattern
  CholmodFactor f;
  REQUIRE(f.factorize(K).ok());
  REQUIRE(f.analysis_count() == 1);
  // Same pattern, new values: no new analysis, and the new factor is the new matrix's.
  SpMat K2 = K;
  for (int k = 0; k < K2.nonZeros(); ++k) K2.valuePtr()[k] *= 3.0;
  REQUIRE(f.factorize(K2).ok());
  CHECK(f.analysis_count() == 1);
  CHECK(f.factorization_count() == 2);
  const Eigen::VectorXd b = Eigen::VectorXd::Ones(60);
  const Eigen::VectorXd x = f.solve(b);
  CHECK((Eigen::MatrixXd(K2) * x - b).norm() <= 1e-10 * b.norm());
  // A new pattern is analysed again.
  SpMat K3 = K2;
  K3.coeffRef(0, 59) += 0.01;
  K3.coeffRef(59, 0) += 0.01;
  K3.makeCompressed();
  REQUIRE(f.factorize(K3).ok());
  CHECK(f.analysis_count() == 2);
}

TEST_CASE("CholmodFactor names the column of a non-positive pivot", "[cholmod]") {
  // A chain with one DOF (index 7) cut loose: its row and column are zero.
  Triplets t;
  for (int i = 0; i < 12; ++i) {
    if (i == 7) continue;
    add_spring(t, i, -1, 1.0);
    if (i + 1 < 12 && i + 1 != 7) add_spring(t, i, i + 1, 2.0);
  }
  t.emplace_back(7, 7, 0.0);  // explicit zero keeps the pattern square
  const SpMat A = from_triplets(12, t);
  for (FactorKind kind : {FactorKind::Supernodal, FactorKind::Simplicial}) {
    CholmodFactor f(kind);
    const FactorStatus st = f.factorize(A);
    CHECK(st.code == FactorStatus::Code::NotPositiveDefinite);
    CHECK(st.column == 7);
    CHECK(st.message.find("7") != std::string::npos);
    CHECK_FALSE(f.factorized());
    CHECK_THROWS_AS(f.solve(Eigen::VectorXd::Ones(12)), std::logic_error);
  }
}

TEST_CASE("CholmodFactor flags a nearly singular matrix", "[cholmod]") {
  SpMat A = chain_stiffness(10, 1.0, true);
  A.coeffRef(4, 4) = 1e-18;  // and decouple DOF 4 so the tiny pivot survives
  for (int j : {3, 5}) {
    A.coeffRef(4, j) = 0.0;
    A.coeffRef(j, 4) = 0.0;
  }
  CholmodFactor f;
  const FactorStatus st = f.factorize(A);
  CHECK(st.code == FactorStatus::Code::NearSingular);
  CHECK(st.rcond < 1e-15);
}

TEST_CASE("CholmodFactor rejects a non-square matrix", "[cholmod]") {
  CholmodFactor f;
  CHECK_THROWS_AS(f.factorize(SpMat(3, 4)), std::invalid_argument);
}

TEST_CASE("count_negative_pivots gives the inertia (Sylvester) of an indefinite matrix", "[cholmod]") {
  for (unsigned seed : {1u, 2u, 3u}) {
    const auto [K, M] = random_pencil(50, seed);
    const Eigen::VectorXd lam = Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd>(
                                    Eigen::MatrixXd(K), Eigen::MatrixXd(M))
                                    .eigenvalues();
    for (int below : {0, 1, 7, 25}) {
      // A shift halfway between two eigenvalues: exactly `below` lie under it.
      const double s = below == 0 ? lam(0) * 0.5 : 0.5 * (lam(below - 1) + lam(below));
      CHECK(count_negative_pivots(K - s * M) == below);
    }
  }
}

TEST_CASE("CholmodFactor with DOF groups: ordering on the group graph, same solutions", "[cholmod]") {
  // A lattice truss numbered in a scrambled order: the three DOFs of a node are
  // far apart in the rows, so the groups are not contiguous ranges.
  const int nn = 4 * 4 * 4;
  std::vector<int> perm(3 * nn);
  for (int i = 0; i < 3 * nn; ++i) perm[static_cast<size_t>(i)] = i;
  std::mt19937 rng(5u);
  std::shuffle(perm.begin(), perm.end(), rng);
  const auto [K0, M] = free_lattice_truss(4, perm);
  const SpMat K = K0 + SpMat(M * 0.5);  // K + 0.5 M: positive definite
  std::vector<long> groups(3 * nn);
  for (int a = 0; a < nn; ++a)
    for (int c = 0; c < 3; ++c) groups[static_cast<size_t>(perm[static_cast<size_t>(3 * a + c)])] = 1000 + 7L * a;

  CholmodFactor plain, grouped;
  grouped.set_dof_groups(groups);
  REQUIRE(plain.factorize(K).ok());
  REQUIRE(grouped.factorize(K).ok());
  CHECK(grouped.ordering().find("on 64 groups") != std::string::npos);
  CHECK(plain.ordering().find("groups") == std::string::npos);
  CHECK(grouped.factor_nnz() > 0.0);
  CHECK(grouped.factor_bytes() >= 8.0 * grouped.factor_nnz());
  const Eigen::MatrixXd B = Eigen::MatrixXd::Random(3 * nn, 4);
  const Eigen::MatrixXd Xd = Eigen::MatrixXd(K).llt().solve(B);
  CHECK((grouped.solve(B) - Xd).norm() <= 1e-10 * Xd.norm());
  CHECK((plain.solve(B) - Xd).norm() <= 1e-10 * Xd.norm());

  // Values change, groups and pattern do not: no new analysis.
  const SpMat K2 = 2.0 * K;
  REQUIRE(grouped.factorize(K2).ok());
  CHECK(grouped.analysis_count() == 1);
  CHECK((grouped.solve(B) - 0.5 * Xd).norm() <= 1e-10 * Xd.norm());
  // The same groups again change nothing; new groups force a new analysis.
  grouped.set_dof_groups(groups);
  REQUIRE(grouped.factorize(K2).ok());
  CHECK(grouped.analysis_count() == 1);
  std::vector<long> singletons(3 * nn);
  for (int i = 0; i < 3 * nn; ++i) singletons[static_cast<size_t>(i)] = i;
  grouped.set_dof_groups(singletons);
  CHECK_FALSE(grouped.factorized());
  REQUIRE(grouped.factorize(K2).ok());
  CHECK(grouped.analysis_count() == 2);
  CHECK(grouped.ordering().find("on 192 groups") != std::string::npos);
  CHECK((grouped.solve(B) - 0.5 * Xd).norm() <= 1e-10 * Xd.norm());
  // NASTRAN-sized grid ids (up to 10^8) as group ids: sorted, not indexed.
  std::vector<long> big_ids(groups);
  for (long& id : big_ids) id = 99999999 - id;
  grouped.set_dof_groups(big_ids);
  REQUIRE(grouped.factorize(K2).ok());
  CHECK(grouped.ordering().find("on 64 groups") != std::string::npos);
  CHECK((grouped.solve(B) - 0.5 * Xd).norm() <= 1e-10 * Xd.norm());
}

TEST_CASE("CholmodFactor rejects bad DOF groups", "[cholmod]") {
  const SpMat K = chain_stiffness(10, 1.0, true);
  CholmodFactor f;
  CHECK_THROWS_AS(f.set_dof_groups({0, 0, 1, -1, 2, 2, 3, 3, 4, 4}), std::invalid_argument);
  f.set_dof_groups({0, 0, 1, 1});  // 4 entries for 10 rows: found at analysis
  CHECK_THROWS_AS(f.factorize(K), std::invalid_argument);
  f.set_dof_groups({});
  CHECK(f.factorize(K).ok());
}

TEST_CASE("CholmodFactor::factor_bytes from the symbolic analysis matches the numeric factor", "[cholmod]") {
  const auto [K0, M] = free_lattice_truss(5);
  const SpMat K = K0 + SpMat(M);
  CholmodFactor f;
  f.analyze(K);
  const double before = f.factor_bytes();  // known before any numeric work
  CHECK(before >= 8.0 * f.factor_nnz());
  REQUIRE(f.factorize(K).ok());
  CHECK(f.analysis_count() == 1);
  CHECK(f.factor_bytes() == before);
}

TEST_CASE("CholmodFactor refuses a factor above its memory limit before any numeric work", "[cholmod]") {
  const auto [K0, M] = free_lattice_truss(4);
  const SpMat K = K0 + SpMat(M);
  CholmodFactor f;
  f.set_memory_limit(1000.0);  // bytes: far below this factor's size
  const FactorStatus st = f.factorize(K);
  CHECK(st.code == FactorStatus::Code::TooLarge);
  CHECK(st.message.find("GiB") != std::string::npos);
  CHECK(st.message.find("limit") != std::string::npos);
  CHECK(f.factorization_count() == 0);
  CHECK(f.analysis_count() == 1);
  CHECK(f.factor_bytes() > 1000.0);
  f.set_memory_limit(2.0 * f.factor_bytes());
  REQUIRE(f.factorize(K).ok());
  CHECK(f.analysis_count() == 1);  // the analysis was kept
  const Eigen::VectorXd b = Eigen::VectorXd::Ones(K.rows());
  CHECK((K * f.solve(b) - b).norm() <= 1e-10 * b.norm());
}
