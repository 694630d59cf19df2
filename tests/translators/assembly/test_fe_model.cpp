// Assembly from decks, checked against closed forms, independent hand-built
// matrices, invariances (coordinate systems, rigid elements vs stiff springs)
// and central finite differences of every designable field.
#include <Eigen/Dense>
#include <catch2/catch.hpp>
#include <cmath>
#include <algorithm>
#include <sstream>

#include "formats/bulk_model.hpp"
#include "formats/deck.hpp"
#include "translators/assembly/fe_model.hpp"
#include "translators/assembly/model_geometry.hpp"

using namespace ssid;
using translators::FeModel;

namespace {

struct Loaded {
  formats::Deck deck;
  std::unique_ptr<FeModel> model;
};

/// `allow_warnings`: the deck may have problems of warning severity, not errors.
Loaded load(const std::string& text, translators::AssemblyOptions options = {}, bool allow_warnings = false) {
  Loaded l{formats::read_deck_text(text, "test.bdf"), nullptr};
  formats::BulkModel bulk = formats::parse_bulk(l.deck);
  formats::resolve(l.deck, bulk);
  std::string problems;
  std::size_t errors = 0;
  for (const auto& p : bulk.problems) {
    problems += p.message + "\n";
    errors += p.severity == formats::Problem::Severity::Error;
  }
  INFO(problems);
  REQUIRE((allow_warnings ? errors : bulk.problems.size()) == 0);
  l.model = std::make_unique<FeModel>(l.deck, std::move(bulk), options);
  return l;
}

/// Finite eigenvalues of the a-set pencil, dense and ascending. M may be
/// singular (massless rotations) and K too (free-free): with A = K + sM
/// positive definite, A = LLᵀ, the eigenvalues μ of L⁻¹ M L⁻ᵀ give λ = 1/μ − s;
/// μ = 0 are the infinite eigenvalues of massless DOFs.
Eigen::VectorXd eigenvalues(const translators::FeOperators& op, double s = 1.0) {
  const Eigen::MatrixXd K(op.K), M(op.M);
  Eigen::LLT<Eigen::MatrixXd> llt(K + s * M);
  REQUIRE(llt.info() == Eigen::Success);
  const Eigen::MatrixXd Li = llt.matrixL().solve(Eigen::MatrixXd::Identity(K.rows(), K.cols()));
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(Li * M * Li.transpose());
  const Eigen::VectorXd mu = es.eigenvalues();
  std::vector<double> out;
  for (int i = 0; i < mu.size(); ++i)
    if (mu(i) > 1e-12 * mu.maxCoeff()) out.push_back(1.0 / mu(i) - s);
  std::sort(out.begin(), out.end());
  return Eigen::Map<Eigen::VectorXd>(out.data(), static_cast<Eigen::Index>(out.size()));
}

double hz(double lambda) { return std::sqrt(std::max(lambda, 0.0)) / (2 * M_PI); }

std::string rod_chain(int n, double L, const std::string& extra = "") {
  std::ostringstream s;
  s << "SOL 103\nCEND\nSPC = 1\nMETHOD = 1\nBEGIN BULK\n";
  for (int i = 0; i <= n; ++i) s << "GRID," << i + 1 << ",," << L * i / n << ",0.,0.\n";
  for (int i = 0; i < n; ++i) s << "CROD," << 100 + i << ",1," << i + 1 << "," << i + 2 << "\n";
  s << "PROD,1,2,1.0E-4,2.0E-8\nMAT1,2,7.0E10,,0.3,2700.\nSPC1,1,123456,1\nEIGRL,1,,,5\n" << extra << "ENDDATA\n";
  return s.str();
}

}  // namespace

TEST_CASE("rod chain: axial frequency, AUTOSPC of the free DOFs", "[assembly]") {
  const int n = 40;
  const double L = 2.0;
  auto l = load(rod_chain(n, L));
  const FeModel& m = *l.model;
  // Each free grid keeps only its axial and torsional DOFs: 4 per grid constrained by AUTOSPC.
  CHECK(m.autospc().size() == 4u * n);
  CHECK(m.reduction().a_to_g.size() == 2u * n);
  const auto op = m.operators(m.initial_parameters(), false);
  const Eigen::VectorXd lambda = eigenvalues(op);
  // Axial: c = √(E/ρ), f₁ = c / 4L. (Lumped CROD mass has no torsional inertia,
  // so the torsion DOFs are massless and their eigenvalues infinite.)
  const double c = std::sqrt(7.0e10 / 2700.0);
  const double f_axial = c / (4 * L);
  // The lowest mode overall is torsion or axial; find the axial one by value.
  double best = 1e9;
  for (int i = 0; i < lambda.size(); ++i) best = std::min(best, std::abs(hz(lambda(i)) / f_axial - 1));
  // 40 lumped elements: first-mode error ≈ (π/2n)²/24 ≈ 6e-5.
  CHECK(best < 1e-3);
  CHECK(best > 1e-6);  // a discretisation, not the closed form itself
}

TEST_CASE("rod chain matches an independently built dense matrix", "[assembly]") {
  const int n = 6;
  auto l = load(rod_chain(n, 1.2));
  const auto op = l.model->operators(l.model->initial_parameters(), false);
  // Axial DOFs only (component 1 of grids 2..n+1), in g-set order, hand-built.
  const double k = 7.0e10 * 1.0e-4 / (1.2 / n), mass = 2700.0 * 1.0e-4 * 1.2 / n;
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n, n), M = Eigen::MatrixXd::Zero(n, n);
  for (int e = 0; e < n; ++e) {
    const int a = e - 1, b = e;  // DOF index of the element's ends (−1: the clamped grid)
    if (a >= 0) { K(a, a) += k; K(a, b) -= k; K(b, a) -= k; M(a, a) += mass / 2; }
    K(b, b) += k;
    M(b, b) += mass / 2;
  }
  const auto& red = l.model->reduction();
  const auto& gset = l.model->geometry().gset();
  Eigen::MatrixXd Ka(op.K), Ma(op.M);
  std::vector<int> axial;
  for (std::size_t i = 0; i < red.a_to_g.size(); ++i)
    if (gset.at(red.a_to_g[i]).component == 1) axial.push_back(static_cast<int>(i));
  REQUIRE(static_cast<int>(axial.size()) == n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      CHECK(Ka(axial[i], axial[j]) == Approx(K(i, j)).margin(1e-6 * k));
      CHECK(Ma(axial[i], axial[j]) == Approx(M(i, j)).margin(1e-12));
    }
}

namespace {

std::string cantilever(int n, double L, const std::string& params, const std::string& cp = "",
                       const std::string& grids = "") {
  std::ostringstream s;
  s << "SOL 103\nCEND\nSPC = 1\nBEGIN BULK\n" << params << cp;
  if (grids.empty())
    for (int i = 0; i <= n; ++i) s << "GRID," << i + 1 << ",," << L * i / n << ",0.,0.\n";
  else
    s << grids;
  for (int i = 0; i < n; ++i) s << "CBAR," << 100 + i << ",1," << i + 1 << "," << i + 2 << ",0.,1.,0.\n";
  s << "PBAR,1,2,1.0E-3,2.0E-7,8.0E-7,1.0E-7\nMAT1,2,7.0E10,,0.3,2700.\nSPC1,1,123456,1\nENDDATA\n";
  return s.str();
}

}  // namespace

TEST_CASE("cantilever CBAR: Euler–Bernoulli frequencies in both planes", "[assembly]") {
  const int n = 20;
  const double L = 3.0, E = 7.0e10, rho = 2700.0, A = 1.0e-3;
  const double b1 = 1.875104068711961;
  auto f_eb = [&](double I) { return b1 * b1 / (2 * M_PI * L * L) * std::sqrt(E * I / (rho * A)); };
  SECTION("coupled mass converges fast") {
    auto l = load(cantilever(n, L, "PARAM,COUPMASS,1\n"));
    const Eigen::VectorXd lambda = eigenvalues(l.model->operators(l.model->initial_parameters(), false));
    // Plane 1 (v along y, I1 = 2e-7) is the softer one; plane 2 uses I2 = 8e-7.
    CHECK(hz(lambda(0)) == Approx(f_eb(2.0e-7)).epsilon(1e-4));
    CHECK(hz(lambda(1)) == Approx(f_eb(8.0e-7)).epsilon(1e-4));
  }
  SECTION("lumped mass (NASTRAN's default) is close and below") {
    auto l = load(cantilever(n, L, ""));
    const Eigen::VectorXd lambda = eigenvalues(l.model->operators(l.model->initial_parameters(), false));
    CHECK(hz(lambda(0)) == Approx(f_eb(2.0e-7)).epsilon(5e-3));
    CHECK_FALSE(l.model->coupled_mass());
  }
}

TEST_CASE("a model defined in cylindrical coordinates gives the same frequencies", "[assembly]") {
  // The cantilever along basic x, with grids given in a cylindrical system whose
  // axis is basic x, and displacement frames in that system: frequencies must
  // not change (frames and positions are both transformed).
  const int n = 8;
  const double L = 2.0;
  std::ostringstream grids;
  // CORD2C 5: origin 0, Z axis along basic X, X axis along basic Y.
  const std::string cord = "CORD2C,5,,0.,0.,0.,1.,0.,0.,\n,0.,1.,0.\n";
  for (int i = 0; i <= n; ++i)
    grids << "GRID," << i + 1 << ",5,0.,0.," << L * i / n << ",5\n";  // R=0 on the axis, Z = x
  auto plain = load(cantilever(n, L, "PARAM,COUPMASS,1\n"));
  auto cyl = load(cantilever(n, L, "PARAM,COUPMASS,1\n", cord, grids.str()));
  const Eigen::VectorXd a = eigenvalues(plain.model->operators(plain.model->initial_parameters(), false));
  const Eigen::VectorXd b = eigenvalues(cyl.model->operators(cyl.model->initial_parameters(), false));
  REQUIRE(a.size() == b.size());
  for (int i = 0; i < 6; ++i) CHECK(b(i) == Approx(a(i)).epsilon(1e-9));
}

namespace {

std::string free_frame(const std::string& link) {
  // Two bars joined at grid 3/4 by `link` (RBE2 or a stiff bar), free-free.
  return "BEGIN BULK\n"
         "GRID,1,,0.,0.,0.\nGRID,2,,1.,0.,0.\nGRID,3,,2.,0.,0.\nGRID,4,,2.,0.5,0.3\nGRID,5,,3.,1.,0.5\n"
         "CBAR,1,1,1,2,0.,0.,1.\nCBAR,2,1,2,3,0.,0.,1.\nCBAR,4,1,4,5,0.,0.,1.\n"
         "PBAR,1,2,1.0E-3,2.0E-7,8.0E-7,1.0E-7\nMAT1,2,7.0E10,,0.3,2700.\n"
         "CONM2,20,5,,3.0\n" +
         link + "ENDDATA\n";
}

}  // namespace

TEST_CASE("free-free: six rigid-body modes; RBE2 equals a very stiff link", "[assembly]") {
  auto rigid = load(free_frame("RBE2,30,3,123456,4\n"));
  const Eigen::VectorXd a = eigenvalues(rigid.model->operators(rigid.model->initial_parameters(), false));
  const double scale = a(a.size() - 1);
  int zeros = 0;
  for (int i = 0; i < a.size(); ++i) zeros += std::abs(a(i)) < 1e-9 * scale;
  CHECK(zeros == 6);
  CHECK(a(6) > 1e-6 * scale);
  // The same joint as a short, very stiff bar: the elastic frequencies converge to the rigid ones.
  auto stiff = load(free_frame("CBAR,3,9,3,4,0.,0.,1.\nPBAR,9,10,1.0,1.0,1.0,1.0\nMAT1,10,7.0E10,,0.3,0.\n"));
  const Eigen::VectorXd b = eigenvalues(stiff.model->operators(stiff.model->initial_parameters(), false));
  for (int i = 6; i < 12; ++i) CHECK(hz(b(i)) == Approx(hz(a(i))).epsilon(1e-4));
}

TEST_CASE("PARAM WTMASS scales the mass", "[assembly]") {
  auto a = load(cantilever(6, 1.0, ""));
  auto b = load(cantilever(6, 1.0, "PARAM,WTMASS,0.25\n"));
  const Eigen::VectorXd la = eigenvalues(a.model->operators(a.model->initial_parameters(), false));
  const Eigen::VectorXd lb = eigenvalues(b.model->operators(b.model->initial_parameters(), false));
  for (int i = 0; i < 4; ++i) CHECK(lb(i) == Approx(4.0 * la(i)).epsilon(1e-10));
}

TEST_CASE("every designable field: exact derivatives against central differences", "[assembly][derivatives]") {
  const std::string deck =
      "SOL 103\nCEND\nSPC = 1\nBEGIN BULK\n"
      "GRID,1,,0.,0.,0.\nGRID,2,,1.,0.,0.\nGRID,3,,2.,0.3,0.\nGRID,4,,3.,0.1,0.4\nGRID,5,,3.,1.,0.4\n"
      "CBAR,1,1,1,2,0.,1.,0.\nCBAR,2,3,2,3,0.,0.,1.\nCROD,3,4,3,4\nCBEAM,5,6,4,5,1.,0.,0.\n"
      "CBUSH,6,7,2,5,0.,0.,1.\nCELAS2,7,5.0E5,5,3\nCONM2,8,4,,2.5,0.05,0.,0.02,,\n,0.1,,0.1,,,0.1\n"
      "PBAR,1,2,1.0E-3,2.0E-7,8.0E-7,1.0E-7\n"
      "PBARL,3,2,,TUBE\n,0.03,0.025\n"
      "PROD,4,8,2.0E-4,1.0E-8\n"
      "PBEAML,6,2,,I\n,0.1,0.06,0.06,0.006,0.008,0.008\n"  // symmetric: CBEAM refuses an off-centroid shear centre

      "PBUSH,7,K,1.0E5,2.0E5,3.0E5,1.0E3,2.0E3,3.0E3\n"
      "MAT1,2,7.0E10,,0.3,2700.\nMAT1,8,2.0E11,8.0E10,,7800.\n"
      "SPC1,1,123456,1\n"
      "DESVAR,1,AREA,1.0E-3,1.0E-5,1.0\nDVPREL1,11,PBAR,1,A,,,,\n,1,1.0\n"
      "DESVAR,2,I1,2.0E-7\nDVPREL1,12,PBAR,1,I1,,,,\n,2,1.0\n"
      "DESVAR,3,ROUT,0.03\nDVPREL1,13,PBARL,3,DIM1,,,,\n,3,1.0\n"
      "DESVAR,4,EAL,7.0E10\nDVMREL1,14,MAT1,2,E,,,,\n,4,1.0\n"
      "DESVAR,5,RHO,2700.\nDVMREL1,15,MAT1,2,RHO,,,,\n,5,1.0\n"
      "DESVAR,6,MTIP,2.5\nDVPREL1,16,CONM2,8,M,,,,\n,6,1.0\n"
      "DESVAR,7,SPRING,5.0E5\nDVPREL1,17,CELAS2,7,K,,,,\n,7,1.0\n"
      "DESVAR,8,BUSHK,1.0\nDVPREL1,18,PBUSH,7,K1,,,,\n,8,1.0E5\nDVPREL1,19,PBUSH,7,K4,,,,\n,8,1.0E3\n"
      "DESVAR,9,WEB,0.006\nDVPREL1,20,PBEAML,6,DIM4,,,,\n,9,1.0\n"
      "DESVAR,10,XOFF,0.05\nDVPREL1,21,CONM2,8,X1,,,,\n,10,1.0\n"
      "DESVAR,11,GST,8.0E10\nDVMREL1,22,MAT1,8,G,,,,\n,11,1.0\n"
      // A thin-walled section of the full PBARL list through DVPREL1 (the hat's top width).
      "CBAR,9,10,1,3,0.,0.,1.\nPBARL,10,2,,HAT\n,0.04,0.003,0.05,0.01\n"
      "DESVAR,12,HATW,0.05\nDVPREL1,23,PBARL,10,DIM3,,,,\n,12,1.0\n"
      "ENDDATA\n";
  auto l = load(deck);
  const FeModel& m = *l.model;
  REQUIRE(m.parameters().size() == 12);
  const Eigen::VectorXd x0 = m.initial_parameters();
  const auto op = m.operators(x0, true);
  for (std::size_t j = 0; j < m.parameters().size(); ++j) {
    INFO("parameter " << m.parameters()[j].label);
    const double h = 1e-5 * std::abs(x0(static_cast<Eigen::Index>(j)));
    Eigen::VectorXd xp = x0, xm = x0;
    xp(static_cast<Eigen::Index>(j)) += h;
    xm(static_cast<Eigen::Index>(j)) -= h;
    const auto p = m.operators(xp, false), q = m.operators(xm, false);
    const Eigen::MatrixXd fdK = (Eigen::MatrixXd(p.K) - Eigen::MatrixXd(q.K)) / (2 * h);
    const Eigen::MatrixXd fdM = (Eigen::MatrixXd(p.M) - Eigen::MatrixXd(q.M)) / (2 * h);
    const Eigen::MatrixXd dK(op.dK[j]), dM(op.dM[j]);
    const double nk = std::max(fdK.norm(), 1e-30), nm = std::max(fdM.norm(), 1e-30);
    CHECK((dK - fdK).norm() <= 1e-6 * nk + 1e-9 * Eigen::MatrixXd(op.K).norm() / std::abs(x0(static_cast<Eigen::Index>(j))));
    CHECK((dM - fdM).norm() <= 1e-6 * nm + 1e-9 * Eigen::MatrixXd(op.M).norm() / std::abs(x0(static_cast<Eigen::Index>(j))));
    CHECK(dK.norm() + dM.norm() > 0);  // every parameter changes something
  }
  // E of MAT1 2 with G blank: G follows E (derived), so ∂K/∂E includes torsion through G.
  CHECK(m.parameters()[3].designs.size() == 1);
}

TEST_CASE("cards that cannot be assembled: refused or noted", "[assembly][errors]") {
  SECTION("a CROD pointing at a PBAR names both") {
    const std::string deck = rod_chain(2, 1.0).replace(rod_chain(2, 1.0).find("PROD,1,2"), 8, "PBAR,1,2");
    formats::Deck d = formats::read_deck_text(deck, "bad.bdf");
    formats::BulkModel b = formats::parse_bulk(d);
    CHECK_THROWS_WITH(FeModel(d, b), Catch::Contains("bad.bdf:") && Catch::Contains("CROD 100") &&
                                         Catch::Contains("is a PBAR, expected PROD"));
  }
  SECTION("a shell element is refused, a load is noted") {
    const std::string deck = rod_chain(2, 1.0, "FORCE,5,2,,1.,1.,0.,0.\nCQUAD4,9,1,1,2,3,1\n");
    formats::Deck d = formats::read_deck_text(deck, "shell.bdf");
    formats::BulkModel b = formats::parse_bulk(d);
    CHECK_THROWS_WITH(FeModel(d, b), Catch::Contains("CQUAD4") && Catch::Contains("cannot assemble"));
    const std::string ok = rod_chain(2, 1.0, "FORCE,5,2,,1.,1.,0.,0.\n");
    auto l = load(ok);
    bool noted = false;
    for (const auto& note : l.model->notes()) noted |= note.find("FORCE") != std::string::npos;
    CHECK(noted);
  }
}

namespace {
/// A massless cantilever of `n` elements (`card` with property 1) along x,
/// orientation vector y, fixed at grid 1, with a point mass m at the tip.
std::string tip_mass_cantilever(const std::string& card, const std::string& property, int n, double L, double m) {
  std::ostringstream s;
  s << "SOL 103\nCEND\nSPC = 1\nBEGIN BULK\n";
  for (int i = 0; i <= n; ++i) s << "GRID," << i + 1 << ",," << L * i / n << ",0.,0.\n";
  for (int i = 0; i < n; ++i) s << card << "," << 100 + i << ",1," << i + 1 << "," << i + 2 << ",0.,1.,0.\n";
  s << property << "MAT1,2,2.0E11,,0.3\nCONM2,900," << n + 1 << ",," << m << "\nSPC1,1,123456,1\nENDDATA\n";
  return s.str();
}
}  // namespace

TEST_CASE("bar and beam shear flexibility: a massless cantilever with a tip mass has the Timoshenko closed form",
          "[assembly][shear]") {
  // The only inertia is the tip mass, so each finite eigenvalue is the tip's
  // stiffness over m: axial EA/L, and in each bending plane the inverse of the
  // Timoshenko tip flexibility L³/(3 E I) + L/(K A G), which the shear-flexible
  // bar element reproduces exactly for end loads, whatever the element count.
  const int n = 4;
  const double L = 2.0, m = 3.0, E = 2.0e11, G = E / (2 * 1.3);
  struct Case {
    std::string name, card, property;
    double a, i1, i2, k1, k2;  // k = 0: no shear flexibility
  };
  const double pi = M_PI, r = 0.05;
  const double rod_a = pi * r * r, rod_i = pi * r * r * r * r / 4;
  // BOX 0.12 (z) x 0.08 (y), top/bottom walls 0.01, side walls 0.006: the side
  // walls carry plane-1 shear, the top and bottom ones plane-2 shear.
  const double bb = 0.12, bh = 0.08, ty = 0.01, tz = 0.006;
  const double box_a = bb * bh - (bb - 2 * tz) * (bh - 2 * ty);
  const double box_i1 = (bb * bh * bh * bh - (bb - 2 * tz) * std::pow(bh - 2 * ty, 3)) / 12;
  const double box_i2 = (bh * bb * bb * bb - (bh - 2 * ty) * std::pow(bb - 2 * tz, 3)) / 12;
  const std::vector<Case> cases = {
      {"PBARL ROD (K = 0.9)", "CBAR", "PBARL,1,2,,ROD\n,0.05\n", rod_a, rod_i, rod_i, 0.9, 0.9},
      {"PBEAML ROD (K = 0.9)", "CBEAM", "PBEAML,1,2,,ROD\n,0.05\n", rod_a, rod_i, rod_i, 0.9, 0.9},
      {"PBARL BOX", "CBAR", "PBARL,1,2,,BOX\n,0.12,0.08,0.01,0.006\n", box_a, box_i1, box_i2,
       2 * (bh - 2 * ty) * tz / box_a, 2 * (bb - 2 * tz) * ty / box_a},
      {"PBEAM, K1 K2 blank (1.0)", "CBEAM", "PBEAM,1,2,1.0E-3,2.0E-7,8.0E-7,,1.0E-7\n", 1e-3, 2e-7, 8e-7, 1.0, 1.0},
      {"PBAR, K1 K2 blank (rigid in shear)", "CBAR", "PBAR,1,2,1.0E-3,2.0E-7,8.0E-7,1.0E-7\n", 1e-3, 2e-7, 8e-7, 0, 0},
      {"PBAR, K1 K2 given", "CBAR", "PBAR,1,2,1.0E-3,2.0E-7,8.0E-7,1.0E-7\n,,,,,,,,\n,0.6,0.7\n", 1e-3, 2e-7,
       8e-7, 0.6, 0.7},
  };
  for (const auto& c : cases) {
    INFO(c.name);
    auto l = load(tip_mass_cantilever(c.card, c.property, n, L, m));
    const Eigen::VectorXd lambda = eigenvalues(l.model->operators(l.model->initial_parameters(), false));
    auto bending = [&](double I, double k) {
      const double flex = L * L * L / (3 * E * I) + (k > 0 ? L / (k * c.a * G) : 0.0);
      return 1.0 / (m * flex);
    };
    std::vector<double> expected = {E * c.a / (L * m), bending(c.i1, c.k1), bending(c.i2, c.k2)};
    std::sort(expected.begin(), expected.end());
    REQUIRE(lambda.size() == 3);
    for (int i = 0; i < 3; ++i) CHECK(lambda(i) == Approx(expected[static_cast<std::size_t>(i)]).epsilon(1e-9));
  }
}

TEST_CASE("scalar points named only by scalar elements are model DOFs; SOL 103's ignored cards are noted",
          "[assembly]") {
  // Two scalar points that no SPOINT defines (NASTRAN's SPOINT remark: a scalar
  // element's connection defines them): k = 1000 between them, 2000 from 200 to
  // ground, masses 2 and 1. det(K − λM) = 2λ² − 7000λ + 2·10⁶ = 0. A damper
  // (CDAMP3, ignored in real modes) names a third point, which the SPC holds;
  // an SPCADD names a set that does not exist (NASTRAN warns and runs).
  auto l = load(
      "SOL 103\nCEND\nSPC = 2\nBEGIN BULK\n"
      "CELAS2,1,1000.,100,,200\nCELAS2,2,2000.,200\nCMASS2,3,2.,100\nCMASS2,4,1.,200\n"
      "CDAMP3,5,9,300\nPDAMP,9,0.5\nSPC1,1,0,300\nSPCADD,2,1,7\n"
      "AERO,,,1.0,1.0\nFLFACT,1,0.1\nEPOINT,900\nTF,10,900,,1.0\nENDDATA\n",
      {}, /*allow_warnings=*/true);
  const Eigen::VectorXd lambda = eigenvalues(l.model->operators(l.model->initial_parameters(), false));
  const double root = std::sqrt(49.0e6 - 16.0e6);
  REQUIRE(lambda.size() == 2);
  CHECK(lambda(0) == Approx((7000.0 - root) / 4).epsilon(1e-12));
  CHECK(lambda(1) == Approx((7000.0 + root) / 4).epsilon(1e-12));
  std::string notes;
  for (const auto& n : l.model->notes()) notes += n + "\n";
  INFO(notes);
  CHECK_THAT(notes, Catch::Contains("1 CDAMP3 card ignored") && Catch::Contains("1 FLFACT card ignored") &&
                        Catch::Contains("1 TF card ignored") && Catch::Contains("1 EPOINT card ignored"));
}

TEST_CASE("CELAS3/4 and CMASS3/4: the scalar-point forms give the chain's closed form", "[assembly]") {
  // The chain of the test above written with the scalar-point forms: CELAS4
  // k = 1000 between 100 and 200, CELAS3 (PELAS 2000) from 200 to ground, CMASS4
  // 2 at 100, CMASS3 (PMASS 1) at 200. det(K − λM) = 2λ² − 7000λ + 2·10⁶ = 0.
  auto l = load(
      "SOL 103\nCEND\nBEGIN BULK\n"
      "CELAS4,1,1000.,100,200\nCELAS3,2,7,200\nPELAS,7,2000.\nCMASS4,3,2.,100\nCMASS3,4,8,,200\nPMASS,8,1.\n"
      "ENDDATA\n");
  const Eigen::VectorXd lambda = eigenvalues(l.model->operators(l.model->initial_parameters(), false));
  const double root = std::sqrt(49.0e6 - 16.0e6);
  REQUIRE(lambda.size() == 2);
  CHECK(lambda(0) == Approx((7000.0 - root) / 4).epsilon(1e-12));
  CHECK(lambda(1) == Approx((7000.0 + root) / 4).epsilon(1e-12));
}

TEST_CASE("case control AUTOSPC = NO keeps a massive, unstiffened DOF; it overrides PARAM AUTOSPC", "[assembly]") {
  // A mass on a scalar point with no stiffness: AUTOSPC removes it; with
  // AUTOSPC = NO (NASTRAN's case control command) it stays, a zero eigenvalue,
  // as in MSC's run of pyNastran's actuator_tf_modeling.bdf.
  const std::string bulk = "BEGIN BULK\nCELAS2,1,100.,1\nCMASS2,2,1.,1\nCMASS2,3,1.,2\n";
  auto yes = load("SOL 103\nCEND\n" + bulk + "ENDDATA\n");
  CHECK(eigenvalues(yes.model->operators(yes.model->initial_parameters(), false)).size() == 1);
  for (const char* cc : {"AUTOSPC = NO\n", "AUTOSPC(NOPRINT)=NO\n", "SUBCASE 1\n  AUTOSPC = NO\n"}) {
    INFO(cc);
    auto no = load(std::string("SOL 103\nCEND\n") + cc + bulk + "PARAM,AUTOSPC,YES\nENDDATA\n");
    const Eigen::VectorXd lambda = eigenvalues(no.model->operators(no.model->initial_parameters(), false));
    REQUIRE(lambda.size() == 2);
    CHECK(std::abs(lambda(0)) < 1e-9);
    CHECK(lambda(1) == Approx(100.0).epsilon(1e-12));
  }
  auto bare = load("SOL 103\nCEND\nAUTOSPC\n" + bulk + "PARAM,AUTOSPC,NO\nENDDATA\n");
  CHECK(eigenvalues(bare.model->operators(bare.model->initial_parameters(), false)).size() == 1);
  const formats::Deck d = formats::read_deck_text("SOL 103\nCEND\nAUTOSPC = MAYBE\n" + bulk + "ENDDATA\n", "a.bdf");
  try {
    FeModel(d, formats::parse_bulk(d));
    FAIL("AUTOSPC = MAYBE accepted");
  } catch (const translators::ModelError& e) {
    CHECK(e.where().str() == "a.bdf:3");
    CHECK(std::string(e.what()) == "case control AUTOSPC = MAYBE: expected AUTOSPC = YES or NO");
  }
}

TEST_CASE("MDLPRM: output and solver controls noted, model parameters refused by name", "[assembly]") {
  const std::string head = "SOL 103\nCEND\nBEGIN BULK\nCELAS2,1,100.,1\nCMASS2,2,1.,1\n";
  auto l = load(head + "MDLPRM,HDF5,1,OFFDEF,LROFF\nENDDATA\n");
  std::string notes;
  for (const auto& n : l.model->notes()) notes += n + "\n";
  CHECK_THAT(notes, Catch::Contains("MDLPRM HDF5 1 ignored: no effect on K or M of the assembled elements") &&
                        Catch::Contains("MDLPRM OFFDEF LROFF ignored"));
  const formats::Deck d = formats::read_deck_text(head + "MDLPRM,OFFDEF,NOMASS\nENDDATA\n", "m.bdf");
  try {
    FeModel(d, formats::parse_bulk(d));
    FAIL("MDLPRM OFFDEF NOMASS accepted");
  } catch (const translators::ModelError& e) {
    CHECK(e.where().str() == "m.bdf:6");
    CHECK(std::string(e.what()) == "MDLPRM OFFDEF NOMASS: ssid does not apply this model parameter and it may change K or M");
  }
}

TEST_CASE("CBEAM extras that ssid does not model are refused by name", "[assembly][errors]") {
  const std::string head =
      "SOL 103\nCEND\nBEGIN BULK\nGRID,1,,0.,0.,0.\nGRID,2,,1.,0.,0.\nCBEAM,7,3,1,2,0.,1.,0.\n"
      "MAT1,2,7.0E10,,0.3,2700.\n";
  auto refusal = [&](const std::string& prop) {
    const formats::Deck d = formats::read_deck_text(head + prop + "ENDDATA\n", "b.bdf");
    try {
      FeModel(d, formats::parse_bulk(d));
    } catch (const std::exception& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  // A channel's shear centre lies off its centroid: NASTRAN's PBEAML offsets the neutral axis.
  CHECK(refusal("PBEAML,3,2,,CHAN\n,0.03,0.06,0.004,0.005\n") ==
        "b.bdf:6: CBEAM 7: PBEAML 3 TYPE CHAN: the shear centre is off the centroid for these dimensions; NASTRAN's "
        "CBEAM offsets the neutral axis from it (coupling bending and torsion), which ssid's CBEAM does not model (a "
        "CBAR with PBARL, which NASTRAN also assembles about one axis, is)");
  // A doubly symmetric I is fine; a warping coefficient is not.
  CHECK(refusal("PBEAML,3,2,,I1\n,0.03,0.004,0.05,0.06\n") == "accepted");
  CHECK(refusal("PBEAM,3,2,1.0E-3,1.0E-7,1.0E-7,,1.0E-7\n,0.,0.,0.,0.,0.,0.,0.,0.\n,,,,,,,1.0E-9\n") ==
        "b.bdf:6: CBEAM 7: PBEAM 3 warping coefficient CW is not assembled (ssid's CBEAM: constant section, shear "
        "centre on the neutral axis)");
}
