// The a-set rigid-body modes (the multilevel eigen-solver's near-null space): a
// free model's stiffness must annihilate them, with grids in rotated and
// cylindrical displacement frames and a rigid element in the model; the same rows
// taken in basic axes (the frames ignored) must not.
#include <Eigen/Dense>
#include <array>
#include <memory>
#include <string>
#include <utility>
#include <catch2/catch.hpp>

#include "formats/bulk_model.hpp"
#include "formats/deck.hpp"
#include "translators/assembly/fe_model.hpp"
#include "translators/assembly/rigid_modes.hpp"
#include "translators/constraints.hpp"

using namespace ssid;

namespace {
/// The model of a deck given as text (the deck is read, resolved and checked).
std::unique_ptr<translators::FeModel> model_of(const std::string& text, const std::string& name) {
  const formats::Deck deck = formats::read_deck_text(text, name);
  formats::BulkModel bulk = formats::parse_bulk(deck);
  formats::resolve(deck, bulk);
  REQUIRE(bulk.problems.empty());
  return std::make_unique<translators::FeModel>(deck, std::move(bulk));
}
}  // namespace

TEST_CASE("a-set rigid-body modes: K annihilates them in displacement frames, with an RBE2", "[assembly]") {
  // Free frame: bars 1-2-3 and 4-5, joined by an RBE2 at 3/4; grid 2 displaced in a
  // rotated rectangular frame, grid 5 in a cylindrical one, grid 4 (dependent) in the
  // rectangular one too.
  const std::string text =
      "BEGIN BULK\n"
      "CORD2R,7,,0.,0.,0.,0.3,0.4,1.,\n,1.,-0.2,0.1\n"
      "CORD2C,8,,0.5,0.,0.,0.5,1.,0.,\n,1.,0.,0.3\n"
      "GRID,1,,0.,0.,0.\nGRID,2,,1.,0.,0.,7\nGRID,3,,2.,0.,0.\nGRID,4,,2.,0.5,0.3,7\nGRID,5,,3.,1.,0.5,8\n"
      "CBAR,1,1,1,2,0.,0.,1.\nCBAR,2,1,2,3,0.,0.,1.\nCBAR,4,1,4,5,0.,0.,1.\n"
      "PBAR,1,2,1.0E-3,2.0E-7,8.0E-7,1.0E-7\nMAT1,2,7.0E10,,0.3,2700.\nCONM2,20,5,,3.0\n"
      "RBE2,30,3,123456,4\nENDDATA\n";
  const auto model_ptr = model_of(text, "free.bdf");
  const translators::FeModel& model = *model_ptr;
  const translators::FeOperators op = model.operators(model.initial_parameters(), false);
  const Eigen::MatrixXd K(op.K);
  const Eigen::MatrixXd B = translators::a_set_rigid_body_modes(model);
  REQUIRE(B.rows() == K.rows());
  REQUIRE(B.cols() == 6);
  CHECK(Eigen::FullPivLU<Eigen::MatrixXd>(B).rank() == 6);
  const double scale = K.norm() * B.norm();
  CHECK((K * B).norm() <= 1e-12 * scale);

  // Control: the rows in basic axes (what a frame-blind version would give).
  const auto& a_to_g = model.reduction().a_to_g;
  Eigen::MatrixXd blind(B.rows(), 6);
  for (std::size_t i = 0; i < a_to_g.size(); ++i) {
    const translators::Dof& d = model.geometry().gset().at(a_to_g[i]);
    Eigen::Vector3d x = Eigen::Vector3d::Zero();
    for (const auto& p : model.geometry().grids())
      if (p.id == d.point) x = p.x;
    blind.row(static_cast<Eigen::Index>(i)) =
        translators::rigid_body_rows(x, Eigen::Vector3d::Zero()).row(d.component - 1);
  }
  CHECK((K * blind).norm() > 1e-3 * scale);
}

namespace {
/// A free 4 x 4 x 4 lattice of CRODs 1 m apart along the edges, with several
/// interior grids displaced in rotated or cylindrical frames.
std::string rod_lattice() {
  std::string s = "BEGIN BULK\nCORD2R,7,,0.,0.,0.,0.3,0.4,1.,\n,1.,-0.2,0.1\nCORD2C,8,,0.5,0.,0.,0.5,1.,0.,\n,1.,0.,0.3\n";
  auto id = [](int i, int j, int k) { return 1 + i + 4 * (j + 4 * k); };
  for (int k = 0; k < 4; ++k)
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < 4; ++i) {
        const bool interior = i > 0 && i < 3 && j > 0 && j < 3 && k > 0 && k < 3;
        const int cd = interior ? (i == 1 ? 7 : 8) : 0;
        s += "GRID," + std::to_string(id(i, j, k)) + ",," + std::to_string(i) + "." + "," + std::to_string(j) + ".," +
             std::to_string(k) + ".," + (cd ? std::to_string(cd) : std::string()) + "\n";
      }
  int eid = 1;
  for (int k = 0; k < 4; ++k)
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < 4; ++i)
        for (int d = 0; d < 3; ++d) {
          const int i2 = i + (d == 0), j2 = j + (d == 1), k2 = k + (d == 2);
          if (i2 > 3 || j2 > 3 || k2 > 3) continue;
          s += "CROD," + std::to_string(eid++) + ",1," + std::to_string(id(i, j, k)) + "," + std::to_string(id(i2, j2, k2)) + "\n";
        }
  s += "PROD,1,2,1.0E-3\nMAT1,2,7.0E10,,0.3,2700.\nENDDATA\n";
  return s;
}
}  // namespace

TEST_CASE("a-set strain fields: affine in basic axes, given in displacement frames", "[assembly]") {
  const auto model_ptr = model_of(rod_lattice(), "rods.bdf");
  const translators::FeModel& model = *model_ptr;
  const translators::FeOperators op = model.operators(model.initial_parameters(), false);
  const Eigen::MatrixXd K(op.K);
  const Eigen::MatrixXd F = translators::a_set_strain_fields(model);
  const Eigen::MatrixXd B = translators::a_set_rigid_body_modes(model);
  REQUIRE(F.rows() == K.rows());
  REQUIRE(F.cols() == 6);
  Eigen::MatrixXd BF(F.rows(), 12);
  BF << B, F;
  CHECK(Eigen::FullPivLU<Eigen::MatrixXd>(BF).rank() == 12);

  // Each row against the field computed independently: the displacement u = E_k (x − x̄)
  // in basic axes (x̄ the mean grid position, (1.5, 1.5, 1.5)), then its component
  // along the DOF's displacement-frame axis; rotations zero.
  const Eigen::Vector3d centre(1.5, 1.5, 1.5);
  const std::array<std::pair<int, int>, 6> pairs{{{0, 0}, {0, 1}, {0, 2}, {1, 1}, {1, 2}, {2, 2}}};
  auto unit_strain = [&](int k) {  // E_k = sym(e_a e_bᵀ)
    const auto [a, b] = pairs[static_cast<size_t>(k)];
    Eigen::Matrix3d E = Eigen::Matrix3d::Zero();
    E(a, b) += 0.5;
    E(b, a) += 0.5;
    return E;
  };
  auto interior_grid = [](const translators::GridPoint& p) { return (p.x.array() > 0.5).all() && (p.x.array() < 2.5).all(); };
  const auto& a_to_g = model.reduction().a_to_g;
  double worst = 0.0;
  int rotated_rows = 0;
  for (std::size_t i = 0; i < a_to_g.size(); ++i) {
    const translators::Dof& d = model.geometry().gset().at(a_to_g[i]);
    const translators::GridPoint& p = model.geometry().grid(d.point, "test");
    if (!p.frame.isIdentity()) ++rotated_rows;
    for (int k = 0; k < 6; ++k) {
      const double expected =
          d.component <= 3 ? p.frame.col(d.component - 1).dot(unit_strain(k) * (p.x - centre)) : 0.0;
      worst = std::max(worst, std::abs(F(static_cast<Eigen::Index>(i), k) - expected));
    }
  }
  CHECK(rotated_rows > 0);
  CHECK(worst < 1e-14);

  // Physics: a uniform strain of a regular truss is in equilibrium without load at
  // every interior grid (each bar has an opposite one carrying the same force), in
  // whatever frame the grid is displaced; the boundary grids carry the reactions.
  // Fields given in basic axes at the rotated grids (a frame-blind version) are not.
  const Eigen::MatrixXd KF = K * F;
  double interior = 0.0, boundary = 0.0;
  Eigen::MatrixXd blind = F;
  for (std::size_t i = 0; i < a_to_g.size(); ++i) {
    const translators::Dof& d = model.geometry().gset().at(a_to_g[i]);
    const translators::GridPoint& p = model.geometry().grid(d.point, "test");
    const bool inside = interior_grid(p);
    const double r = KF.row(static_cast<Eigen::Index>(i)).norm();
    (inside ? interior : boundary) = std::max(inside ? interior : boundary, r);
    if (d.component <= 3)
      for (int k = 0; k < 6; ++k) blind(static_cast<Eigen::Index>(i), k) = (unit_strain(k) * (p.x - centre))(d.component - 1);
  }
  INFO("largest |K F| row: interior " << interior << ", boundary " << boundary);
  CHECK(boundary > 1e6);
  CHECK(interior <= 1e-12 * boundary);
  double blind_interior = 0.0;
  const Eigen::MatrixXd KB = K * blind;
  for (std::size_t i = 0; i < a_to_g.size(); ++i) {
    const translators::GridPoint& p = model.geometry().grid(model.geometry().gset().at(a_to_g[i]).point, "test");
    if (interior_grid(p)) blind_interior = std::max(blind_interior, KB.row(static_cast<Eigen::Index>(i)).norm());
  }
  CHECK(blind_interior > 1e-3 * boundary);
}
