#pragma once
/// \file orientation.hpp
/// The element orientation fields shared by CBAR, CBEAM, CBUSH and their
/// BAROR/BEAMOR defaults: either a vector X1, X2, X3 (reals) or a grid G0
/// (an integer in the first of the three fields, the other two blank).
#include <array>
#include <cstdint>
#include <vector>

#include "formats/card.hpp"
#include "formats/field_reader.hpp"

namespace ssid::formats {

/// Reads fields i, i+1, i+2 into g0 (> 0: the vector runs from GA to grid G0) or x
/// (g0 = 0; in the displacement system of GA). Returns false (and leaves both alone)
/// when all three are blank.
/// "X1-X3 all zero" is an error: there is no direction.
bool read_orientation(const FieldReader& r, std::size_t i, std::int64_t& g0, std::array<double, 3>& x);

/// Writes the three fields at i (blank when `blank`).
void write_orientation(std::vector<FieldValue>& v, std::size_t i, std::int64_t g0, const std::array<double, 3>& x,
                       bool blank);

}  // namespace ssid::formats
