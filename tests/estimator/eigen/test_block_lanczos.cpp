// block_lanczos on its own (the eigen-solver's tests run it through
// EigenSolver): the lowest modes against a dense generalised eigen-solve, with
// M V kept beside the basis (keep_mass_basis) and without, and the products with
// M that keeping it saves.
#include <Eigen/Dense>
#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include "estimator/eigen/block_lanczos.hpp"

using namespace ssid::estimator;

namespace {

/// A banded SPD stiffness (a chain with longer springs) and a consistent,
/// banded mass matrix; `massless` DOFs (every fourth) get no mass at all.
struct Pencil {
  Eigen::MatrixXd K, M;
};

Pencil pencil(int n, bool massless) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.5, 1.5);
  Pencil p{Eigen::MatrixXd::Zero(n, n), Eigen::MatrixXd::Zero(n, n)};
  auto spring = [&](int i, int j, double k) {
    p.K(i, i) += k, p.K(j, j) += k, p.K(i, j) -= k, p.K(j, i) -= k;
  };
  for (int i = 0; i + 1 < n; ++i) spring(i, i + 1, 1000.0 * u(rng));
  for (int i = 0; i + 3 < n; ++i) spring(i, i + 3, 200.0 * u(rng));
  p.K(0, 0) += 500.0;  // grounded: K positive definite
  for (int i = 0; i + 1 < n; ++i) {
    if (massless && (i % 4 == 3 || (i + 1) % 4 == 3)) continue;
    const double m = u(rng);  // a consistent two-node mass: [2 1; 1 2] m / 6
    p.M(i, i) += m / 3, p.M(i + 1, i + 1) += m / 3, p.M(i, i + 1) += m / 6, p.M(i + 1, i) += m / 6;
  }
  return p;
}

struct Run {
  BlockLanczosResult result;
  long mass_products = 0;
};

Run run(const Pencil& p, double sigma, int nev, bool keep, long max_basis = 0) {
  const Eigen::LLT<Eigen::MatrixXd> llt(p.K - sigma * p.M);
  REQUIRE(llt.info() == Eigen::Success);
  Run r;
  BlockLanczosOptions o;
  o.nev = nev;
  o.block = 4;
  o.keep_mass_basis = keep;
  o.max_basis = max_basis;
  r.result = block_lanczos([&](const Eigen::MatrixXd& X) { return Eigen::MatrixXd(llt.solve(X)); },
                           [&](const Eigen::MatrixXd& X) {
                             ++r.mass_products;
                             return Eigen::MatrixXd(p.M * X);
                           },
                           p.K.rows(), sigma, o);
  return r;
}

}  // namespace

TEST_CASE("block Lanczos: the lowest modes with and without M V kept", "[eigen][block_lanczos]") {
  const bool massless = GENERATE(false, true);
  CAPTURE(massless);
  const int n = 160, nev = 12;
  const Pencil p = pencil(n, massless);
  // Dense reference on the DOFs with mass: the massless ones condensed out
  // statically (their rows of M are zero, so they carry no finite eigenvalue).
  std::vector<int> mdof, zdof;
  for (int i = 0; i < n; ++i) (p.M.row(i).norm() > 0 ? mdof : zdof).push_back(i);
  Eigen::MatrixXd Kc(mdof.size(), mdof.size()), Mc(mdof.size(), mdof.size());
  {
    Eigen::MatrixXd Kmm(mdof.size(), mdof.size()), Kmz(mdof.size(), zdof.size()), Kzz(zdof.size(), zdof.size());
    for (std::size_t a = 0; a < mdof.size(); ++a) {
      for (std::size_t b = 0; b < mdof.size(); ++b) Kmm(a, b) = p.K(mdof[a], mdof[b]), Mc(a, b) = p.M(mdof[a], mdof[b]);
      for (std::size_t b = 0; b < zdof.size(); ++b) Kmz(a, b) = p.K(mdof[a], zdof[b]);
    }
    for (std::size_t a = 0; a < zdof.size(); ++a)
      for (std::size_t b = 0; b < zdof.size(); ++b) Kzz(a, b) = p.K(zdof[a], zdof[b]);
    Kc = zdof.empty() ? Kmm : Eigen::MatrixXd(Kmm - Kmz * Kzz.ldlt().solve(Kmz.transpose()));
  }
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> ref(Kc, Mc);
  const double sigma = -0.01 * ref.eigenvalues()(0);

  const Run plain = run(p, sigma, nev, false), kept = run(p, sigma, nev, true);
  for (const Run* r : {&plain, &kept}) {
    const BlockLanczosResult& res = r->result;
    REQUIRE(res.converged);
    REQUIRE(res.lambda.size() >= nev);
    for (int i = 0; i < nev; ++i) CHECK(res.lambda(i) == Approx(ref.eigenvalues()(i)).epsilon(1e-9));
    // M-orthonormal Ritz vectors, each an eigenvector: ‖Kφ − λMφ‖ / ‖Kφ‖ small.
    const Eigen::MatrixXd& V = res.vectors;
    const Eigen::MatrixXd G = V.leftCols(nev).transpose() * p.M * V.leftCols(nev);
    CHECK((G - Eigen::MatrixXd::Identity(nev, nev)).cwiseAbs().maxCoeff() < 1e-10);
    for (int i = 0; i < nev; ++i) {
      const Eigen::VectorXd kphi = p.K * V.col(i);
      CHECK((kphi - res.lambda(i) * (p.M * V.col(i))).norm() <= 1e-7 * kphi.norm());
    }
  }
  // The same Krylov space, so (up to rounding at the tolerance) the same number of
  // block solves; far fewer products with M: about one a block (each column that
  // cancels heavily in the block's own Gram–Schmidt takes two more, either way).
  CHECK(std::abs(kept.result.block_solves - plain.result.block_solves) <= 1);
  CAPTURE(plain.mass_products, kept.mass_products, kept.result.block_solves);
  CHECK(kept.mass_products <= 2 * kept.result.block_solves);
  CHECK(kept.mass_products * 2 < plain.mass_products);
}

TEST_CASE("block Lanczos: a basis grown past its first size, and one held at a small cap", "[eigen][block_lanczos]") {
  const int n = 160;
  const Pencil p = pencil(n, false);
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> ref(p.K, p.M);
  const double sigma = -0.01 * ref.eigenvalues()(0);
  for (bool keep : {false, true}) {
    CAPTURE(keep);
    // nev 2 with blocks of 2: the basis is first sized 8 nev + 4 b = 24 columns. A
    // shift far below the spectrum (minus its middle eigenvalue: the inverted
    // spectrum nearly flat) needs a basis about five times that, grown by copies
    // (and M V with it).
    {
      const Pencil& q = p;
      const double far = -ref.eigenvalues()(n / 2);
      const Eigen::LLT<Eigen::MatrixXd> llt(q.K - far * q.M);
      BlockLanczosOptions o;
      o.nev = 2;
      o.block = 2;
      o.keep_mass_basis = keep;
      const BlockLanczosResult res =
          block_lanczos([&](const Eigen::MatrixXd& X) { return Eigen::MatrixXd(llt.solve(X)); },
                        [&](const Eigen::MatrixXd& X) { return Eigen::MatrixXd(q.M * X); }, n, far, o);
      CAPTURE(res.basis);
      REQUIRE(res.converged);
      CHECK(res.basis > 2 * 24);
      for (int i = 0; i < 2; ++i) CHECK(res.lambda(i) == Approx(ref.eigenvalues()(i)).epsilon(1e-9));
      const Eigen::MatrixXd G = res.vectors.transpose() * q.M * res.vectors;
      CHECK((G - Eigen::MatrixXd::Identity(G.rows(), G.cols())).cwiseAbs().maxCoeff() < 1e-10);
    }
    // A cap of 16 columns for 12 modes: the run stops at the cap, not converged,
    // and returns only the pairs that did converge: the lowest, in order.
    const Run capped = run(p, sigma, 12, keep, 16);
    CHECK(capped.result.basis <= 16);
    CHECK_FALSE(capped.result.converged);
    CHECK(capped.result.lambda.size() < 12);
    for (Eigen::Index i = 0; i < capped.result.lambda.size(); ++i)
      CHECK(capped.result.lambda(i) == Approx(ref.eigenvalues()(i)).epsilon(1e-9));
  }
}
