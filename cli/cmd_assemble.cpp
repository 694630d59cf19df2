/// \file cmd_assemble.cpp
/// `ssid assemble DECK -o DIR` (NASDSA analogue): K, M, ∂K/∂r_j, ∂M/∂r_j on the
/// analysis set as OP4 files plus manifest.json; `ssid assemble --import SPEC -o DIR`
/// builds the same set from another FE code's OP4 exports by finite differences.
#include <iostream>
#include <map>

#include "cli/cli_util.hpp"
#include "cli/model_load.hpp"
#include "formats/parse_error.hpp"
#include "translators/operator_import.hpp"
#include "translators/operator_set.hpp"

namespace ssid::cli {

namespace {

/// "LABEL=VALUE" or "ID=VALUE" → (parameter index, value).
std::pair<std::size_t, double> parse_set(const std::string& s, const translators::FeModel& model) {
  const auto eq = s.find('=');
  if (eq == std::string::npos) throw formats::InputError("--set \"" + s + "\": expected LABEL=VALUE or ID=VALUE");
  const std::string name = s.substr(0, eq), val = s.substr(eq + 1);
  double v = 0;
  std::size_t used = 0;
  try {
    v = std::stod(val, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != val.size()) throw formats::InputError("--set \"" + s + "\": \"" + val + "\" is not a number");
  const auto& ps = model.parameters();
  for (std::size_t j = 0; j < ps.size(); ++j)
    if (ps[j].label == name || std::to_string(ps[j].id) == name) return {j, v};
  throw formats::InputError("--set \"" + s + "\": no DESVAR with label or id " + name);
}

}  // namespace

int cmd_assemble(const Args& args) {
  po::options_description desc("ssid assemble options");
  desc.add_options()("deck", po::value<std::string>(), "NASTRAN input file")(
      "output,o", po::value<std::string>()->required(), "output folder (created): OP4 files and manifest.json")(
      "ascii", po::bool_switch(), "write ASCII OP4 (1P,3E23.16) instead of binary")(
      "no-derivatives", po::bool_switch(), "K and M only")(
      "set", po::value<std::vector<std::string>>(),
      "assemble at a changed DESVAR value, LABEL=VALUE or ID=VALUE (repeatable)")(
      "import", po::value<std::string>(), "build the operators from another code's OP4 or DMIG exports (JSON spec)");
  po::positional_options_description pos;
  pos.add("deck", 1);
  po::variables_map vm;
  int rc = 0;
  if (!parse_options(args,
                     "ssid assemble DECK -o DIR [--ascii] [--no-derivatives] [--set LABEL=VALUE ...]\n"
                     "       ssid assemble --import SPEC.json -o DIR [--ascii]",
                     desc, pos, vm, rc))
    return rc;
  const bool import = vm.count("import") != 0;
  if (import == (vm.count("deck") != 0)) {
    print_error("give a DECK or --import SPEC.json (one of them)");
    return 2;
  }
  if (import && (vm.count("set") || vm["no-derivatives"].as<bool>())) {
    print_error("--set and --no-derivatives apply to a deck, not to --import");
    return 2;
  }
  formats::Op4WriteOptions op4;
  op4.encoding = vm["ascii"].as<bool>() ? formats::Op4Encoding::Ascii : formats::Op4Encoding::Binary;
  op4.precision = static_cast<int>(formats::Op4Precision::RealDouble);
  const std::string dir = vm["output"].as<std::string>();

  translators::OperatorSet set;
  if (import) {
    set = translators::import_operators(vm["import"].as<std::string>());
  } else {
    LoadedModel lm = load_model(vm["deck"].as<std::string>());
    print_model_notes(lm);
    Eigen::VectorXd x = lm.model->initial_parameters();
    if (vm.count("set"))
      for (const auto& s : vm["set"].as<std::vector<std::string>>()) {
        auto [j, v] = parse_set(s, *lm.model);
        x(static_cast<Eigen::Index>(j)) = v;
      }
    const bool deriv = !vm["no-derivatives"].as<bool>();
    set = translators::operators_from_model(*lm.model, x, deriv, lm.path);
    if (deriv && set.parameters.empty())
      std::cerr << "note: the deck has no DESVAR: K and M only\n";
  }
  translators::write_operator_set(set, dir, op4);

  std::cout << (import ? "imported " : "assembled ") << set.source << ": " << set.dofs.size()
            << " analysis-set DOF(s), K " << set.K.nonZeros() << " and M " << set.M.nonZeros() << " non-zeros\n";
  if (!set.parameters.empty()) {
    std::cout << "parameters:\n";
    for (std::size_t j = 0; j < set.parameters.size(); ++j) {
      const auto& p = set.parameters[j];
      std::cout << "  " << p.label << (p.id ? " (DESVAR " + std::to_string(p.id) + ")" : std::string()) << " = "
                << p.value;
      if (!set.dK.empty()) {
        std::cout << ": dK " << set.dK[j].nonZeros() << ", dM " << set.dM[j].nonZeros() << " non-zeros, " << p.method;
        if (p.step != 0) std::cout << " (step " << p.step << ")";
      }
      std::cout << "\n";
    }
  }
  for (const auto& n : set.notes)
    if (import) std::cerr << "note: " << n << "\n";
  std::cout << "wrote " << dir << "/manifest.json and " << (2 + 2 * set.dK.size()) << " OP4 file(s)\n";
  return 0;
}

}  // namespace ssid::cli
