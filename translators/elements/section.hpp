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
///
/// Shear factors K1, K2 (shear stiffness K·A·G in planes 1 and 2). NASTRAN
/// derives them from the section (PBARL remark 4: "the cross-sectional
/// properties, shear flexibility factors, and stress recovery points are
/// computed using the TYPE and DIMi"), so a PBARL/PBEAML bar is shear-flexible
/// where a PBAR with blank K1, K2 is not. The figures give no formula; the values
/// below are those NASTRAN prints for its equivalent PBAR/PBEAM (USER
/// INFORMATION MESSAGE 4379, "THE USER SUPPLIED PBARL BULK DATA ENTRIES ARE
/// REPLACED BY THE FOLLOWING PBAR ENTRIES"), read in Simcenter/NX Nastran .f06
/// files (docs/elements.md lists them):
///   ROD   K1 = K2 = 0.9                                   (NX, DIM1 = 1)
///   TUBE  K1 = K2 = 0.5                                   (NX, r_o 0.2, r_i 0.195: a thin
///         wall; whether NASTRAN lets K grow for thick walls is not known to us)
///   BOX   K1 = 2 (h − 2 t_y) t_z / A,  K2 = 2 (b − 2 t_z) t_y / A
///         (the walls parallel to the shear, corners excluded; NX, 6 × 1 × 0.1 × 0.1:
///         0.11765, 0.85294)
///   I     K1 = (h − t_bot − t_top) t_web / A,  K2 = (b_bot t_bot + b_top t_top) / A
///         (the same rule: web and flanges, as NX prints for TYPE=T: web/A and
///         flange/A; not seen for I itself)
///   BAR   K1 = K2 = 5/6 (the rectangle's shear coefficient; no NASTRAN output
///         seen for BAR: an assumption, said in docs/elements.md)
#include <Eigen/Core>
#include <string>
#include <vector>

namespace ssid::translators::elements {

enum class SectionShape { Rod, Tube, Bar, Box, I };

/// The section properties NASTRAN derives, in PBAR order, and the shear factors.
struct SectionProperties {
  double a = 0, i1 = 0, i2 = 0, i12 = 0, j = 0, k1 = 0, k2 = 0;
};

/// Rows of section_jacobian, in the order of SectionProperties.
constexpr int kSectionValues = 7;

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

/// Exact Jacobian ∂(A, I1, I2, I12, J, K1, K2)/∂DIMj: 7 rows, one column per DIM.
Eigen::Matrix<double, kSectionValues, Eigen::Dynamic> section_jacobian(SectionShape s, const std::vector<double>& dims);

}  // namespace ssid::translators::elements
