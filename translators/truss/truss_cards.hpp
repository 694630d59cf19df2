#pragma once
/// \file truss_cards.hpp
/// A truss model form (rod or beam) as a plain list of NASTRAN entities: grids,
/// rods, bars, concentrated masses, scalar springs, rigid elements, SPCs and the
/// design-variable table. One structure feeds both the deck writer
/// (truss_deck.hpp) and the generator's own reference assembler
/// (reference_modes.hpp), so what is verified is exactly what is written.
#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "translators/truss/truss_model.hpp"

namespace ssid::translators::truss {

enum class ModelForm { Rod, Beam };

struct FeGrid {
  int id = 0;
  Eigen::Vector3d x = Eigen::Vector3d::Zero();
  std::string ps;          ///< permanent single-point constraints (GRID field 8), e.g. "456"
  std::string kind;        ///< "ball", "ball_surface", "strut", "spring"
};
struct FeMaterial { int id = 1; double E = 0, nu = 0, rho = 0; };
struct FeRodProp { int id = 0; double A = 0, J = 0, nsm = 0; std::string kind; };
struct FeRod { int id = 0, pid = 0, g1 = 0, g2 = 0; int member = 0; };
struct FeBarProp { int id = 0; double A = 0, I1 = 0, I2 = 0, J = 0, nsm = 0; std::string kind; };
/// CBAR with orientation vector v (basic); kind: "bnut", "endcap", "tube", "long_bnut".
struct FeBar { int id = 0, pid = 0, g1 = 0, g2 = 0; Eigen::Vector3d v = Eigen::Vector3d::UnitZ(); int member = 0; };
/// CONM2 at a grid, no offset; I11 = I22 = I33 = inertia (spheres and points).
struct FeMass { int id = 0, grid = 0; double m = 0, inertia = 0; std::string kind; };
/// CELAS1: scalar spring between (g1, c1) and (g2, c2); g2 = 0 means grounded.
struct FeSpringProp { int id = 0; double k = 0; std::string kind; };
struct FeSpring { int id = 0, pid = 0, g1 = 0, c1 = 0, g2 = 0, c2 = 0; };
/// RBE2: independent grid gn, all six components of each dependent grid.
struct FeRigid { int id = 0, gn = 0; std::vector<int> gm; };
struct FeSpc { int grid = 0; std::string components; };
struct FeDesvar { int id = 0; std::string label; double init = 0, lower = 0, upper = 0; std::string what; };
/// DVPREL1: property (or CONM2/PELAS element) field = coef * DESVAR dvid (+ the `more` terms).
struct FeDvprel {
  int id = 0;
  std::string type;
  int pid = 0;
  std::string pname;
  int dvid = 0;
  double coef = 0;
  std::vector<std::pair<int, double>> more;  ///< further (DESVAR, coefficient) terms
};

/// The cards of one model form, as the generator writes them (not an assembled
/// model: translators::FeModel, built from the written deck, is that).
struct TrussCards {
  ModelForm form = ModelForm::Rod;
  std::string title;
  FeMaterial mat;
  std::vector<FeGrid> grids;
  std::vector<FeRodProp> rod_props;
  std::vector<FeRod> rods;
  std::vector<FeBarProp> bar_props;
  std::vector<FeBar> bars;
  std::vector<FeMass> masses;
  std::vector<FeSpringProp> spring_props;
  std::vector<FeSpring> springs;
  std::vector<FeRigid> rigids;
  std::vector<FeSpc> spcs;   ///< SPC1 set 1 (suspension spring ceilings and chain grids' lateral DOF)
  std::vector<FeDesvar> desvars;
  std::vector<FeDvprel> dvprels;
  int eigrl_nd = 40;         ///< EIGRL: modes wanted
  double eigrl_v2 = 100.0;   ///< EIGRL upper frequency, Hz

  std::size_t dof_count() const;  ///< 6 per grid less permanent constraints (GRID PS)
  /// Total mass as NASTRAN's lumped mass would see it: CONM2 + (rho A + nsm) L for rods and bars.
  double total_mass() const;
  const FeGrid& grid(int id) const;
};

/// Builds a model form of a truss. Rod: one grid per ball (rotations fixed by
/// GRID PS=456), one CROD per strut with the strut's series-equivalent axial
/// area, all mass lumped as CONM2 on the balls. Beam: CONM2 balls, RBE2 out to
/// the ball radius, each strut as B-nut, end cap and tube CBARs (mass as NSM),
/// tube subdivided so local bending exists. Suspension springs as CELAS1, surge
/// springs as chains of CELAS1 and CONM2.
TrussCards build_truss_cards(const TrussModel& t, ModelForm form);

/// Series-equivalent axial area of a strut over its centre-to-centre length:
/// L / sum(L_i / A_i) over tube, end caps and B-nuts, the ball radii rigid.
double equivalent_axial_area(const TrussModel& t, const Member& m);

/// Derivatives of equivalent_axial_area with respect to the tube, end-cap and
/// B-nut areas: dA/dA_i = A^2 L_i / (L A_i^2). A is homogeneous of degree one in
/// the areas, so A = sum_i (dA/dA_i) A_i exactly: the rod form's DVPREL1 (no C0)
/// reproduces the PROD area at the nominal point with the exact first derivatives.
Eigen::Vector3d equivalent_area_gradient(const TrussModel& t, const Member& m);

/// Number of tube elements a strut gets in the beam form.
int tube_segments(const TrussModel& t, const Member& m);

}  // namespace ssid::translators::truss
