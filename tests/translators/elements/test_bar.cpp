#include <catch2/catch.hpp>

#include "element_test_util.hpp"
#include "translators/constraints.hpp"
#include "translators/elements/bar.hpp"
#include "translators/elements/rigid_body.hpp"

using namespace ssid::translators::elements;
using namespace element_test;
using Eigen::MatrixXd;
using Eigen::Vector3d;

namespace {
const BarParam kAllParams[] = {BarParam::A,   BarParam::I1, BarParam::I2, BarParam::I12, BarParam::J, BarParam::Nsm,
                               BarParam::K1,  BarParam::K2, BarParam::E,  BarParam::G,   BarParam::Rho};

double& field(BarSection& s, Material& m, BarParam p) {
  switch (p) {
    case BarParam::A: return s.a;
    case BarParam::I1: return s.i1;
    case BarParam::I2: return s.i2;
    case BarParam::I12: return s.i12;
    case BarParam::J: return s.j;
    case BarParam::Nsm: return s.nsm;
    case BarParam::K1: return s.k1;
    case BarParam::K2: return s.k2;
    case BarParam::E: return m.e;
    case BarParam::G: return m.g;
    case BarParam::Rho: return m.rho;
  }
  return s.a;
}

BarGeometry random_bar(std::mt19937& rng, bool offsets, int pa, int pb) {
  BarGeometry g;
  g.grids.xa = random_vector(rng, 2);
  g.grids.xb = g.grids.xa + random_vector(rng, 2);
  g.grids.ta = random_rotation(rng);
  g.grids.tb = random_rotation(rng);
  g.v = random_vector(rng);
  if (offsets) g.wa = random_vector(rng, 0.3), g.wb = random_vector(rng, 0.3);
  g.pa = pa, g.pb = pb;
  return g;
}

/// A straight cantilever / free beam of n elements along `dir` with v.
struct Line {
  int n;
  Vector3d dir, v;
  double L;
  Dense d;
  Line(int n_, Vector3d dir_, Vector3d v_, double L_) : n(n_), dir(dir_.normalized()), v(v_), L(L_), d(n_ + 1) {}
  BarGeometry geom(int e) const {
    BarGeometry g;
    g.grids.xa = dir * (L * e / n);
    g.grids.xb = dir * (L * (e + 1) / n);
    g.v = v;
    return g;
  }
};

const BarSection kSec{0.5, 0.04, 0.02, 0.0, 0.03, 0.1, 0.8, 0.7};
const Material kMat{3.0, 1.2, 0.25, 2.0};
}  // namespace

TEST_CASE("bar/beam: symmetric, K Φ = 0 for rigid-body modes in any orientation, offsets, pins", "[bar]") {
  std::mt19937 rng(7);
  const int pins[][2] = {{0, 0}, {56, 0}, {0, 6}, {4, 56}, {456, 0}, {5, 5}, {1, 0}, {23, 0}};
  int count = 0;
  for (auto [pa, pb] : pins)
    for (bool off : {false, true})
      for (double i12 : {0.0, 0.01})
        for (MassKind mk : {MassKind::Lumped, MassKind::Coupled})
          for (bool beam : {false, true}) {
            const BarGeometry g = random_bar(rng, off, pa, pb);
            BarSection s = kSec;
            s.i12 = i12;
            const ElementMatrices em = beam ? beam_matrices(g, s, kMat, mk) : bar_matrices(g, s, kMat, mk);
            CHECK((em.k - em.k.transpose()).norm() == 0.0);
            CHECK((em.m - em.m.transpose()).norm() == 0.0);
            const MatrixXd phi = rigid_body_modes({g.grids.xa, g.grids.xb}, {g.grids.ta, g.grids.tb});
            INFO("pins " << pa << "/" << pb << " offsets " << off << " I12 " << i12);
            CHECK(rigid_body_residual(em.k, phi) < 1e-14);
            // Positive semi-definite.
            Eigen::SelfAdjointEigenSolver<MatrixXd> es(em.k);
            CHECK(es.eigenvalues()(0) > -1e-12 * es.eigenvalues().maxCoeff());
            // Rigid translation carries the whole mass μ L (lumped: at the
            // grids; coupled: exactly, also through the pin condensation).
            const double L = ((g.grids.xb + g.wb) - (g.grids.xa + g.wa)).norm();
            for (int dcol = 0; dcol < 3; ++dcol)
              CHECK((phi.col(dcol).transpose() * em.m * phi.col(dcol))(0) ==
                    Approx((kSec.a * kMat.rho + kSec.nsm) * L).epsilon(1e-12));
            ++count;
          }
  CHECK(count == 128);
}

TEST_CASE("bar/beam: every derivative matches central differences", "[bar][derivative]") {
  std::mt19937 rng(11);
  struct Config {
    bool offsets;
    int pa, pb;
    double i12;
  };
  // Shear active (I12 = 0); I12 active (K ignored); pins with offsets and shear.
  const Config configs[] = {{false, 0, 0, 0.0}, {false, 0, 0, 0.01}, {true, 56, 4, 0.0}, {true, 0, 6, 0.01}};
  for (const Config& cfg : configs)
    for (MassKind mk : {MassKind::Lumped, MassKind::Coupled})
      for (bool beam : {false, true}) {
        const BarGeometry g = random_bar(rng, cfg.offsets, cfg.pa, cfg.pb);
        BarSection s0 = kSec;
        s0.i12 = cfg.i12;
        auto eval = [&](const BarSection& s, const Material& m) {
          return beam ? beam_matrices(g, s, m, mk) : bar_matrices(g, s, m, mk);
        };
        for (BarParam p : kAllParams) {
          if (p == BarParam::I12 && cfg.i12 == 0.0) continue;  // K1/K2 switch off at I12 ≠ 0: no derivative
          BarSection sp = s0, sm = s0;
          Material mp = kMat, mm = kMat;
          const double h = 1e-6 * std::abs(field(sp, mp, p));
          field(sp, mp, p) += h;
          field(sm, mm, p) -= h;
          const ElementMatrices plus = eval(sp, mp), minus = eval(sm, mm);
          const ElementMatrices d = beam ? beam_derivative(g, s0, kMat, mk, p) : bar_derivative(g, s0, kMat, mk, p);
          const MatrixXd fdk = (plus.k - minus.k) / (2 * h), fdm = (plus.m - minus.m) / (2 * h);
          INFO("param " << static_cast<int>(p) << " beam " << beam << " pins " << cfg.pa << "/" << cfg.pb
                        << " I12 " << cfg.i12);
          // Tolerance: FD truncation (relative 1e-6) or FD rounding, about
          // eps |K| / h, when the true derivative vanishes (e.g. ∂M/∂E of a
          // pin-condensed coupled mass, where E cancels in K_cc⁻¹ K_cr).
          BarSection scopy = s0;
          Material mcopy = kMat;
          const double pval = std::abs(field(scopy, mcopy, p));
          const ElementMatrices base = eval(s0, kMat);
          CHECK((d.k - fdk).norm() <= std::max(1e-6 * d.k.norm(), 1e-8 * base.k.norm() / pval));
          CHECK((d.m - fdm).norm() <= std::max(1e-6 * d.m.norm(), 1e-8 * base.m.norm() / pval));
          // Parameters that must enter: K through E, G, A, I1, I2, J; M through ρ, A, NSM.
          // (J does not enter when a pin flag releases the torsion.)
          const bool torsion_free = cfg.pa % 10 == 4 || cfg.pa / 10 % 10 == 4 || cfg.pb % 10 == 4;
          if (p == BarParam::E || p == BarParam::I1 || (p == BarParam::J && !torsion_free)) CHECK(d.k.norm() > 0);
          if (p == BarParam::Rho || p == BarParam::Nsm) CHECK(d.m.norm() > 0);
          if ((p == BarParam::K1 || p == BarParam::K2) && cfg.i12 != 0.0) CHECK(d.k.norm() == 0.0);
        }
        // Directional derivative = the same linear combination of partials.
        BarSection ds;
        Material dm;
        ds.a = 0.3, ds.i1 = -2.0, dm.e = 0.5;
        const ElementMatrices dd = beam ? beam_directional_derivative(g, s0, kMat, mk, ds, dm)
                                        : bar_directional_derivative(g, s0, kMat, mk, ds, dm);
        auto part = [&](BarParam p) {
          return beam ? beam_derivative(g, s0, kMat, mk, p) : bar_derivative(g, s0, kMat, mk, p);
        };
        const MatrixXd combo = 0.3 * part(BarParam::A).k - 2.0 * part(BarParam::I1).k + 0.5 * part(BarParam::E).k;
        CHECK(rel_err(dd.k, combo) < 1e-12);
      }
}

TEST_CASE("bar: I12 is the product of inertia about the element y and z axes", "[bar]") {
  // The same section described in axes rotated by α about x (v rotated by α)
  // must give the same K: I1' = I1 c² + 2 I12 c s + I2 s², etc.
  std::mt19937 rng(3);
  BarGeometry g = random_bar(rng, true, 0, 0);
  const Eigen::Matrix3d R = bar_element_axes(g);
  const double I1 = 0.05, I2 = 0.02, I12 = 0.012;
  for (double alpha : {0.3, 1.1, -2.0}) {
    const double c = std::cos(alpha), s = std::sin(alpha);
    BarGeometry g2 = g;
    g2.v = c * R.row(1).transpose() + s * R.row(2).transpose();  // new y' axis
    BarSection a = kSec, b = kSec;
    a.i1 = I1, a.i2 = I2, a.i12 = I12;
    b.i1 = I1 * c * c + 2 * I12 * c * s + I2 * s * s;
    b.i2 = I1 * s * s - 2 * I12 * c * s + I2 * c * c;
    b.i12 = -I1 * c * s + I12 * (c * c - s * s) + I2 * c * s;
    CHECK(rel_err(bar_matrices(g, a, kMat, MassKind::Coupled).k, bar_matrices(g2, b, kMat, MassKind::Coupled).k) <
          1e-13);
    // And wrongly signed I12 would not.
    BarSection wrong = b;
    wrong.i12 = -b.i12;
    CHECK(rel_err(bar_matrices(g, a, kMat, MassKind::Coupled).k, bar_matrices(g2, wrong, kMat, MassKind::Coupled).k) >
          1e-3);
  }
}

namespace {
/// Bending frequencies of a straight line of bars in plane 1 or 2 (ω², sorted),
/// keeping only that plane's translation and rotation DOFs of the free grids.
Eigen::VectorXd plane_eigs(int n, double L, MassKind mk, int plane, bool clamped, bool beam,
                           const BarSection& s, const Material& mat) {
  const Vector3d dir = Vector3d(2, -1, 2).normalized();
  const Vector3d v = Vector3d(1, 1, 0);
  Line line(n, dir, v, L);
  for (int e = 0; e < n; ++e) {
    const ElementMatrices em = beam ? beam_matrices(line.geom(e), s, mat, mk) : bar_matrices(line.geom(e), s, mat, mk);
    line.d.add(em.k, em.m, e, e + 1);
  }
  const Eigen::Matrix3d R = bar_element_axes(line.geom(0));
  const Vector3d y = R.row(1), z = R.row(2);
  const int first = clamped ? 1 : 0;
  MatrixXd P = MatrixXd::Zero(6 * (n + 1), 2 * (n + 1 - first));
  int col = 0;
  for (int gidx = first; gidx <= n; ++gidx) {
    add_projection(P, col, gidx, plane == 1 ? y : z, false);
    add_projection(P, col, gidx, plane == 1 ? z : y, true);
  }
  return eig_condensed(P.transpose() * line.d.K * P, P.transpose() * line.d.M * P);
}
}  // namespace

TEST_CASE("bar: Euler-Bernoulli clamped-free and free-free frequencies (beta L tables)", "[bar][frequency]") {
  const double L = 2.0;
  BarSection s{0.01, 2e-5, 5e-6, 0, 1e-5, 0, 0, 0};
  const Material mat{2e11, 8e10, 0.3, 7800};
  const double mu = mat.rho * s.a;
  const double cf[] = {1.87510407, 4.69409113}, ff[] = {4.73004074, 7.85320462};
  for (int plane : {1, 2}) {
    const double EI = mat.e * (plane == 1 ? s.i1 : s.i2);
    auto omega2 = [&](double bl) { return std::pow(bl / L, 4) * EI / mu; };
    // Coupled (consistent) mass: O(h⁴), converged to 1e-5 with 40 elements.
    Eigen::VectorXd ev = plane_eigs(40, L, MassKind::Coupled, plane, true, false, s, mat);
    for (int i = 0; i < 2; ++i) CHECK(std::sqrt(ev(i) / omega2(cf[i])) == Approx(1.0).epsilon(1e-5));
    ev = plane_eigs(40, L, MassKind::Coupled, plane, false, false, s, mat);
    // Two rigid-body modes of the plane, then the free-free pair.
    CHECK(std::abs(ev(0)) < 1e-9 * ev(2));
    CHECK(std::abs(ev(1)) < 1e-9 * ev(2));
    for (int i = 0; i < 2; ++i) CHECK(std::sqrt(ev(i + 2) / omega2(ff[i])) == Approx(1.0).epsilon(1e-5));
    // Lumped (translational only): converges O(h²) from below.
    Eigen::VectorXd e20 = plane_eigs(20, L, MassKind::Lumped, plane, true, false, s, mat);
    Eigen::VectorXd e80 = plane_eigs(80, L, MassKind::Lumped, plane, true, false, s, mat);
    for (int i = 0; i < 2; ++i) {
      const double err20 = std::sqrt(e20(i) / omega2(cf[i])) - 1, err80 = std::sqrt(e80(i) / omega2(cf[i])) - 1;
      CHECK(std::abs(err80) < 5e-4);
      CHECK(err80 < 0);
      CHECK(std::abs(err80) == Approx(std::abs(err20) / 16).epsilon(0.1));
    }
  }
}

TEST_CASE("beam: torsion frequencies of a fixed-free shaft with torsional inertia", "[bar][frequency]") {
  // Circular section: J = I1 + I2, so c = sqrt(G J / ρ Ip) = sqrt(G/ρ).
  const double L = 1.5, r = 0.05;
  const BarSection s{M_PI * r * r, M_PI * std::pow(r, 4) / 4, M_PI * std::pow(r, 4) / 4, 0,
                     M_PI * std::pow(r, 4) / 2, 0, 0, 0};
  const Material mat{2e11, 8e10, 0.3, 7800};
  const double c = std::sqrt(mat.g / mat.rho);
  for (MassKind mk : {MassKind::Lumped, MassKind::Coupled}) {
    const int n = 40;
    Line line(n, Vector3d(0.3, 0.4, -1), Vector3d(1, 0, 0), L);
    for (int e = 0; e < n; ++e) {
      const ElementMatrices em = beam_matrices(line.geom(e), s, mat, mk);
      line.d.add(em.k, em.m, e, e + 1);
    }
    MatrixXd P = MatrixXd::Zero(6 * (n + 1), n);
    int col = 0;
    for (int gidx = 1; gidx <= n; ++gidx) add_projection(P, col, gidx, line.dir, true);
    const Eigen::VectorXd ev = eig_condensed(P.transpose() * line.d.K * P, P.transpose() * line.d.M * P);
    for (int mode = 1; mode <= 3; ++mode) {
      const double exact = (2 * mode - 1) * M_PI * c / (2 * L);
      CHECK(std::sqrt(ev(mode - 1)) / exact == Approx(1.0).epsilon(2e-3));
    }
  }
  // CBAR's lumped mass has no torsional inertia (PARAM,BARMASS = 0), CBEAM's has.
  BarGeometry g;
  g.grids.xb = Vector3d(1, 0, 0);
  CHECK(bar_matrices(g, s, mat, MassKind::Lumped).m(3, 3) == 0.0);
  CHECK(bar_matrices(g, s, mat, MassKind::Lumped, true).m(3, 3) == Approx(mat.rho * s.j / 2));
  CHECK(beam_matrices(g, s, mat, MassKind::Lumped).m(3, 3) == Approx(mat.rho * s.j / 2));
}

TEST_CASE("bar: offsets equal a bar between the offset points plus RBAR rigid links", "[bar][offset]") {
  using namespace ssid::translators;
  std::mt19937 rng(5);
  for (MassKind mk : {MassKind::Lumped, MassKind::Coupled}) {
    BarGeometry g = random_bar(rng, true, 0, 0);
    g.grids.ta = g.grids.tb = Eigen::Matrix3d::Identity();
    const ElementMatrices direct = bar_matrices(g, kSec, kMat, mk);
    // Grids 0 = GA, 1 = A (offset point), 2 = B, 3 = GB.
    BarGeometry inner = g;
    inner.grids.xa = g.grids.xa + g.wa;
    inner.grids.xb = g.grids.xb + g.wb;
    inner.wa.setZero();
    inner.wb.setZero();
    const ElementMatrices em = bar_matrices(inner, kSec, kMat, mk);
    Dense d(4);
    d.add(em.k, em.m, 1, 2);
    auto idx = [](int grid) {
      std::array<std::size_t, 6> a;
      for (int c = 0; c < 6; ++c) a[c] = 6 * grid + c;
      return a;
    };
    std::vector<MpcEquation> mpcs;
    for (auto [gi, gd, x, w] : {std::tuple{0, 1, g.grids.xa, g.wa}, std::tuple{3, 2, g.grids.xb, g.wb}}) {
      std::vector<RigidGrid> rg = {{x, idx(gi), "123456", ""}, {x + w, idx(gd), "", "123456"}};
      auto eq = rigid_equations(rg, "RBAR");
      mpcs.insert(mpcs.end(), eq.begin(), eq.end());
    }
    const Reduction red = build_reduction(24, mpcs, {});
    const MatrixXd T = MatrixXd(red.T);
    const MatrixXd Ka = T.transpose() * d.K * T, Ma = T.transpose() * d.M * T;
    // a-set order follows g order: GA's then GB's DOFs.
    REQUIRE(red.a_to_g.size() == 12);
    CHECK(red.a_to_g[0] == 0);
    CHECK(red.a_to_g[6] == 18);
    CHECK(rel_err(Ka, direct.k) < 1e-12);
    CHECK(rel_err(Ma, direct.m) < 1e-12);
  }
}

TEST_CASE("bar: pin flags by condensation — hinge statics and pinned supports", "[bar][pin]") {
  const Material mat{1.0, 0.4, 0.25, 1.0};
  const BarSection s{1.0, 0.01, 0.02, 0, 0.005, 0, 0, 0};
  SECTION("clamped-hinge-clamped: the hinge load splits between two cantilevers") {
    const double L1 = 1.0, L2 = 1.5, P = 2.0;
    BarGeometry e1, e2;
    e1.grids.xb = Vector3d(L1, 0, 0);
    e1.pb = 6;  // release θz at the hinge end: plane-1 moment free
    e2.grids.xa = e1.grids.xb;
    e2.grids.xb = Vector3d(L1 + L2, 0, 0);
    e1.v = e2.v = Vector3d(0, 1, 0);
    Dense d(3);
    for (auto [g, a, b] : {std::tuple{e1, 0, 1}, std::tuple{e2, 1, 2}}) {
      const ElementMatrices em = bar_matrices(g, s, mat, MassKind::Lumped);
      d.add(em.k, em.m, a, b);
    }
    // Free DOFs: grid 1 only.
    const Eigen::Matrix<double, 6, 6> k = d.K.block<6, 6>(6, 6);
    Eigen::Matrix<double, 6, 1> f = Eigen::Matrix<double, 6, 1>::Zero();
    f(1) = P;
    const Eigen::Matrix<double, 6, 1> u = k.ldlt().solve(f);
    const double EI = mat.e * s.i1;
    CHECK(u(1) == Approx(P / (3 * EI / std::pow(L1, 3) + 3 * EI / std::pow(L2, 3))));
    // Without the pin: fixed-fixed beam with an off-centre load,
    // δ = P a³ b³ / (3 EI L³).
    BarGeometry e1b = e1;
    e1b.pb = 0;
    Dense d2(3);
    for (auto [g, a, b] : {std::tuple{e1b, 0, 1}, std::tuple{e2, 1, 2}}) {
      const ElementMatrices em = bar_matrices(g, s, mat, MassKind::Lumped);
      d2.add(em.k, em.m, a, b);
    }
    const Eigen::Matrix<double, 6, 1> u2 = d2.K.block<6, 6>(6, 6).ldlt().solve(f);
    const double Lt = L1 + L2;
    CHECK(u2(1) == Approx(P * std::pow(L1, 3) * std::pow(L2, 3) / (3 * EI * std::pow(Lt, 3))));
  }
  SECTION("pinned-pinned: condensed pin flags equal explicit rotation DOFs; closed-form frequencies") {
    const int n = 24;
    const double L = 3.0;
    for (MassKind mk : {MassKind::Lumped, MassKind::Coupled}) {
      Line pinned(n, Vector3d(1, 0, 0), Vector3d(0, 1, 0), L), explicit_(n, Vector3d(1, 0, 0), Vector3d(0, 1, 0), L);
      for (int e = 0; e < n; ++e) {
        BarGeometry g = pinned.geom(e);
        ElementMatrices em = bar_matrices(g, s, mat, mk);
        explicit_.d.add(em.k, em.m, e, e + 1);
        if (e == 0) g.pa = 56;
        if (e == n - 1) g.pb = 56;
        em = bar_matrices(g, s, mat, mk);
        pinned.d.add(em.k, em.m, e, e + 1);
      }
      // Pin-flag model: end grids fully fixed. Explicit model: end
      // translations and torsion fixed, bending rotations free.
      std::vector<int> fixed_pin = dofs_of(0), fixed_exp = dofs_of(0, {1, 2, 3, 4});
      for (int c : dofs_of(n)) fixed_pin.push_back(c);
      for (int c : dofs_of(n, {1, 2, 3, 4})) fixed_exp.push_back(c);
      auto reduce = [](const Dense& d, const std::vector<int>& fixed) {
        std::vector<int> keep;
        for (int i = 0; i < d.K.rows(); ++i)
          if (std::find(fixed.begin(), fixed.end(), i) == fixed.end()) keep.push_back(i);
        MatrixXd P = MatrixXd::Zero(d.K.rows(), keep.size());
        for (std::size_t j = 0; j < keep.size(); ++j) P(keep[j], j) = 1;
        return eig_condensed(P.transpose() * d.K * P, P.transpose() * d.M * P);
      };
      const Eigen::VectorXd a = reduce(pinned.d, fixed_pin), b = reduce(explicit_.d, fixed_exp);
      // Plane 1 (I1 = 0.01) modes are the lowest: ω_n = (nπ/L)² sqrt(EI1/μ).
      for (int mode = 1; mode <= 2; ++mode) {
        const double exact2 = std::pow(mode * M_PI / L, 4) * mat.e * s.i1 / (mat.rho * s.a);
        const double tol = mk == MassKind::Coupled ? 1e-5 : 2e-3;
        CHECK(std::sqrt(nearest(a, exact2) / exact2) == Approx(1.0).epsilon(tol));
        CHECK(std::sqrt(nearest(b, exact2) / exact2) == Approx(1.0).epsilon(tol));
      }
      // Lumped mass leaves the released rotations massless, so condensing them
      // is exact: the two models agree to rounding.
      if (mk == MassKind::Lumped) {
        REQUIRE(a.size() == b.size());
        CHECK(rel_err(a.head(10), b.head(10)) < 1e-10);
      }
    }
  }
  CHECK_THROWS_WITH(bar_matrices([] {
                      BarGeometry g;
                      g.grids.xb = Vector3d(1, 0, 0);
                      g.pa = 1, g.pb = 1;
                      return g;
                    }(), s, mat, MassKind::Lumped),
                    Catch::Matchers::Contains("mechanism"));
}

TEST_CASE("bar/beam: Timoshenko shear flexibility against closed forms", "[bar][shear]") {
  const Material mat{1.0, 0.35, 0.3, 1.0};
  const BarSection s{0.2, 0.004, 0.002, 0, 0.003, 0, 0.85, 0.6};
  SECTION("cantilever tip load: δ = PL³/3EI + PL/kGA, θ = PL²/2EI, exact with one element") {
    const double L = 0.7, P = 1.3;
    BarGeometry g;
    g.grids.xb = Vector3d(L, 0, 0);
    g.v = Vector3d(0, 1, 0);
    for (bool beam : {false, true}) {
      const ElementMatrices em = beam ? beam_matrices(g, s, mat, MassKind::Lumped) : bar_matrices(g, s, mat, MassKind::Lumped);
      const Eigen::Matrix<double, 6, 6> k = em.k.bottomRightCorner<6, 6>();
      Eigen::Matrix<double, 6, 1> f = Eigen::Matrix<double, 6, 1>::Zero();
      f(1) = P, f(2) = P;  // both planes at once
      const Eigen::Matrix<double, 6, 1> u = k.ldlt().solve(f);
      CHECK(u(1) == Approx(P * L * L * L / (3 * mat.e * s.i1) + P * L / (s.k1 * mat.g * s.a)));
      CHECK(u(2) == Approx(P * L * L * L / (3 * mat.e * s.i2) + P * L / (s.k2 * mat.g * s.a)));
      CHECK(u(5) == Approx(P * L * L / (2 * mat.e * s.i1)));
      CHECK(u(4) == Approx(-P * L * L / (2 * mat.e * s.i2)));
    }
  }
  SECTION("simply supported shear beam: ω² = (EI/μ)(nπ/L)⁴ / (1 + (nπ/L)² EI/kGA)") {
    // The coupled mass uses Euler–Bernoulli shape functions, which the shear
    // deformation does not follow, so the frequencies converge O(h²) (error /4
    // per halving) rather than O(h⁴); the limit is the closed form.
    auto errors = [&](int n) {
      const double L = 1.0;
      Line line(n, Vector3d(1, 0, 0), Vector3d(0, 1, 0), L);
      for (int e = 0; e < n; ++e) {
        const ElementMatrices em = beam_matrices(line.geom(e), s, mat, MassKind::Coupled);
        line.d.add(em.k, em.m, e, e + 1);
      }
      // Plane 1 only: y translation and z rotation of every grid; ends pinned.
      MatrixXd P = MatrixXd::Zero(6 * (n + 1), 2 * (n + 1) - 2);
      int col = 0;
      for (int gidx = 0; gidx <= n; ++gidx) {
        if (gidx != 0 && gidx != n) add_projection(P, col, gidx, Vector3d::UnitY(), false);
        add_projection(P, col, gidx, Vector3d::UnitZ(), true);
      }
      const Eigen::VectorXd ev = eig_condensed(P.transpose() * line.d.K * P, P.transpose() * line.d.M * P);
      const double EI = mat.e * s.i1, kGA = s.k1 * mat.g * s.a, mu = mat.rho * s.a;
      std::vector<double> err;
      for (int mode = 1; mode <= 3; ++mode) {
        const double kn = mode * M_PI / L;
        const double eb = EI / mu * std::pow(kn, 4);
        const double timo = eb / (1 + kn * kn * EI / kGA);
        CHECK(timo < 0.97 * eb);  // the correction is substantial here
        err.push_back(ev(mode - 1) / timo - 1);
      }
      return err;
    };
    const auto e40 = errors(40), e80 = errors(80);
    for (int i = 0; i < 3; ++i) {
      CHECK(std::abs(e80[i]) < 1e-3);
      CHECK(e80[i] / e40[i] == Approx(0.25).epsilon(0.02));
    }
  }
}

TEST_CASE("bar: lumped mass at offset points, total mass and geometry errors", "[bar]") {
  BarGeometry g;
  g.grids.xb = Vector3d(2, 0, 0);
  g.v = Vector3d(0, 1, 0);
  g.wa = Vector3d(0, 0, 1);
  g.wb = Vector3d(0, 0, 1);
  const BarSection s{0.5, 0.01, 0.01, 0, 0.01, 0.25, 0, 0};
  const Material mat{1, 0.4, 0.25, 3};
  const ElementMatrices em = bar_matrices(g, s, mat, MassKind::Lumped);
  const double half = (0.5 * 3 + 0.25) * 2 / 2;
  CHECK(em.m(0, 0) == Approx(half));
  CHECK(em.m(3, 3) == Approx(half));  // m w² about x (w along z)
  CHECK(em.m(4, 4) == Approx(half));  // about y
  CHECK(em.m(5, 5) == 0.0);           // about z: w parallel
  CHECK(em.m(0, 4) == Approx(half));  // u_x = u + θy w_z
  using Catch::Matchers::Contains;
  BarGeometry bad = g;
  bad.v = Vector3d(1, 0, 0);
  CHECK_THROWS_WITH(bar_matrices(bad, s, mat, MassKind::Lumped), Contains("parallel"));
  bad = g;
  bad.pa = 7;
  CHECK_THROWS_WITH(bar_matrices(bad, s, mat, MassKind::Lumped), Contains("digit 7"));
}

#include "translators/elements/section.hpp"

TEST_CASE("bar: PBARL dimension derivatives by the chain rule match central differences", "[bar][derivative][section]") {
  std::mt19937 rng(17);
  const BarGeometry g = random_bar(rng, true, 0, 6);
  // Sections of each kind: open, with I12 (L, Z), closed (two cells, hat on a
  // plate), solid polygon. Dimensions scaled to the bar's length.
  const std::pair<SectionShape, std::vector<double>> shapes[] = {
      {SectionShape::I, {12.0, 8.0, 4.0, 0.6, 1.2, 0.8}},
      {SectionShape::L, {3.0, 4.0, 0.3, 0.4}},
      {SectionShape::Z, {2.5, 0.4, 5.0, 6.0}},
      {SectionShape::Chan2, {0.3, 0.4, 2.0, 5.0}},
      {SectionShape::Hat1, {4.0, 2.0, 2.0, 0.15, 0.2}},
      {SectionShape::DBox, {6.0, 2.0, 3.5, 0.2, 0.3, 0.25, 0.15, 0.2, 0.1, 0.3}},
      {SectionShape::Hexa, {0.5, 3.0, 1.7}}};
  for (const auto& [shape, dims0] : shapes) {
  std::vector<double> dims = dims0;
  for (double& d : dims) d *= 0.01;
  auto section = [shape = shape](const std::vector<double>& d) {
    const SectionProperties p = section_properties(shape, d);
    return BarSection{p.a, p.i1, p.i2, p.i12, p.j, 0.1, p.k1, p.k2};
  };
  const auto jac = section_jacobian(shape, dims);
  for (MassKind mk : {MassKind::Lumped, MassKind::Coupled})
    for (std::size_t k = 0; k < dims.size(); ++k) {
      BarSection ds{jac(0, k), jac(1, k), jac(2, k), jac(3, k), jac(4, k), 0, jac(5, k), jac(6, k)};
      const ElementMatrices d = beam_directional_derivative(g, section(dims), kMat, mk, ds, Material{0, 0, 0, 0});
      // 1e-4: HAT1's area does not depend on DIM3, so its mass derivative is small
      // against M and a smaller step would leave the difference to rounding.
      const double h = 1e-4 * dims[k];
      auto dp = dims, dm = dims;
      dp[k] += h, dm[k] -= h;
      const ElementMatrices p = beam_matrices(g, section(dp), kMat, mk), m = beam_matrices(g, section(dm), kMat, mk);
      INFO(section_shape_name(shape) << " DIM" << k + 1);
      CHECK(rel_err(d.k, (p.k - m.k) / (2 * h)) < 1e-6);
      CHECK(rel_err(d.m, (p.m - m.m) / (2 * h)) < 1e-6);
    }
  }
}

TEST_CASE("bar/beam/rod: a free 3D frame has exactly six zero eigenvalues", "[bar][frequency]") {
  // A non-planar frame of bars and beams in random CD frames, coupled mass.
  std::mt19937 rng(23);
  const std::vector<Vector3d> x = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0.3}, {0.5, 0.5, 1}};
  std::vector<Eigen::Matrix3d> t;
  for (std::size_t i = 0; i < x.size(); ++i) t.push_back(random_rotation(rng));
  const int members[][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {0, 4}, {1, 4}, {2, 4}, {3, 4}};
  Dense d(static_cast<int>(x.size()));
  int e = 0;
  for (auto [a, b] : members) {
    BarGeometry g;
    g.grids = {x[a], x[b], t[a], t[b]};
    g.v = Vector3d(0.3, -0.2, 1.0).cross(x[b] - x[a]) + Vector3d(0.1, 0.2, 0.3);
    g.wa = Vector3d(0.01, -0.02, 0.03);
    const ElementMatrices em = (e++ % 2) ? bar_matrices(g, kSec, kMat, MassKind::Coupled)
                                          : beam_matrices(g, kSec, kMat, MassKind::Coupled);
    d.add(em.k, em.m, a, b);
  }
  const Eigen::VectorXd ev = d.eigenvalues({});
  for (int i = 0; i < 6; ++i) CHECK(std::abs(ev(i)) < 1e-9 * ev(6));
  CHECK(ev(6) > 1e-6 * ev(ev.size() - 1));  // the seventh is a real elastic mode
}
