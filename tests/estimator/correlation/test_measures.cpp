#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <random>
#include <sstream>

#include "estimator/correlation/measures.hpp"

using namespace ssid::estimator;
using Sparse = Eigen::SparseMatrix<double>;

namespace {

Eigen::MatrixXd random_matrix(Eigen::Index r, Eigen::Index c, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> g;
  Eigen::MatrixXd A(r, c);
  for (Eigen::Index i = 0; i < A.size(); ++i) A(i) = g(rng);
  return A;
}

/// A grounded spring chain: DOF i connected to i+1 with stiffness k_i, DOF 0 to ground.
Eigen::MatrixXd chain_stiffness(const std::vector<double>& k) {
  const auto n = static_cast<Eigen::Index>(k.size());
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n, n);
  K(0, 0) += k[0];
  for (Eigen::Index i = 1; i < n; ++i) {
    const double s = k[static_cast<std::size_t>(i)];
    K(i - 1, i - 1) += s;
    K(i, i) += s;
    K(i - 1, i) -= s;
    K(i, i - 1) -= s;
  }
  return K;
}

/// Random SPD matrix.
Eigen::MatrixXd spd(Eigen::Index n, unsigned seed) {
  Eigen::MatrixXd A = random_matrix(n, n, seed);
  return A * A.transpose() + Eigen::MatrixXd::Identity(n, n) * static_cast<double>(n);
}

/// Finite eigenvalues λ of K φ = λ M φ with M possibly singular, from the
/// eigenvalues μ = 1/λ of K⁻¹M (K positive definite), ascending.
std::vector<double> eigenvalues_singular_mass(const Eigen::MatrixXd& K, const Eigen::MatrixXd& M) {
  Eigen::MatrixXd A = K.llt().solve(M);
  Eigen::EigenSolver<Eigen::MatrixXd> es(A);
  std::vector<double> lam;
  for (Eigen::Index i = 0; i < A.rows(); ++i) {
    const double mu = es.eigenvalues()(i).real();
    if (std::abs(mu) > 1e-12 * A.norm()) lam.push_back(1.0 / mu);
  }
  std::sort(lam.begin(), lam.end());
  return lam;
}

std::vector<std::string> words(const std::string& line) {
  std::istringstream s(line);
  std::vector<std::string> w;
  for (std::string t; s >> t;) w.push_back(t);
  return w;
}

}  // namespace

TEST_CASE("MAC: hand values, self, scale and sign invariance, squared = non-squared^2", "[correlation][mac]") {
  Eigen::Vector3d a(1, 0, 0), e(1, 1, 0);
  CHECK(mac(a, e) == Approx(0.5));
  CHECK(mac(a, e, MacForm::NonSquared) == Approx(1.0 / std::sqrt(2.0)));
  Eigen::Vector3d b(1, 2, 3), c(3, -1, 0.5);
  // (b·c)² / (|b|²|c|²) = (3 - 2 + 1.5)² / (14 * 10.25)
  CHECK(mac(b, c) == Approx(6.25 / (14 * 10.25)).epsilon(1e-14));
  CHECK(mac(b, b) == Approx(1.0).epsilon(1e-15));
  CHECK(mac(b, -3.7 * b) == Approx(1.0).epsilon(1e-15));
  CHECK(mac(b, -3.7 * b, MacForm::NonSquared) == Approx(1.0).epsilon(1e-15));
  CHECK(mac(b, Eigen::Vector3d::Zero()) == 0.0);
  const Eigen::MatrixXd A = random_matrix(12, 4, 1), E = random_matrix(12, 5, 2);
  const Eigen::MatrixXd M2 = mac_matrix(A, E), Mn = mac_matrix(A, E, MacForm::NonSquared);
  CHECK((M2 - Mn.cwiseProduct(Mn)).cwiseAbs().maxCoeff() < 1e-14);
  CHECK((mac_matrix(E, A) - M2.transpose()).cwiseAbs().maxCoeff() < 1e-15);
  Eigen::MatrixXd Es = E * Eigen::Vector4d(2.0, -0.1, 7.0, -3.0).homogeneous().asDiagonal();
  CHECK((mac_matrix(A, Es) - M2).cwiseAbs().maxCoeff() < 1e-14);
  CHECK((M2.array() >= 0).all());
  CHECK((M2.array() <= 1).all());
  const Eigen::MatrixXd AA = auto_mac(E);
  CHECK((AA.diagonal().array() - 1).abs().maxCoeff() < 1e-15);
  CHECK((AA - AA.transpose()).cwiseAbs().maxCoeff() == 0.0);
  // Orthogonal shapes: auto-MAC is the identity.
  Eigen::MatrixXd Q = Eigen::HouseholderQR<Eigen::MatrixXd>(random_matrix(6, 6, 3)).householderQ();
  CHECK((auto_mac(Q) - Eigen::MatrixXd::Identity(6, 6)).cwiseAbs().maxCoeff() < 1e-14);
}

TEST_CASE("Modal scale factor takes the test shape onto the analysis shape", "[correlation][mac]") {
  Eigen::VectorXd a = random_matrix(9, 1, 4);
  Eigen::VectorXd e = -2.5 * a;
  CHECK(modal_scale_factor(a, e) == Approx(-0.4).epsilon(1e-15));
  CHECK((modal_scale_factor(a, e) * e - a).norm() < 1e-14);
  // Least squares: the residual is orthogonal to the scaled shape.
  Eigen::VectorXd n = random_matrix(9, 1, 5);
  const double s = modal_scale_factor(a, n);
  CHECK(std::abs((a - s * n).dot(n)) < 1e-13);
}

TEST_CASE("Guyan reduction: closed form for a massless middle node, exact modes when the a-set carries all mass",
          "[correlation][guyan]") {
  // ground -k- [0, mass m] -k- [1, massless] -k- [2, mass m]
  const double k = 1000.0, m = 2.0;
  Eigen::MatrixXd K = chain_stiffness({k, k, k});
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(3, 3);
  M(0, 0) = M(2, 2) = m;
  auto r = guyan_reduce(K.sparseView(), M.sparseView(), {0, 2});
  REQUIRE(r.status == ReductionStatus::Ok);
  // Two springs k in series through the massless node: k/2 between DOFs 0 and 2.
  Eigen::Matrix2d Kr;
  Kr << k + k / 2, -k / 2, -k / 2, k / 2;
  CHECK((r.K - Kr).cwiseAbs().maxCoeff() < 1e-10);
  CHECK((r.M - Eigen::Matrix2d::Identity() * m).cwiseAbs().maxCoeff() < 1e-14);
  // T interpolates the massless node halfway.
  CHECK(r.T(1, 0) == Approx(0.5));
  CHECK(r.T(1, 1) == Approx(0.5));

  // Random grounded chain, masses only at the a-set DOFs: reduced eigenvalues equal
  // the full model's (computed from K⁻¹M, an independent route).
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.5, 2.0);
  std::vector<double> springs(10);
  for (auto& s : springs) s = 1000 * u(rng);
  Eigen::MatrixXd K10 = chain_stiffness(springs);
  K10(3, 7) = K10(7, 3) = -50.0;  // a cross link, still SPD
  K10(3, 3) += 50.0;
  K10(7, 7) += 50.0;
  std::vector<Eigen::Index> a_set{1, 4, 6, 9};
  Eigen::MatrixXd M10 = Eigen::MatrixXd::Zero(10, 10);
  for (auto i : a_set) M10(i, i) = u(rng);
  M10(4, 6) = M10(6, 4) = 0.1;  // consistent-mass coupling within the a-set
  auto g = guyan_reduce(K10.sparseView(), M10.sparseView(), a_set);
  REQUIRE(g.status == ReductionStatus::Ok);
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> red(g.K, g.M);
  auto full = eigenvalues_singular_mass(K10, M10);
  REQUIRE(full.size() == 4);
  for (int i = 0; i < 4; ++i) CHECK(red.eigenvalues()(i) == Approx(full[static_cast<std::size_t>(i)]).epsilon(1e-10));

  // The a-set = every DOF: T = I, M_r = M.
  auto all = guyan_reduce(K10.sparseView(), M10.sparseView(), {0, 1, 2, 3, 4, 5, 6, 7, 8, 9});
  CHECK((all.M - M10).cwiseAbs().maxCoeff() == 0.0);
  CHECK((all.T - Eigen::MatrixXd::Identity(10, 10)).cwiseAbs().maxCoeff() == 0.0);

  // An omitted DOF with no stiffness: a status, not an exception.
  Eigen::MatrixXd Ks = K;
  Ks.row(1).setZero();
  Ks.col(1).setZero();
  auto bad = guyan_reduce(Ks.sparseView(), M.sparseView(), {0, 2});
  CHECK(bad.status == ReductionStatus::SingularOmittedStiffness);
  CHECK_THAT(bad.message, Catch::Contains("not positive definite"));
  CHECK(guyan_reduce(K.sparseView(), M.sparseView(), {0, 0}).status == ReductionStatus::BadInput);
  CHECK(guyan_reduce(K.sparseView(), M.sparseView(), {3}).status == ReductionStatus::BadInput);
}

TEST_CASE("SEREP reproduces the modes it was built from", "[correlation][serep]") {
  const Eigen::Index n = 8;
  Eigen::MatrixXd K = spd(n, 11), M = spd(n, 12) / 10.0;
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(K, M);
  const Eigen::MatrixXd Phi = es.eigenvectors().leftCols(3);  // mass-normalised
  const Eigen::VectorXd lam = es.eigenvalues().head(3);
  std::vector<Eigen::Index> a5{0, 2, 3, 5, 7};
  auto r = serep_reduce(K.sparseView(), M.sparseView(), Phi, a5);
  REQUIRE(r.status == ReductionStatus::Ok);
  Eigen::MatrixXd Pa(5, 3);
  for (int i = 0; i < 5; ++i) Pa.row(i) = Phi.row(a5[static_cast<std::size_t>(i)]);
  CHECK((Pa.transpose() * r.M * Pa - Eigen::MatrixXd::Identity(3, 3)).cwiseAbs().maxCoeff() < 1e-10);
  CHECK((Pa.transpose() * r.K * Pa - Eigen::MatrixXd(lam.asDiagonal())).cwiseAbs().maxCoeff() < 1e-8 * lam.maxCoeff());
  // Expansion: T reproduces the full modes from their a-set rows.
  CHECK((r.T * Pa - Phi).cwiseAbs().maxCoeff() < 1e-10);
  // As many sensors as modes: the reduced eigenproblem returns the same eigenvalues.
  std::vector<Eigen::Index> a3{1, 4, 6};
  auto s = serep_reduce(K.sparseView(), M.sparseView(), Phi, a3);
  REQUIRE(s.status == ReductionStatus::Ok);
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> red(s.K, s.M);
  for (int i = 0; i < 3; ++i) CHECK(red.eigenvalues()(i) == Approx(lam(i)).epsilon(1e-9));
  // Fewer sensors than modes: a status.
  auto bad = serep_reduce(K.sparseView(), M.sparseView(), Phi, {0, 1});
  CHECK(bad.status == ReductionStatus::RankDeficientModes);
}

TEST_CASE("Cross-orthogonality: identity for full-DOF modes, scale-free when normalised", "[correlation][xor]") {
  const Eigen::Index n = 7;
  Eigen::MatrixXd K = spd(n, 21), M = spd(n, 22);
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(K, M);
  const Eigen::MatrixXd Phi = es.eigenvectors();
  CHECK((cross_orthogonality(Phi, M, Phi, false) - Eigen::MatrixXd::Identity(n, n)).cwiseAbs().maxCoeff() < 1e-12);
  // Test modes with arbitrary scale: the normalised form is still ±identity.
  Eigen::VectorXd sc = random_matrix(n, 1, 23).array() * 5.0;
  const Eigen::MatrixXd X = cross_orthogonality(Phi, M, Phi * sc.asDiagonal(), true);
  CHECK((X.cwiseAbs() - Eigen::MatrixXd::Identity(n, n)).cwiseAbs().maxCoeff() < 1e-12);
  // Hand case: M_r = diag(2, 1), a = (1, 0), e = (1, 1): aᵀMe = 2, aᵀMa = 2, eᵀMe = 3.
  Eigen::Matrix2d Mr;
  Mr << 2, 0, 0, 1;
  CHECK(cross_orthogonality(Eigen::Vector2d(1, 0), Mr, Eigen::Vector2d(1, 1), false)(0, 0) == 2.0);
  CHECK(cross_orthogonality(Eigen::Vector2d(1, 0), Mr, Eigen::Vector2d(1, 1), true)(0, 0) ==
        Approx(2.0 / std::sqrt(6.0)));
}

TEST_CASE("MEMS: least-squares superposition, error and error mode (reconciliation paper Eqs. 2-3)",
          "[correlation][mems]") {
  // Hand case: φ = (1, 1) fitted by ψ = (1, 0): α = 1, ê = (0, 1), e² = 1/2.
  Eigen::MatrixXd psi(2, 1);
  psi << 1, 0;
  auto r = mems(Eigen::Vector2d(1, 1), psi);
  CHECK(r.alpha(0) == Approx(1.0));
  CHECK(r.error_squared == Approx(0.5));
  CHECK(r.error_mode.isApprox(Eigen::Vector2d(0, 1)));
  CHECK(r.mac_superposition == Approx(0.5));
  // Scaling of the comparison set: unit norm and unit mass.
  psi(0, 0) = 2;
  CHECK(mems(Eigen::Vector2d(1, 1), psi, ComparisonScaling::UnitNorm).alpha(0) == Approx(1.0));
  Eigen::MatrixXd Mr = Eigen::Vector2d(4, 1).asDiagonal();
  // ψ = (2, 0): ψᵀMψ = 16, scaled ψ = (0.5, 0), α = 2.
  CHECK(mems(Eigen::Vector2d(1, 1), psi, ComparisonScaling::UnitMass, &Mr).alpha(0) == Approx(2.0));
  // An exact combination is recovered with zero error.
  const Eigen::MatrixXd C = random_matrix(10, 3, 31);
  Eigen::VectorXd ref = 2.0 * C.col(0) - 3.0 * C.col(2);
  auto x = mems(ref, C);
  CHECK(x.alpha.isApprox(Eigen::Vector3d(2, 0, -3), 1e-12));
  CHECK(x.error_squared < 1e-24);
  CHECK(x.mac_superposition == Approx(1.0));
  // The error mode is orthogonal to every comparison mode.
  Eigen::VectorXd other = random_matrix(10, 1, 32);
  auto y = mems(other, C);
  CHECK((C.transpose() * y.error_mode).cwiseAbs().maxCoeff() < 1e-12);
  CHECK(y.error_squared == Approx(y.error_mode.squaredNorm() / other.squaredNorm()));
  // Dependent comparison modes do not break the fit.
  Eigen::MatrixXd D(10, 2);
  D << C.col(0), C.col(0) * 2.0;
  auto z = mems(C.col(0), D);
  CHECK(z.error_squared < 1e-24);
}

TEST_CASE("Pairing reproduces the reconciliation paper's Table 4 (MPI FEM / Test Set 1)", "[correlation][pairing]") {
  const std::vector<double> fem{7.86,  11.68, 12.77, 29.29, 34.18, 37.37, 42.43, 46.08,
                                49.37, 51.11, 53.80, 56.72, 58.58, 59.14, 60.26};
  const std::vector<double> test{7.75,  11.65, 12.67, 29.36, 34.06, 37.34, 42.25, 46.04,
                                 48.06, 49.50, 51.69, 53.00, 56.87, 58.01, 60.04};
  // Non-squared MAC values as printed in the table; everything else small.
  Eigen::MatrixXd mac_ns = Eigen::MatrixXd::Constant(15, 15, 0.05);
  const double pairs[][3] = {{1, 1, .9984},  {2, 2, .9966},  {3, 3, .9971},   {4, 4, .9978},   {5, 5, .9985},
                             {6, 6, .9950},  {7, 7, .9960},  {8, 8, .9955},   {9, 10, .9890},  {10, 11, .7696},
                             {11, 12, .9677}, {12, 14, .9628}, {15, 15, .9836}, {9, 9, .7474},   {11, 13, .7714},
                             {13, 15, .6824}, {14, 14, .9441}};
  for (const auto& p : pairs) mac_ns(static_cast<int>(p[0]) - 1, static_cast<int>(p[1]) - 1) = p[2];
  PairingOptions o;
  o.form = MacForm::NonSquared;
  o.min_mac = 0.9;
  Pairing p = pair_modes(fem, test, mac_ns, o);
  // Accepted pairs: 12 of them; FEM 10/test 11 is a mutual best below the threshold.
  int accepted = 0;
  for (const auto& mp : p.pairs) accepted += mp.accepted;
  CHECK(accepted == 12);
  CHECK(p.pairs.size() == 13);
  // "three analysis modes, 10, 13, and 14 had no apparent counterparts ...; nor did test modes 9, 11, and 13"
  CHECK(p.unpaired_fe == std::vector<int>{9, 12, 13});
  CHECK(p.unpaired_test == std::vector<int>{8, 10, 12});

  const std::string table = format_pairing_table(p, fem, test, {}, {}, "Test Set 1");
  std::istringstream lines(table);
  std::string header;
  std::getline(lines, header);
  CHECK(header.rfind("FEM Frequency (Hz)/#", 0) == 0);
  CHECK_THAT(header, Catch::Contains("Test Set 1 Frequency (Hz)/#") && Catch::Contains("Maximum FEM MAC") &&
                         Catch::Contains("Maximum Test MAC") && Catch::Contains("Frequency Error(%)"));
  const char* expected[] = {
      "7.86/1 7.75/1 0.9984 0.9984 1.42(*)",       "11.68/2 11.65/2 0.9966 0.9966 0.26(*)",
      "12.77/3 12.67/3 0.9971 0.9971 0.79(*)",     "29.29/4 29.36/4 0.9978 0.9978 -0.24(*)",
      "34.18/5 34.06/5 0.9985 0.9985 0.35(*)",     "37.37/6 37.34/6 0.9950 0.9950 0.08(*)",
      "42.43/7 42.25/7 0.9960 0.9960 0.43(*)",     "46.08/8 46.04/8 0.9955 0.9955 0.09(*)",
      "-9- 48.06/9 \u2014 0.7474 \u2014",          "49.37/9 49.50/10 0.9890 0.9890 -0.26(*)",
      "51.11/10 51.69/11 0.7696 0.7696 -1.12",     "53.80/11 53.00/12 0.9677 0.9677 1.51(*)",
      "-11- 56.87/13 \u2014 0.7714 \u2014",        "56.72/12 58.01/14 0.9628 0.9628 -2.22(*)",
      "58.58/13 -15- 0.6824 \u2014 \u2014",        "59.14/14 -14- 0.9441 \u2014 \u2014",
      "60.26/15 60.04/15 0.9836 0.9836 0.37(*)"};
  std::size_t row = 0;
  for (std::string line; std::getline(lines, line); ++row) {
    REQUIRE(row < 17);
    CHECK(words(line) == words(expected[row]));
  }
  CHECK(row == 17);
}

TEST_CASE("Pairing from shapes: MSF per pair, frequency threshold, unpaired on both sides", "[correlation][pairing]") {
  // Three orthogonal FE shapes; the test saw modes 1 and 3 (scaled, sign-flipped, slightly noisy)
  // and one spurious shape.
  Eigen::MatrixXd Q = Eigen::HouseholderQR<Eigen::MatrixXd>(random_matrix(12, 12, 41)).householderQ();
  Eigen::MatrixXd fe = Q.leftCols(3);
  Eigen::MatrixXd tst(12, 3);
  tst.col(0) = -3.0 * fe.col(0) + 0.01 * Q.col(5);
  tst.col(1) = Q.col(8);
  tst.col(2) = 0.5 * fe.col(2);
  const std::vector<double> fhz{10.0, 20.0, 30.0}, thz{10.5, 22.0, 27.0};
  Pairing p = pair_modes(fhz, fe, thz, tst);
  REQUIRE(p.pairs.size() == 2);
  CHECK(p.pairs[0].fe == 0);
  CHECK(p.pairs[0].test == 0);
  CHECK(p.pairs[0].accepted);
  CHECK(p.pairs[0].msf == Approx(modal_scale_factor(fe.col(0), tst.col(0))));
  CHECK(p.pairs[0].msf == Approx(-1.0 / 3.0).epsilon(1e-3));
  CHECK(p.pairs[0].error_pct == Approx(100.0 * (10.0 - 10.5) / 10.5));
  CHECK(p.pairs[1].fe == 2);
  CHECK(p.pairs[1].test == 2);
  CHECK(p.pairs[1].msf == Approx(2.0));
  CHECK(p.pairs[1].error_pct == Approx(100.0 * 3.0 / 27.0));
  CHECK_FALSE(p.pairs[1].accepted);  // 11.1 % > 10 %
  CHECK(p.unpaired_fe == std::vector<int>{1, 2});
  CHECK(p.unpaired_test == std::vector<int>{1, 2});
  PairingOptions loose;
  loose.max_frequency_error_pct = 12.0;
  Pairing q = pair_modes(fhz, fe, thz, tst, loose);
  CHECK(q.pairs[1].accepted);
  CHECK(q.unpaired_fe == std::vector<int>{1});
  CHECK(q.unpaired_test == std::vector<int>{1});
  // Rows: pair 1, FE 2 alone (20 Hz) before test 2 alone (22 Hz), then pair 3.
  REQUIRE(q.table.size() == 4);
  CHECK((q.table[1].fe == 1 && !q.table[1].test));
  CHECK((q.table[2].test == 1 && !q.table[2].fe));
  CHECK(q.table[3].accepted);
}
