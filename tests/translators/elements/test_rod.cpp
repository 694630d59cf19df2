#include <catch2/catch.hpp>

#include "element_test_util.hpp"
#include "translators/elements/rigid_body.hpp"
#include "translators/elements/rod.hpp"

using namespace ssid::translators::elements;
using namespace element_test;

namespace {
GridPair random_pair(std::mt19937& rng) {
  GridPair g;
  g.xa = random_vector(rng, 2);
  g.xb = g.xa + random_vector(rng, 2);
  g.ta = random_rotation(rng);
  g.tb = random_rotation(rng);
  return g;
}
}  // namespace

TEST_CASE("rod: symmetric, rigid-body free, hand stiffness along the axis", "[rod]") {
  std::mt19937 rng(1);
  const RodSection s{0.3, 0.05, 0.2};
  const Material mat{70e9, 27e9, 0.3, 2700};
  for (int trial = 0; trial < 10; ++trial) {
    const GridPair g = random_pair(rng);
    for (MassKind mk : {MassKind::Lumped, MassKind::Coupled}) {
      const ElementMatrices em = rod_matrices(g, s, mat, mk);
      CHECK((em.k - em.k.transpose()).norm() == 0.0);
      CHECK((em.m - em.m.transpose()).norm() == 0.0);
      const Eigen::MatrixXd phi = rigid_body_modes({g.xa, g.xb}, {g.ta, g.tb});
      CHECK(rigid_body_residual(em.k, phi) < 1e-14);
      // Mass is rigid-body exact: translation in any direction carries μL.
      const double total = (s.a * mat.rho + s.nsm) * (g.xb - g.xa).norm();
      for (int d = 0; d < 3; ++d) CHECK((phi.col(d).transpose() * em.m * phi.col(d))(0) == Approx(total));
    }
    // Pull along the axis: force EA/L per unit stretch, in the grid frames.
    const ElementMatrices em = rod_matrices(g, s, mat, MassKind::Lumped);
    const Eigen::Vector3d e = (g.xb - g.xa).normalized();
    const double L = (g.xb - g.xa).norm();
    Eigen::Matrix<double, 12, 1> u = Eigen::Matrix<double, 12, 1>::Zero();
    u.segment<3>(6) = g.tb.transpose() * e;  // unit stretch at B
    u.segment<3>(9) = g.tb.transpose() * e;  // unit twist at B
    const Eigen::Matrix<double, 12, 1> f = em.k * u;
    CHECK((g.tb * f.segment<3>(6) - mat.e * s.a / L * e).norm() < 1e-6 * mat.e * s.a / L);
    CHECK((g.tb * f.segment<3>(9) - mat.g * s.j / L * e).norm() < 1e-6 * mat.g * s.j / L);
  }
}

TEST_CASE("rod: derivatives match central differences for every parameter", "[rod][derivative]") {
  std::mt19937 rng(2);
  const GridPair g = random_pair(rng);
  const RodSection s{0.3, 0.05, 0.2};
  const Material mat{70.0, 27.0, 0.3, 2.7};
  for (MassKind mk : {MassKind::Lumped, MassKind::Coupled})
    for (RodParam p : {RodParam::A, RodParam::J, RodParam::Nsm, RodParam::E, RodParam::G, RodParam::Rho}) {
      auto perturbed = [&](double h) {
        RodSection s2 = s;
        Material m2 = mat;
        switch (p) {
          case RodParam::A: s2.a += h; break;
          case RodParam::J: s2.j += h; break;
          case RodParam::Nsm: s2.nsm += h; break;
          case RodParam::E: m2.e += h; break;
          case RodParam::G: m2.g += h; break;
          case RodParam::Rho: m2.rho += h; break;
        }
        return rod_matrices(g, s2, m2, mk);
      };
      const double h = 1e-5;
      const ElementMatrices d = rod_derivative(g, s, mat, mk, p);
      const ElementMatrices plus = perturbed(h), minus = perturbed(-h);
      const Eigen::MatrixXd fdk = (plus.k - minus.k) / (2 * h), fdm = (plus.m - minus.m) / (2 * h);
      INFO("param " << static_cast<int>(p));
      CHECK(d.k.norm() + d.m.norm() > 0);
      CHECK((d.k - fdk).norm() <= 1e-7 * std::max(1.0, d.k.norm()));
      CHECK((d.m - fdm).norm() <= 1e-7 * std::max(1.0, d.m.norm()));
    }
}

TEST_CASE("rod: axial frequencies of a fixed-free rod converge to (2n-1) pi c / 2L", "[rod][frequency]") {
  // Rod along a skew direction so the test exercises the 3D transformation.
  const Eigen::Vector3d dir = Eigen::Vector3d(1, 2, -2).normalized();
  const double Ltot = 3.0, E = 2e11, rho = 7800, A = 1e-3;
  const RodSection s{A, 0, 0};
  const Material mat{E, 8e10, 0.3, rho};
  const double c = std::sqrt(E / rho);
  auto errors = [&](int n, MassKind mk) {
    Dense d(n + 1);
    for (int e = 0; e < n; ++e) {
      GridPair g;
      g.xa = dir * (Ltot * e / n);
      g.xb = dir * (Ltot * (e + 1) / n);
      const ElementMatrices em = rod_matrices(g, s, mat, mk);
      d.add(em.k, em.m, e, e + 1);
    }
    // Keep only the axial motion: project with a DOF per grid along dir.
    Eigen::MatrixXd P = Eigen::MatrixXd::Zero(6 * (n + 1), n);
    for (int i = 1; i <= n; ++i) P.block<3, 1>(6 * i, i - 1) = dir;
    const Eigen::MatrixXd k = P.transpose() * d.K * P, m = P.transpose() * d.M * P;
    Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(k, m);
    std::vector<double> err;
    for (int mode = 1; mode <= 3; ++mode) {
      const double exact = (2 * mode - 1) * M_PI * c / (2 * Ltot);
      err.push_back(std::sqrt(es.eigenvalues()(mode - 1)) / exact - 1);
    }
    return err;
  };
  for (MassKind mk : {MassKind::Lumped, MassKind::Coupled}) {
    auto e10 = errors(10, mk), e40 = errors(40, mk);
    for (int i = 0; i < 3; ++i) {
      CHECK(std::abs(e40[i]) < 2e-3);
      // Second-order convergence: error / 16 when the mesh is 4x finer.
      CHECK(std::abs(e40[i]) == Approx(std::abs(e10[i]) / 16).epsilon(0.1));
      // Lumped mass under-estimates, coupled over-estimates.
      CHECK((mk == MassKind::Lumped ? e40[i] < 0 : e40[i] > 0));
    }
  }
}
