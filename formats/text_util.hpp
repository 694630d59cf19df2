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

}  // namespace ssid::formats::detail
