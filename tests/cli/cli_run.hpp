#pragma once
/// Runs the built `ssid` with arguments and captures exit code, stdout and stderr.
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <string>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>
#include <vector>

struct CliResult {
  int code = -1;
  std::string out, err;
};

inline std::string cli_slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

/// A test file's scratch folder, TMP/ssid_cli_<tag>_<pid>, created: per process so
/// that ctest's parallel runs of the same executable do not share files.
inline std::filesystem::path cli_scratch(const std::string& tag) {
  const auto dir = std::filesystem::temp_directory_path() / ("ssid_cli_" + tag + "_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  return dir;
}

/// `args` is appended to the ssid path as is (quote paths with spaces yourself).
inline CliResult run_ssid(const std::string& args) {
  namespace fs = std::filesystem;
  static int counter = 0;
  const fs::path dir = cli_scratch("run");
  const fs::path o = dir / ("out" + std::to_string(counter)), e = dir / ("err" + std::to_string(counter++));
  const std::string cmd = std::string(SSID_EXE) + " " + args + " >" + o.string() + " 2>" + e.string();
  const int status = std::system(cmd.c_str());
  CliResult r;
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = cli_slurp(o);
  r.err = cli_slurp(e);
  return r;
}

/// A running ssid (start_ssid), its output going to two files.
struct RunningSsid {
  pid_t pid = -1;
  std::filesystem::path out, err;
  bool ended = false;  ///< reaped already (by wait_for_stderr), with `status`
  int status = 0;
};

/// Starts ssid with `args` (each one argument, no shell), stdout and stderr to files.
inline RunningSsid start_ssid(const std::vector<std::string>& args) {
  namespace fs = std::filesystem;
  static int counter = 0;
  const fs::path dir = cli_scratch("run");
  RunningSsid r;
  r.out = dir / ("bg_out" + std::to_string(counter));
  r.err = dir / ("bg_err" + std::to_string(counter++));
  std::vector<std::string> argv_s{SSID_EXE};
  argv_s.insert(argv_s.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : argv_s) argv.push_back(a.data());
  argv.push_back(nullptr);
  r.pid = ::fork();
  if (r.pid == 0) {
    const int o = ::open(r.out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int e = ::open(r.err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ::dup2(o, 1);
    ::dup2(e, 2);
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
  return r;
}

/// Waits until `needle` appears in the run's stderr (true), or the run ends or
/// `timeout_s` passes (false). Polls: the run's pace decides, not a fixed delay.
inline bool wait_for_stderr(RunningSsid& r, const std::string& needle, double timeout_s) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  while (std::chrono::steady_clock::now() < end) {
    if (cli_slurp(r.err).find(needle) != std::string::npos) return true;
    if (::waitpid(r.pid, &r.status, WNOHANG) == r.pid) {  // ended before the line came
      r.ended = true;
      return cli_slurp(r.err).find(needle) != std::string::npos;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return false;
}

/// Waits (at most `timeout_s`, then kills it) for the run; code 128 + n when a signal n ended it.
inline CliResult wait_ssid(const RunningSsid& r, double timeout_s) {
  CliResult out;
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  int status = r.status;
  pid_t got = r.ended ? r.pid : 0;
  while (got == 0 && (got = ::waitpid(r.pid, &status, WNOHANG)) == 0 && std::chrono::steady_clock::now() < end)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  if (got == 0) {  // still running: the test fails on the code, and leaves no process behind
    ::kill(r.pid, SIGKILL);
    ::waitpid(r.pid, &status, 0);
  }
  if (got > 0) out.code = WIFEXITED(status) ? WEXITSTATUS(status) : WIFSIGNALED(status) ? 128 + WTERMSIG(status) : -1;
  out.out = cli_slurp(r.out);
  out.err = cli_slurp(r.err);
  return out;
}
