/// \file cmd_correlate.cpp
/// `ssid correlate DECK|FE.unv TEST.unv`: pairing table (reconciliation paper
/// Tables 4–6 layout), MAC, auto-MAC, with --json. From a deck, the modes are
/// solved and sampled at the grids the test nodes map to (in basic X, Y, Z, and
/// rotations when the test has them).
#include <Eigen/SparseCore>
#include <algorithm>
#include <fmt/format.h>
#include <fstream>
#include <iostream>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <variant>

#include "cli/cli_util.hpp"
#include "cli/model_load.hpp"
#include "cli/report/frf_comparison.hpp"
#include "cli/report/report_data.hpp"
#include "cli/report/tam_xor.hpp"
#include "estimator/correlation/correlate.hpp"
#include "estimator/correlation/measures.hpp"
#include "estimator/pretest/measurement_coordinates.hpp"
#include "formats/parse_error.hpp"
#include "formats/uff.hpp"
#include "translators/measurement/mode_set.hpp"
#include "translators/synthetic_modes.hpp"

namespace ssid::cli {

namespace {

namespace uff = formats::uff;

/// True when the file starts (after blank lines) with a UFF delimiter.
bool looks_like_uff(const std::string& path) {
  std::ifstream in(path);
  if (!in) return true;  // let the reader report "not found"
  for (std::string line; std::getline(in, line);) {
    std::size_t b = line.find_first_not_of(" \t\r");
    if (b == std::string::npos) continue;
    return line.compare(b, 2, "-1") == 0;
  }
  return true;
}

nlohmann::json matrix_json(const Eigen::MatrixXd& m) {
  nlohmann::json j = nlohmann::json::array();
  for (Eigen::Index i = 0; i < m.rows(); ++i) {
    nlohmann::json row = nlohmann::json::array();
    for (Eigen::Index k = 0; k < m.cols(); ++k) row.push_back(m(i, k));
    j.push_back(row);
  }
  return j;
}

}  // namespace

int cmd_correlate(const Args& args) {
  po::options_description desc("ssid correlate options");
  desc.add_options()("fe", po::value<std::string>()->required(),
                     "analysis modes: a NASTRAN deck (solved here), or a universal file with dataset 55")(
      "test", po::value<std::string>()->required(), "test modes: universal file with dataset 55 (+ nodes 15/2411)")(
      "json", po::value<std::string>(), "write the results as JSON to this file ('-' for stdout)")(
      "report", po::value<std::string>(),
      "write an HTML report (MAC, frequencies, mode shapes) to this file; the JSON then also holds the run, "
      "geometry and shapes (docs/report.md)")(
      "mac", po::value<std::string>()->default_value("squared"),
      "MAC form: squared, or ns (the seed report's non-squared MAC)")(
      "min-mac", po::value<double>()->default_value(0.9, "0.9"), "accept a mutual-best pair at this MAC or above")(
      "max-freq-error", po::value<double>()->default_value(10.0, "10"),
      "accept a pair only within this frequency error (%)")(
      "map", po::value<std::string>()->default_value("id"),
      "test node to analysis node: id, position, or id-then-position (positions from 15/2411 in both files)")(
      "tol", po::value<double>()->default_value(0.0, "0"), "distance tolerance for position mapping (model units)")(
      "nmodes", po::value<int>(), "deck: solve the lowest N modes (default: the deck's EIGRL/EIGR)")(
      "tam", po::value<std::string>(),
      "deck: cross-orthogonality also with these test-analysis models' masses on the test DOFs, guyan and/or irs "
      "(comma-separated; SEREP's is always computed)");
  report::add_frf_options(desc,
                          "deck: measured FRFs (universal file, dataset 58) to lay the deck's FRFs over (modal "
                          "superposition; JSON frf_comparison, the report's FRF figures); with --report the test "
                          "file's own FRFs are used when it holds some");
  po::positional_options_description pos;
  pos.add("fe", 1).add("test", 1);
  po::variables_map vm;
  int rc = 0;
  if (!parse_options(args,
                     "ssid correlate DECK|FE.unv TEST.unv [--json FILE] [--report FILE.html] [--nmodes N] [--mac squared|ns] [--min-mac X] "
                     "[--max-freq-error PCT] [--map id|position|id-then-position --tol D] [--tam guyan,irs] "
                     "[--frf MEASURED.unv [--frf-damping Z] [--frf-max N]]",
                     desc, pos, vm, rc))
    return rc;
  const std::string fe_path = vm["fe"].as<std::string>(), test_path = vm["test"].as<std::string>();
  const bool from_deck = !looks_like_uff(fe_path);
  if (!from_deck && vm.count("nmodes")) {
    print_error("--nmodes applies when the first argument is a deck");
    return 2;
  }
  std::vector<std::string> tams;
  if (vm.count("tam")) {
    if (!report::parse_tams(vm["tam"].as<std::string>(), tams)) return 2;
    if (!from_deck) {
      print_error("--tam needs the deck's stiffness and mass: give a deck as the first argument");
      return 2;
    }
  }
  if (!from_deck && vm.count("frf")) {
    print_error("--frf needs the deck's modes: give a deck as the first argument");
    return 2;
  }
  const std::optional<report::FrfOptions> frf_opt = report::frf_options(vm);
  if (!frf_opt) return 2;

  estimator::PairingOptions opt;
  const std::string form = vm["mac"].as<std::string>();
  if (form == "squared") opt.form = estimator::MacForm::Squared;
  else if (form == "ns" || form == "non-squared") opt.form = estimator::MacForm::NonSquared;
  else {
    print_error("--mac: expected squared or ns, got \"" + form + "\"");
    return 2;
  }
  opt.min_mac = vm["min-mac"].as<double>();
  opt.max_frequency_error_pct = vm["max-freq-error"].as<double>();

  // The analysis side: a universal file, or a deck solved here.
  LoadedModel lm;
  estimator::EigenResult fe_modes;
  uff::UffFile fe_file;
  std::optional<translators::FeOperators> op_kept;  // the deck's K and M, for --tam
  if (from_deck) {
    lm = load_model(fe_path);
    print_model_notes(lm);
    const auto& op = op_kept.emplace(lm.model->operators(lm.model->initial_parameters(), false));
    std::string source;
    std::optional<int> nmodes;
    if (vm.count("nmodes")) nmodes = vm["nmodes"].as<int>();
    fe_modes = solve_model(op, eigen_options(*lm.model, nmodes, op.K.rows(), source), a_set_dofs(*lm.model));
    for (const auto& w : fe_modes.warnings) std::cerr << "warning: " << w << "\n";
    std::cerr << "note: " << fe_path << ": " << fe_modes.size() << " analysis mode(s) (" << source << ")\n";
  } else {
    fe_file = uff::read_uff(fe_path);
  }
  const uff::UffFile test_file = uff::read_uff(test_path);
  translators::ModeSetReport fe_rep, test_rep;
  translators::ModeSet fe = from_deck ? translators::ModeSet{} : translators::modes_from_uff(fe_file, &fe_rep);
  translators::ModeSet test = translators::modes_from_uff(test_file, &test_rep);
  if (!from_deck && fe.frequency_hz.empty()) throw formats::InputError(fe_path + ": no real normal modes (dataset 55, analysis type 2)");
  if (test.frequency_hz.empty())
    throw formats::InputError(test_path + ": no real normal modes (dataset 55, analysis type 2)");
  std::vector<std::string> problems;
  for (const auto& p : fe_rep.problems) problems.push_back(fe_path + ": " + p);
  for (const auto& p : test_rep.problems) problems.push_back(test_path + ": " + p);
  if (test_rep.complex_modes)
    problems.push_back(test_path + ": " + std::to_string(test_rep.complex_modes) +
                       " complex mode(s) not used (real normal modes are compared)");

  // Test nodes onto the analysis nodes.
  const std::string map = vm["map"].as<std::string>();
  nlohmann::json mapping_json;
  report::Lines test_trace;  // the test file's trace lines (82) in grid ids, for the report
  translators::NodeMapOptions mo;
  std::vector<translators::TestNode> nodes = translators::test_nodes(test_file);
  {
    if (map == "id") mo.by = translators::MapBy::Id;
    else if (map == "position") mo.by = translators::MapBy::Position;
    else if (map == "id-then-position") mo.by = translators::MapBy::IdThenPosition;
    else {
      print_error("--map: expected id, position or id-then-position, got \"" + map + "\"");
      return 2;
    }
    mo.tolerance = vm["tol"].as<double>();
    std::vector<translators::GridPosition> grids;
    if (from_deck) grids = grid_positions(*lm.model);
    for (const auto& n : fe_file.nodes())
      grids.push_back({n.id, Eigen::Vector3d(n.xyz[0], n.xyz[1], n.xyz[2]), Eigen::Matrix3d::Identity()});
    if (map == "id") {
      // Node geometry is optional for id matching: every test node id in the modes maps to itself
      // when the analysis file lists no nodes.
      std::set<std::int64_t> ids;
      for (const auto& d : test.dofs) ids.insert(d.node);
      if (grids.empty() && !from_deck)
        for (auto id : ids) grids.push_back({id, Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity()});
      if (nodes.empty())
        for (auto id : ids) nodes.push_back({id, Eigen::Vector3d::Zero(), 0});
    } else if (grids.empty() || nodes.empty()) {
      throw formats::InputError("--map " + map + " needs node positions (dataset 15 or 2411) in both files" +
                               std::string(from_deck ? " (the test file has none)" : ""));
    }
    auto m = translators::map_test_nodes(nodes, grids, mo);
    for (const auto& p : m.problems) problems.push_back(test_path + ": " + p);
    if (from_deck) translators::require_mapped(test.dofs, m, test_path, "the deck " + fe_path);
    mapping_json = {{"by", map}, {"mapped", m.matches.size()}, {"unmapped", m.unmapped}};
    test = translators::relabel(test, m);
    test_trace = translators::segments_in_grids(translators::trace_segments(test_file), m);
    if (from_deck) {
      // The analysis modes at the grids the test nodes map to, in basic directions.
      translators::SyntheticTestOptions so;
      for (const auto& match : m.matches) so.sensors.push_back(match.grid);
      for (const auto& d : test.dofs) so.rotations |= std::abs(d.direction) > 3;
      if (so.sensors.empty()) throw formats::InputError(test_path + ": no test node maps to a grid of " + fe_path);
      translators::FeModeData fd;
      fd.shapes = fe_modes.modes;
      for (int i = 0; i < fe_modes.size(); ++i) {
        fd.frequency_hz.push_back(fe_modes.cycles(i));
        fd.generalized_mass.push_back(fe_modes.generalized_mass(i));
      }
      fe = translators::synthetic_test(fd, lm.model->reduction(), lm.model->geometry().gset(), grids, so).modes;
    }
  }

  const estimator::Correlation c = estimator::correlate(fe, test, opt);
  const auto& p = c.pairing;
  auto fe_no = [&](int i) { return c.fe.numbers[static_cast<std::size_t>(i)]; };
  auto test_no = [&](int j) { return c.test.numbers[static_cast<std::size_t>(j)]; };

  nlohmann::json j;
  j["fe_file"] = fe_path;
  j["test_file"] = test_path;
  j["mac_form"] = opt.form == estimator::MacForm::Squared ? "squared" : "non-squared";
  j["min_mac"] = opt.min_mac;
  j["max_frequency_error_pct"] = opt.max_frequency_error_pct;
  j["dofs"] = c.dofs.size();
  j["mapping"] = mapping_json;
  j["pairs"] = nlohmann::json::array();
  for (const auto& mp : p.pairs)
    j["pairs"].push_back({{"fe_mode", fe_no(mp.fe)},
                          {"test_mode", test_no(mp.test)},
                          {"fe_hz", c.fe.frequency_hz[static_cast<std::size_t>(mp.fe)]},
                          {"test_hz", c.test.frequency_hz[static_cast<std::size_t>(mp.test)]},
                          {"error_pct", mp.error_pct},
                          {"mac", mp.mac},
                          {"msf", mp.msf},
                          {"accepted", mp.accepted}});
  j["unpaired_fe"] = nlohmann::json::array();
  for (int i : p.unpaired_fe) j["unpaired_fe"].push_back(fe_no(i));
  j["unpaired_test"] = nlohmann::json::array();
  for (int k : p.unpaired_test) j["unpaired_test"].push_back(test_no(k));
  j["table"] = nlohmann::json::array();
  for (const auto& r : p.table) {
    nlohmann::json row;
    row["fe_mode"] = r.fe ? nlohmann::json(fe_no(*r.fe)) : nlohmann::json(nullptr);
    row["test_mode"] = r.test ? nlohmann::json(test_no(*r.test)) : nlohmann::json(nullptr);
    if (!r.fe && r.fe_best >= 0) row["fe_best"] = fe_no(r.fe_best);
    if (!r.test && r.test_best >= 0) row["test_best"] = test_no(r.test_best);
    row["max_fe_mac"] = r.max_fe_mac ? nlohmann::json(*r.max_fe_mac) : nlohmann::json(nullptr);
    row["max_test_mac"] = r.max_test_mac ? nlohmann::json(*r.max_test_mac) : nlohmann::json(nullptr);
    row["error_pct"] = r.error_pct ? nlohmann::json(*r.error_pct) : nlohmann::json(nullptr);
    row["accepted"] = r.accepted;
    j["table"].push_back(row);
  }
  j["fe_modes"] = nlohmann::json::array();  // the rows of "mac"
  for (std::size_t i = 0; i < c.fe.numbers.size(); ++i)
    j["fe_modes"].push_back({{"mode", c.fe.numbers[i]}, {"hz", c.fe.frequency_hz[i]}});
  j["test_modes"] = nlohmann::json::array();  // its columns
  for (std::size_t k = 0; k < c.test.numbers.size(); ++k)
    j["test_modes"].push_back({{"mode", c.test.numbers[k]}, {"hz", c.test.frequency_hz[k]}});
  j["mac"] = matrix_json(p.mac);
  j["auto_mac_fe"] = matrix_json(c.auto_mac_fe);
  j["auto_mac_test"] = matrix_json(c.auto_mac_test);
  {
    std::vector<std::pair<int, int>> accepted;
    for (const auto& mp : p.pairs)
      if (mp.accepted) accepted.emplace_back(fe_no(mp.fe), test_no(mp.test));
    j["cross_orthogonality"] = report::cross_orthogonality_json(c.fe.shapes, c.fe.modal_mass, c.fe.numbers,
                                                                c.test.shapes, c.test.numbers, accepted);
    // Guyan and IRS need K and M: the analysis shapes at the test DOFs are those of
    // synthetic_test (each basic direction's component), the coordinates the TAMs reduce onto.
    if (!tams.empty())
      j["cross_orthogonality_tam"] = report::tam_cross_orthogonality_json(
          tams, *lm.model, *op_kept, c.dofs, c.fe.shapes, c.fe.numbers, c.test.shapes, c.test.numbers, accepted, problems);
  }
  // FE FRFs over the measured ones: --frf's file, or with --report the test file's own.
  std::optional<uff::UffFile> frf_file;
  if (vm.count("frf")) frf_file = uff::read_uff(vm["frf"].as<std::string>());
  else if (from_deck && vm.count("report") &&
           std::any_of(test_file.functions().begin(), test_file.functions().end(),
                       [](const uff::Function58* f) { return f->function_type == 4; }))
    frf_file = test_file;
  if (frf_file) {
    Eigen::MatrixXd unit_modes = fe_modes.modes;  // Eq. 2 needs φᵀMφ = 1, whatever the deck's NORM
    for (int i = 0; i < fe_modes.size(); ++i) unit_modes.col(i) /= std::sqrt(fe_modes.generalized_mass(i));
    const report::FrfDamping damping{test.frequency_hz, test.damping, test.numbers, frf_opt->zeta_fallback, 0.1};
    j["frf_comparison"] = report::frf_comparison_json(*frf_file, nodes, mo,
                                                      {{"analysis", lm.model.get(), fe_modes.eigenvalues, unit_modes}},
                                                      damping, frf_opt->max_frfs, problems);
  }
  j["problems"] = problems;

  if (vm.count("report")) {
    std::vector<std::string> inputs{fe_path, test_path};
    if (vm.count("frf")) inputs.push_back(vm["frf"].as<std::string>());
    j["run"] = report::run_json("correlate", args, inputs);
    if (from_deck) {
      // The accepted pairs drawn on the deck: every grid for the analysis, the common DOFs for the test.
      std::vector<report::ShapePair> sp;
      for (const auto& mp : p.pairs) {
        if (!mp.accepted) continue;
        const auto i = static_cast<std::size_t>(mp.fe), k = static_cast<std::size_t>(mp.test);
        sp.push_back({fe_no(mp.fe), test_no(mp.test), c.fe.frequency_hz[i], c.test.frequency_hz[k], mp.mac,
                      static_cast<Eigen::Index>(mp.fe), c.fe.shapes.col(mp.fe), c.test.shapes.col(mp.test)});
      }
      report::add_shapes(j, *lm.model, fe_modes.modes, c.dofs, sp, c.test.shapes, c.test.numbers, test_trace);
    }
    report::write_report(vm["report"].as<std::string>(), j);
  }
  const std::string json_path = vm.count("json") ? vm["json"].as<std::string>() : "";
  for (const auto& s : problems) std::cerr << "warning: " << s << "\n";
  if (json_path == "-") {
    write_json("-", j);
    return 0;
  }
  std::size_t accepted = 0;
  for (const auto& mp : p.pairs) accepted += mp.accepted;
  std::cout << "analysis: " << fe_path << " (" << c.fe.frequency_hz.size() << " modes); test: " << test_path << " ("
            << c.test.frequency_hz.size() << " modes); compared at " << c.dofs.size() << " common DOF(s), MAC "
            << j["mac_form"].get<std::string>() << "\n\n";
  std::cout << estimator::format_pairing_table(p, c.fe.frequency_hz, c.test.frequency_hz, c.fe.numbers, c.test.numbers);
  std::cout << "\n(*) accepted: MAC >= " << opt.min_mac << " and |error| <= " << opt.max_frequency_error_pct
            << " %; -n-: best partner n preferred a mode with higher MAC\n";
  std::cout << "accepted pairs: " << accepted << " of " << p.pairs.size() << " mutual-best\n";
  std::cout << "unpaired analysis modes:";
  if (p.unpaired_fe.empty()) std::cout << " none";
  for (int i : p.unpaired_fe) std::cout << " " << fe_no(i);
  std::cout << "\nunpaired test modes:";
  if (p.unpaired_test.empty()) std::cout << " none";
  for (int k : p.unpaired_test) std::cout << " " << test_no(k);
  std::cout << "\n";
  if (j.contains("frf_comparison")) std::cout << "\n" << report::frf_comparison_text(j["frf_comparison"]);
  if (!json_path.empty()) write_json(json_path, j);
  return 0;
}

}  // namespace ssid::cli
