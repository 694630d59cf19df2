#pragma once
/// \file complex_step.hpp
/// Exact first derivatives by the complex step: for f analytic in a real
/// parameter p, f(p + i h) = f(p) + i h f'(p) − h² f''(p)/2 + …, so
///   f'(p) = Im f(p + i h) / h
/// with no subtractive cancellation; with h = 1e-30 the truncation error
/// (∝ h²) is far below rounding, so the result is the derivative to machine
/// precision (Squire & Trapp, SIAM Review 40, 1998). The element routines are
/// written once, templated on the scalar, and evaluated in complex arithmetic
/// to differentiate K and M with respect to section, material and spring
/// values — including the non-linear paths (Timoshenko φ, pin-flag
/// condensation, PBARL dimensions) where a hand-written derivative would be
/// long and error-prone. Branches compare real parts only.
#include <complex>

namespace ssid::translators::elements::detail {

using Complex = std::complex<double>;
inline constexpr double kComplexStep = 1e-30;

inline double real_part(double x) { return x; }
inline double real_part(const Complex& x) { return x.real(); }

}  // namespace ssid::translators::elements::detail
