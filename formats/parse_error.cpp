#include "formats/parse_error.hpp"

namespace ssid::formats {

std::string SourceLocation::str() const {
  std::string s = file;
  if (line > 0) s += ":" + std::to_string(line);
  return s;
}

namespace {
std::string with_chain(const SourceLocation& w, const std::string& msg) {
  std::string s = w.str() + ": " + msg;
  for (const auto& inc : w.included_from) s += " (included from " + inc + ")";
  return s;
}
}  // namespace

ParseError::ParseError(SourceLocation where, const std::string& message)
    : InputError(with_chain(where, message)), m_where(std::move(where)), m_detail(message) {}

std::string Problem::str() const {
  return with_chain(where, (severity == Severity::Warning ? "warning: " : "") + message);
}

}  // namespace ssid::formats
