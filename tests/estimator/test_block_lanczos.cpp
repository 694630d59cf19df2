// block_lanczos on its own (the eigen-solver's tests run it through
// EigenSolver): the lowest modes against a dense generalised eigen-solve, with
// M V kept beside the basis (keep_mass_basis) and without, and the products with
// M that keeping it saves.
#include <Eigen/Dense>
#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include "estimator/block_lanczos.hpp"

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

Run run(const Pencil& p, double sigma, int nev, bool keep) {
  const Eigen::LLT<Eigen::MatrixXd> llt(p.K - sigma * p.M);
  REQUIRE(llt.info() == Eigen::Success);
  Run r;
  BlockLanczosOptions o;
  o.nev = nev;
  o.block = 4;
  o.keep_mass_basis = keep;
  r.result = block_lanczos([&](const Eigen::MatrixXd& X) { return Eigen::MatrixXd(llt.solve(X)); },
                           [&](const Eigen::MatrixXd& X) {
                             r.mass_products += X.cols() > 1 ? 1 : 0;  // block products (the rare per-column ones apart)
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
  // The same Krylov space, so the same number of block solves; far fewer products with M.
  CHECK(kept.result.block_solves == plain.result.block_solves);
  CAPTURE(plain.mass_products, kept.mass_products);
  CHECK(kept.mass_products <= kept.result.block_solves + 2);
  CHECK(kept.mass_products * 2 < plain.mass_products);
}
