#pragma once
/// \file rod.hpp
/// CROD / CONROD: axial and torsional stiffness between two grids.
///
/// With L = |x_b − x_a|, e the unit axis and μ = ρA + NSM:
///   K: axial EA/L and torsion GJ/L along e (12 x 12, before the CD frames),
///   M lumped (NASTRAN default): μL/2 on each translational DOF of each end,
///     no rotational inertia;
///   M coupled (COUPMASS > 0): μL/6 [2 1; 1 2] on each translational direction
///     (NASTRAN's coupled rod mass acts on all three translations, not only
///     the axial one, so it stays invariant under rigid rotation); no
///     torsional inertia.
/// Derivatives are exact: K and M are linear in each of A, J, E, G, ρ, NSM
/// except through the products EA, GJ, ρA, which the complex step handles.
#include "translators/elements/element_types.hpp"

namespace ssid::translators::elements {

/// PROD (or CONROD) values.
struct RodSection {
  double a = 0, j = 0, nsm = 0;
};

enum class RodParam { A, J, Nsm, E, G, Rho };

/// K and M in the grids' displacement frames. Throws std::invalid_argument if
/// the grids coincide.
ElementMatrices rod_matrices(const GridPair& g, const RodSection& s, const Material& mat, MassKind mass);

/// ∂K/∂p and ∂M/∂p for one parameter (returned in the k and m members).
ElementMatrices rod_derivative(const GridPair& g, const RodSection& s, const Material& mat, MassKind mass,
                               RodParam which);

/// Directional derivative d/dt [K, M](s + t ds, mat + t dmat) at t = 0: one
/// call per DVPREL1/DVMREL1 linear combination.
ElementMatrices rod_directional_derivative(const GridPair& g, const RodSection& s, const Material& mat,
                                           MassKind mass, const RodSection& ds, const Material& dmat);

}  // namespace ssid::translators::elements
