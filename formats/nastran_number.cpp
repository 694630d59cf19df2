#include "formats/nastran_number.hpp"

#include <charconv>
#include <cmath>
#include <stdexcept>

namespace ssid::formats {

namespace {
inline bool is_digit(char c) { return c >= '0' && c <= '9'; }

/// Decimal digits and exponent of a double as written by to_chars in scientific form:
/// value = sign * 0.d1d2d3... * 10^(exp+1), i.e. d1.d2d3... * 10^exp.
struct Decimal {
  bool negative = false;
  std::string digits;
  int exp = 0;
};

Decimal decompose(double v, int precision /* -1 = shortest */) {
  char buf[64];
  auto res = precision < 0 ? std::to_chars(buf, buf + sizeof buf, v, std::chars_format::scientific)
                           : std::to_chars(buf, buf + sizeof buf, v, std::chars_format::scientific, precision);
  Decimal d;
  const char* p = buf;
  if (*p == '-') { d.negative = true; ++p; }
  for (; p < res.ptr && *p != 'e'; ++p)
    if (is_digit(*p)) d.digits += *p;
  if (p < res.ptr && *p == 'e') std::from_chars(p + 1 + (p[1] == '+'), res.ptr, d.exp);
  // Trailing zeros of the mantissa carry no information.
  while (d.digits.size() > 1 && d.digits.back() == '0') d.digits.pop_back();
  return d;
}

/// Shortest NASTRAN spelling of a decimal: fixed ("12.5", ".0015", "100.") or
/// exponent without E ("1.5-5", "1.+20").
std::string spell(const Decimal& d) {
  const std::string sign = d.negative ? "-" : "";
  const int n = static_cast<int>(d.digits.size());
  std::string fixed;
  if (d.digits == "0") {
    fixed = "0.";
  } else if (d.exp >= 0) {
    if (d.exp + 1 >= n) fixed = d.digits + std::string(d.exp + 1 - n, '0') + ".";
    else fixed = d.digits.substr(0, d.exp + 1) + "." + d.digits.substr(d.exp + 1);
  } else {
    fixed = "." + std::string(-d.exp - 1, '0') + d.digits;
  }
  fixed = sign + fixed;
  if (d.exp == 0 || d.digits == "0") return fixed;
  std::string sci = sign + d.digits.substr(0, 1) + "." + d.digits.substr(1) +
                    (d.exp > 0 ? "+" : "-") + std::to_string(std::abs(d.exp));
  return sci.size() < fixed.size() ? sci : fixed;
}

void require_finite(double v) {
  if (!std::isfinite(v)) throw std::invalid_argument("format_real: NASTRAN cannot represent a non-finite value");
}
}  // namespace

FieldKind classify_field(std::string_view s) {
  if (s.empty()) return FieldKind::Blank;
  if (parse_integer(s)) return FieldKind::Integer;
  if (parse_real(s)) return FieldKind::Real;
  return FieldKind::Text;
}

std::optional<std::int64_t> parse_integer(std::string_view s) {
  if (s.empty()) return std::nullopt;
  std::size_t i = (s[0] == '+' || s[0] == '-') ? 1 : 0;
  if (i == s.size()) return std::nullopt;
  for (std::size_t k = i; k < s.size(); ++k)
    if (!is_digit(s[k])) return std::nullopt;
  std::int64_t v = 0;
  auto res = std::from_chars(s.data() + i, s.data() + s.size(), v);
  if (res.ec != std::errc() || res.ptr != s.data() + s.size()) return std::nullopt;
  return s[0] == '-' ? -v : v;
}

std::optional<double> parse_real(std::string_view s) {
  const std::size_t n = s.size();
  std::size_t i = 0;
  char buf[96];
  std::size_t b = 0;
  if (n == 0 || n > 80) return std::nullopt;
  if (s[i] == '+' || s[i] == '-') {
    if (s[i] == '-') buf[b++] = '-';
    ++i;
  }
  std::size_t mantissa_digits = 0;
  while (i < n && is_digit(s[i])) { buf[b++] = s[i++]; ++mantissa_digits; }
  if (i < n && s[i] == '.') {
    buf[b++] = s[i++];
    while (i < n && is_digit(s[i])) { buf[b++] = s[i++]; ++mantissa_digits; }
  }
  if (mantissa_digits == 0) return std::nullopt;
  if (i < n) {
    // Exponent: E/D with optional sign, or a bare sign (NASTRAN's "1.-3").
    buf[b++] = 'e';
    char c = s[i];
    if (c == 'E' || c == 'e' || c == 'D' || c == 'd') {
      ++i;
      if (i < n && (s[i] == '+' || s[i] == '-')) {
        if (s[i] == '-') buf[b++] = '-';
        ++i;
      }
    } else if (c == '+' || c == '-') {
      if (c == '-') buf[b++] = '-';
      ++i;
    } else {
      return std::nullopt;
    }
    std::size_t exp_digits = 0;
    while (i < n && is_digit(s[i])) { buf[b++] = s[i++]; ++exp_digits; }
    if (exp_digits == 0 || i != n) return std::nullopt;
  }
  double v = 0;
  auto res = std::from_chars(buf, buf + b, v);
  if (res.ec == std::errc::result_out_of_range) return std::nullopt;
  if (res.ec != std::errc() || res.ptr != buf + b) return std::nullopt;
  return v;
}

std::optional<std::string> format_real_exact(double v, int width) {
  require_finite(v);
  std::string s = spell(decompose(v, -1));
  if (static_cast<int>(s.size()) <= width) return s;
  return std::nullopt;
}

std::string format_real_rounded(double v, int width) {
  require_finite(v);
  for (int p = 16; p >= 0; --p) {
    std::string s = spell(decompose(v, p));
    if (static_cast<int>(s.size()) <= width) return s;
  }
  throw std::invalid_argument("format_real: value does not fit in " + std::to_string(width) + " characters");
}

}  // namespace ssid::formats
