// The model-form extensions (estimator/diagnosis/hypotheses) as physics — here, not in
// the translators tests, because the checks need the eigen-solver: each extended deck assembles; the
// screening derivatives equal the extended model's own ∂K/∂β, ∂M/∂β (assembled
// from the written cards); the limits of the new parameters give back the
// nominal model (a massless spring's surge at infinity, a rigid joint).
#include <Eigen/Dense>
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

TEST_CASE("support_dynamics: static rate kept, surge at sqrt(4k/m)/2pi, light spring gives the nominal modes",
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
  // The start places the isolated spring's surge (ball held) at 48 Hz: m = 4k/(2π·48)².
  const ext::ExtendedDeck xd = kind->apply(text, "x.bdf", *nominal.fe, *vertical);
  const double k = 600.0;
  CHECK(xd.parameters[0].start == Approx(4 * k / std::pow(2 * M_PI * 48.0, 2)));
  // The spring's rate stays designed by KSUSP through the doubled PELAS.
  const Loaded x = load(xd.text);
  bool doubled = false;
  for (const auto& r : x.fe->bulk().dvprel1s)
    if (r.type == "PELAS" && r.pid > 1000)
      for (const auto& [dv, coef] : r.terms) doubled = doubled || (coef == Approx(2.0));
  CHECK(doubled);
  // Static rate unchanged: the rigid-body-like suspension modes do not move (checked above); the
  // isolated chain ground–2k–m–2k–(ball held) has ω² = 4k/m.
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

TEST_CASE("local_modes: the strut's bending mode at the start frequency; stiff and massless gives the rod back",
          "[translators][extensions]") {
  // One rod between two grids held in every DOF, each carrying a 2 kg CONM2
  // (the strut mass lumped at its ends, as in a rod model): refined, the only
  // modes are those of the middle grid. With μ moved to the middle, the
  // bending pair (two bars pinned at the strut's ends) sits at
  // √(48 E I / L³ / μ)/2π; axially the middle sees two halves of rate 2EA/L.
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
  const double E = 7e10, A = 1e-4, L = 1.0, I = cands[0].start[0];
  CHECK(f(0) == Approx(40.0).epsilon(1e-9));
  CHECK(f(1) == Approx(40.0).epsilon(1e-9));
  CHECK(48 * E * I / (L * L * L) / mu == Approx(std::pow(2 * M_PI * 40.0, 2)));
  // The axial rate at the middle is the two halves' 2·2EA/L: the rod's EA/L in series.
  const auto ops = x.fe->operators(x.fe->initial_parameters(), false);
  const auto& gm = x.fe->geometry().grid(1001, "test");
  const auto ax = static_cast<Eigen::Index>(gm.dofs[0]);
  CHECK(ops.Kg.coeff(ax, ax) == Approx(4 * E * A / L));
  CHECK(ops.Mg.coeff(ax, ax) == Approx(mu));
  // Total mass unchanged: +μ in the middle, −μ/2 at each end.
  CHECK(ext::total_mass(*x.fe) == Approx(ext::total_mass(*nominal.fe)));
  // The written deck designs the new PBAR from the DESVAR: I1 = I2 = I.
  int designed = 0;
  for (const auto& r : x.fe->bulk().dvprel1s)
    if (r.type == "PBAR") ++designed;
  CHECK(designed == 2);
}

TEST_CASE("local_modes on the rod truss: a stiff, massless refinement leaves the modes unchanged",
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
  ext::Candidate stiff = cands[100];
  stiff.start = {1e-4, 0.0};  // bending inertia far above the real tube's, nothing moved
  const Loaded l = load(kind->apply(text, "x.bdf", *nominal.fe, stiff).text);
  const Eigen::VectorXd f1 = frequencies(*l.fe, l.fe->initial_parameters(), 20);
  for (int i = 0; i < 20; ++i) CHECK(f1(i) == Approx(f0(i)).epsilon(1e-6).margin(1e-6));
  // The lower bound on I is positive (no mechanism), and a soft strut adds modes below the nominal band top.
  ext::Candidate soft = cands[100];
  soft.start = {};
  const ext::ExtendedDeck xd = kind->apply(text, "x.bdf", *nominal.fe, soft);
  CHECK(xd.parameters[0].lower > 0);
}
