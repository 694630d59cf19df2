#pragma once
/// \file commands.hpp
/// The subcommands of `ssid`. Each takes its arguments (after the subcommand
/// name) and returns the process exit code of cli/exit_codes.hpp (errors it
/// throws are mapped to theirs by main.cpp). Only the CLI prints; the libraries
/// return values.
#include <string>
#include <vector>

namespace ssid::cli {

using Args = std::vector<std::string>;

struct Command {
  const char* name;
  const char* summary;
  int (*run)(const Args& args);
};

/// All subcommands, in the order `ssid --help` lists them.
const std::vector<Command>& commands();

int cmd_deck(const Args& args);
int cmd_uff(const Args& args);
int cmd_correlate(const Args& args);
int cmd_truss(const Args& args);
int cmd_op4(const Args& args);
int cmd_dmig(const Args& args);
int cmd_modes(const Args& args);
int cmd_assemble(const Args& args);
int cmd_estimate(const Args& args);
int cmd_translate(const Args& args);
int cmd_update_deck(const Args& args);
int cmd_diagnose(const Args& args);
int cmd_identify(const Args& args);
int cmd_pretest(const Args& args);
int cmd_frf(const Args& args);

}  // namespace ssid::cli
