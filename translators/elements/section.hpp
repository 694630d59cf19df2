#pragma once
/// \file section.hpp
/// Section properties of PBARL/PBEAML cross-section types ROD, TUBE, BAR, BOX
/// and I from their dimensions, with exact derivatives with respect to every
/// dimension.
///
/// Axes follow the NASTRAN PBARL figures: the section lies in the element y–z
/// plane, y is the plane-1 direction, and
///   I1 = ∫ y² dA (bending in plane 1),  I2 = ∫ z² dA,  I12 = ∫ y z dA
/// about the centroid (all five types are symmetric about y, so I12 = 0).
///
/// | TYPE | DIM1 | DIM2 | DIM3 | DIM4 | DIM5 | DIM6 |
/// |------|------|------|------|------|------|------|
/// | ROD  | r    |      |      |      |      |      |
/// | TUBE | r_o  | r_i  |      |      |      |      |
/// | BAR  | b (along z) | h (along y) | | |   |      |
/// | BOX  | b (along z) | h (along y) | t_y: top/bottom wall | t_z: side wall | | |
/// | I    | h (depth, y) | b_bot | b_top | t_web | t_bot | t_top |
///
/// Torsion constant J (the QRG figures give A, I1, I2 but not the J formula
/// NASTRAN uses internally; we use the standard ones and say so):
///   ROD   J = π r⁴ / 2                          (exact, circular)
///   TUBE  J = π (r_o⁴ − r_i⁴) / 2               (exact, circular)
///   BAR   J = a c³ [1/3 − 0.21 (c/a)(1 − c⁴/(12 a⁴))],  a = max(b,h), c = min(b,h)
///         (Roark's Formulas for Stress and Strain, Table 10.7 case 4; error < 0.5 %)
///   BOX   J = 2 t_y t_z (b − t_z)² (h − t_y)² / (b t_z + h t_y − t_z² − t_y²)
///         (Bredt–Batho single-cell thin-walled tube on the wall centre lines)
///   I     J = (b_bot t_bot³ + b_top t_top³ + (h − t_bot − t_top) t_web³) / 3
///         (open thin-walled section: sum of b t³/3 of the three plates, web
///         between the flanges)
#include <Eigen/Core>
#include <string>
#include <vector>

namespace ssid::translators::elements {

enum class SectionShape { Rod, Tube, Bar, Box, I };

/// The five section properties, in PBAR order.
struct SectionProperties {
  double a = 0, i1 = 0, i2 = 0, i12 = 0, j = 0;
};

/// "ROD", "TUBE", "BAR", "BOX", "I" (upper case, as on the card) to the shape.
/// Throws std::invalid_argument naming the supported types otherwise.
SectionShape parse_section_shape(const std::string& type);
const char* section_shape_name(SectionShape s);
/// Number of DIMi the type takes (1, 2, 2, 4, 6).
int section_dim_count(SectionShape s);

/// Properties from dimensions. Throws std::invalid_argument for the wrong
/// number of dimensions, a non-positive dimension, or an impossible shape
/// (TUBE r_i ≥ r_o; BOX 2 t ≥ outer size; I flanges thicker than the depth).
SectionProperties section_properties(SectionShape s, const std::vector<double>& dims);

/// Exact Jacobian ∂(A, I1, I2, I12, J)/∂DIMj: 5 rows, one column per DIM.
Eigen::Matrix<double, 5, Eigen::Dynamic> section_jacobian(SectionShape s, const std::vector<double>& dims);

}  // namespace ssid::translators::elements
