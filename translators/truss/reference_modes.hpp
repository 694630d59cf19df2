#pragma once
/// \file reference_modes.hpp
/// The truss generator's own small assembler and eigen-solve, used to aim the
/// generated structure at the report's frequency band and to verify each
/// configuration's effect. It reads the TrussCards (exactly what the deck holds),
/// not the deck, so it is an independent check on any deck assembler:
///
///  - CROD: k = EA/L along the axis; lumped mass (rho A + NSM) L / 2 per end.
///  - CBAR: Euler-Bernoulli 12x12 frame element (no shear flexibility, as PBAR
///    with K1, K2 blank), element y in the plane of the axis and v; lumped
///    translational mass (rho A + NSM) L / 2 per end, no rotary inertia
///    (NASTRAN's default lumped mass).
///  - CONM2: m on the translations, I on the rotations. CELAS1: scalar spring.
///  - RBE2: dependent grid = rigid motion of the independent one,
///    u_d = u_n + theta_n x (x_d - x_n), theta_d = theta_n, eliminated by u = T u_a.
///  - GRID PS and DOFs with neither stiffness nor mass (AUTOSPC) removed.
///
/// Solve: K phi = lambda M phi. Dense (n <= 3000): the pencil (M, K + sM) with a
/// positive shift s so massless rotations and rigid-body modes are handled;
/// lambda = 1/mu - s. Larger: Spectra Lanczos, shift-invert about a negative shift.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <string>
#include <vector>

#include "translators/truss/truss_cards.hpp"

namespace ssid::translators::truss {

struct ReferenceModes {
  std::vector<double> frequency_hz;   ///< ascending; negative eigenvalues give -sqrt(|lambda|)/2pi
  Eigen::MatrixXd shapes;             ///< g-set shapes (6 per grid, grid order of TrussCards::grids), mass-normalised
  std::vector<int> grid_ids;          ///< TrussCards grid order
  std::size_t a_set_size = 0;         ///< independent DOFs solved
  bool converged = true;
};

struct Assembled {
  Eigen::SparseMatrix<double> K, M;   ///< g-set, 6 DOF per grid
  Eigen::SparseMatrix<double> T;      ///< g-set x a-set: u_g = T u_a
};

/// Assembles K, M (g-set) and the reduction T.
Assembled assemble_reference(const TrussCards& fe);

/// Lowest `count` modes (rigid-body modes included).
ReferenceModes reference_modes(const TrussCards& fe, int count);

/// Kinetic-energy fraction of mode j on a set of grids: sum over their
/// translational DOFs of phi_i (M phi)_i (mass-normalised mode, sums to 1).
double energy_fraction(const TrussCards& fe, const Assembled& a, const ReferenceModes& modes, int j,
                       const std::vector<int>& grids);

/// Kinetic-energy fractions of mode j in x, y and z translation over all grids
/// (the rest is rotary inertia). Classifies component modes: axial (x), bending (y, z).
Eigen::Vector3d translational_energy(const Assembled& a, const ReferenceModes& modes, int j);

/// First bending and first axial frequencies (Hz) of a component assembly laid
/// along x, from the lowest `count` modes: the first elastic mode (> 1 Hz) whose
/// kinetic energy is mostly lateral (y + z > 0.5), and mostly axial (x > 0.5).
/// NaN when not found among them.
std::pair<double, double> component_bending_axial(const TrussCards& fe, int count = 60);

}  // namespace ssid::translators::truss
