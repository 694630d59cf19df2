/// \file cmd_uff.cpp
/// `ssid uff list FILE [--json OUT]`: what a universal file holds.
#include <cstdio>
#include <iostream>
#include <map>
#include <optional>

#include "cli/cli_util.hpp"
#include "formats/uff.hpp"
#include "translators/measurement/mode_set.hpp"

namespace ssid::cli {

namespace {

namespace uff = formats::uff;

std::string direction_name(int d) {
  static const char* axes[] = {"X", "Y", "Z", "RX", "RY", "RZ"};
  if (d == 0 || d < -6 || d > 6) return "scalar";
  return std::string(d < 0 ? "-" : "+") + axes[std::abs(d) - 1];
}

const char* analysis_name(int t) {
  switch (t) {
    case 0: return "unknown";
    case 1: return "static";
    case 2: return "normal mode";
    case 3: return "complex mode";
    case 4: return "transient";
    case 5: return "frequency response";
    case 6: return "buckling";
    case 7: return "complex mode (2nd order)";
    default: return "other";
  }
}

/// Text of a universal file as JSON can carry it: valid UTF-8 sequences kept,
/// any other byte of 0x80 and above taken as Latin-1 (Test.Lab and VibControl
/// write "g²/Hz" in Latin-1).
std::string utf8_text(const std::string& s) {
  std::string o;
  for (std::size_t i = 0; i < s.size();) {
    const auto c = static_cast<unsigned char>(s[i]);
    std::size_t len = c < 0x80 ? 1 : (c >> 5) == 0x6 ? 2 : (c >> 4) == 0xE ? 3 : (c >> 3) == 0x1E ? 4 : 0;
    bool valid = len > 0 && i + len <= s.size();
    for (std::size_t k = 1; valid && k < len; ++k) valid = (static_cast<unsigned char>(s[i + k]) & 0xC0) == 0x80;
    if (valid) {
      o.append(s, i, len);
      i += len;
    } else {
      o += static_cast<char>(0xC0 | (c >> 6));
      o += static_cast<char>(0x80 | (c & 0x3F));
      ++i;
    }
  }
  return o;
}

/// Function types of dataset 58 record 6 field 1.
const char* function_type_name(int t) {
  static const char* names[] = {"general",
                                "time response",
                                "auto spectrum",
                                "cross spectrum",
                                "frequency response function",
                                "transmissibility",
                                "coherence",
                                "auto correlation",
                                "cross correlation",
                                "power spectral density",
                                "energy spectral density",
                                "probability density function",
                                "spectrum",
                                "cumulative frequency distribution",
                                "peaks valley",
                                "stress/cycles",
                                "strain/cycles",
                                "orbit",
                                "mode indicator function",
                                "force pattern",
                                "partial power",
                                "partial coherence",
                                "eigenvalue",
                                "eigenvector",
                                "shock response spectrum",
                                "finite impulse response filter",
                                "multiple coherence",
                                "order function"};
  return t >= 0 && t < static_cast<int>(sizeof names / sizeof names[0]) ? names[t] : "other";
}

const char* ordinate_type_name(int t) {
  switch (t) {
    case 2: return "real single";
    case 4: return "real double";
    case 5: return "complex single";
    case 6: return "complex double";
    default: return "other";
  }
}

nlohmann::json axis_json(const uff::Axis58& a) {
  return {{"specific_data_type", a.specific_data_type},
          {"label", utf8_text(a.label)},
          {"units", utf8_text(a.units)},
          {"exponents", {a.length_exponent, a.force_exponent, a.temperature_exponent}}};
}

/// One 58/58b: what it measures, where, and how its abscissa and ordinate are laid out.
nlohmann::json function_json(const uff::Function58& fn, bool values) {
  nlohmann::json e{{"function_type", fn.function_type},
                   {"function", function_type_name(fn.function_type)},
                   {"binary", fn.binary},
                   {"ordinate_type", fn.ordinate_type},
                   {"ordinate", ordinate_type_name(fn.ordinate_type)},
                   {"complex", fn.is_complex()},
                   {"spacing", fn.even ? "even" : "uneven"},
                   {"even", fn.even},
                   {"points", fn.y.size()},
                   {"abscissa_min", fn.x.empty() ? 0.0 : fn.x.front()},
                   {"abscissa_max", fn.x.empty() ? 0.0 : fn.x.back()},
                   {"response_node", fn.response_node},
                   {"response_direction", fn.response_direction},
                   {"response", std::to_string(fn.response_node) + direction_name(fn.response_direction)},
                   {"reference_node", fn.reference_node},
                   {"reference_direction", fn.reference_direction},
                   {"reference", fn.reference_node == 0 && fn.reference_direction == 0
                                     ? std::string("none")
                                     : std::to_string(fn.reference_node) + direction_name(fn.reference_direction)},
                   {"id_line", utf8_text(fn.id_lines[0])},
                   {"abscissa_axis", axis_json(fn.axes[0])},
                   {"ordinate_axis", axis_json(fn.axes[1])},
                   {"denominator_axis", axis_json(fn.axes[2])}};
  if (fn.even) e["abscissa_increment"] = fn.abscissa_increment;
  if (fn.binary) e["byte_order"] = fn.byte_order == 2 ? "big endian" : "little endian";
  if (values) {
    e["x"] = fn.x;
    nlohmann::json y = nlohmann::json::array();
    for (const auto& v : fn.y) {
      if (fn.is_complex()) y.push_back({v.real(), v.imag()});
      else y.push_back(v.real());
    }
    e["y"] = std::move(y);
  }
  return e;
}

/// Per-dataset details for the listing ("datasets" of the JSON).
struct DatasetJson {
  nlohmann::json& e;
  bool values;
  void operator()(const uff::Header151&) const { e["type"] = "header"; }
  void operator()(const uff::Units164& u) const {
    e["type"] = "units";
    e["units_code"] = u.code;
  }
  void operator()(const uff::NodeSet& s) const {
    e["type"] = "nodes";
    e["nodes"] = s.nodes.size();
  }
  void operator()(const uff::NodalData55& m) const {
    e["type"] = "data at nodes";
    e["analysis"] = analysis_name(m.analysis_type);
    e["mode"] = m.mode_number();
    e["frequency_hz"] = m.frequency_hz();
    e["nodes"] = m.nodes.size();
    e["values_per_node"] = m.values_per_node;
    e["complex"] = m.is_complex();
    if (m.analysis2414) e["analysis_dataset_name"] = utf8_text(m.analysis2414->name);
  }
  void operator()(const uff::Function58& fn) const {
    e["type"] = "function";
    e.update(function_json(fn, values));
  }
  void operator()(const uff::Qualifiers1858& q) const {
    e["type"] = "function qualifiers";
    e["window"] = q.window();
    e["samples"] = q.samples();
    e["exponential_window_damping"] = q.exponential_damping();
  }
  void operator()(const uff::ElementSet2412& s) const {
    e["type"] = "elements";
    e["elements"] = s.elements.size();
  }
  void operator()(const uff::TraceLine82& t) const {
    e["type"] = "trace line";
    e["trace_line"] = t.id;
    e["label"] = utf8_text(t.label);
    e["nodes"] = t.nodes.size();
  }
  void operator()(const uff::CoordinateSystems18& s) const {
    e["type"] = "coordinate systems";
    e["systems"] = s.systems.size();
  }
  void operator()(const uff::CoordinateSystems2420& s) const {
    e["type"] = "coordinate systems";
    e["systems"] = s.systems.size();
  }
  void operator()(const uff::UnknownDataset&) const { e["type"] = "kept verbatim"; }
};

nlohmann::json to_json(const uff::UffFile& f, bool values) {
  nlohmann::json j;
  j["file"] = utf8_text(f.path);
  j["datasets"] = nlohmann::json::array();
  for (const auto& d : f.datasets) {
    nlohmann::json e;
    e["number"] = uff::dataset_number(d);
    std::visit([&](const auto& x) { e["line"] = x.where.line; }, d);
    e["kept_verbatim"] = std::holds_alternative<uff::UnknownDataset>(d);
    std::visit(DatasetJson{e, values}, d);
    j["datasets"].push_back(e);
  }
  for (const auto& d : f.datasets) {
    if (auto h = std::get_if<uff::Header151>(&d)) {
      j["header"] = {{"model", utf8_text(h->model_name())},
                     {"description", utf8_text(h->description())},
                     {"program", utf8_text(h->program())}};
    } else if (auto u = std::get_if<uff::Units164>(&d)) {
      j["units"] = {{"code", u->code},       {"description", utf8_text(u->description)}, {"length", u->length},
                    {"force", u->force},     {"temperature", u->temperature}, {"temperature_offset", u->temperature_offset}};
    }
  }
  j["nodes"] = nlohmann::json::array();
  // Positions in the global system too, where a node is defined in a local one
  // (datasets 18, 2420); a system the file lacks is a problem, listed below.
  std::vector<uff::Node> global;
  std::string cs_problem;
  try {
    global = f.nodes_in_global();
  } catch (const formats::InputError& e) {
    cs_problem = e.what();
  }
  const auto nodes = f.nodes();
  for (std::size_t k = 0; k < nodes.size(); ++k) {
    const auto& n = nodes[k];
    nlohmann::json e{{"id", n.id}, {"xyz", n.xyz}, {"definition_cs", n.definition_cs},
                     {"displacement_cs", n.displacement_cs}};
    if (n.definition_cs != 0 && k < global.size()) e["xyz_global"] = global[k].xyz;
    j["nodes"].push_back(e);
  }
  j["modes"] = nlohmann::json::array();
  for (const auto* m : f.nodal_data()) {
    nlohmann::json e{{"line", m->where.line},
                     {"analysis", analysis_name(m->analysis_type)},
                     {"analysis_type", m->analysis_type},
                     {"mode", m->mode_number()},
                     {"frequency_hz", m->frequency_hz()},
                     {"nodes", m->nodes.size()},
                     {"values_per_node", m->values_per_node},
                     {"complex", m->is_complex()},
                     {"id_line", utf8_text(m->id_lines[0])}};
    if (m->is_normal_mode()) {
      e["modal_mass"] = m->modal_mass();
      e["viscous_damping"] = m->viscous_damping();
      e["hysteretic_damping"] = m->hysteretic_damping();
    }
    if (m->is_complex_mode()) {
      const auto lam = m->eigenvalue();
      e["eigenvalue"] = {lam.real(), lam.imag()};
      e["damping_ratio"] = std::abs(lam) > 0 ? -lam.real() / std::abs(lam) : 0.0;
    }
    j["modes"].push_back(e);
  }
  j["functions"] = nlohmann::json::array();
  // Measured directions given in a node's local displacement system, as global unit vectors.
  std::map<std::int64_t, uff::Node> by_id;
  for (const auto& n : nodes) by_id.emplace(n.id, n);
  const auto global_axis = [&](std::int64_t node, int direction) -> std::optional<std::array<double, 3>> {
    auto it = by_id.find(node);
    if (it == by_id.end() || it->second.displacement_cs == 0 || direction == 0 || !cs_problem.empty())
      return std::nullopt;
    return f.direction_in_global(it->second, direction);
  };
  for (const auto* fn : f.functions()) {
    nlohmann::json e{{"line", fn->where.line}};
    e.update(function_json(*fn, false));
    if (auto a = global_axis(fn->response_node, fn->response_direction)) e["response_axis_global"] = *a;
    if (auto a = global_axis(fn->reference_node, fn->reference_direction)) e["reference_axis_global"] = *a;
    j["functions"].push_back(e);
  }
  nlohmann::json sk = nlohmann::json::object();
  for (const auto& [n, c] : f.skipped()) sk[std::to_string(n)] = c;
  j["skipped"] = sk;
  translators::ModeSetReport rep;
  auto set = translators::modes_from_uff(f, &rep);
  j["normal_modes"] = set.frequency_hz.size();
  j["complex_modes"] = rep.complex_modes;
  j["measured_dofs"] = set.dofs.size();
  j["problems"] = rep.problems;
  if (!cs_problem.empty()) j["problems"].push_back(cs_problem);
  return j;
}

int uff_list(const Args& args) {
  po::options_description desc("ssid uff list options");
  desc.add_options()("file", po::value<std::string>()->required(), "universal file (.unv/.uff)")(
      "json", po::value<std::string>(), "write the listing as JSON to this file ('-' for stdout)")(
      "values", "with --json: the abscissa and ordinate values of every 58/58b ([re, im] pairs when complex)");
  po::positional_options_description pos;
  pos.add("file", 1);
  po::variables_map vm;
  int rc = 0;
  if (!parse_options(args, "ssid uff list FILE [--json OUT] [--values]", desc, pos, vm, rc)) return rc;
  if (vm.count("values") && !vm.count("json"))
    throw formats::InputError("ssid uff list: --values adds the values to the JSON listing; give --json OUT (or --json -)");
  const uff::UffFile f = uff::read_uff(vm["file"].as<std::string>());
  const nlohmann::json j = to_json(f, vm.count("values") > 0);
  const std::string json_path = vm.count("json") ? vm["json"].as<std::string>() : "";
  if (json_path == "-") {
    write_json("-", j);
    return 0;
  }
  std::cout << "universal file " << f.path << ": " << f.datasets.size() << " dataset(s)\n";
  if (j.contains("header"))
    std::cout << "  header (151): model \"" << j["header"]["model"].get<std::string>() << "\", written by \""
              << j["header"]["program"].get<std::string>() << "\"\n";
  if (j.contains("units"))
    std::cout << "  units (164): code " << j["units"]["code"] << " \"" << j["units"]["description"].get<std::string>()
              << "\"\n";
  std::size_t n15 = 0, n2411 = 0;
  for (const auto& d : f.datasets)
    if (auto s = std::get_if<uff::NodeSet>(&d)) (s->dataset == 15 ? n15 : n2411) += s->nodes.size();
  std::cout << "nodes: " << n15 + n2411 << " (dataset 15: " << n15 << ", dataset 2411: " << n2411 << ")\n";
  const auto modes = f.nodal_data();
  std::cout << "data at nodes (55, 2414): " << modes.size() << "\n";
  if (!modes.empty()) {
    std::printf("  %5s %6s %14s %12s %10s %6s %4s  %s\n", "line", "mode", "frequency Hz", "modal mass", "damping",
                "nodes", "NDV", "analysis");
    std::fflush(stdout);
    for (const auto* m : modes) {
      double damping = m->viscous_damping();
      if (m->is_complex_mode()) {
        const auto lam = m->eigenvalue();
        damping = std::abs(lam) > 0 ? -lam.real() / std::abs(lam) : 0.0;
      }
      std::printf("  %5u %6lld %14.6g %12.6g %10.4g %6zu %4d  %s%s\n", m->where.line,
                  static_cast<long long>(m->mode_number()), m->frequency_hz(), m->modal_mass(), damping,
                  m->nodes.size(), m->values_per_node, analysis_name(m->analysis_type),
                  m->is_complex() ? " (complex values)" : "");
    }
    std::fflush(stdout);
  }
  const auto fns = f.functions();
  std::cout << "functions at nodal DOFs (58, 58b): " << fns.size() << "\n";
  for (const auto* fn : fns)
    std::cout << "  line " << fn->where.line << (fn->binary ? " (58b)" : "") << ": type " << fn->function_type << " ("
              << function_type_name(fn->function_type) << "), response " << fn->response_node
              << direction_name(fn->response_direction) << ", reference "
              << (fn->reference_node == 0 && fn->reference_direction == 0
                      ? std::string("none")
                      : std::to_string(fn->reference_node) + direction_name(fn->reference_direction))
              << ", " << fn->y.size() << " points, " << (fn->even ? "even" : "uneven") << " abscissa, "
              << ordinate_type_name(fn->ordinate_type) << "\n";
  std::size_t n1858 = 0, n2412 = 0, n82 = 0, ncs = 0;
  for (const auto& d : f.datasets) {
    if (std::holds_alternative<uff::Qualifiers1858>(d)) ++n1858;
    if (auto e = std::get_if<uff::ElementSet2412>(&d)) n2412 += e->elements.size();
    if (std::holds_alternative<uff::TraceLine82>(d)) ++n82;
    if (auto c = std::get_if<uff::CoordinateSystems18>(&d)) ncs += c->systems.size();
    if (auto c = std::get_if<uff::CoordinateSystems2420>(&d)) ncs += c->systems.size();
  }
  std::cout << "function qualifiers (1858): " << n1858 << "; elements (2412): " << n2412
            << "; trace lines (82): " << n82 << "; coordinate systems (18, 2420): " << ncs << "\n";
  std::cout << "skipped (kept verbatim):";
  if (f.skipped().empty()) std::cout << " none";
  for (const auto& [n, c] : f.skipped()) std::cout << " " << n << " x" << c;
  std::cout << "\n";
  std::cout << "real normal modes usable for correlation: " << j["normal_modes"] << " at " << j["measured_dofs"]
            << " DOF(s)";
  if (j["complex_modes"].get<std::size_t>() > 0) std::cout << "; complex modes reported, not used: " << j["complex_modes"];
  std::cout << std::endl;
  for (const auto& p : j["problems"]) std::cerr << f.path << ": " << p.get<std::string>() << "\n";
  if (!json_path.empty()) write_json(json_path, j);
  return 0;
}

}  // namespace

int cmd_uff(const Args& args) {
  const std::string usage = "usage: ssid uff list FILE [--json OUT] [--values]\n";
  if (args.empty()) {
    std::cerr << usage;
    return 2;
  }
  if (args[0] == "--help" || args[0] == "-h") {
    std::cout << usage << "\n  list   datasets, nodes, modes and functions of a universal file\n";
    return 0;
  }
  if (args[0] == "list") return uff_list(Args(args.begin() + 1, args.end()));
  std::cerr << "ssid uff: unknown subcommand '" << args[0] << "'\n" << usage;
  return 2;
}

}  // namespace ssid::cli
