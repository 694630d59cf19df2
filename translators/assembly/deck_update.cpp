#include "translators/assembly/deck_update.hpp"

#include <cctype>
#include <cmath>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

#include "formats/bulk_model.hpp"
#include "formats/parse_error.hpp"
#include "translators/assembly/fe_model.hpp"
#include "formats/text_util.hpp"

namespace ssid::translators {

namespace {

std::string number(double v) {
  std::ostringstream o;
  o.precision(12);
  o << v;
  return o.str();
}

bool same(const formats::FieldValue& a, const formats::FieldValue& b) { return a == b; }

}  // namespace

DeckUpdateReport update_deck(formats::Deck& deck, const std::map<std::string, double>& values) {
  const std::unique_ptr<FeModel> model = assemble_deck(deck, deck.files.front().path);
  const FeModel& fe = *model;
  const formats::BulkModel& bulk = fe.bulk();
  const auto& params = fe.parameters();

  DeckUpdateReport report;
  const Eigen::VectorXd x0 = fe.initial_parameters();
  Eigen::VectorXd x = x0;
  for (const auto& [name, value] : values) {
    std::size_t j = params.size();
    for (std::size_t k = 0; k < params.size(); ++k)
      if (formats::detail::upper(params[k].label) == formats::detail::upper(name)) j = k;
    if (j == params.size()) {
      std::string labels;
      for (const auto& p : params) labels += (labels.empty() ? "" : ", ") + p.label;
      throw formats::InputError("parameter '" + name + "' is not a DESVAR label of " + deck.files.front().path +
                                  " (its DESVARs: " + (labels.empty() ? "none" : labels) + ")");
    }
    const auto& p = params[j];
    if (!std::isfinite(value))
      throw formats::InputError("parameter '" + name + "': the value is not a finite number");
    if (value < p.lower || value > p.upper)
      throw formats::InputError("parameter '" + name + "' = " + number(value) + " lies outside its DESVAR " +
                                  std::to_string(p.id) + " bounds [" + number(p.lower) + ", " + number(p.upper) + "]");
    x(static_cast<Eigen::Index>(j)) = value;
    if (value != p.initial)
      report.parameters.push_back(p.label + " (DESVAR " + std::to_string(p.id) + "): " + number(p.initial) + " -> " +
                                  number(value));
  }

  // Values at the old and the new parameters: the fields that differ are
  // exactly those designed by a changed parameter. Fields of a touched card
  // that did not move keep the deck's own values (and text).
  formats::BulkModel nominal = fe.values_at(x0);
  formats::BulkModel updated = fe.values_at(x);
  for (auto& d : updated.desvars)
    for (std::size_t j = 0; j < params.size(); ++j)
      if (params[j].id == d.id) d.xinit = x(static_cast<Eigen::Index>(j));
  const auto before = formats::write_bulk(bulk);
  const auto at_x0 = formats::write_bulk(nominal);
  const auto at_x = formats::write_bulk(updated);
  for (const auto& [card, new_values] : at_x) {
    const auto old_it = at_x0.find(card);
    const auto orig_it = before.find(card);
    if (old_it == at_x0.end() || orig_it == before.end()) continue;
    const auto& old_values = old_it->second;
    std::vector<formats::FieldValue> merged = orig_it->second;
    bool changed = false;
    const std::size_t n = std::max(new_values.size(), merged.size());
    merged.resize(n);
    for (std::size_t f = 1; f < n; ++f) {
      const formats::FieldValue nv = f < new_values.size() ? new_values[f] : formats::FieldValue{};
      const formats::FieldValue ov = f < old_values.size() ? old_values[f] : formats::FieldValue{};
      if (same(nv, ov)) continue;
      if (!same(merged[f], nv)) {
        std::string before_text = std::holds_alternative<double>(merged[f]) ? number(std::get<double>(merged[f])) : "?";
        std::string after_text = std::holds_alternative<double>(nv) ? number(std::get<double>(nv)) : "?";
        const auto& c = deck.cards[card];
        report.fields.push_back(c.name + " " + std::string(c.field(1)) + " field " + std::to_string(f + 1) + ": " +
                                before_text + " -> " + after_text + " (" + deck.location(c, f).str() + ")");
        merged[f] = nv;
        changed = true;
      }
    }
    while (merged.size() > 1 && std::holds_alternative<std::monostate>(merged.back())) merged.pop_back();
    if (changed) {
      deck.set_values(card, std::move(merged));
      ++report.cards_changed;
    }
  }
  return report;
}

std::map<std::string, double> parameter_values_from_json(const std::string& text, const std::string& source) {
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    throw formats::InputError(source + ": not valid JSON: " + e.what());
  }
  if (!j.is_object() || !j.contains("parameters") || !j["parameters"].is_array())
    throw formats::InputError(source + ": expected an object with a \"parameters\" array of {\"name\", \"estimate\"}");
  std::map<std::string, double> out;
  std::size_t k = 0;
  for (const auto& p : j["parameters"]) {
    const std::string where = source + ": parameters[" + std::to_string(k++) + "]";
    if (!p.is_object() || !p.contains("name") || !p["name"].is_string())
      throw formats::InputError(where + ": expected an object with a string \"name\"");
    if (!p.contains("estimate") || !p["estimate"].is_number())
      throw formats::InputError(where + " (" + p["name"].get<std::string>() + "): expected a number \"estimate\"");
    const std::string name = p["name"].get<std::string>();
    for (const auto& [other, v] : out)
      if (formats::detail::upper(other) == formats::detail::upper(name))
        throw formats::InputError(where + ": parameter '" + name + "' is given twice");
    out[name] = p["estimate"].get<double>();
  }
  if (out.empty()) throw formats::InputError(source + ": \"parameters\" is empty: nothing to update");
  return out;
}

}  // namespace ssid::translators
