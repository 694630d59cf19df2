// The a-set rigid-body modes (the multilevel eigen-solver's near-null space): a
// free model's stiffness must annihilate them, with grids in rotated and
// cylindrical displacement frames and a rigid element in the model; the same rows
// taken in basic axes (the frames ignored) must not.
#include <Eigen/Dense>
#include <catch2/catch.hpp>

#include "formats/bulk_model.hpp"
#include "formats/deck.hpp"
#include "translators/assembly/fe_model.hpp"
#include "translators/assembly/rigid_modes.hpp"
#include "translators/constraints.hpp"

using namespace ssid;

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
  const formats::Deck deck = formats::read_deck_text(text, "free.bdf");
  formats::BulkModel bulk = formats::parse_bulk(deck);
  formats::resolve(deck, bulk);
  REQUIRE(bulk.problems.empty());
  const translators::FeModel model(deck, std::move(bulk));
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
