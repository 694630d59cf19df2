/// \file cmd_modes.cpp
/// `ssid modes DECK`: the real eigenvalue table as NASTRAN prints it, JSON, and
/// the synthetic modal test (`--uff`): modes at sensors with reproducible noise.
#include <fstream>
#include <iostream>
#include <unordered_map>
#include <sstream>

#include "cli/cli_util.hpp"
#include "cli/exit_codes.hpp"
#include "cli/model_load.hpp"
#include "cli/progress_lines.hpp"
#include "estimator/eigen/eigen_table.hpp"
#include "formats/parse_error.hpp"
#include "translators/synthetic_modes.hpp"
#include "translators/weight_table.hpp"

namespace ssid::cli {

namespace {

/// The mode shapes on the g-set into `j`: "shape_dofs" [[grid, component], ...]
/// once, each mode's "shape" in that order, and the convention in words.
void add_shapes(nlohmann::json& j, const translators::FeModel& model, const estimator::EigenResult& r,
                estimator::ModeNormalization norm) {
  const Eigen::MatrixXd g = model.expand(r.modes);
  const auto& gset = model.geometry().gset();
  nlohmann::json dofs = nlohmann::json::array();
  for (std::size_t i = 0; i < gset.size(); ++i) dofs.push_back({gset.at(i).point, gset.at(i).component});
  j["shape_dofs"] = dofs;
  j["shape_convention"] = {
      {"dofs", "every grid's components 1-6 (T1, T2, T3, R1, R2, R3) in the grid's displacement frame (GRID CD), "
               "scalar points as component 0: the g-set, in the order of shape_dofs"},
      {"values", "translations in the deck's length unit, rotations in radians; constrained DOFs 0, dependent DOFs "
                 "from their constraints (u_g = T u_a)"},
      {"normalization",
       norm == estimator::ModeNormalization::Max
           ? "MAX: the largest |component| of each shape is 1"
           : "MASS: phi^T M phi = 1 with M the mass matrix as assembled (PARAM WTMASS applied), so that a value "
             "is a displacement per square root of mass unit (m/sqrt(kg) in SI)"},
      {"sign", "as the solver returned it (a shape and its negative are the same mode)"}};
  for (int i = 0; i < r.size(); ++i) {
    const Eigen::VectorXd c = g.col(i);
    j["modes"][static_cast<std::size_t>(i)]["shape"] = std::vector<double>(c.data(), c.data() + c.size());
  }
}

}  // namespace

int cmd_modes(const Args& args) {
  po::options_description desc("ssid modes options");
  desc.add_options()("deck", po::value<std::string>()->required(), "NASTRAN input file (SOL 103 bulk data)")(
      "nmodes", po::value<int>(), "the lowest N modes (default: the deck's EIGRL/EIGR; every mode of a small model)")(
      "json", po::value<std::string>(), "write the modes as JSON to this file ('-' for stdout)")(
      "uff", po::value<std::string>(), "write the synthetic modal test (UFF 2411 nodes + 55 modes) to this file")(
      "sensors", po::value<std::string>(),
      "sensor grids for --uff: ids and ranges, e.g. \"1,5,10:20\" (default: every grid)")(
      "sensor-file", po::value<std::string>(), "sensor grids for --uff, read from a file (same syntax, # comments)")(
      "rotations", po::bool_switch(), "--uff: also write rotations (components 4-6)")(
      "noise-freq", po::value<double>()->default_value(0.0, "0"), "--uff: frequency noise, % (std of the relative error)")(
      "noise-shape", po::value<double>()->default_value(0.0, "0"),
      "--uff: shape noise, % of each mode's largest sensor value (std)")(
      "seed", po::value<std::uint64_t>()->default_value(1), "--uff: noise seed (same seed, same file)")(
      "weight", po::value<std::int64_t>()->implicit_value(0),
      "print the grid point weight generator output about this grid (0: the origin; default: PARAM GRDPNT)")(
      "method", po::value<std::string>()->default_value("auto"),
      "eigen-solver: auto (Lanczos over a Cholesky factor, or multilevel where that factor would not fit in memory "
      "or is predicted slower; the choice and its reason on stderr), "
      "lanczos, block-lanczos, or multilevel (LOBPCG with an aggregation multigrid preconditioner: no factor, "
      "for the largest models; lowest N modes only)")(
      "uff-precision", po::value<std::string>()->default_value("extended"),
      "--uff: extended (1P E25.16, exact round trip) or standard (E13.5 as test-lab software writes)")(
      "shapes", po::bool_switch(),
      "--json: also write each mode's shape on every grid DOF (g-set), with the convention stated in the JSON")(
      "quiet,q", "no progress lines on stderr (the eigen-solver's phases, from 2 s into the solve)");
  po::positional_options_description pos;
  pos.add("deck", 1);
  po::variables_map vm;
  int rc = 0;
  if (!parse_options(args,
                     "ssid modes DECK [--nmodes N] [--method M] [--json FILE [--shapes]] [--weight [GRID]] [--uff OUT.unv [--sensors GRIDS|--sensor-file F] "
                     "[--noise-freq PCT --noise-shape PCT --seed N]]",
                     desc, pos, vm, rc))
    return rc;
  if (vm.count("sensors") && vm.count("sensor-file")) {
    print_error("give --sensors or --sensor-file, not both");
    return 2;
  }
  const bool uff = vm.count("uff") != 0;
  if (!uff && (vm.count("sensors") || vm.count("sensor-file") || !vm["noise-freq"].defaulted() ||
               !vm["noise-shape"].defaulted() || !vm["seed"].defaulted() || vm["rotations"].as<bool>())) {
    print_error("--sensors, --sensor-file, --rotations, --noise-freq, --noise-shape and --seed need --uff OUT.unv");
    return 2;
  }
  if (vm["shapes"].as<bool>() && !vm.count("json")) {
    print_error("--shapes adds the mode shapes to the JSON: give --json FILE too");
    return kExitBadInput;
  }
  const std::string prec = vm["uff-precision"].as<std::string>();
  if (prec != "extended" && prec != "standard") {
    print_error("--uff-precision: expected extended or standard, got \"" + prec + "\"");
    return 2;
  }

  LoadedModel lm = load_model(vm["deck"].as<std::string>());
  print_model_notes(lm);
  const translators::FeModel& model = *lm.model;
  const translators::FeOperators op = model.operators(model.initial_parameters(), false);
  const long n = op.K.rows();
  std::string source;
  std::optional<int> nmodes;
  if (vm.count("nmodes")) nmodes = vm["nmodes"].as<int>();
  estimator::EigenOptions eo = eigen_options(model, nmodes, n, source);
  const std::string method = vm["method"].as<std::string>();
  if (method == "lanczos") eo.method = estimator::EigenMethod::Spectra;
  else if (method == "block-lanczos") eo.method = estimator::EigenMethod::BlockLanczos;
  else if (method == "multilevel") eo.method = estimator::EigenMethod::Multilevel;
  else if (method != "auto") {
    print_error("--method: expected auto, lanczos, block-lanczos or multilevel, got \"" + method + "\"");
    return 2;
  }
  // The eigen-solver's phases on stderr (counts of converged modes, the time left)
  // once a solve has taken 2 s: a quick one stays quiet.
  ProgressLines lines("ssid modes", vm.count("quiet") != 0, 5.0, 2.0);
  eo.progress = lines.callback();
  const estimator::EigenResult r = solve_model(op, eo, a_set_dofs(model));
  for (const auto& w : r.warnings) std::cerr << "warning: " << w << "\n";
  // Auto's choice between the direct and the multilevel method, and why (by
  // predicted cost: estimator/eigen/method_choice.hpp).
  if (eo.method == estimator::EigenMethod::Auto && !r.method_reason.empty() && !vm.count("quiet"))
    std::cerr << "ssid modes: eigen-solver " << r.method_reason << "\n";

  nlohmann::json j;
  j["dof"] = n;
  j["modes"] = nlohmann::json::array();
  for (int i = 0; i < r.size(); ++i)
    j["modes"].push_back({{"mode", i + 1},
                          {"eigenvalue", r.eigenvalues(i)},
                          {"radians", r.radians(i)},
                          {"cycles", r.cycles(i)},
                          {"generalized_mass", r.generalized_mass(i)},
                          {"generalized_stiffness", r.generalized_stiffness(i)}});
  if (vm["shapes"].as<bool>()) add_shapes(j, model, r, eo.norm);
  // Modes missing from the band: the table is printed, but not to be trusted.
  const std::string untrusted =
      r.sturm_mismatch ? "the Sturm count disagrees with the modes found in the band: modes may be missing" : "";
  j["partial"] = !untrusted.empty();
  if (!untrusted.empty()) j["partial_reason"] = untrusted;

  const std::string json_path = vm.count("json") ? vm["json"].as<std::string>() : "";
  if (json_path != "-") {
    std::cout << lm.path << ": " << n << " analysis-set DOF(s), " << r.size() << " mode(s) (" << source << "; "
              << (r.method.empty() ? "Lanczos" : r.method) << " solver)\n\n";
    std::cout << estimator::format_real_eigenvalues(r);
    double res = 0, be = 0;
    for (int i = 0; i < r.size(); ++i) {
      be = std::max(be, r.backward_errors(i));
      if (r.eigenvalues(i) > 1e-6 * std::abs(r.eigenvalues(r.size() - 1))) res = std::max(res, r.residuals(i));
    }
    std::cout << "\nchecks: max |K phi - lambda M phi| / |K phi| (elastic modes) " << res << ", max backward error "
              << be << ", M-orthogonality " << r.orthogonality << "\n";

    // Grid point weight: --weight GRID, or PARAM GRDPNT >= 0 as NASTRAN does.
    std::optional<std::int64_t> grdpnt;
    if (vm.count("weight")) grdpnt = vm["weight"].as<std::int64_t>();
    else
      for (const auto& p : model.bulk().params)
        if (p.name == "GRDPNT" && p.integer() && *p.integer() >= 0) grdpnt = *p.integer();
    if (grdpnt) {
      Eigen::Vector3d ref = Eigen::Vector3d::Zero();
      if (*grdpnt != 0) ref = model.geometry().grid(*grdpnt, "GRDPNT").x;
      std::unordered_map<std::int64_t, Eigen::Vector3d> pos;
      for (const auto& g : model.geometry().grids()) pos.emplace(g.id, g.x);
      // NASTRAN prints the mass before PARAM WTMASS is applied (the deck's units).
      const auto w = translators::grid_point_weight(op.Mg / model.wtmass(), model.geometry().gset(), pos, ref);
      std::cout << "\n" << translators::format_grid_point_weight(w, *grdpnt);
    }
  }
  if (!json_path.empty()) write_json(json_path, j);

  if (uff) {
    const auto grids = grid_positions(model);
    translators::SyntheticTestOptions so;
    if (vm.count("sensors")) so.sensors = translators::parse_sensor_list(vm["sensors"].as<std::string>(), grids, "--sensors");
    if (vm.count("sensor-file")) {
      const std::string f = vm["sensor-file"].as<std::string>();
      std::ifstream in(f);
      if (!in) throw formats::InputError(f + ": cannot open the sensor file");
      std::stringstream ss;
      ss << in.rdbuf();
      so.sensors = translators::parse_sensor_list(ss.str(), grids, f);
      if (so.sensors.empty()) throw formats::InputError(f + ": no sensor grids in the file");
    }
    so.rotations = vm["rotations"].as<bool>();
    so.noise_freq_pct = vm["noise-freq"].as<double>();
    so.noise_shape_pct = vm["noise-shape"].as<double>();
    so.seed = vm["seed"].as<std::uint64_t>();
    so.description = "ssid synthetic test of " + lm.path;
    translators::FeModeData fe;
    fe.shapes = r.modes;
    for (int i = 0; i < r.size(); ++i) {
      fe.frequency_hz.push_back(r.cycles(i));
      fe.generalized_mass.push_back(r.generalized_mass(i));
    }
    const auto t = translators::synthetic_test(fe, model.reduction(), model.geometry().gset(), grids, so);
    const std::string out = vm["uff"].as<std::string>();
    formats::uff::write_uff(t.file, out,
                            prec == "standard" ? formats::uff::Precision::Standard : formats::uff::Precision::Extended);
    std::cerr << "wrote " << out << ": " << t.modes.shapes.cols() << " mode(s) at " << t.modes.dofs.size()
              << " sensor DOF(s) on " << t.modes.dofs.size() / (so.rotations ? 6 : 3) << " grid(s); noise "
              << so.noise_freq_pct << " % frequency, " << so.noise_shape_pct << " % shape, seed " << so.seed << "\n";
  }
  if (!untrusted.empty()) {
    print_error("modes: " + untrusted + " (the table above, and the JSON marked \"partial\": true)");
    return kExitUntrusted;
  }
  return kExitSuccess;
}

}  // namespace ssid::cli
