#pragma once
/// \file parse_error.hpp
/// The failure kinds every layer throws, and the problem list used where all
/// problems of a deck are reported together.
///
/// Three kinds, each with its own channel (the CLI maps them to exit codes,
/// README "Exit codes"):
/// - bad input (a file's content, a model's data, an option): InputError, or
///   ParseError when a file and line are known;
/// - a numerical outcome that makes a result untrustworthy (did not converge, a
///   factor that failed): NumericalError, where the caller cannot act on a status;
/// - anything else is a bug in ssid (std::logic_error and the rest).
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

/// Bad user input without one file position (an option, a model's data seen as a
/// whole, a test node that is not a grid). The message names the cause.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A run that finished without a result that can be trusted: an iteration that did
/// not converge, a factorisation that failed. The message says what and by how much.
class NumericalError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Bad input in a file. The message always starts with "file:line:" and names what was
/// expected, e.g. `truss.bdf:120: CROD 10 field 4 (G1): expected integer, got "1.5"`.
class ParseError : public InputError {
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
