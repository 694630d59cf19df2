#include "formats/cards/param.hpp"

#include "formats/nastran_number.hpp"

namespace ssid::formats {

std::optional<std::int64_t> Param::integer() const {
  if (values.empty()) return std::nullopt;
  if (auto* i = std::get_if<std::int64_t>(&values[0])) return *i;
  return std::nullopt;
}

std::optional<double> Param::real() const {
  if (values.empty()) return std::nullopt;
  if (auto* d = std::get_if<double>(&values[0])) return *d;
  if (auto* i = std::get_if<std::int64_t>(&values[0])) return static_cast<double>(*i);
  return std::nullopt;
}

std::optional<std::string> Param::text() const {
  if (values.empty()) return std::nullopt;
  if (auto* s = std::get_if<std::string>(&values[0])) return *s;
  return std::nullopt;
}

Param parse_param(const FieldReader& r) {
  Param p;
  p.name = r.text(1, "N");
  if (r.is_integer(1) || r.is_real(1)) r.fail(1, "N", "a parameter name");
  for (std::size_t i = 2; i < r.size(); ++i) {
    std::string_view f = r.card().field(i);
    if (f.empty()) {
      p.values.emplace_back();
    } else if (auto n = parse_integer(f)) {
      p.values.emplace_back(*n);
    } else if (auto x = parse_real(f)) {
      p.values.emplace_back(*x);
    } else {
      p.values.emplace_back(std::string(f));
    }
  }
  if (p.values.empty()) r.fail(2, "V1", "a value");
  r.at_most(4);
  return p;
}

std::vector<FieldValue> write_param(const Param& p) {
  std::vector<FieldValue> v = {std::string("PARAM"), p.name};
  v.insert(v.end(), p.values.begin(), p.values.end());
  return v;
}

}  // namespace ssid::formats
