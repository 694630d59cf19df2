#pragma once
/// \file cli_util.hpp
/// Helpers shared by the subcommands: option parsing, JSON output, errors.
#include <boost/program_options.hpp>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "cli/commands.hpp"

namespace ssid::cli {

namespace po = boost::program_options;

/// Parses `args` with `desc` and positional names; prints help and returns false
/// (with `exit_code` set) when --help was given or parsing failed.
bool parse_options(const Args& args, const std::string& usage, po::options_description& desc,
                   const po::positional_options_description& pos, po::variables_map& vm, int& exit_code);

/// Writes JSON to a file (pretty-printed); "-" writes to stdout.
void write_json(const std::string& path, const nlohmann::json& j);

/// Prints "ssid: error: msg" to stderr.
void print_error(const std::string& message);

/// Where a command's readable text goes: stdout, or nowhere when `--json -` (or
/// `json_path` "-") makes stdout the JSON's, which the text would corrupt.
class TextOut {
 public:
  explicit TextOut(const po::variables_map& vm)
      : TextOut(vm.count("json") ? vm["json"].as<std::string>() : std::string()) {}
  explicit TextOut(const std::string& json_path) : m_discard(json_path == "-") {}
  std::ostream& stream() { return m_discard ? m_sink : std::cout; }

 private:
  bool m_discard;
  std::ostringstream m_sink;
};

}  // namespace ssid::cli
