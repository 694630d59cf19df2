#pragma once
/// \file study_reader.hpp
/// Typed readers of a study file's JSON values: the only place study errors are
/// raised, so every error names the file and the key path
/// ("study.json: priors.STRUTA.std: expected a positive number, got \"x\"").
/// Shared by the study (deck_study.cpp) and its "diagnosis" section
/// (estimator/diagnosis/diagnosis.cpp).
#include <cmath>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "formats/parse_error.hpp"

namespace ssid::estimator {

/// Reads values of the study file `source`; every failure throws
/// formats::InputError naming the source and the key path.
class StudyReader {
 public:
  explicit StudyReader(std::string source) : m_source(std::move(source)) {}

  [[noreturn]] void fail(const std::string& path, const std::string& what) const {
    throw formats::InputError(m_source + ": " + path + ": " + what);
  }
  static std::string shown(const nlohmann::json& v) {
    std::string s = v.dump();
    return s.size() > 60 ? s.substr(0, 57) + "..." : s;
  }
  void keys(const nlohmann::json& obj, const std::string& path, const std::set<std::string>& allowed) const {
    if (!obj.is_object()) fail(path.empty() ? "(top level)" : path, "expected an object, got " + shown(obj));
    for (const auto& [k, v] : obj.items())
      if (!allowed.count(k)) {
        std::string list;
        for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
        fail(path.empty() ? k : path + "." + k, "unknown key (allowed here: " + list + ")");
      }
  }
  double number(const nlohmann::json& v, const std::string& path, bool positive = false, bool non_negative = false) const {
    if (!v.is_number()) fail(path, "expected a number, got " + shown(v));
    const double x = v.get<double>();
    if (!std::isfinite(x)) fail(path, "expected a finite number");
    if (positive && !(x > 0)) fail(path, "expected a positive number, got " + shown(v));
    if (non_negative && x < 0) fail(path, "expected a number >= 0, got " + shown(v));
    return x;
  }
  int integer(const nlohmann::json& v, const std::string& path, int min = 1) const {
    if (!v.is_number_integer()) fail(path, "expected an integer, got " + shown(v));
    const auto x = v.get<long long>();
    if (x < min || x > 1000000000) fail(path, "expected an integer >= " + std::to_string(min) + ", got " + shown(v));
    return static_cast<int>(x);
  }
  bool boolean(const nlohmann::json& v, const std::string& path) const {
    if (!v.is_boolean()) fail(path, "expected true or false, got " + shown(v));
    return v.get<bool>();
  }
  std::string text(const nlohmann::json& v, const std::string& path) const {
    if (!v.is_string()) fail(path, "expected a string, got " + shown(v));
    return v.get<std::string>();
  }
  std::string choice(const nlohmann::json& v, const std::string& path, const std::vector<std::string>& options) const {
    const std::string s = text(v, path);
    for (const auto& o : options)
      if (s == o) return s;
    std::string list;
    for (const auto& o : options) list += (list.empty() ? "" : ", ") + o;
    fail(path, "expected one of " + list + ", got " + shown(v));
  }
  std::vector<int> integers(const nlohmann::json& v, const std::string& path) const {
    if (!v.is_array()) fail(path, "expected an array of mode numbers, got " + shown(v));
    std::vector<int> out;
    for (std::size_t i = 0; i < v.size(); ++i) out.push_back(integer(v[i], path + "[" + std::to_string(i) + "]", 0));
    return out;
  }

 private:
  std::string m_source;
};

}  // namespace ssid::estimator
