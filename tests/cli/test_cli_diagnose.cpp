// `ssid diagnose` end to end: a nominal rod-truss deck and a "measured" UFF of a
// truth with a hidden mass; the JSON layout of the issue, the report, the
// written deck (the new DESVAR at the estimate); bad input refused clearly.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "formats/bulk_model.hpp"
#include "estimator/study/deck_study.hpp"
#include "formats/uff.hpp"
#include "tests/cli/cli_run.hpp"
#include "tests/estimator/diagnosis/truss_cases.hpp"

namespace fs = std::filesystem;
using namespace ssid;
using namespace ssid::test_support;

TEST_CASE("ssid diagnose: hidden mass found, JSON layout, extended deck written", "[cli][diagnose]") {
  const fs::path dir = cli_scratch("diag");
  const Case nominal = rod_case();
  {
    std::ofstream(dir / "rod.bdf") << deck_text(nominal.t, nominal.fe);
  }
  Case truth = rod_case();
  truth.fe.masses.push_back({9001, 29, 2.0, 0.0, "hidden"});
  TestSpec spec;
  spec.seed = 3;
  formats::uff::write_uff(translators::mode_set_to_uff(synthetic_test(truth.fe, spec)), (dir / "test.unv").string());

  const auto r = run_ssid("diagnose " + (dir / "rod.bdf").string() + " " + (dir / "test.unv").string() +
                              " --kinds missing_mass,local_stiffness --json " + (dir / "d.json").string() + " -o " +
                              (dir / "out").string());
  CAPTURE(r.out, r.err);
  REQUIRE(r.code == 0);
  CHECK(r.out.find("Cause: missing_mass") != std::string::npos);
  CHECK(r.out.find("Gain:") != std::string::npos);
  const auto j = nlohmann::json::parse(cli_slurp(dir / "d.json"));
  CHECK(j["cause"]["kind"] == "missing_mass");
  CHECK(j["cause"]["location"]["grids"][0] == 29);
  for (const char* k : {"grids", "elements", "properties"}) CHECK(j["cause"]["location"].contains(k));
  const double value = j["cause"]["value"], sd = j["cause"]["std"];
  CHECK(std::abs(value - 2.0) < std::max(3 * sd, 0.2));
  CHECK(j["cause"]["summary"].is_string());
  REQUIRE(j["ranking"].size() >= 2);
  for (const auto& h : j["ranking"])
    for (const char* k : {"kind", "location", "log_evidence", "freq_rms_pct", "mean_mac"}) CHECK(h.contains(k));
  CHECK(j["gain"]["after"]["freq_rms_pct"] < j["gain"]["before"]["freq_rms_pct"]);
  // The calibrated decision's figures: the noise the data imply, the test of
  // what is left, the cause's false-alarm probability and held-out gain.
  CHECK(j["noise"]["mode"] == "estimated");
  CHECK(j["noise"]["frequency"]["assumed_pct"] == 1.0);  // the default shared with ssid estimate (issue 26)
  CHECK(j["noise"]["shape"]["implied_pct"].is_number());
  CHECK(j["noise"]["shape"]["implied_with_cause_pct"].is_number());
  CHECK(j["residual_test"]["consistent"] == false);
  CHECK(j["residual_test"]["replicates"] == 199);
  CHECK(j["residual_test"]["p"] <= 0.01);
  CHECK(j["cause"]["false_alarm_p"] <= 0.01);
  CHECK(j["cause"]["held_out_gain"] > 0);
  CHECK(j["cause"]["why"] == "named");
  CHECK(r.out.find("anything left to explain? something is left to explain: ") != std::string::npos);
  CHECK(r.out.find("false-alarm p") != std::string::npos);
  CHECK(j["gain"]["after"]["paired"] >= j["gain"]["before"]["paired"]);
  const std::string deck = j["deck"];
  REQUIRE(fs::exists(deck));
  // The written deck holds the new DESVAR at the estimate and assembles.
  const std::string text = cli_slurp(deck);
  formats::Deck d = formats::read_deck_text(text, deck);
  const formats::BulkModel b = formats::resolved_bulk(d);
  bool found = false;
  for (const auto& dv : b.desvars)
    if (dv.label == "XM29") {
      found = true;
      CHECK(dv.xinit == Approx(value).epsilon(1e-6));
    }
  CHECK(found);
  bool conm2 = false;
  for (const auto& m : b.conm2s) conm2 = conm2 || (m.g == 29 && m.m == Approx(value).epsilon(1e-6) && m.eid > 8000);
  CHECK(conm2);
  // Too few replicates to show the 1 % target: refused, with what would do.
  const auto few = run_ssid("diagnose " + (dir / "rod.bdf").string() + " " + (dir / "test.unv").string() + " --replicates 50");
  CHECK(few.code == 2);
  CHECK(few.err.find("diagnose: 50 bootstrap replicates cannot show a false-alarm probability of 0.01 or less (the smallest "
                     "is 1/(replicates + 1)); use at least 99") != std::string::npos);
  // A false-alarm level that is not a probability: refused before any work.
  const auto one = run_ssid("diagnose " + (dir / "rod.bdf").string() + " " + (dir / "test.unv").string() + " --false-alarm 1");
  CHECK(one.code == 2);
  CHECK(one.err.find("diagnose: the false-alarm target must lie between 0 and 1, got 1") != std::string::npos);
  // One too small for any practical bootstrap: the replicates it would need, as a number.
  const auto tiny = run_ssid("diagnose " + (dir / "rod.bdf").string() + " " + (dir / "test.unv").string() + " --false-alarm 1e-300");
  CHECK(tiny.code == 2);
  CHECK(tiny.err.find("or less (the smallest is 1/(replicates + 1)); no replicate count can (it would need 1e+300)") !=
        std::string::npos);
  // The same file read for its frequencies only: no shape noise is implied or
  // tested (there are no shape rows), and none is printed.
  const auto fo = run_ssid("diagnose " + (dir / "rod.bdf").string() + " " + (dir / "test.unv").string() +
                           " --frequencies-only --kinds missing_mass --shortlist 1");
  CAPTURE(fo.out, fo.err);
  REQUIRE((fo.code == 0 || fo.code == 3));
  CHECK(fo.out.find("degrees of freedom; no shapes measured)") != std::string::npos);
  CHECK(fo.out.find("% of the RMS component") == std::string::npos);
  CHECK(fo.out.find("shape chi^2") == std::string::npos);
  CHECK(fo.err.find("no shapes measured)") != std::string::npos);
  fs::remove_all(dir);
}

TEST_CASE("ssid diagnose: bad input is refused with a clear message", "[cli][diagnose][errors]") {
  const auto missing = run_ssid("diagnose /nonexistent/deck.bdf /nonexistent/test.unv");
  CHECK(missing.code == 2);
  CHECK(missing.err.find("/nonexistent/deck.bdf") != std::string::npos);
  const auto kind = run_ssid("diagnose a.bdf b.unv --kinds gravity");
  CHECK(kind.code == 2);
  CHECK(kind.err.find("unknown extension kind") != std::string::npos);
  const fs::path study = cli_scratch("diag_study") / "study.json";
  // One study file for estimate and diagnose: errors by key path.
  std::ofstream(study) << R"({"diagnosis": {"kinds": ["missing_mass"], "shortlist": 2}, "frequency_std": 0.3})";
  const auto bad = run_ssid("diagnose a.bdf b.unv --study " + study.string());
  CHECK(bad.code == 2);
  CHECK_THAT(bad.err, Catch::Contains(study.string() + ": frequency_std: unknown key (allowed here: "));
  std::ofstream(study) << R"({"diagnosis": {"shortlist": "two"}})";
  const auto bad_type = run_ssid("diagnose a.bdf b.unv --study " + study.string());
  CHECK(bad_type.code == 2);
  CHECK_THAT(bad_type.err, Catch::Contains(study.string() + ": diagnosis.shortlist: expected an integer, got \"two\""));
  std::ofstream(study) << "{\"kinds\": [";
  const auto broken = run_ssid("diagnose a.bdf b.unv --study " + study.string());
  CHECK(broken.code == 2);
  CHECK(broken.err.find("not valid JSON") != std::string::npos);
  fs::remove(study);
  const auto noise = run_ssid("diagnose a.bdf b.unv --noise guessed");
  CHECK(noise.code == 2);
  CHECK(noise.err.find("--noise: expected \"estimated\" or \"given\", got \"guessed\"") != std::string::npos);
  const auto help = run_ssid("diagnose --help");
  CHECK(help.code == 0);
  CHECK(help.out.find("--study") != std::string::npos);
}

TEST_CASE("ssid diagnose's \"parameter\" hypothesis is ssid estimate's result on the same study", "[cli][diagnose][study]") {
  // One estimation problem, one study file: the same deck, data and study give
  // the same estimates, covariance and evidence (issue 26 item 1).
  const fs::path dir = cli_scratch("diag_same");
  std::ofstream(dir / "study.json") << R"({"measurement": {"frequency_std_pct": 0.8, "shape_std_pct": 4},
      "priors": {"STRUTA": {"std_pct": 20}}, "modes": {"exclude": [12]},
      "convergence": {"max_iterations": 60, "tolerance": 1e-3},
      "diagnosis": {"kinds": ["missing_mass"], "shortlist": 1, "noise": "given"}})";
  const std::string args = std::string(SSID_SOURCE_DIR) + "/samples/mpi_rod.bdf " + SSID_SOURCE_DIR +
                           "/samples/mpi_rod_hidden_mass.unv --study " + (dir / "study.json").string() + " --json -";
  const auto e = run_ssid("estimate " + args);
  const auto d = run_ssid("diagnose " + args);
  CAPTURE(e.err, d.err);
  REQUIRE(e.code == 0);
  REQUIRE(d.code == 0);
  const auto je = nlohmann::json::parse(e.out), jd = nlohmann::json::parse(d.out);
  const nlohmann::json* p = nullptr;
  for (const auto& h : jd["ranking"])
    if (h["kind"] == "parameter") p = &h;
  REQUIRE(p);
  const auto& ep = je["parameters"];
  REQUIRE((*p)["all_parameters"].size() == ep.size());
  for (std::size_t k = 0; k < ep.size(); ++k) {
    CHECK((*p)["all_parameters"][k]["name"] == ep[k]["name"]);
    CHECK((*p)["all_parameters"][k]["estimate"].get<double>() == Approx(ep[k]["estimate"].get<double>()).epsilon(1e-10));
    CHECK((*p)["all_parameters"][k]["std"].get<double>() == Approx(ep[k]["posterior_std"].get<double>()).epsilon(1e-8));
    for (std::size_t l = 0; l < ep.size(); ++l)
      CHECK((*p)["posterior_covariance"][k][l].get<double>() ==
            Approx(je["posterior_covariance"][k][l].get<double>()).epsilon(1e-8).margin(1e-30));
  }
  CHECK((*p)["laplace_log_evidence"].get<double>() == Approx(je["log_evidence"].get<double>()).epsilon(1e-10));
  CHECK((*p)["paired"] == je["pairs"].size());
  fs::remove_all(dir);
}
