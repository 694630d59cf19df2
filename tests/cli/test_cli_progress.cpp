// Exit codes that mean something, progress lines with the time left, --quiet,
// and Ctrl-C (SIGINT) leaving the partial JSON: `ssid estimate` and
// `ssid diagnose` on the shipped rod sample (samples/mpi_rod.bdf and its
// measured modes, samples/estimate/measured.unv).
#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>
#include <unistd.h>

#include "cli/exit_codes.hpp"
#include "cli/progress_lines.hpp"
#include "cli_run.hpp"

namespace fs = std::filesystem;
using json = nlohmann::json;
using ssid::estimator::ProgressEvent;

namespace {

fs::path scratch() { return cli_scratch("progress"); }

const std::string kDeck = std::string(SSID_SOURCE_DIR) + "/samples/mpi_rod.bdf";
const std::string kMeasured = std::string(SSID_SOURCE_DIR) + "/samples/estimate/measured.unv";

/// The sample study with its convergence settings replaced.
fs::path study_with(const json& convergence, const std::string& name) {
  json s = json::parse(cli_slurp(std::string(SSID_SOURCE_DIR) + "/samples/estimate/study.json"));
  s["convergence"] = convergence;
  const fs::path p = scratch() / name;
  std::ofstream(p) << s.dump(1);
  return p;
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) out.push_back(l);
  return out;
}

/// The lines of `text` that start with `prefix`.
std::vector<std::string> starting(const std::string& text, const std::string& prefix) {
  std::vector<std::string> out;
  for (const auto& l : lines_of(text))
    if (l.rfind(prefix, 0) == 0) out.push_back(l);
  return out;
}

ProgressEvent counted(const std::string& phase, long done, long total, const std::string& detail = "",
                      bool bound = false) {
  ProgressEvent e;
  e.phase = phase;
  e.done = done;
  e.total = total;
  e.detail = detail;
  e.total_is_bound = bound;
  return e;
}

}  // namespace

TEST_CASE("progress lines: counts, time elapsed and left, in words people read", "[cli][progress]") {
  using ssid::cli::duration_text;
  CHECK(duration_text(0.4) == "0 s");
  CHECK(duration_text(35.2) == "35 s");
  CHECK(duration_text(105) == "1 min 45 s");
  CHECK(duration_text(3600 + 5 * 60 + 20) == "1 h 5 min");
  const ssid::cli::ProgressLines p("ssid diagnose", false, 2.0);
  // 120 of 480 in 35 s: 360 more at the same pace take 105 s.
  CHECK(p.line(counted("screening candidates", 120, 480), 35.0) ==
        "ssid diagnose: screening candidates 120/480, 35 s elapsed, ~1 min 45 s left");
  CHECK(p.line(counted("screening candidates", 480, 480), 140.0) ==
        "ssid diagnose: screening candidates 480/480, 2 min 20 s elapsed");
  CHECK(p.line(counted("testing candidates", 0, 12, "missing_mass at GRID 29"), 0.0) ==
        "ssid diagnose: testing candidates 0/12: missing_mass at GRID 29 (0 s elapsed)");
  // An iteration limit is a bound: so is the time left.
  CHECK(p.line(counted("cycle", 4, 21, "J = 12.5", true), 8.0) ==
        "ssid diagnose: cycle 4 of at most 21: J = 12.5 (8 s elapsed, at most ~34 s left)");
  // A count without a known end: no time left.
  CHECK(p.line(counted("Lanczos solves", 450, -1), 75.0) == "ssid diagnose: Lanczos solves 450, 1 min 15 s elapsed");
  ProgressEvent phase;
  phase.phase = "ordinary update of the deck's parameters";
  CHECK(p.line(phase, 3.0) == "ssid diagnose: ordinary update of the deck's parameters");
}

TEST_CASE("ssid estimate: not converged exits 3, says why, suggests ssid diagnose, marks the JSON partial",
          "[cli][estimate][progress]") {
  const fs::path dir = scratch(), result = dir / "short.json";
  const fs::path study = study_with({{"max_iterations", 1}, {"tolerance", 1e-4}}, "short.json.study");
  const auto r = run_ssid("estimate " + kDeck + " " + kMeasured + " --study " + study.string() + " --json " + result.string());
  INFO(r.err);
  CHECK(r.code == ssid::cli::kExitUntrusted);
  CHECK(r.code == 3);
  CHECK_THAT(r.out, Catch::StartsWith("NOT converged after 2 cycle(s); operators exact\n"
                                      "PARTIAL RESULT (not converged after 2 cycle(s)): the values below are those of "
                                      "the last accepted cycle, not an estimate to trust\n"));
  const std::string error =
      "ssid: error: estimate: not converged after 2 cycle(s): the result is not trustworthy; " + result.string() +
      " holds it, marked \"partial\": true. If the frequency error stays large or grows while J falls, the model "
      "form may be wrong (not only its parameters): `ssid diagnose " + kDeck + " " + kMeasured +
      "` tests model-form extensions (docs/diagnosis.md); otherwise raise \"convergence\": {\"max_iterations\"} in "
      "the study\n";
  CHECK_THAT(r.err, Catch::EndsWith(error));
  const json j = json::parse(cli_slurp(result));
  CHECK(j["partial"] == true);
  CHECK(j["converged"] == false);
  CHECK(j["partial_reason"] == "not converged after 2 cycle(s)");
  CHECK(j["iterations"].size() == 2);

  // Progress: one line per cycle, with J explained, the frequency error and the time left.
  const auto cycles = starting(r.err, "ssid estimate: cycle ");
  REQUIRE(cycles.size() >= 2);
  const std::regex line(
      R"(ssid estimate: cycle [12] of at most 2: J = [0-9.e+-]+ \(data misfit [0-9.e+-]+, prior [0-9.e+-]+\), )"
      R"(frequency RMS error [0-9.e+-]+ %, [0-9]+ pairs \([0-9]+ s elapsed(, at most ~[0-9]+ s left)?\))");
  for (const auto& l : cycles)
    if (l.find("trial point rejected") == std::string::npos) CHECK(std::regex_match(l, line));

  // --quiet: the error line alone.
  const auto q = run_ssid("estimate " + kDeck + " " + kMeasured + " --study " + study.string() + " --json " +
                          result.string() + " --quiet");
  CHECK(q.code == 3);
  CHECK(q.err == error);
  CHECK(q.out == r.out);
}

TEST_CASE("ssid estimate: Ctrl-C leaves the partial JSON (last accepted cycle) and exits 130", "[cli][estimate][progress]") {
  const fs::path dir = scratch(), result = dir / "interrupted.json";
  fs::remove(result);
  // A run that would last for hours: 100000 cycles to a tolerance never met.
  const fs::path study = study_with({{"max_iterations", 100000}, {"tolerance", 1e-300}}, "long.study.json");
  RunningSsid run = start_ssid({"estimate", kDeck, kMeasured, "--study", study.string(), "--json", result.string()});
  // Two cycles accepted (their lines printed), however slow the machine.
  const bool running = wait_for_stderr(run, "ssid estimate: cycle 2 of at most 100001", 300);
  if (running) ::kill(run.pid, SIGINT);
  const CliResult r = wait_ssid(run, 300);
  INFO(r.err);
  REQUIRE(running);
  CHECK(r.code == ssid::cli::kExitInterrupted);
  CHECK(r.code == 130);
  CHECK_THAT(r.out, Catch::StartsWith("INTERRUPTED after "));
  const json j = json::parse(cli_slurp(result));
  CHECK(j["partial"] == true);
  CHECK(j["converged"] == false);
  const std::string reason = j["partial_reason"];
  CHECK(std::regex_match(reason, std::regex(R"(interrupted \(Ctrl-C\) after [0-9]+ cycle\(s\))")));
  const auto cycles = j["iterations"].size();
  CHECK(cycles >= 2);
  CHECK(reason == "interrupted (Ctrl-C) after " + std::to_string(cycles) + " cycle(s)");
  // The parameters are the last accepted cycle's, with their posterior.
  REQUIRE(j["parameters"].size() == 5);
  const json& last = j["iterations"].back();
  for (const auto& p : j["parameters"]) {
    CHECK(p["estimate"] == last["parameters"][p["name"].get<std::string>()]);
    CHECK(p["posterior_std"].get<double>() > 0);
  }
  CHECK_THAT(r.err, Catch::EndsWith("ssid: error: estimate: " + reason +
                                    ": the result is that of the last accepted cycle; " + result.string() +
                                    " holds it, marked \"partial\": true\n"));
}

TEST_CASE("ssid diagnose: long phases report counts; Ctrl-C leaves the partial JSON and exits 130",
          "[cli][diagnose][progress]") {
  const fs::path dir = scratch(), result = dir / "diagnosis.json";
  fs::remove(result);
  RunningSsid run = start_ssid({"diagnose", kDeck, kMeasured, "--shortlist", "10", "--json", result.string()});
  // Interrupted among the candidates' re-estimation: the ordinary update and the screening are done.
  const bool running = wait_for_stderr(run, "ssid diagnose: testing candidates 0/", 600);
  if (running) ::kill(run.pid, SIGINT);
  const CliResult r = wait_ssid(run, 300);
  INFO(r.err);
  REQUIRE(running);
  CHECK(r.code == 130);
  const auto err = lines_of(r.err);
  REQUIRE(!err.empty());
  CHECK(err.front() == "ssid diagnose: ordinary update of the deck's parameters");
  CHECK(std::regex_search(r.err, std::regex(R"(\nssid diagnose: ordinary update: cycle 1 of at most 21: J = )")));
  CHECK(std::regex_search(
      r.err, std::regex(R"(\nssid diagnose: screening candidates ([0-9]+)/\1, [0-9]+ s elapsed\n)")));
  CHECK(std::regex_search(r.err, std::regex(R"(\nssid diagnose: testing candidates 0/[0-9]+: [a-z_]+ at )")));
  const json j = json::parse(cli_slurp(result));
  CHECK(j["partial"] == true);
  const std::string reason = j["partial_reason"];
  CHECK(std::regex_match(reason, std::regex(R"(interrupted \(Ctrl-C\) while testing candidates \([0-9]+ of [0-9]+ tested\))")));
  // The ranking holds the ordinary update and the candidates tested before the interruption.
  REQUIRE(j["ranking"].size() >= 1);
  bool parameter = false;
  for (const auto& h : j["ranking"]) parameter = parameter || h["kind"] == "parameter";
  CHECK(parameter);
  CHECK_THAT(r.err, Catch::EndsWith("ssid: error: diagnose: " + reason +
                                    ": the ranking holds the hypotheses tested so far; " + result.string() +
                                    " is marked \"partial\": true\n"));
}
