#include "translators/assembly/parameter_units.hpp"

#include <algorithm>
#include <cctype>
#include <map>
#include <set>
#include <utility>

#include "formats/text_util.hpp"

namespace ssid::translators {

namespace {

/// The quantity of each designable field, by card type and field name.
const std::string& field_quantity(const std::string& type, const std::string& field) {
  static const std::map<std::pair<std::string, std::string>, std::string> table = [] {
    std::map<std::pair<std::string, std::string>, std::string> t;
    auto add = [&](const std::string& type, std::initializer_list<const char*> fields, const std::string& q) {
      for (const char* f : fields) t[{type, f}] = q;
    };
    for (const char* ty : {"PROD", "CONROD"}) {
      add(ty, {"A"}, "area");
      add(ty, {"J"}, "torsion constant");
      add(ty, {"C"}, "length");
      add(ty, {"NSM"}, "mass per length");
    }
    add("PTUBE", {"OD", "T", "OD2"}, "length");
    add("PTUBE", {"NSM"}, "mass per length");
    for (const char* ty : {"PBAR", "PBEAM"}) {
      add(ty, {"A"}, "area");
      add(ty, {"I1", "I2", "I12"}, "second moment of area");
      add(ty, {"J"}, "torsion constant");
      add(ty, {"NSM"}, "mass per length");
    }
    for (const char* ty : {"PBARL", "PBEAML"}) {
      add(ty, {"DIM1", "DIM2", "DIM3", "DIM4", "DIM5", "DIM6"}, "length");
      add(ty, {"NSM"}, "mass per length");
    }
    for (const char* ty : {"PELAS", "CELAS2"}) {
      add(ty, {"K"}, "spring stiffness");
      add(ty, {"GE"}, "damping coefficient");
    }
    for (const char* ty : {"PMASS", "CMASS2"}) add(ty, {"M"}, "mass");
    add("PBUSH", {"K1", "K2", "K3"}, "translational stiffness");
    add("PBUSH", {"K4", "K5", "K6"}, "rotational stiffness");
    add("PSHELL", {"T"}, "length");
    add("CONM2", {"M"}, "mass");
    add("CONM2", {"X1", "X2", "X3"}, "length");
    add("CONM2", {"I11", "I21", "I22", "I31", "I32", "I33"}, "mass moment of inertia");
    add("MAT1", {"E", "G"}, "modulus");
    add("MAT1", {"NU"}, "Poisson's ratio");
    add("MAT1", {"RHO"}, "density");
    add("MAT1", {"GE"}, "damping coefficient");
    return t;
  }();
  static const std::string none;
  auto it = table.find({type, field});
  return it == table.end() ? none : it->second;
}

const std::map<std::string, std::string>& si_units() {
  static const std::map<std::string, std::string> unit = {
      {"area", "m^2"},
      {"torsion constant", "m^4"},
      {"second moment of area", "m^4"},
      {"length", "m"},
      {"mass per length", "kg/m"},
      {"spring stiffness", "N/m or N m/rad"},  // a spring on translations and rotations, or on scalar points
      {"translational stiffness", "N/m"},
      {"rotational stiffness", "N m/rad"},
      {"damping coefficient", "1"},
      {"mass", "kg"},
      {"mass moment of inertia", "kg m^2"},
      {"modulus", "Pa"},
      {"Poisson's ratio", "1"},
      {"density", "kg/m^3"},
  };
  return unit;
}

}  // namespace

std::string quantity(const std::string& type, const std::string& field) { return field_quantity(type, field); }

std::string si_unit(const std::string& type, const std::string& field) {
  const auto& unit = si_units();
  auto it = unit.find(field_quantity(type, field));
  return it == unit.end() ? std::string() : it->second;
}

DeckUnits deck_units(const formats::Deck& deck) {
  DeckUnits u;
  for (std::uint32_t f = 0; f < deck.files.size(); ++f) {
    const std::string& text = deck.files[f].text;
    std::uint32_t line = 1;
    for (std::size_t at = 0; at < text.size(); ++line) {
      std::size_t end = text.find('\n', at);
      if (end == std::string::npos) end = text.size();
      const std::string_view l = formats::detail::trim(std::string_view(text).substr(at, end - at));
      at = end + 1;
      if (l.empty() || l[0] != '$') continue;
      const std::string_view body = formats::detail::trim(l.substr(1));
      if (!formats::detail::iequals_prefix(body, "UNITS:")) continue;
      u.text = std::string(formats::detail::trim(body.substr(6)));
      u.source = deck.location(f, line).str();
      const std::string up = formats::detail::upper(u.text);
      // "SI" as a word: "SI", "SI (m, kg, N, Pa, s)".
      u.si = up.rfind("SI", 0) == 0 && (up.size() == 2 || !std::isalnum(static_cast<unsigned char>(up[2])));
      return u;
    }
  }
  return u;
}

namespace {

/// A spring's quantity from the components it connects: "translational
/// stiffness" (1-3), "rotational stiffness" (4-6), or "spring stiffness" (mixed,
/// scalar points, none found).
std::string spring_quantity(const std::string& type, std::int64_t id, const formats::BulkModel& bulk) {
  std::set<std::int64_t> comps;
  auto add = [&](std::int64_t g1, std::int64_t c1, std::int64_t g2, std::int64_t c2) {
    if (g1) comps.insert(c1);
    if (g2) comps.insert(c2);
  };
  if (type == "PELAS")
    for (const auto& e : bulk.celas1s)
      if (e.pid == id) add(e.g1, e.c1, e.g2, e.c2);
  if (type == "CELAS2")
    for (const auto& e : bulk.celas2s)
      if (e.eid == id) add(e.g1, e.c1, e.g2, e.c2);
  if (comps.empty()) return "spring stiffness";
  if (std::all_of(comps.begin(), comps.end(), [](std::int64_t c) { return c >= 1 && c <= 3; }))
    return "translational stiffness";
  if (std::all_of(comps.begin(), comps.end(), [](std::int64_t c) { return c >= 4 && c <= 6; }))
    return "rotational stiffness";
  return "spring stiffness";
}

}  // namespace

ParameterUnit parameter_unit(const DesignParameter& p, const DeckUnits& units, const formats::BulkModel& bulk) {
  ParameterUnit out;
  if (p.fields.empty()) return out;
  // What it designs: each type and field with its card count, in first-seen order.
  std::vector<std::pair<std::string, std::set<std::int64_t>>> groups;
  bool any_unit_coefficient = false;
  for (const auto& f : p.fields) {
    const std::string key = f.type + " " + f.field;
    auto it = std::find_if(groups.begin(), groups.end(), [&](const auto& g) { return g.first == key; });
    if (it == groups.end()) groups.push_back({key, {f.id}});
    else it->second.insert(f.id);
    any_unit_coefficient = any_unit_coefficient || f.coefficient == 1.0;
  }
  for (const auto& [key, ids] : groups)
    out.designs += (out.designs.empty() ? "" : ", ") + key + " (" + std::to_string(ids.size()) + " card" +
                   (ids.size() > 1 ? "s" : "") + ")";
  if (p.initial == 1.0 && !any_unit_coefficient) {
    out.unit = "scale factor";
    return out;
  }
  // The fields' unit when they agree; each field's when they do not.
  std::vector<std::string> units_seen;
  for (const auto& f : p.fields) {
    std::string q = quantity(f.type, f.field);
    if (q == "spring stiffness") q = spring_quantity(f.type, f.id, bulk);
    std::string u;
    if (units.si)
      if (auto it = si_units().find(q); it != si_units().end()) u = it->second;
    if (u.empty()) u = "deck units" + (q.empty() ? std::string() : " (" + q + ")");
    if (std::find(units_seen.begin(), units_seen.end(), u) == units_seen.end()) units_seen.push_back(u);
  }
  for (const auto& u : units_seen) out.unit += (out.unit.empty() ? "" : " | ") + u;
  return out;
}

}  // namespace ssid::translators
