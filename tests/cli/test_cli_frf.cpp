// `ssid frf`: FRFs by modal superposition of a deck's modes, checked against the dense
// direct solve (K − ω²M + iωC)⁻¹ of a spring–mass deck whose K and M are written out by
// hand here; the overlay on measured FRFs (built here from that direct solve); located
// errors.
#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <cmath>
#include <complex>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "cli/cli_run.hpp"
#include "cli/spring_deck.hpp"
#include "formats/uff.hpp"

namespace fs = std::filesystem;
namespace uff = ssid::formats::uff;
using cd = std::complex<double>;

namespace {

fs::path scratch(const std::string& name) { return cli_scratch("frf") / name; }

fs::path spring_deck() {
  const fs::path p = scratch("springs.bdf");
  std::ofstream(p) << spring_deck_text();
  return p;
}

nlohmann::json read_json(const fs::path& p) {
  std::ifstream in(p);
  nlohmann::json j;
  in >> j;
  return j;
}

}  // namespace

TEST_CASE("ssid frf equals the dense direct solve of a spring-mass deck", "[cli][frf]") {
  const Spring3 s;
  const fs::path deck = spring_deck(), json = scratch("frf.json"), unv = scratch("frf.unv");
  const CliResult r = run_ssid("frf " + deck.string() + " --drive 1,1 --response 1,1 2,1,3,1 --damping 0.02 --band 0:60 "
                                               "--lines 601 --json " + json.string() + " --uff " + unv.string());
  INFO(r.err);
  REQUIRE(r.code == 0);
  CHECK(r.out.find("3 mode(s)") != std::string::npos);
  CHECK(r.out.find("mode   frequency (Hz)   damping (%)  damping from") != std::string::npos);
  CHECK(r.out.find("peak |H| (length/force)") != std::string::npos);
  const nlohmann::json j = read_json(json);
  REQUIRE(j["frequency_hz"].size() == 601);
  REQUIRE(j["responses"].size() == 3);
  CHECK(j["quantity"] == "displacement");
  for (int r3 = 0; r3 < 3; ++r3)
    CHECK(j["modes"][static_cast<std::size_t>(r3)]["hz"].get<double>() ==
          Approx(std::sqrt(s.lambda(r3)) / (2 * M_PI)).epsilon(1e-10));
  double worst = 0;
  for (std::size_t k = 0; k < 601; ++k) {
    const double f = j["frequency_hz"][k];
    CHECK(f == Approx(0.1 * static_cast<double>(k)).margin(1e-12));
    const Eigen::Matrix3cd h = s.direct(f, Eigen::Vector3d::Constant(0.02));
    for (int o = 0; o < 3; ++o) {
      const auto& jr = j["responses"][static_cast<std::size_t>(o)];
      const cd got(jr["re"][k].get<double>(), jr["im"][k].get<double>());
      worst = std::max(worst, std::abs(got - h(o, 0)) / std::abs(h(o, 0)));
    }
  }
  CHECK(worst < 1e-9);

  // UFF 58 back: three complex FRFs from the drive, 12 digits.
  const uff::UffFile back = uff::read_uff(unv.string());
  REQUIRE(back.functions().size() == 3);
  const uff::Function58& f2 = *back.functions()[1];
  CHECK(f2.function_type == 4);
  CHECK(f2.response_node == 2);
  CHECK(f2.response_direction == 1);
  CHECK(f2.reference_node == 1);
  CHECK(f2.reference_direction == 1);
  CHECK(f2.axes[1].specific_data_type == 8);
  CHECK(f2.axes[2].specific_data_type == 13);
  REQUIRE(f2.y.size() == 601);
  CHECK(std::abs(f2.y[300] - s.direct(30.0, Eigen::Vector3d::Constant(0.02))(1, 0)) <
        1e-10 * std::abs(f2.y[300]));
  const CliResult l = run_ssid("uff list " + unv.string());
  CHECK(l.code == 0);
  CHECK(l.out.find("type 4 (frequency response function)") != std::string::npos);
}

TEST_CASE("ssid frf: default band without rigid-body modes, and reciprocity on the frame sample", "[cli][frf]") {
  const fs::path deck = fs::path(SSID_SOURCE_DIR) / "samples" / "frame.bdf";
  const fs::path a = scratch("ab.json"), b = scratch("ba.json");
  const CliResult r1 = run_ssid("frf " + deck.string() + " --drive 31,3 --response 34,2 --damping 0.01 --json " + a.string());
  const CliResult r2 = run_ssid("frf " + deck.string() + " --drive 34,2 --response 31,3 --damping 0.01 --json " + b.string());
  INFO(r1.err << r2.err);
  REQUIRE(r1.code == 0);
  REQUIRE(r2.code == 0);
  const nlohmann::json ja = read_json(a), jb = read_json(b);
  REQUIRE(ja["frequency_hz"].size() == 1001);
  CHECK(ja["frequency_hz"][0].get<double>() == 0.0);
  CHECK(ja["frequency_hz"][1000].get<double>() ==
        Approx(1.2 * ja["modes"][ja["modes"].size() - 1]["hz"].get<double>()).epsilon(1e-12));
  double diff = 0, norm = 0;
  for (std::size_t k = 0; k < 1001; ++k) {
    const cd x(ja["responses"][0]["re"][k].get<double>(), ja["responses"][0]["im"][k].get<double>());
    const cd y(jb["responses"][0]["re"][k].get<double>(), jb["responses"][0]["im"][k].get<double>());
    diff = std::max(diff, std::abs(x - y));
    norm = std::max(norm, std::abs(x));
  }
  CHECK(norm > 0);
  CHECK(diff <= 1e-12 * norm);
}

TEST_CASE("ssid frf --measured: overlay, FRAC, directions and the measured quantity", "[cli][frf]") {
  const Spring3 s;
  const fs::path deck = spring_deck();
  // Measured accelerance from the dense solve at ζ = 2 %, 0.5 … 60 Hz every 0.25 Hz;
  // response 3 measured in −X (values negated), response 2 missing.
  const Eigen::Vector3d zeta = Eigen::Vector3d::Constant(0.02);
  uff::UffFile m;
  for (int o : {0, 2}) {
    uff::Function58 fn;
    fn.function_type = 4;
    fn.function_id = o + 1;
    fn.response_node = o + 1;
    fn.response_direction = o == 2 ? -1 : 1;
    fn.reference_node = 1;
    fn.reference_direction = 1;
    fn.ordinate_type = 6;
    fn.even = true;
    fn.abscissa_min = 0.5;
    fn.abscissa_increment = 0.25;
    fn.axes[1].specific_data_type = 12;  // acceleration
    fn.axes[2].specific_data_type = 13;
    for (int k = 0; k < 239; ++k) {
      const double f = 0.5 + 0.25 * k, w = 2 * M_PI * f;
      fn.x.push_back(f);
      fn.y.push_back((o == 2 ? -1.0 : 1.0) * (-w * w) * s.direct(f, zeta)(o, 0));
    }
    m.datasets.emplace_back(fn);
  }
  const fs::path meas = scratch("measured.unv"), json = scratch("overlay.json"), svg = scratch("overlay.svg");
  uff::write_uff(m, meas.string(), uff::Precision::Extended);

  const CliResult r = run_ssid("frf " + deck.string() + " --drive 1,1 --response 1,1 2,1 3,1 --damping 0.02 --measured " +
                               meas.string() + " --band 1:50 --json " + json.string() + " --svg " + svg.string());
  INFO(r.err);
  REQUIRE(r.code == 0);
  CHECK(r.err.find("note: " + meas.string() + " has no FRF of response 2,1 to the drive 1,1 (dataset 58, type 4): "
                                              "analysis only for it") != std::string::npos);
  CHECK(r.out.find("acceleration per force") != std::string::npos);
  CHECK(r.out.find("peak |H| (length/s²/force)") != std::string::npos);
  const nlohmann::json j = read_json(json);
  CHECK(j["quantity"] == "acceleration");
  REQUIRE(j["frequency_hz"].size() == 197);  // 1 … 50 Hz every 0.25 Hz
  CHECK(j["frequency_hz"][0].get<double>() == 1.0);
  CHECK(j["responses"][0]["measured"]["frac"].get<double>() == Approx(1.0).epsilon(1e-12));
  CHECK(j["responses"][2]["measured"]["frac"].get<double>() == Approx(1.0).epsilon(1e-12));
  CHECK_FALSE(j["responses"][1].contains("measured"));
  for (std::size_t k = 0; k < 197; k += 49) {  // the measured −X record turned to +X
    const double a = j["responses"][2]["re"][k], b = j["responses"][2]["measured"]["re"][k];
    CHECK(a == Approx(b).epsilon(1e-10));
  }
  const std::string text = cli_slurp(svg);
  CHECK(text.rfind("<svg xmlns=\"http://www.w3.org/2000/svg\"", 0) == 0);
  for (const char* id : {"frf-1-1-mag", "frf-1-1-phase", "frf-2-1-mag", "frf-3-1-phase"})
    CHECK(text.find(std::string("id=\"") + id + "\"") != std::string::npos);
  CHECK(text.find("class=\"measured\"") != std::string::npos);
  CHECK(text.find("|H| [length/s²/force]") != std::string::npos);

  // At ζ = 4 % the analysis differs from the measurement: FRAC below 1.
  const CliResult r4 = run_ssid("frf " + deck.string() + " --drive 1,1 --response 1,1 --damping 0.04 --measured " + meas.string() +
                                " --json " + json.string());
  REQUIRE(r4.code == 0);
  const double frac = read_json(json)["responses"][0]["measured"]["frac"];
  CHECK(frac < 0.9);
  CHECK(frac > 0.3);

  // Asking for another quantity than the measured one is refused.
  const CliResult rq = run_ssid("frf " + deck.string() + " --drive 1,1 --response 1,1 --damping 0.02 --quantity displacement "
                                                "--measured " + meas.string());
  CHECK(rq.code == 2);
  CHECK(rq.err.find("the measured FRFs are of acceleration (ordinate type 12), --quantity asks for displacement") !=
        std::string::npos);
}

TEST_CASE("ssid frf --modes-from takes each mode's damping from the identified mode nearest", "[cli][frf]") {
  const Spring3 s;
  const fs::path deck = spring_deck(), ident = scratch("ident.json"), json = scratch("mf.json");
  const double f1 = std::sqrt(s.lambda(0)) / (2 * M_PI), f3 = std::sqrt(s.lambda(2)) / (2 * M_PI);
  std::ofstream(ident) << nlohmann::json{{"modes", {{{"hz", 1.02 * f1}, {"zeta", 0.015}},
                                                    {{"hz", 0.97 * f3}, {"zeta", 0.03}}}}}.dump();
  const CliResult r = run_ssid("frf " + deck.string() + " --drive 1,1 --response 2,1 --modes-from " + ident.string() +
                               " --damping 0.005 --band 1:40 --lines 40 --json " + json.string());
  INFO(r.err);
  REQUIRE(r.code == 0);
  const nlohmann::json j = read_json(json);
  CHECK(j["modes"][0]["zeta"].get<double>() == 0.015);
  CHECK(j["modes"][1]["zeta"].get<double>() == 0.005);
  CHECK(j["modes"][1]["damping_from"] == "--damping (no identified mode near)");
  CHECK(j["modes"][2]["zeta"].get<double>() == 0.03);
  CHECK(j["modes"][2]["damping_from"].get<std::string>().rfind("identified mode 2 at ", 0) == 0);
  const Eigen::Vector3d zeta(0.015, 0.005, 0.03);
  for (std::size_t k = 0; k < 40; ++k) {
    const double f = j["frequency_hz"][k];
    const cd h = s.direct(f, zeta)(1, 0);
    const cd got(j["responses"][0]["re"][k].get<double>(), j["responses"][0]["im"][k].get<double>());
    CHECK(std::abs(got - h) < 1e-9 * std::abs(h));
  }
}

TEST_CASE("ssid frf: bad input is refused with exit 2 and a located message", "[cli][frf]") {
  const std::string deck = spring_deck().string();
  CHECK(run_ssid("frf --help").code == 0);
  // --json -: the JSON alone on stdout.
  const CliResult js = run_ssid("frf " + deck + " --drive 1,1 --response 2,1 --damping 0.01 --band 1:5 --lines 5 --json -");
  CHECK(js.code == 0);
  CHECK(nlohmann::json::parse(js.out)["responses"][0]["re"].size() == 5);
  const auto err = [](const CliResult& r) {
    CHECK(r.code == 2);
    return r.err;
  };
  CHECK(err(run_ssid("frf " + deck + " --drive 1,1 --response 2,1")) ==
        "ssid: error: give the modal damping: --damping Z (a ratio, 0.01 = 1 %) or --modes-from IDENTIFIED.json\n");
  CHECK(err(run_ssid("frf " + deck + " --drive 1 --response 2,1 --damping 0.01")) ==
        "ssid: error: --drive \"1\": expected GRID,COMPONENT pairs (e.g. 12,3 or 12,3,14,1)\n");
  CHECK(err(run_ssid("frf " + deck + " --drive 1,7 --response 2,1 --damping 0.01")) ==
        "ssid: error: --drive \"1,7\": \"1,7\" is not a grid id ≥ 1 and a component 1–6\n");
  CHECK(err(run_ssid("frf " + deck + " --drive 1,1 --response 9,1 --damping 0.01")) ==
        "ssid: error: " + deck + ": --response 9,1: the model has no such DOF (grid 9 is not in the deck)\n");
  CHECK(err(run_ssid("frf " + deck + " --drive 1,2 --response 2,1 --damping 0.01")) ==
        "ssid: error: " + deck + ": --drive 1,2 does not move in any mode (constrained): no force enters there\n");
  CHECK(err(run_ssid("frf " + deck + " --drive 1,1 --response 2,1 --damping 0.01 --band 5:2")) ==
        "ssid: error: --band: expected F1:F2 in Hz with 0 ≤ F1 < F2, got \"5:2\"\n");
  CHECK(err(run_ssid("frf " + deck + " --drive 1,1 --response 2,1 --damping 1.5")) ==
        "ssid: error: --damping: expected a ratio 0 ≤ ζ < 1 (0.01 = 1 %), got 1.5\n");
}
