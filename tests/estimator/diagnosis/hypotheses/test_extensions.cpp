// The model-form extensions (estimator/diagnosis/hypotheses) as physics — here, not in
// the translators tests, because the checks need the eigen-solver: each extended deck assembles; the
// screening derivatives equal the extended model's own ∂K/∂β, ∂M/∂β (assembled
// from the written cards); the limits of the new parameters give back the
// nominal model (a massless spring's surge at infinity, a rigid joint).
#include <Eigen/Dense>
#include <set>
#include <catch2/catch.hpp>

#include "formats/bulk_model.hpp"
#include "estimator/study/deck_study.hpp"
#include "estimator/eigen/eigen_solver.hpp"
#include "tests/estimator/diagnosis/truss_cases.hpp"
#include "estimator/diagnosis/hypotheses/model_extension.hpp"

using namespace ssid;
using namespace ssid::test_support;
namespace ext = ssid::estimator::diagnosis::hypotheses;

namespace {

struct Loaded {
  std::unique_ptr<formats::Deck> deck;
  std::unique_ptr<translators::FeModel> fe;
};
Loaded load(const std::string& text) {
  Loaded l;
  l.deck = std::make_unique<formats::Deck>(formats::read_deck_text(text, "x.bdf"));
  l.fe = std::make_unique<translators::FeModel>(*l.deck, formats::resolved_bulk(*l.deck));
  return l;
}

Eigen::VectorXd frequencies(const translators::FeModel& fe, const Eigen::VectorXd& x, int n) {
  const auto ops = fe.operators(x, false);
  estimator::EigenOptions o;
  o.nd = n;
  const auto r = estimator::solve_modes(ops.K, ops.M, o);
  REQUIRE(r.ok());
  Eigen::VectorXd f(r.size());
  for (int i = 0; i < r.size(); ++i) f(i) = r.cycles(i);
  return f;
}

double max_abs(const Eigen::SparseMatrix<double>& A) {
  double m = 0;
  for (int k = 0; k < A.outerSize(); ++k)
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, k); it; ++it) m = std::max(m, std::abs(it.value()));
  return m;
}

}  // namespace

TEST_CASE("missing_mass and local_stiffness: screening derivatives are the extended deck's", "[translators][extensions]") {
  const Case c = rod_case();
  const std::string text = deck_text(c.t, c.fe);
  const Loaded nominal = load(text);
  for (const auto& kind : {ext::make_missing_mass({}), ext::make_local_stiffness({})}) {
    const auto cands = kind->candidates(*nominal.fe);
    REQUIRE(cands.size() >= 80);
    for (std::size_t i : {std::size_t{0}, cands.size() / 2, cands.size() - 1}) {
      const auto& cand = cands[i];
      CAPTURE(kind->kind(), cand.location.text);
      const auto s = kind->screening(*nominal.fe, cand);
      REQUIRE(s);
      const ext::ExtendedDeck xd = kind->apply(text, "x.bdf", *nominal.fe, cand);
      REQUIRE(xd.parameters.size() == 1);
      CHECK(xd.parameters[0].prior_std == Approx(s->prior_std[0]));
      const Loaded extended = load(xd.text);
      REQUIRE(extended.fe->parameters().size() == nominal.fe->parameters().size() + 1);
      const auto ops = extended.fe->operators(extended.fe->initial_parameters(), true);
      REQUIRE(ops.K.rows() == s->dK[0].rows());
      const Eigen::SparseMatrix<double> dK = ops.dK.back() - s->dK[0], dM = ops.dM.back() - s->dM[0];
      CHECK(max_abs(dK) <= 1e-9 * std::max(1.0, max_abs(ops.dK.back())));
      CHECK(max_abs(dM) <= 1e-9 * std::max(1.0, max_abs(ops.dM.back())));
      CHECK(max_abs(ops.dK.back()) + max_abs(ops.dM.back()) > 0);
      // At β = 0 (the prior mean) the extended model is the nominal one.
      const auto K0 = nominal.fe->operators(nominal.fe->initial_parameters(), false);
      CHECK(max_abs(ops.K - K0.K) <= 1e-9 * max_abs(K0.K));
      CHECK(max_abs(ops.M - K0.M) <= 1e-9 * max_abs(K0.M));
    }
  }
}

TEST_CASE("local_stiffness of a CBAR: a PBAR of its own, its section x (1 + beta), scales bending as well",
          "[translators][extensions]") {
  Case c = frame_case();
  c.fe.mat.rho = 2700.0;  // tubes with mass of their own: the change must keep it
  const std::string text = deck_text(c.t, c.fe);
  const Loaded nominal = load(text);
  const auto kind = ext::make_local_stiffness({});
  const auto cands = kind->candidates(*nominal.fe);
  REQUIRE(cands.size() == 32);  // the frame's 32 members
  const auto K0 = nominal.fe->operators(nominal.fe->initial_parameters(), false);
  for (std::size_t i : {std::size_t{0}, std::size_t{17}, std::size_t{31}}) {
    const auto& cand = cands[i];
    CAPTURE(cand.location.text);
    REQUIRE(cand.location.text.rfind("CBAR", 0) != std::string::npos);
    const auto s = kind->screening(*nominal.fe, cand);
    REQUIRE(s);
    const ext::ExtendedDeck xd = kind->apply(text, "x.bdf", *nominal.fe, cand);
    REQUIRE(xd.parameters.size() == 1);
    CHECK(xd.parameters[0].prior_std == Approx(s->prior_std[0]));
    CHECK(xd.parameters[0].lower == -0.95);
    const Loaded extended = load(xd.text);
    const auto ops = extended.fe->operators(extended.fe->initial_parameters(), true);
    const Eigen::SparseMatrix<double> dK = ops.dK.back() - s->dK[0];
    CHECK(max_abs(dK) <= 1e-9 * max_abs(ops.dK.back()));
    CHECK(max_abs(ops.dM.back()) == 0.0);  // no mass added or removed
    CHECK(max_abs(s->dM[0]) <= 1e-12 * max_abs(K0.M));
    CHECK(max_abs(ops.K - K0.K) <= 1e-9 * max_abs(K0.K));
    CHECK(max_abs(ops.M - K0.M) <= 1e-12 * max_abs(K0.M));
    // The derivative carries the member's bending and torsion, not only its tension: on
    // a rotation of a ball-surface grid, where an axial rod adds nothing.
    const Eigen::MatrixXd d(s->dK[0]);
    double rotational = 0;
    const auto& gset = nominal.fe->geometry().gset();
    const auto& a_to_g = nominal.fe->reduction().a_to_g;
    for (Eigen::Index r = 0; r < d.rows(); ++r)
      if (gset.at(a_to_g[static_cast<std::size_t>(r)]).component >= 4) rotational = std::max(rotational, std::abs(d(r, r)));
    CHECK(rotational > 0);
    // β = −0.5 halves the member: the extended K is K0 − 0.5 · K_e, the mass unchanged.
    ext::Candidate half = cand;
    half.start = {-0.5};
    const Loaded h = load(kind->apply(text, "x.bdf", *nominal.fe, half).text);
    const auto Oh = h.fe->operators(h.fe->initial_parameters(), false);
    const Eigen::SparseMatrix<double> expect = K0.K - 0.5 * s->dK[0];
    CHECK(max_abs(Oh.K - expect) <= 1e-9 * max_abs(K0.K));
    CHECK(max_abs(Oh.M - K0.M) <= 1e-12 * max_abs(K0.M));
    // The member still follows the deck's parameter (TUBEI designs I1, I2, J): at TUBEI x 2,
    // with β = 0, the extended model is the nominal one.
    const Loaded x = load(xd.text);
    Eigen::VectorXd p = x.fe->initial_parameters();
    Eigen::VectorXd pn = nominal.fe->initial_parameters();
    p(0) *= 2;
    pn(0) *= 2;
    CHECK(max_abs(x.fe->operators(p, false).K - nominal.fe->operators(pn, false).K) <=
          1e-9 * max_abs(K0.K));
  }
  // Coupled mass: the rotary terms ρI move with the section; the screening's ∂M/∂β is the deck's.
  std::string coupled = text;
  coupled.insert(coupled.find("ENDDATA"), "PARAM   COUPMASS1\nPARAM   WTMASS  .5\n");
  const Loaded cn = load(coupled);
  REQUIRE(cn.fe->coupled_mass());
  const auto s = kind->screening(*cn.fe, cands[5]);
  REQUIRE(s);
  const Loaded cx = load(kind->apply(coupled, "x.bdf", *cn.fe, cands[5]).text);
  const auto ops = cx.fe->operators(cx.fe->initial_parameters(), true);
  CHECK(max_abs(ops.dK.back() - s->dK[0]) <= 1e-9 * max_abs(ops.dK.back()));
  CHECK(max_abs(ops.dM.back() - s->dM[0]) <= 1e-9 * std::max(max_abs(ops.dM.back()), 1e-30));
}

TEST_CASE("support_dynamics: static rate kept, first surge at sqrt(5k/2m)/2pi, light spring gives the nominal modes",
          "[translators][extensions]") {
  const Case c = rod_case();
  const std::string text = deck_text(c.t, c.fe);
  const Loaded nominal = load(text);
  ext::ExtensionOptions o;
  o.unexplained_hz = {48.0};
  const auto kind = ext::make_support_dynamics(o);
  const auto cands = kind->candidates(*nominal.fe);
  const ext::Candidate* vertical = nullptr;
  for (const auto& cand : cands)
    if (cand.ids.size() == 1 && cand.location.text.find("component 3") != std::string::npos) vertical = &cand;
  REQUIRE(vertical);
  const Eigen::VectorXd f0 = frequencies(*nominal.fe, nominal.fe->initial_parameters(), 20);
  // A very light spring: the surge is far above, the structure's modes unchanged.
  ext::Candidate light = *vertical;
  light.start = {1e-9};
  const Loaded l = load(kind->apply(text, "x.bdf", *nominal.fe, light).text);
  const Eigen::VectorXd f1 = frequencies(*l.fe, l.fe->initial_parameters(), 20);
  for (int i = 0; i < 20; ++i) CHECK(f1(i) == Approx(f0(i)).epsilon(1e-6).margin(1e-6));
  // The start places the isolated spring's first surge (ball held) at 48 Hz: m₁ = 5k/(2(2π·48)²).
  const ext::ExtendedDeck xd = kind->apply(text, "x.bdf", *nominal.fe, *vertical);
  const double k = 600.0;
  CHECK(xd.parameters[0].start == Approx(2.5 * k / std::pow(2 * M_PI * 48.0, 2)));
  // The spring's rate stays designed by KSUSP through the three new PELAS, × 5, × 7/2 and × 35/18.
  const Loaded x = load(xd.text);
  std::set<double> factors;
  for (const auto& r : x.fe->bulk().dvprel1s)
    if (r.type == "PELAS" && r.pid > 1000)
      for (const auto& [dv, coef] : r.terms) factors.insert(coef);
  REQUIRE(factors.size() == 3);
  CHECK(*factors.begin() == Approx(35.0 / 18.0));
  CHECK(*std::next(factors.begin()) == Approx(3.5));
  CHECK(*factors.rbegin() == Approx(5.0));
  // Static rate unchanged: the rigid-body-like suspension modes do not move (checked above).
  // Hypotheses start from the ordinary update: with KSUSP moved to 150 N/m the
  // start keeps the surge at 48 Hz with that rate, m₁ = 5·150/(2(2π·48)²).
  ext::ExtensionOptions moved = o;
  moved.updated = {{"KSUSP", 150.0}};
  int found = 0;
  for (const auto& cand : ext::make_support_dynamics(moved)->candidates(*nominal.fe))
    if (cand.location.text == vertical->location.text) {
      ++found;
      REQUIRE(cand.start.size() == 1);
      CHECK(cand.start[0] == Approx(2.5 * 150.0 / std::pow(2 * M_PI * 48.0, 2)));
    }
  CHECK(found == 1);
}

TEST_CASE("support_dynamics: a mass on the refined spring moves as on a continuous spring's two first surges",
          "[translators][extensions]") {
  // A 10 kg mass on a 600 N/m spring, free along z only. A continuous spring
  // with its far end held pulls on the mass with K(ω) = k x cot x =
  // k − Σ_n 2k s/(n² s₁ − s), s = ω² (the partial fractions of x cot x, worked
  // by hand, not ssid's chain); the refined spring is built to have the first
  // two terms exactly and the rest as their low-frequency limit, a mass
  // Σ_{n≥3} 2k/(n² s₁) = (2k/s₁)(π²/6 − 5/4), so each mode of the extended deck solves
  // M s = k − M_r s − 2k s/(s₁ − s) − 2k s/(4 s₁ − s), s₁ = (2π·30)² the start's surge;
  // with the mass held the chain surges at 30 and 60 Hz; and as s → 0 the spring
  // pulls with k − s m/3, m = π²k/s₁ the continuous spring's mass.
  const std::string text =
      "SOL 103\nCEND\nBEGIN BULK\n"
      "GRID    1               0.      0.      0.              12456\n"
      "CONM2   5       1               10.\n"
      "PELAS   11      600.\n"
      "CELAS1  7       11      1       3\n"
      "ENDDATA\n";
  const Loaded nominal = load(text);
  ext::ExtensionOptions o;
  o.unexplained_hz = {30.0};
  o.lowest_test_hz = 1.0;
  const auto kind = ext::make_support_dynamics(o);
  const auto cands = kind->candidates(*nominal.fe);
  REQUIRE(cands.size() == 1);
  const ext::ExtendedDeck xd = kind->apply(text, "x.bdf", *nominal.fe, cands[0]);
  const Loaded x = load(xd.text);
  // Every mode of the 3-DOF a-set, by a dense solve (the Lanczos solver stops short of n).
  const auto ops = x.fe->operators(x.fe->initial_parameters(), false);
  REQUIRE(ops.K.rows() == 3);
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(Eigen::MatrixXd(ops.K), Eigen::MatrixXd(ops.M));
  const double k = 600, M = 10, s1 = std::pow(2 * M_PI * 30.0, 2);
  const double Mr = 2 * k / s1 * (M_PI * M_PI / 6 - 1.25);
  for (Eigen::Index i = 0; i < 3; ++i) {
    const double s = es.eigenvalues()(i);
    CAPTURE(i, std::sqrt(s) / (2 * M_PI));
    CHECK(M * s - (k - Mr * s - 2 * k * s / (s1 - s) - 2 * k * s / (4 * s1 - s)) == Approx(0.0).margin(1e-8 * k));
  }

  // The mass held (its row and column out): the chain's own surges.
  Eigen::MatrixXd K = Eigen::MatrixXd(ops.K), Mm = Eigen::MatrixXd(ops.M);
  Eigen::Index held = 0;
  Mm.diagonal().maxCoeff(&held);  // the 10 kg grid
  std::vector<Eigen::Index> keep;
  for (Eigen::Index i = 0; i < 3; ++i)
    if (i != held) keep.push_back(i);
  Eigen::Matrix2d Kc, Mc;
  for (int r = 0; r < 2; ++r)
    for (int c = 0; c < 2; ++c) {
      Kc(r, c) = K(keep[static_cast<std::size_t>(r)], keep[static_cast<std::size_t>(c)]);
      Mc(r, c) = Mm(keep[static_cast<std::size_t>(r)], keep[static_cast<std::size_t>(c)]);
    }
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::Matrix2d> chain(Kc, Mc);
  CHECK(std::sqrt(chain.eigenvalues()(0)) / (2 * M_PI) == Approx(30.0).epsilon(1e-12));
  CHECK(std::sqrt(chain.eigenvalues()(1)) / (2 * M_PI) == Approx(60.0).epsilon(1e-12));
  // The low-frequency inertia on the mass, −dK(s)/ds at s = 0 of the condensed pull
  // K(s) = K_gg − s M_gg − K_gi (K_ii − s M_ii)⁻¹ K_ig less the 10 kg:
  // (M_gg − 10) + tᵀ M_ii t, t = K_ii⁻¹ K_ig, is the continuous spring's m/3.
  Eigen::Vector2d kig;
  for (int r = 0; r < 2; ++r) kig(r) = K(keep[static_cast<std::size_t>(r)], held);
  const Eigen::Vector2d t = Kc.ldlt().solve(kig);
  CHECK(Mm(held, held) - M + t.dot(Mc * t) == Approx(M_PI * M_PI * k / s1 / 3).epsilon(1e-10));
}

TEST_CASE("joint_flexibility: a stiff rotational spring gives the rigid joint back, a soft one lowers modes",
          "[translators][extensions]") {
  // Beam form of the first optics bay (8 balls), free-free.
  Case c{tr::build_configured({}), {}};
  c.t.suspension.clear();
  c.t.balls.resize(8);
  std::vector<tr::Member> kept;
  for (const auto& m : c.t.members)
    if (m.a <= 8 && m.b <= 8) kept.push_back(m);
  c.t.members = kept;
  c.fe = tr::build_truss_cards(c.t, tr::ModelForm::Beam);
  fix_property_ids(c.fe);
  const std::string text = deck_text(c.t, c.fe);
  const Loaded nominal = load(text);
  const auto kind = ext::make_joint_flexibility({});
  const auto cands = kind->candidates(*nominal.fe);
  REQUIRE(cands.size() == 27);  // 8 balls and "all", three starts each (k̄/10, k̄/100, k̄/1000)
  CHECK(cands[0].location.text == cands[2].location.text);
  CHECK(cands[1].start.at(0) == Approx(0.1 * cands[0].start.at(0)));
  const Eigen::VectorXd f0 = frequencies(*nominal.fe, nominal.fe->initial_parameters(), 30);
  ext::Candidate all = cands.back();
  REQUIRE(all.ids.front() == 0);
  const double kbar = kind->apply(text, "x.bdf", *nominal.fe, all).parameters[0].prior_mean;
  all.start = {1e6 * kbar};
  const Loaded stiff = load(kind->apply(text, "x.bdf", *nominal.fe, all).text);
  const Eigen::VectorXd f1 = frequencies(*stiff.fe, stiff.fe->initial_parameters(), 30);
  for (int i = 6; i < 30; ++i) CHECK(f1(i) == Approx(f0(i)).epsilon(1e-4));
  all.start = {1e-3 * kbar};
  const Loaded soft = load(kind->apply(text, "x.bdf", *nominal.fe, all).text);
  const Eigen::VectorXd f2 = frequencies(*soft.fe, soft.fe->initial_parameters(), 30);
  int lower = 0;
  for (int i = 6; i < 30; ++i) lower += f2(i) < f0(i) * (1 - 1e-3);
  CHECK(lower >= 12);
  for (int i = 6; i < 30; ++i) CHECK(f2(i) <= f0(i) * (1 + 1e-9));  // softening never stiffens
}

TEST_CASE("local_modes: the strut's bending mode at the start frequency; soft and massless gives the rod back",
          "[translators][extensions]") {
  // One rod between two grids held in every DOF, each carrying a 2 kg CONM2
  // (the strut mass lumped at its ends, as in a rod model): refined, the only
  // modes are those of the three inner grids. With μ moved inwards (μ/3 at each),
  // the first bending pair of the chain of four bars clamped at both ends
  // sits where the 3×3 problem of the inner translations puts it once the
  // rotations are condensed out of the Euler–Bernoulli bar matrices (worked
  // apart from the code, in numpy): its symmetric eigenvalues solve
  // x² − 39x + 72 = 0 and the antisymmetric one is 96/7, in units of EI/(m h³).
  // Axially each inner grid sees two quarters of rate 4EA/L.
  const std::string text =
      "SOL 103\nCEND\nBEGIN BULK\n"
      "GRID    1               0.      0.      0.              123456\n"
      "GRID    2               1.      0.      0.              123456\n"
      "MAT1    1       7.+10           .3      0.\n"
      "PROD    7       1       1.-4\n"
      "CROD    11      7       1       2\n"
      "CONM2   21      1               2.\n"
      "CONM2   22      2               2.\n"
      "ENDDATA\n";
  const Loaded nominal = load(text);
  ext::ExtensionOptions o;
  o.unexplained_hz = {40.0};
  o.lowest_test_hz = 10.0;
  o.highest_test_hz = 60.0;
  const auto kind = ext::make_local_modes(o);
  const auto cands = kind->candidates(*nominal.fe);
  REQUIRE(cands.size() == 1);
  REQUIRE(cands[0].start.size() == 2);  // I and the moved mass μ
  const double mu = cands[0].start[1];
  CHECK(mu == Approx(0.25 * 2.0));
  const ext::ExtendedDeck xd = kind->apply(text, "x.bdf", *nominal.fe, cands[0]);
  REQUIRE(xd.parameters.size() == 2);
  const Loaded x = load(xd.text);
  const Eigen::VectorXd f = frequencies(*x.fe, x.fe->initial_parameters(), 2);
  CAPTURE(f.transpose(), xd.text);
  REQUIRE(f.size() == 2);
  const double E = 7e10, A = 1e-4, L = 1.0, I = cands[0].start[0], h = L / 4, m = mu / 3;
  CHECK(f(0) == Approx(40.0).epsilon(1e-9));
  CHECK(f(1) == Approx(40.0).epsilon(1e-9));
  const double x1 = (39 - std::sqrt(1233.0)) / 2;
  CHECK(x1 * E * I / (m * h * h * h) == Approx(std::pow(2 * M_PI * 40.0, 2)));
  // Every mode of the chain: per plane x1, 96/7, (39 + √1233)/2; axially the
  // fixed–fixed chain of four springs 4EA/L with three masses m: (2 ∓ √2, 2)·4EA/(L m).
  const Eigen::VectorXd all = frequencies(*x.fe, x.fe->initial_parameters(), 8);
  REQUIRE(all.size() == 8);
  std::vector<double> expected;
  for (double xb : {x1, 96.0 / 7.0, (39 + std::sqrt(1233.0)) / 2})
    for (int plane = 0; plane < 2; ++plane) expected.push_back(std::sqrt(xb * E * I / (m * h * h * h)) / (2 * M_PI));
  for (double xa : {2 - std::sqrt(2.0), 2.0, 2 + std::sqrt(2.0)})
    expected.push_back(std::sqrt(xa * 4 * E * A / (L * m)) / (2 * M_PI));
  std::sort(expected.begin(), expected.end());
  for (int i = 0; i < 8; ++i) CHECK(all(i) == Approx(expected[static_cast<std::size_t>(i)]).epsilon(1e-8));
  // The axial rate at an inner grid is the two quarters' 2·4EA/L: the rod's EA/L in series.
  const auto ops = x.fe->operators(x.fe->initial_parameters(), false);
  const auto& gm = x.fe->geometry().grid(1002, "test");
  const auto ax = static_cast<Eigen::Index>(gm.dofs[0]);
  CHECK(ops.Kg.coeff(ax, ax) == Approx(8 * E * A / L));
  CHECK(ops.Mg.coeff(ax, ax) == Approx(m));
  // Total mass unchanged: +μ in the middle, −μ/2 at each end.
  CHECK(ext::total_mass(*x.fe) == Approx(ext::total_mass(*nominal.fe)));
  // The written deck designs the new PBAR from the DESVAR: I1 = I2 = I.
  int designed = 0;
  for (const auto& r : x.fe->bulk().dvprel1s)
    if (r.type == "PBAR") ++designed;
  CHECK(designed == 2);
}

TEST_CASE("local_modes on the rod truss: a stiff or a soft massless refinement leaves the modes unchanged",
          "[translators][extensions]") {
  const Case c = rod_case();
  const std::string text = deck_text(c.t, c.fe);
  const Loaded nominal = load(text);
  ext::ExtensionOptions o;
  o.lowest_test_hz = 2.0;
  o.highest_test_hz = 66.0;
  CHECK(ext::make_local_modes(o)->candidates(*nominal.fe).empty());  // nothing unexplained: nothing offered
  o.always_offer = true;
  const auto kind = ext::make_local_modes(o);
  const auto cands = kind->candidates(*nominal.fe);
  REQUIRE(cands.size() == 252);  // every CROD, one start each
  const Eigen::VectorXd f0 = frequencies(*nominal.fe, nominal.fe->initial_parameters(), 20);
  // The bars are clamped to the strut's chord, not to the balls' rotations (held
  // to ground by PS 456 in the rod model): bending inertia far above the real
  // tube's or the lowest the prior allows, nothing moved (massless inner grids),
  // the 20 lowest modes — the suspension's six at 0.3-0.6 Hz among them, which a
  // clamp into the held rotations moved by 1.7e-5 at the lowest I and by far
  // more at a tube's — stay as they were.
  for (double inertia : {1e-4, 0.0}) {
    ext::Candidate c100 = cands[100];
    c100.start = {inertia, 0.0};
    const Loaded l = load(kind->apply(text, "x.bdf", *nominal.fe, c100).text);
    const Eigen::VectorXd f1 = frequencies(*l.fe, l.fe->initial_parameters(), 20);
    CAPTURE(inertia);
    for (int i = 0; i < 20; ++i) CHECK(f1(i) == Approx(f0(i)).epsilon(1e-6).margin(1e-6));
  }
  // The lower bound on I is positive (no mechanism), and a soft strut adds modes below the nominal band top.
  ext::Candidate prior = cands[100];
  prior.start = {};
  const ext::ExtendedDeck xd = kind->apply(text, "x.bdf", *nominal.fe, prior);
  CHECK(xd.parameters[0].lower > 0);
}

TEST_CASE("support_dynamics: a group of springs also starts matched, each at the mode its surge's shape gives",
          "[translators][extensions]") {
  // Two masses free along z, each on a spring of the same PELAS. Made-up
  // analysis modes: mode 1 moves grid 1 only (10 Hz), mode 2 grid 2 only
  // (20 Hz), seen by two sensors (grid 1 z, grid 2 z). Unexplained test modes at
  // 15 Hz moving grid 2 and at 25 Hz moving grid 1: a force at grid 1's spring
  // is answered at grid 1 only, so spring 1 matches the 25 Hz mode and spring 2
  // the 15 Hz one, the reverse of the "spread" start (spring i at frequency i).
  const std::string text =
      "SOL 103\nCEND\nBEGIN BULK\n"
      "GRID    1               0.      0.      0.              12456\n"
      "GRID    2               1.      0.      0.              12456\n"
      "CONM2   5       1               10.\n"
      "CONM2   6       2               10.\n"
      "PELAS   11      600.\n"
      "CELAS1  7       11      1       3\n"
      "CELAS1  8       11      2       3\n"
      "ENDDATA\n";
  const Loaded nominal = load(text);
  const auto& g1 = nominal.fe->geometry().grid(1, "test");
  const auto& g2 = nominal.fe->geometry().grid(2, "test");
  const auto n = static_cast<Eigen::Index>(nominal.fe->geometry().gset().size());
  ext::ExtensionOptions o;
  o.unexplained_hz = {15.0, 25.0};
  o.lowest_test_hz = 5.0;
  auto& x = o.unexplained;
  x.eigenvalues = Eigen::Vector2d(std::pow(2 * M_PI * 10, 2), std::pow(2 * M_PI * 20, 2));
  x.g_shapes = Eigen::MatrixXd::Zero(n, 2);
  x.g_shapes(static_cast<Eigen::Index>(g1.dofs[2]), 0) = 1.0;
  x.g_shapes(static_cast<Eigen::Index>(g2.dofs[2]), 1) = 1.0;
  x.sensor_shapes = Eigen::Matrix2d::Identity();
  x.test_shapes = {Eigen::Vector2d(0.1, 1.0), Eigen::Vector2d(1.0, -0.1)};
  x.neighbour = {1, 0};
  const auto cands = ext::make_support_dynamics(o)->candidates(*nominal.fe);
  const double k = 600;
  auto mass = [&](double f) { return 2.5 * k / std::pow(2 * M_PI * f, 2); };
  bool matched = false, spread = false;
  for (const auto& c : cands) {
    if (c.ids.size() != 2) continue;
    REQUIRE(c.start.size() == 2);
    const bool first_is_grid1 = c.location.grids.at(0) == 1;
    const double m1 = first_is_grid1 ? c.start[0] : c.start[1], m2 = first_is_grid1 ? c.start[1] : c.start[0];
    matched = matched || (m1 == Approx(mass(25.0)) && m2 == Approx(mass(15.0)));
    spread = spread || (m1 == Approx(mass(15.0)) && m2 == Approx(mass(25.0)));
  }
  CHECK(matched);
  CHECK(spread);
}
