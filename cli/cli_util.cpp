#include "cli/cli_util.hpp"

#include <fstream>
#include <iostream>
#include <stdexcept>

#include "cli/exit_codes.hpp"
#include "formats/parse_error.hpp"

namespace ssid::cli {

bool parse_options(const Args& args, const std::string& usage, po::options_description& desc,
                   const po::positional_options_description& pos, po::variables_map& vm, int& exit_code) {
  desc.add_options()("help,h", "show this help");
  try {
    po::store(po::command_line_parser(args).options(desc).positional(pos).run(), vm);
    if (vm.count("help")) {
      std::cout << "usage: " << usage << "\n\n" << desc << "\n" << kExitCodesHelp;
      exit_code = kExitSuccess;
      return false;
    }
    po::notify(vm);
  } catch (const po::error& e) {
    std::cerr << "ssid: " << e.what() << "\nusage: " << usage << "\n(try --help)\n";
    exit_code = kExitBadInput;
    return false;
  }
  return true;
}

void write_json(const std::string& path, const nlohmann::json& j) {
  if (path == "-") {
    std::cout << j.dump(2) << "\n";
    return;
  }
  std::ofstream o(path);
  if (!o) throw formats::InputError("cannot write " + path);
  o << j.dump(2) << "\n";
}

void print_error(const std::string& message) { std::cerr << "ssid: error: " << message << "\n"; }

}  // namespace ssid::cli
