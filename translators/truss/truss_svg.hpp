#pragma once
/// \file truss_svg.hpp
/// A picture of the truss drawn from its own geometry: an axonometric view of
/// every strut coloured by boom or tower, the balls, the suspension points, and
/// labels for the optics boom, the metrology boom and the tower.
#include <string>

#include "translators/truss/truss_model.hpp"

namespace ssid::translators::truss {

/// SVG text (self-contained, no external resources). `azimuth_deg` turns the
/// view about the vertical, `elevation_deg` tilts it.
std::string render_svg(const TrussModel& t, double azimuth_deg = -35.0, double elevation_deg = 22.0);

}  // namespace ssid::translators::truss
