#pragma once
/// \file exit_codes.hpp
/// What `ssid`'s exit status means (README "Exit codes"). Scripts rely on these.

namespace ssid::cli {

enum ExitCode : int {
  kExitSuccess = 0,      ///< the command did what was asked and the result can be trusted
  kExitFailure = 1,      ///< ssid itself failed (a bug): the message says so
  kExitBadInput = 2,     ///< bad input: an option, a file, a model; nothing was computed from it
  kExitUntrusted = 3,    ///< it ran, but the result is not trustworthy (did not converge, partial)
  kExitInterrupted = 130 ///< stopped by Ctrl-C (SIGINT); partial results are marked as partial
};

/// The epilogue of every command's --help (and of README's "Exit codes").
inline constexpr const char* kExitCodesHelp =
    "exit status: 0 success; 1 ssid failed (a bug: please report it); 2 bad input (an option, a file, a\n"
    "model: the message names it; nothing was computed); 3 it ran, but the result is not trustworthy (not\n"
    "converged, stopped early: JSON marked \"partial\": true); 130 interrupted by Ctrl-C (JSON marked partial)\n";

}  // namespace ssid::cli
