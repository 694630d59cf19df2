/// \file cmd_truss.cpp
/// `ssid truss mpi|list-configs`: the built-in MPI-like truss generator.
#include <fmt/format.h>
#include <fstream>
#include <iostream>

#include "cli/cli_util.hpp"
#include "formats/deck_writer.hpp"
#include "formats/parse_error.hpp"
#include "translators/truss/configurations.hpp"
#include "translators/truss/reference_modes.hpp"
#include "translators/truss/truss_deck.hpp"
#include "translators/truss/truss_svg.hpp"

namespace ssid::cli {

namespace {

namespace tr = ssid::translators::truss;

int truss_list(const Args& args) {
  po::options_description desc("ssid truss list-configs options");
  desc.add_options()("json", po::value<std::string>(), "write the list as JSON to this file ('-' for stdout)");
  po::positional_options_description pos;
  po::variables_map vm;
  int rc = 0;
  if (!parse_options(args, "ssid truss list-configs [--json FILE]", desc, pos, vm, rc)) return rc;
  nlohmann::json j = nlohmann::json::array();
  for (const auto& c : tr::list_configs()) j.push_back({{"name", c.name}, {"description", c.description}, {"component", c.component}});
  if (vm.count("json") && vm["json"].as<std::string>() == "-") {
    write_json("-", j);
    return 0;
  }
  std::cout << "structure configurations (combine with several --config):\n";
  for (const auto& c : tr::list_configs())
    if (!c.component) std::cout << fmt::format("  {:<20} {}\n", c.name, c.description);
  std::cout << "component assemblies (one alone, free-free):\n";
  for (const auto& c : tr::list_configs())
    if (c.component) std::cout << fmt::format("  {:<20} {}\n", c.name, c.description);
  if (vm.count("json")) write_json(vm["json"].as<std::string>(), j);
  return 0;
}

int truss_mpi(const Args& args) {
  po::options_description desc("ssid truss mpi options");
  desc.add_options()("model", po::value<std::string>()->default_value("rod"), "model form: rod (240 DOF) or beam (~10k DOF)")(
      "config", po::value<std::vector<std::string>>()->composing(), "configuration (repeatable; see list-configs)")(
      "output,o", po::value<std::string>(), "deck to write")(
      "json", po::value<std::string>(), "write counts, mass, parameters (and modes) as JSON ('-' for stdout)")(
      "modes", po::value<int>()->default_value(0),
      "also compute this many modes with the generator's reference assembler and print them")(
      "svg", po::value<std::string>(), "draw the truss (axonometric view, booms and tower labelled) to this SVG file")(
      "quiet,q", "no progress line on stderr (before the reference eigen-solve of --modes)");
  po::positional_options_description pos;
  po::variables_map vm;
  int rc = 0;
  const std::string usage = "ssid truss mpi --model rod|beam [--config NAME ...] -o DECK [--json FILE] [--modes N] [--svg FILE]";
  if (!parse_options(args, usage, desc, pos, vm, rc)) return rc;
  const std::string model = vm["model"].as<std::string>();
  if (model != "rod" && model != "beam") {
    std::cerr << "ssid: --model must be rod or beam, not '" << model << "'\nusage: " << usage << "\n";
    return 2;
  }
  if (!vm.count("output") && !vm.count("json") && !vm.count("svg") && vm["modes"].as<int>() <= 0) {
    std::cerr << "ssid: nothing to do: give -o DECK, --json, --svg or --modes\nusage: " << usage << "\n";
    return 2;
  }
  std::vector<std::string> configs = vm.count("config") ? vm["config"].as<std::vector<std::string>>() : std::vector<std::string>{};
  if (configs.empty()) configs.push_back("bare");

  const tr::TrussModel t = tr::build_configured(configs);
  const tr::TrussCards fe = tr::build_truss_cards(t, model == "rod" ? tr::ModelForm::Rod : tr::ModelForm::Beam);
  std::string command = "ssid truss mpi --model " + model;
  for (const auto& c : configs) command += " --config " + c;
  nlohmann::json j = tr::summary_json(t, fe);
  const bool json_stdout = vm.count("json") && vm["json"].as<std::string>() == "-";
  std::ostream& out = json_stdout ? std::cerr : std::cout;

  if (vm.count("output")) {
    // The generated deck has no input file: name it so the writer's overwrite guard
    // (which protects input files) never mistakes the output for one.
    const auto written = formats::write_deck(tr::to_deck(t, fe, command, "<ssid truss mpi>"), vm["output"].as<std::string>());
    for (const auto& w : written) out << "wrote " << w << "\n";
  }
  if (vm.count("svg")) {
    std::ofstream svg(vm["svg"].as<std::string>());
    if (!svg) throw formats::InputError("cannot write " + vm["svg"].as<std::string>());
    svg << tr::render_svg(t);
    out << "wrote " << vm["svg"].as<std::string>() << "\n";
  }
  const Eigen::Vector3d cg = t.center_of_gravity(), ex = t.extent();
  out << fmt::format("{} {} model ({}): {} balls, {} struts, {} grids, {} DOF\n", t.name, model,
                     fmt::join(configs, ", "), t.balls.size(), t.members.size(), fe.grids.size(), fe.dof_count());
  out << fmt::format("mass {:.3f} kg (deck {:.3f} kg), CG ({:.3f}, {:.3f}, {:.3f}) m, extent {:.2f} x {:.2f} x {:.2f} m\n",
                     t.total_mass(), fe.total_mass(), cg.x(), cg.y(), cg.z(), ex.x(), ex.y(), ex.z());
  out << "parameters:";
  for (const auto& d : fe.desvars) out << " " << d.label;
  out << "\n";

  const int nmodes = vm["modes"].as<int>();
  if (nmodes > 0) {
    if (!vm.count("quiet"))
      std::cerr << "ssid truss: reference eigen-solve, the lowest " << nmodes << " modes of " << fe.dof_count()
                << " DOFs\n";
    const tr::ReferenceModes m = tr::reference_modes(fe, nmodes);
    if (!m.converged)
      throw formats::NumericalError("the reference eigen-solve did not converge (" + std::to_string(nmodes) +
                                    " modes of the " + model + " model): its frequencies are not trustworthy");
    out << "modes (generator's reference assembler, " << m.a_set_size << " independent DOF):\n";
    for (std::size_t k = 0; k < m.frequency_hz.size(); ++k) out << fmt::format("  {:3d} {:10.3f} Hz\n", k + 1, m.frequency_hz[k]);
    j["modes_hz"] = m.frequency_hz;
  }
  if (vm.count("json")) write_json(vm["json"].as<std::string>(), j);
  return 0;
}

}  // namespace

int cmd_truss(const Args& args) {
  const std::string usage =
      "usage: ssid truss <mpi|list-configs> ...\n"
      "  mpi --model rod|beam [--config NAME ...] -o DECK [--json FILE] [--modes N] [--svg FILE]\n"
      "                        write an MPI-like truss deck (SOL 103, EIGRL, DESVAR/DVPREL1)\n"
      "  list-configs [--json FILE]   the report's test configurations and component assemblies\n";
  if (args.empty() || args[0] == "--help" || args[0] == "-h") {
    (args.empty() ? std::cerr : std::cout) << usage;
    return args.empty() ? 2 : 0;
  }
  Args rest(args.begin() + 1, args.end());
  if (args[0] == "mpi") return truss_mpi(rest);
  if (args[0] == "list-configs") return truss_list(rest);
  std::cerr << "ssid truss: unknown subcommand '" << args[0] << "'\n" << usage;
  return 2;
}

}  // namespace ssid::cli
