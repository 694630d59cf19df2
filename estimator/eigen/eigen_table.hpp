#pragma once
/// \file eigen_table.hpp
/// The modes of a solve as NASTRAN prints them in the .f06 under
/// "R E A L   E I G E N V A L U E S": one line per mode, (I9, I10, 5(7X,1PE13.6)):
/// mode number, extraction order, eigenvalue λ [(rad/s)²], radians √|λ|,
/// cycles √|λ|/2π [Hz], generalised mass φᵀMφ, generalised stiffness φᵀKφ.
#include <string>

#include "estimator/eigen/eigen_solver.hpp"

namespace ssid::estimator {

/// The title, the two column-heading lines and one line per mode.
std::string format_real_eigenvalues(const EigenResult& result);

}  // namespace ssid::estimator
