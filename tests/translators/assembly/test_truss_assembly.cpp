// The deck assembler (FeModel) against the truss generator's own reference
// assembler on the generated MPI decks: two independent codes, one from the
// deck text (cards, DVPREL1, RBE2 elimination, AUTOSPC), the other from the
// generator's in-memory model. Every reference eigenpair must be an eigenpair
// of FeModel's a-set operators: ‖K φ − λ M φ‖ small relative to ‖K φ‖, and the
// generalised mass φᵀ M φ = 1.
#include <Eigen/Dense>
#include <catch2/catch.hpp>
#include <cmath>

#include "formats/bulk_model.hpp"
#include "formats/deck.hpp"
#include "formats/deck_writer.hpp"
#include "translators/assembly/fe_model.hpp"
#include "translators/truss/configurations.hpp"
#include "translators/truss/reference_modes.hpp"
#include "translators/truss/truss_deck.hpp"

using namespace ssid;

namespace {

struct Check {
  double worst_residual = 0, worst_mass_error = 0;
  int modes = 0;
};

/// Reference modes (g-set, 6 per grid in the generator's grid order) taken to
/// FeModel's a-set by (grid, component), then the eigen-residual in FeModel's
/// operators. Rigid-body and suspension modes (f < 1 Hz) are measured against
/// ‖M φ‖ ω² scale so a near-zero λ does not inflate the ratio.
Check cross_check(const std::vector<std::string>& configs, translators::truss::ModelForm form, int count) {
  using namespace translators::truss;
  const TrussModel t = build_configured(configs);
  const translators::truss::TrussCards gen = build_truss_cards(t, form);
  const formats::Deck written = to_deck(t, gen, "cross-check");
  // Through the text, as a user would load it.
  const formats::Deck deck = formats::read_deck_text(formats::render_file(written, 0), "mpi.bdf");
  formats::BulkModel bulk = formats::parse_bulk(deck);
  formats::resolve(deck, bulk);
  REQUIRE(bulk.problems.empty());
  const translators::FeModel fe(deck, std::move(bulk));
  const translators::FeOperators op = fe.operators(fe.initial_parameters(), false);

  const ReferenceModes ref = reference_modes(gen, count);
  REQUIRE(ref.converged);
  // FeModel's a-set must be as large as the reference's independent set.
  CHECK(static_cast<std::size_t>(op.K.rows()) == ref.a_set_size);

  const auto& gset = fe.geometry().gset();
  const auto& red = fe.reduction();
  Eigen::MatrixXd phi_a(op.K.rows(), ref.shapes.cols());
  for (Eigen::Index a = 0; a < op.K.rows(); ++a) {
    const translators::Dof d = gset.at(red.a_to_g[static_cast<std::size_t>(a)]);
    std::size_t gi = 0;
    while (gi < ref.grid_ids.size() && ref.grid_ids[gi] != d.point) ++gi;
    REQUIRE(gi < ref.grid_ids.size());
    phi_a.row(a) = ref.shapes.row(static_cast<Eigen::Index>(6 * gi + d.component - 1));
  }
  Check c;
  for (Eigen::Index j = 0; j < phi_a.cols(); ++j) {
    const double f = ref.frequency_hz[static_cast<std::size_t>(j)];
    const double lambda = std::copysign(std::pow(2 * M_PI * f, 2), f);
    const Eigen::VectorXd phi = phi_a.col(j);
    const Eigen::VectorXd Kphi = op.K * phi, Mphi = op.M * phi;
    const double scale = std::max(Kphi.norm(), Mphi.norm() * std::pow(2 * M_PI, 2));
    c.worst_residual = std::max(c.worst_residual, (Kphi - lambda * Mphi).norm() / scale);
    c.worst_mass_error = std::max(c.worst_mass_error, std::abs(phi.dot(Mphi) - 1.0));
    ++c.modes;
  }
  return c;
}

}  // namespace

TEST_CASE("MPI rod deck: FeModel's operators have the reference assembler's modes", "[assembly][truss]") {
  for (const auto& configs : std::vector<std::vector<std::string>>{
           {"bare"}, {"surge_springs", "metrology_tip_mass"}, {"tower_diagonal_2", "free"}}) {
    INFO(configs.front());
    const Check c = cross_check(configs, translators::truss::ModelForm::Rod, 30);
    CHECK(c.modes == 30);
    CHECK(c.worst_residual < 1e-8);
    CHECK(c.worst_mass_error < 1e-8);
  }
}

TEST_CASE("MPI beam deck: FeModel's operators have the reference assembler's modes", "[assembly][truss][beam]") {
  const Check c = cross_check({"long_bnut", "strut_mass"}, translators::truss::ModelForm::Beam, 25);
  CHECK(c.modes == 25);
  CHECK(c.worst_residual < 1e-6);
  CHECK(c.worst_mass_error < 1e-6);
}
