#pragma once
/// \file weight_table.hpp
/// The grid point weight generator's output (PARAM GRDPNT) in the layout of
/// NASTRAN's .f06 block "O U T P U T   F R O M   G R I D   P O I N T   W E I G H T
/// G E N E R A T O R": MO (6 x 6 rigid-body mass about the reference point, basic
/// system), S (the mass axis system: identity, since ssid's masses are isotropic
/// per direction in basic), mass and C.G. per direction, I(S) (inertia about the
/// C.G.), I(Q) (principal inertias) and Q (their axes, I(Q) = Qᵀ I(S) Q).
#include <cstdint>
#include <string>

#include "translators/weight.hpp"

namespace ssid::translators {

/// `reference` is the GRDPNT value (a grid id; 0 = the basic origin). Values are
/// printed as given (scale by 1/WTMASS beforehand for NASTRAN's weight units).
std::string format_grid_point_weight(const WeightSummary& w, std::int64_t reference);

}  // namespace ssid::translators
