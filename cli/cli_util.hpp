#pragma once
/// \file cli_util.hpp
/// Helpers shared by the subcommands: option parsing, JSON output, errors.
#include <boost/program_options.hpp>
#include <nlohmann/json.hpp>
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

}  // namespace ssid::cli
