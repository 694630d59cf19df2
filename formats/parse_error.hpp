#pragma once
/// \file parse_error.hpp
/// The one exception type for bad user input in files, and the problem list
/// used where all problems of a deck are reported together.
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace ssid::formats {

/// Where a piece of input came from. `file` is a path as the user (or the
/// INCLUDE statement) gave it, `line` is 1-based; 0 means "whole file".
struct SourceLocation {
  std::string file;
  std::uint32_t line = 0;
  /// Include chain, innermost first: "main.bdf:12" for each INCLUDE that led here.
  std::vector<std::string> included_from;

  /// "file:line" (or "file" when line is 0).
  std::string str() const;
};

/// Bad input. The message always starts with "file:line:" and names what was
/// expected, e.g. `truss.bdf:120: CROD 10 field 4 (G1): expected integer, got "1.5"`.
class ParseError : public std::runtime_error {
public:
  ParseError(SourceLocation where, const std::string& message);
  const SourceLocation& where() const { return m_where; }
  /// The message without the location prefix.
  const std::string& detail() const { return m_detail; }

private:
  SourceLocation m_where;
  std::string m_detail;
};

/// A problem found while checking a deck as a whole; collected, not thrown.
struct Problem {
  enum class Severity { Error, Warning };
  Severity severity = Severity::Error;
  SourceLocation where;
  std::string message;  ///< without the location prefix
  /// "file:line: message" with the include chain appended.
  std::string str() const;
};

}  // namespace ssid::formats
