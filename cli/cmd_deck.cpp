/// \file cmd_deck.cpp
/// `ssid deck summary|write`.
#include <iostream>

#include "cli/cli_util.hpp"
#include "cli/exit_codes.hpp"
#include "formats/bulk_catalogue.hpp"
#include "formats/bulk_model.hpp"
#include "formats/deck_writer.hpp"

namespace ssid::cli {

namespace {

int deck_summary(const Args& args) {
  po::options_description desc("ssid deck summary options");
  desc.add_options()("deck", po::value<std::string>()->required(), "NASTRAN input file")(
      "json", po::value<std::string>(), "write the summary as JSON to this file ('-' for stdout)");
  po::positional_options_description pos;
  pos.add("deck", 1);
  po::variables_map vm;
  int rc = 0;
  if (!parse_options(args, "ssid deck summary DECK [--json FILE]", desc, pos, vm, rc)) return rc;

  const std::string path = vm["deck"].as<std::string>();
  formats::Deck deck = formats::read_deck(path);
  formats::BulkModel model = formats::parse_bulk(deck);
  formats::resolve(deck, model);
  std::vector<formats::Problem> problems = deck.problems;
  problems.insert(problems.end(), model.problems.begin(), model.problems.end());

  std::map<std::string, std::size_t> counts;
  for (const auto& c : deck.cards) ++counts[c.name];
  std::size_t errors = 0;
  for (const auto& p : problems) errors += p.severity == formats::Problem::Severity::Error;

  nlohmann::json j;
  j["files"] = nlohmann::json::array();
  for (const auto& f : deck.files) j["files"].push_back(f.path);
  j["cards"] = counts;
  j["typed"] = model.supported;
  j["unsupported"] = model.unsupported;
  j["unknown"] = nlohmann::json::array();  // names that are no bulk data entry (each card an error)
  for (const auto& [name, n] : model.unsupported)
    if (!formats::is_bulk_entry_name(name)) j["unknown"].push_back(name);
  j["problems"] = nlohmann::json::array();
  for (const auto& p : problems) j["problems"].push_back(p.str());
  j["total_cards"] = deck.cards.size();
  j["partitions"] = nlohmann::json::array();  // BEGIN SUPER = n ... : bulk data kept verbatim
  for (const auto& st : deck.statements)
    if (st.section == formats::Section::Bulk)
      j["partitions"].push_back({{"statement", st.text}, {"at", deck.location(st.file, st.line).str()}});

  if (vm.count("json") && vm["json"].as<std::string>() == "-") {
    write_json("-", j);
  } else {
    std::cout << "deck " << path << ": " << deck.cards.size() << " bulk data cards in " << deck.files.size()
              << " file(s)\n";
    for (const auto& f : deck.files)
      std::cout << "  file " << f.path << (f.include_name.empty() ? "" : " (INCLUDE '" + f.include_name + "')")
                << "\n";
    std::cout << "cards:\n";
    for (const auto& [name, n] : counts)
      std::cout << "  " << name << std::string(name.size() < 10 ? 10 - name.size() : 1, ' ') << n
                << (!model.unsupported.count(name)            ? "  (typed)"
                    : formats::is_bulk_entry_name(name) ? "  (kept verbatim)"
                                                        : "  (unknown name: an error)")
                << "\n";
    std::size_t typed = 0;
    for (const auto& [name, n] : model.supported) typed += n;
    std::cout << "typed: " << typed << " card(s) of " << model.supported.size() << " type(s)\n";
    std::size_t verbatim = 0;
    for (const auto& [name, n] : model.unsupported) verbatim += n;
    std::cout << "kept verbatim (no typed parser): " << verbatim << " card(s) of " << model.unsupported.size()
              << " type(s)\n";
    for (const auto& st : deck.statements)
      if (st.section == formats::Section::Bulk)
        std::cout << "partition " << st.text << " at " << deck.location(st.file, st.line).str()
                  << ": its bulk data kept verbatim, not read (ssid modes refuses it)\n";
    std::cout << "problems: " << problems.size() << " (" << errors << " error(s), " << problems.size() - errors
              << " warning(s); listed on stderr)\n";
    if (vm.count("json")) write_json(vm["json"].as<std::string>(), j);
  }
  // One write: std::cerr is unbuffered, and a broken deck can have a million problems.
  std::string report;
  for (const auto& p : problems) report += p.str() + "\n";
  std::cerr << report << std::flush;
  // A summary that lists errors is a deck the other commands refuse: bad input.
  return errors ? kExitBadInput : kExitSuccess;
}

int deck_write(const Args& args) {
  po::options_description desc("ssid deck write options");
  desc.add_options()("deck", po::value<std::string>()->required(), "NASTRAN input file")(
      "output,o", po::value<std::string>()->required(), "output file (INCLUDEd files are written beside it)");
  po::positional_options_description pos;
  pos.add("deck", 1);
  po::variables_map vm;
  int rc = 0;
  if (!parse_options(args, "ssid deck write DECK -o OUT", desc, pos, vm, rc)) return rc;
  formats::Deck deck = formats::read_deck(vm["deck"].as<std::string>());
  for (const auto& p : deck.problems) std::cerr << p.str() << "\n";
  auto written = formats::write_deck(deck, vm["output"].as<std::string>());
  for (const auto& w : written) std::cout << "wrote " << w << "\n";
  return 0;
}

}  // namespace

int cmd_deck(const Args& args) {
  const std::string usage =
      "usage: ssid deck <summary|write> ...\n"
      "  summary DECK [--json FILE]   card counts, cards kept verbatim, files read, problems\n"
      "  write DECK -o OUT            parse and write back (unchanged cards byte for byte)\n";
  if (args.empty() || args[0] == "--help" || args[0] == "-h") {
    (args.empty() ? std::cerr : std::cout) << usage;
    return args.empty() ? 2 : 0;
  }
  Args rest(args.begin() + 1, args.end());
  if (args[0] == "summary") return deck_summary(rest);
  if (args[0] == "write") return deck_write(rest);
  std::cerr << "ssid deck: unknown subcommand '" << args[0] << "'\n" << usage;
  return 2;
}

}  // namespace ssid::cli
