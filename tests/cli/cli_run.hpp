#pragma once
/// Runs the built `ssid` with arguments and captures exit code, stdout and stderr.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <sys/wait.h>

struct CliResult {
  int code = -1;
  std::string out, err;
};

inline std::string cli_slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

/// `args` is appended to the ssid path as is (quote paths with spaces yourself).
inline CliResult run_ssid(const std::string& args) {
  namespace fs = std::filesystem;
  static int counter = 0;
  const fs::path dir = fs::temp_directory_path() / ("ssid_cli_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path o = dir / ("out" + std::to_string(counter)), e = dir / ("err" + std::to_string(counter++));
  const std::string cmd = std::string(SSID_EXE) + " " + args + " >" + o.string() + " 2>" + e.string();
  const int status = std::system(cmd.c_str());
  CliResult r;
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = cli_slurp(o);
  r.err = cli_slurp(e);
  return r;
}
