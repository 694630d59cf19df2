#pragma once
/// \file section.hpp
/// Section properties of every PBARL/PBEAML cross-section type of the MSC
/// Quick Reference Guide (PBARL/PBEAML Figure 1) from its dimensions, with
/// exact derivatives with respect to every dimension (complex step).
///
/// Axes follow the QRG figures: the section lies in the element y–z plane, y
/// up (the depth; plane 1), z across (the width), and
///   I1 = ∫ y² dA (bending in plane 1),  I2 = ∫ z² dA,  I12 = ∫ y z dA
/// about the centroid. A, I1, I2, I12 are exact for the drawn shapes (sums of
/// rectangles, HEXA a hexagon, by Green's theorem over the outline); the
/// dimension meanings agree with the area formulas MSC publishes for the beam
/// library and are checked against the PBAR/PBEAM NASTRAN prints for ROD, TUBE,
/// BOX and T (docs/elements.md).
///
/// | TYPE | DIM1 | DIM2 | DIM3 | DIM4 | DIM5.. |
/// |------|------|------|------|------|--------|
/// | ROD  | r    |      |      |      |        |
/// | TUBE | r_o  | r_i  |      |      |        |
/// | TUBE2| r_o  | t    |      |      |        |
/// | BAR  | b (z) | h (y) |     |      |        |
/// | BOX  | b (z) | h (y) | t top/bottom | t sides | |
/// | BOX1 | b    | h    | t top | t bottom | t left, t right |
/// | DBOX | b    | h    | left cell width (to the middle wall's centre) | t left | t middle, t right, t top/bottom left, t top/bottom right |
/// | I    | h    | b bottom | b top | t web | t bottom, t top |
/// | I1   | b − t_w (both outstands) | t web | web clear height | h | |
/// | CHAN | b (with web) | h | t web | t flanges | |
/// | CHAN1| outstand | t web | web clear height | h | |
/// | CHAN2| t legs | t base | h | b | |
/// | T    | b flange | h | t flange | t web (flange on top) | |
/// | T1   | flange height | web length | t flange | t web (flange upright, web to +z) | |
/// | T2   | b flange | h | t flange | t web (flange at the bottom) | |
/// | L    | b (leg along +z) | h (leg along +y) | t of the z-leg | t of the y-leg | |
/// | CROSS| both arms together | t upright | h upright | t arms | |
/// | H    | gap between legs | both legs' thickness together | h legs | t web | |
/// | Z    | outstand | t web | web clear height | h (top flange to −z) | |
/// | HEXA | tip length | b | h | | |
/// | HAT  | h | t | top width | lip width | |
/// | HAT1 | base width | h | top width | t hat | t base |
///
/// Torsion constant J. The QRG does not publish NASTRAN's J formulas; NX
/// Nastran's element library reference gives them for several open sections as
/// the thin-walled sum over plates of (centre-line length) t³/3, and NX's
/// printed J for TYPE=T (web from the tip to the flange's mid-line) equals it
/// to the five printed digits. So:
///   ROD, TUBE, TUBE2  π (r_o⁴ − r_i⁴)/2 (exact)
///   BAR     a c³ [1/3 − 0.21 (c/a)(1 − c⁴/(12 a⁴))], a ≥ c (Roark Table 10.7 case 4)
///   open sections (I, I1, CHAN, CHAN1, CHAN2, T, T1, T2, L, CROSS, H, Z, HAT)
///           Σ l t³/3, l the plate's centre-line length (a flange that a web meets
///           in its middle counts its full width; a web or leg runs to the mid-line
///           of the plate it meets)
///   BOX, BOX1  Bredt–Batho 4 A_m² / ∮ ds/t on the wall centre lines (NX printed
///           the BOX value to five digits)
///   DBOX    two-cell Bredt–Batho (the shared wall's length the mean of the two
///           cells' heights)
///   HAT1    Bredt–Batho for the cell of hat and base, plus the outstands (lip on
///           base, thickness t + t_base) as open plates
///   HEXA    Saint-Venant's approximation A⁴ / (4π² I_p) (exact for the ellipse)
///
/// Shear factors K1, K2 (shear stiffness K·A·G in planes 1 and 2). NASTRAN
/// derives them from the section (PBARL remark 4: "the cross-sectional
/// properties, shear flexibility factors, and stress recovery points are
/// computed using the TYPE and DIMi"), so a PBARL/PBEAML bar is shear-flexible
/// where a PBAR with blank K1, K2 is not. The QRG gives no formula; NASTRAN's
/// printed values (USER INFORMATION MESSAGE 4379, the equivalent PBAR/PBEAM):
///   ROD 0.9; TUBE 0.5 (a thin wall); BOX 2 (h − 2 t_y) t_z / A, 2 (b − 2 t_z) t_y / A;
///   T web (h − t_f) t_w / A, flange b t_f / A.
/// The thin-walled types take K = (area of the plates parallel to the shear) / A:
/// a plate that another meets in its middle (flanges of T, I, I1, T1, the upright
/// of CROSS, the legs of H) counts whole, the plate meeting it counts clear of it;
/// where plates meet at their ends (corners of BOX, BOX1, DBOX, CHAN, CHAN1,
/// CHAN2, L, Z, HAT, HAT1) the corner block counts in neither (NX's formulas
/// for CHAN and L say so). Solid BAR and HEXA take 5/6, TUBE2 0.5 as TUBE.
/// Only ROD, TUBE, BOX and T are confirmed by NASTRAN output (docs/elements.md).
#include <Eigen/Core>
#include <string>
#include <vector>

namespace ssid::translators::elements {

/// In the order of section.cpp's name table.
enum class SectionShape {
  Rod, Tube, Bar, Box, I, Tube2, I1, Chan, Chan1, Chan2, T, T1, T2, L, Box1, Cross, H, Z, Hexa, Hat, Hat1, DBox
};

/// The section properties NASTRAN derives, in PBAR order, and the shear factors.
struct SectionProperties {
  double a = 0, i1 = 0, i2 = 0, i12 = 0, j = 0, k1 = 0, k2 = 0;
};

/// Rows of section_jacobian, in the order of SectionProperties.
constexpr int kSectionValues = 7;

/// The TYPE name (upper case, as on the card) to the shape.
/// Throws std::invalid_argument naming the supported types otherwise.
SectionShape parse_section_shape(const std::string& type);
/// "ROD, TUBE, BAR, ..." — every supported TYPE, for messages.
std::string supported_section_types();
const char* section_shape_name(SectionShape s);
/// Number of DIMi the type takes (the QRG's counts).
int section_dim_count(SectionShape s);
/// Whether the shear centre coincides with the centroid for these dimensions
/// (doubly symmetric or point-symmetric sections). NASTRAN's CBEAM offsets the
/// neutral axis from the shear centre for the others (PBEAML), which ssid's
/// CBEAM does not model.
bool shear_centre_at_centroid(SectionShape s, const std::vector<double>& dims);

/// Properties from dimensions. Throws std::invalid_argument for the wrong
/// number of dimensions, a non-positive dimension, or an impossible shape
/// (TUBE r_i ≥ r_o; BOX 2 t ≥ outer size; I flanges thicker than the depth; ...),
/// the message naming the TYPE and the dimensions at fault.
SectionProperties section_properties(SectionShape s, const std::vector<double>& dims);

/// Exact Jacobian ∂(A, I1, I2, I12, J, K1, K2)/∂DIMj: 7 rows, one column per DIM.
Eigen::Matrix<double, kSectionValues, Eigen::Dynamic> section_jacobian(SectionShape s, const std::vector<double>& dims);

}  // namespace ssid::translators::elements
