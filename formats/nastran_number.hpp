#pragma once
/// \file nastran_number.hpp
/// NASTRAN's number syntax, both ways.
///
/// Reading accepts every real form NASTRAN does: `1.`, `.5`, `1.-3` (exponent
/// without E), `-2.5+4`, `1.E-3`, `1.D-3`, and integers where a real is allowed.
/// Writing produces the shortest text that reads back to the same double and
/// always carries a decimal point, so the result is a valid NASTRAN real.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace ssid::formats {

enum class FieldKind { Blank, Integer, Real, Text };

/// Classifies a trimmed, upper-case field as NASTRAN would read it.
FieldKind classify_field(std::string_view s);

/// Parses a NASTRAN integer (`[+-]digits`); nullopt when `s` is not one or overflows int64.
std::optional<std::int64_t> parse_integer(std::string_view s);

/// Parses a NASTRAN real in any of its forms, or a plain integer; nullopt otherwise.
/// Exact: the result is the double nearest the decimal value written.
std::optional<double> parse_real(std::string_view s);

/// Shortest NASTRAN text for `v` within `width` characters that reads back to
/// exactly `v`; when no text of that width can hold `v` exactly, nullopt.
std::optional<std::string> format_real_exact(double v, int width);

/// The NASTRAN text for `v` in at most `width` characters, rounded to the most
/// significant digits that fit (used only when exactness is impossible).
std::string format_real_rounded(double v, int width);

}  // namespace ssid::formats
