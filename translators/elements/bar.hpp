#pragma once
/// \file bar.hpp
/// CBAR and CBEAM (constant section): Euler–Bernoulli bending in two planes
/// with I12 coupling, axial, torsion, Timoshenko shear flexibility when K1/K2
/// are given, offsets WA/WB and pin flags PA/PB.
///
/// Element frame (NASTRAN CBAR/CBEAM): ends A = GA + WA and B = GB + WB;
///   x = (B − A)/|B − A|,  z = (x × v)/|x × v|,  y = z × x,
/// so the orientation vector v lies in the x–y plane, plane 1 = x–y (I1,
/// displacement v along y, rotation θz), plane 2 = x–z (I2, w along z, θy).
/// With L = |B − A| and the local DOFs of each end (u v w θx θy θz):
///   axial EA/L, torsion GJ/L;
///   bending, with q1 = (v_a, θz_a, v_b, θz_b), q2 = (w_a, −θy_a, w_b, −θy_b)
///   (w' = −θy) and the strain energy E/2 ∫ (I1 v''² + 2 I12 v'' w'' + I2 w''²):
///     U = E/2 [I1 q1ᵀ Kb(φ1) q1 + 2 I12 q1ᵀ Kb q2 + I2 q2ᵀ Kb(φ2) q2],
///     Kb(φ) = 1/((1+φ)L³) [12 6L −12 6L; 6L (4+φ)L² −6L (2−φ)L²; …]
///   (Przemieniecki), φi = 12 E Ii / (Ki A G L²) when Ki > 0, else 0.
///   As PBAR remark 4 says, K1 and K2 are ignored when I12 ≠ 0.
/// Offsets: u_end = u_grid + θ_grid × W (W in basic), applied to K and M.
/// Pin flags (digits 1–6 in the element frame) are released by static
/// condensation K_rr − K_rc K_cc⁻¹ K_cr; released DOFs carry no stiffness.
///
/// Mass, μ = ρA + NSM, polar inertia per length ρ(I1 + I2):
///   Lumped: μL/2 on the three translations of each end. CBAR omits the
///     torsional inertia, as MSC Nastran does unless PARAM,BARMASS > 0
///     (MSC QRG, PARAM BARMASS; PARAM COUPMASS says the lumped matrices "may
///     include torsion inertia for beam elements"): CBEAM adds ρ(I1+I2)L/2
///     about x at each end. Lumped mass ignores pin flags (it is placed at the
///     grids) but follows offsets.
///   Coupled: consistent matrices of the same shape functions: axial μL/6
///     [2 1; 1 2], transverse μL/420 [156 22L 54 −13L; …] in both planes
///     (Euler–Bernoulli shape functions, no rotary inertia of the section, also
///     when φ > 0 — frequencies then still converge to the shear-beam closed
///     form, but O(h²) instead of O(h⁴), see the tests), torsion
///     ρ(I1+I2)L/6 [2 1; 1 2]. With pin flags the coupled
///     mass is reduced with the same condensation (Guyan) transformation.
///   Sources: PARAM COUPMASS and PARAM BARMASS in the MSC QRG as we read them
///   (the BARMASS wording could not be re-checked against a stored copy while
///   writing this); NASTRAN's exact CBAR coupled-mass terms are not published
///   in the QRG, so the coupled matrix is the standard consistent one.
/// Derivatives: exact via the complex step (see complex_step.hpp), which
/// carries φ and the condensation exactly.
#include <string>

#include "translators/elements/element_types.hpp"

namespace ssid::translators::elements {

/// Geometry of a CBAR/CBEAM in basic: grid positions and CD frames, the
/// orientation vector v (basic; from G0 the caller uses x_G0 − x_GA), the
/// offsets WA, WB in basic (the caller rotates them from the grids'
/// displacement frames as OFFT "G" prescribes), and pin flags as the card's
/// integers (e.g. 456; 0 = none).
struct BarGeometry {
  GridPair grids;
  Eigen::Vector3d v = Eigen::Vector3d::UnitY();
  Eigen::Vector3d wa = Eigen::Vector3d::Zero(), wb = Eigen::Vector3d::Zero();
  int pa = 0, pb = 0;
};

/// PBAR / PBEAM (constant section) values; PBARL dims go through
/// section_properties first. k1, k2: shear area factors (0 = no shear
/// flexibility; PBEAM's default is 1.0, PBAR's blank means 0 here).
struct BarSection {
  double a = 0, i1 = 0, i2 = 0, i12 = 0, j = 0, nsm = 0, k1 = 0, k2 = 0;
};

enum class BarParam { A, I1, I2, I12, J, Nsm, K1, K2, E, G, Rho };

/// Element frame: rows are x, y, z of the element in basic. Throws
/// std::invalid_argument if the ends coincide or v is parallel to x.
Eigen::Matrix3d bar_element_axes(const BarGeometry& g);

/// CBAR: K, M in the grids' displacement frames (12 x 12). `barmass` adds the
/// lumped torsional inertia (PARAM,BARMASS > 0). Throws std::invalid_argument
/// for bad geometry or pin flags that leave a mechanism.
ElementMatrices bar_matrices(const BarGeometry& g, const BarSection& s, const Material& mat, MassKind mass,
                             bool barmass = false);
ElementMatrices bar_derivative(const BarGeometry& g, const BarSection& s, const Material& mat, MassKind mass,
                               BarParam which, bool barmass = false);
/// d/dt [K, M](s + t ds, mat + t dmat): DVPREL1/DVMREL1 combinations and the
/// chain rule through PBARL dimensions (ds = a column of section_jacobian).
ElementMatrices bar_directional_derivative(const BarGeometry& g, const BarSection& s, const Material& mat,
                                           MassKind mass, const BarSection& ds, const Material& dmat,
                                           bool barmass = false);

/// CBEAM with a constant section: as CBAR, with lumped torsional inertia.
ElementMatrices beam_matrices(const BarGeometry& g, const BarSection& s, const Material& mat, MassKind mass);
ElementMatrices beam_derivative(const BarGeometry& g, const BarSection& s, const Material& mat, MassKind mass,
                                BarParam which);
ElementMatrices beam_directional_derivative(const BarGeometry& g, const BarSection& s, const Material& mat,
                                            MassKind mass, const BarSection& ds, const Material& dmat);

}  // namespace ssid::translators::elements
