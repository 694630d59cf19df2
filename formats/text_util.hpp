#pragma once
/// \file text_util.hpp
/// Small string helpers shared by the readers and writers.
#include <algorithm>
#include <cctype>
#include <string>
#include <string_view>

namespace ssid::formats::detail {

inline std::string_view trim(std::string_view s) {
  std::size_t b = 0, e = s.size();
  while (b < e && (s[b] == ' ' || s[b] == '\t' || s[b] == '\r' || s[b] == '\f')) ++b;
  while (e > b && (s[e - 1] == ' ' || s[e - 1] == '\t' || s[e - 1] == '\r' || s[e - 1] == '\f')) --e;
  return s.substr(b, e - b);
}

inline std::string upper(std::string_view s) {
  std::string r(s);
  for (auto& c : r) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return r;
}

inline bool iequals_prefix(std::string_view s, std::string_view prefix) {
  if (s.size() < prefix.size()) return false;
  for (std::size_t i = 0; i < prefix.size(); ++i)
    if (std::toupper(static_cast<unsigned char>(s[i])) != prefix[i]) return false;
  return true;
}

/// Expands tabs to the next multiple of 8 columns, as NASTRAN reads them.
inline std::string expand_tabs(std::string_view s) {
  std::string r;
  r.reserve(s.size() + 16);
  for (char c : s) {
    if (c == '\t') {
      do r += ' '; while (r.size() % 8 != 0);
    } else {
      r += c;
    }
  }
  return r;
}

/// "0x1F": a byte as messages show it.
inline std::string byte_hex(char c) {
  static const char* digits = "0123456789ABCDEF";
  const auto u = static_cast<unsigned char>(c);
  return std::string("0x") + digits[u >> 4] + digits[u & 15];
}

/// `s` as a message shows text from a file: bytes outside printable ASCII as
/// \xNN and `"`, `\` escaped, so no raw byte of a damaged file reaches the terminal.
inline std::string printable(std::string_view s) {
  static const char* digits = "0123456789ABCDEF";
  std::string r;
  for (char ch : s) {
    const auto c = static_cast<unsigned char>(ch);
    if (c == '"' || c == '\\') {
      r += '\\';
      r += ch;
    } else if (c >= 0x20 && c < 0x7f) {
      r += ch;
    } else {
      r += "\\x";
      r += digits[c >> 4];
      r += digits[c & 15];
    }
  }
  return r;
}

/// `s` in double quotes as messages show it (printable), at most `max_chars`
/// characters of it, then "...".
inline std::string quoted(std::string_view s, std::size_t max_chars = 40) {
  if (s.size() <= max_chars) return "\"" + printable(s) + "\"";
  return "\"" + printable(s.substr(0, max_chars)) + "...\"";
}

}  // namespace ssid::formats::detail
