/// \file cmd_estimate.cpp
/// `ssid estimate` (SSID analogue), `ssid translate` (NASSID analogue: the
/// problem file) and `ssid update-deck` (SD2NAS analogue). See docs/estimation.md.
#include <cmath>
#include <fstream>
#include <iostream>
#include <sstream>

#include "cli/cli_util.hpp"
#include "cli/exit_codes.hpp"
#include "cli/progress_lines.hpp"
#include "cli/report/frf_comparison.hpp"
#include "cli/report/report_data.hpp"
#include "cli/report/tam_xor.hpp"
#include "estimator/study/deck_study.hpp"
#include "formats/deck_writer.hpp"
#include "formats/parse_error.hpp"
#include "formats/problem_file.hpp"
#include "translators/assembly/deck_update.hpp"

namespace ssid::cli {

namespace {

/// True when the file starts with the problem file's magic.
bool is_problem_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  char magic[8] = {};
  in.read(magic, 8);
  return in.gcount() == 8 && std::string(magic, 8) == "SSIDPROB";
}

estimator::EstimationProblem load_problem(const po::variables_map& vm, bool allow_problem) {
  std::string problem = allow_problem && vm.count("problem") ? vm["problem"].as<std::string>() : "";
  const std::string deck = vm.count("deck") ? vm["deck"].as<std::string>() : "";
  if (problem.empty() && allow_problem && !deck.empty() && is_problem_file(deck)) problem = deck;
  if (!problem.empty()) {
    if (vm.count("study"))
      throw formats::InputError("--study applies to decks; " + problem + " is a problem file that holds its own settings");
    if (vm.count("measured") || (!deck.empty() && deck != problem))
      throw formats::InputError("give either a problem file (--problem) or DECK MEASURED.unv, not both");
    return estimator::problem_from_file(formats::read_problem(problem));
  }
  if (deck.empty()) throw formats::InputError("no deck: give DECK MEASURED.unv (or --problem FILE)");
  if (is_problem_file(deck)) throw formats::InputError(deck + " is a problem file, not a deck");
  const std::string measured = vm.count("measured") ? vm["measured"].as<std::string>() : "";
  // Assigned, not chosen by ?: (GCC 12 then warns of a maybe-uninitialized Study).
  estimator::Study study;
  if (vm.count("study")) study = estimator::read_study(vm["study"].as<std::string>());
  if (vm.count("frequencies-only")) study.frequencies_only = true;
  if (measured.empty() && study.configurations.empty())
    throw formats::InputError("no measured modes: give MEASURED.unv after the deck (or configurations in --study)");
  return estimator::prepare_problem(study, deck, measured);
}

/// The JSON of a run stopped before its first cycle: the parameters' prior, marked partial.
nlohmann::json partial_problem_json(const estimator::EstimationProblem& problem, const std::string& why) {
  nlohmann::json j;
  if (!problem.title.empty()) j["title"] = problem.title;
  j["converged"] = false;
  j["partial"] = true;
  j["partial_reason"] = why;
  j["iterations"] = nlohmann::json::array();
  j["parameters"] = nlohmann::json::array();
  for (std::size_t k = 0; k < problem.prior.names.size(); ++k) {
    const auto e = static_cast<Eigen::Index>(k);
    nlohmann::json p = {{"name", problem.prior.names[k]},
                        {"initial", problem.prior.mean(e)},
                        {"prior_std", std::sqrt(problem.prior.cov(e, e))}};
    if (k < problem.units.size()) p["unit"] = problem.units[k].unit;
    j["parameters"].push_back(p);
  }
  return j;
}

}  // namespace

int cmd_estimate(const Args& args) {
  po::options_description desc("ssid estimate options");
  desc.add_options()("deck", po::value<std::string>(), "NASTRAN deck with DESVAR parameters")(
      "measured", po::value<std::string>(),
      "measured modes: universal file with dataset 55 (+ nodes 15/2411), the JSON of ssid identify modes (modes with their sigma), or frequencies only (.csv, .txt, .json)")(
      "study", po::value<std::string>(), "study file (JSON, docs/estimation.md): priors, weights, pairing, pairs, configurations")(
      "frequencies-only", "use the measured frequencies only, not the shapes (study \"measurement\": {\"frequencies_only\": true})")(
      "json", po::value<std::string>(), "write the result as JSON to this file ('-' for stdout)")(
      "report", po::value<std::string>(),
      "write an HTML report (MAC, frequencies before and after, parameters, convergence, mode shapes) to this file; "
      "the JSON then also holds the run, geometry and shapes (docs/report.md)")(
      "problem", po::value<std::string>(),
      "estimate from this problem file (ssid translate) instead of DECK MEASURED.unv: imported operators, Taylor model")(
      "quiet,q", "no progress lines on stderr (each cycle's J and frequency error, the time left)");
  desc.add_options()("tam", po::value<std::string>(),
                     "cross-orthogonality at the estimate also with these test-analysis models' masses on the sensor "
                     "DOFs, guyan and/or irs (comma-separated; first configuration; JSON cross_orthogonality_tam)");
  report::add_frf_options(desc,
                          "measured FRFs (universal file, dataset 58) to lay the deck's FRFs at the prior mean and at "
                          "the estimate over (first configuration; JSON frf_comparison, the report's FRF figures)");
  po::positional_options_description pos;
  pos.add("deck", 1).add("measured", 1);
  po::variables_map vm;
  int rc = 0;
  if (!parse_options(args, "ssid estimate DECK MEASURED.unv [--study FILE] [--json FILE] [--report FILE.html] [--frf FRF.unv "
                     "[--frf-damping Z] [--frf-max N]] [--tam guyan,irs] | ssid estimate --problem FILE [--json FILE]",
                     desc, pos, vm, rc))
    return rc;
  if (!vm.count("deck") && !vm.count("problem")) {
    print_error("estimate: give DECK MEASURED.unv, or --problem FILE (ssid estimate --help)");
    return kExitBadInput;
  }
  const std::optional<report::FrfOptions> frf_opt = report::frf_options(vm);
  if (!frf_opt) return kExitBadInput;
  std::vector<std::string> tams;
  if (vm.count("tam") && !report::parse_tams(vm["tam"].as<std::string>(), tams)) return kExitBadInput;
  estimator::EstimationProblem problem = load_problem(vm, true);
  // The measured FRFs before the estimate: a bad file is reported before the cycles run.
  std::optional<formats::uff::UffFile> frf_file;
  if (vm.count("frf")) frf_file = formats::uff::read_uff(vm["frf"].as<std::string>());
  // Both need the deck's geometry and K, M: refused before the cycles, not after.
  if ((frf_file || !tams.empty()) && !problem.configurations.front().fe) {
    print_error(std::string(frf_file ? "--frf" : "--tam") +
                " needs the deck: a problem file's estimate has only its operators' Taylor model (give DECK MEASURED.unv)");
    return kExitBadInput;
  }
  const std::string json_path = vm.count("json") ? vm["json"].as<std::string>() : "";
  const std::string diagnose_args = vm.count("deck") && vm.count("measured")
                                        ? vm["deck"].as<std::string>() + " " + vm["measured"].as<std::string>()
                                        : "DECK MEASURED.unv";
  // Every cycle gets its line (J and the frequency error): cycles take seconds on large models.
  ProgressLines lines("ssid estimate", vm.count("quiet") != 0, 0.0);
  const InterruptFlag interrupt;
  estimator::EstimationResult result;
  try {
    result = estimator::run_problem(problem, lines.callback());
  } catch (const estimator::Interrupted& e) {
    // Stopped before any cycle was accepted: the JSON says so, with the prior.
    const std::string why = std::string(e.what()) + " before the first cycle was complete";
    if (!json_path.empty()) write_json(json_path, partial_problem_json(problem, why));
    print_error("estimate: " + why + ": no estimate" +
                (json_path.empty() || json_path == "-" ? "" : " (" + json_path + " is marked \"partial\": true)"));
    return kExitInterrupted;
  }
  nlohmann::json j = estimator::result_json(problem, result);
  std::vector<std::string> notes;
  if (frf_file)
    j["frf_comparison"] = report::estimate_frf_comparison(
        *frf_file, problem.configurations.front(), problem.prior.mean, result.update.r, frf_opt->zeta_fallback,
        frf_opt->max_frfs, notes);
  if (!tams.empty())
    j["cross_orthogonality_tam"] = report::estimate_tam_json(problem.configurations.front(), result.update.r,
                                                             j["configurations"][0]["pairs"], tams, notes);
  for (const auto& n : notes) std::cerr << "note: " << n << "\n";
  if (vm.count("report")) report::write_estimate_report(vm["report"].as<std::string>(), args, vm, problem, result, j);
  if (json_path == "-") {
    write_json("-", j);
  } else {
    std::cout << estimator::format_summary(problem, result);
    if (j.contains("frf_comparison")) std::cout << "\n" << report::frf_comparison_text(j["frf_comparison"]);
    if (!json_path.empty()) write_json(json_path, j);
  }
  if (!result.partial()) return kExitSuccess;
  const std::string marked =
      json_path.empty() || json_path == "-" ? "" : "; " + json_path + " holds it, marked \"partial\": true";
  if (result.interrupted) {
    print_error("estimate: " + result.partial_reason + ": the result is that of the last accepted cycle" + marked);
    return kExitInterrupted;
  }
  print_error("estimate: " + result.partial_reason + ": the result is not trustworthy" + marked +
              ". If the frequency error stays large or grows while J falls, the model form may be wrong (not only "
              "its parameters): `ssid diagnose " + diagnose_args +
              "` tests model-form extensions (docs/diagnosis.md); otherwise raise \"convergence\": "
              "{\"max_iterations\"} in the study");
  return kExitUntrusted;
}

int cmd_translate(const Args& args) {
  po::options_description desc("ssid translate options");
  desc.add_options()("deck", po::value<std::string>()->required(), "NASTRAN deck with DESVAR parameters")(
      "measured", po::value<std::string>(), "measured modes: universal file with dataset 55")(
      "study", po::value<std::string>(), "study file (JSON): priors, weights, pairing, configurations")(
      "output,o", po::value<std::string>()->required(), "problem file to write");
  po::positional_options_description pos;
  pos.add("deck", 1).add("measured", 1);
  po::variables_map vm;
  int rc = 0;
  if (!parse_options(args, "ssid translate DECK MEASURED.unv [--study FILE] -o PROBLEM", desc, pos, vm, rc)) return rc;
  const estimator::EstimationProblem problem = load_problem(vm, false);
  const formats::ProblemFile file = estimator::to_problem_file(problem);
  const std::string out = vm["output"].as<std::string>();
  formats::write_problem(out, file);
  std::size_t modes = 0, dofs = 0;
  for (const auto& c : file.configurations) {
    modes += c.measured.size();
    dofs += c.dofs.size();
  }
  std::cout << "wrote " << out << " (problem file version " << formats::ProblemFile::version << "): "
            << file.parameters.size() << " parameter(s), " << file.configurations.size() << " configuration(s), "
            << dofs << " analysis DOFs, " << modes << " measured mode(s)\n";
  for (const auto& c : problem.configurations)
    for (const auto& n : c.notes) std::cerr << "note: " << n << "\n";
  return 0;
}

int cmd_update_deck(const Args& args) {
  po::options_description desc("ssid update-deck options");
  desc.add_options()("deck", po::value<std::string>()->required(), "NASTRAN deck with DESVAR parameters")(
      "result", po::value<std::string>()->required(),
      "JSON with \"parameters\": [{\"name\": DESVAR label, \"estimate\": value}] (ssid estimate --json)")(
      "output,o", po::value<std::string>()->required(), "updated deck to write (never an input file)");
  po::positional_options_description pos;
  pos.add("deck", 1).add("result", 1);
  po::variables_map vm;
  int rc = 0;
  if (!parse_options(args, "ssid update-deck DECK RESULT.json -o NEW.bdf", desc, pos, vm, rc)) return rc;
  const std::string result_path = vm["result"].as<std::string>();
  std::ifstream in(result_path, std::ios::binary);
  if (!in) throw formats::InputError(result_path + ": cannot open");
  std::stringstream ss;
  ss << in.rdbuf();
  const auto values = translators::parameter_values_from_json(ss.str(), result_path);
  formats::Deck deck = formats::read_deck(vm["deck"].as<std::string>());
  const translators::DeckUpdateReport rep = translators::update_deck(deck, values);
  const auto written = formats::write_deck(deck, vm["output"].as<std::string>());
  for (const auto& p : rep.parameters) std::cout << "DESVAR " << p << "\n";
  std::size_t desvar_fields = 0;
  for (const auto& f : rep.fields) desvar_fields += f.rfind("DESVAR", 0) == 0;
  std::cout << rep.fields.size() << " field(s) changed (" << desvar_fields << " DESVAR XINIT, "
            << rep.fields.size() - desvar_fields << " designed through DVPREL1/DVMREL1) on " << rep.cards_changed
            << " card(s); wrote";
  for (const auto& w : written) std::cout << " " << w;
  std::cout << "\n";
  return 0;
}

}  // namespace ssid::cli
