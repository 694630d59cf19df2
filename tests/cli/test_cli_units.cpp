// Every printed quantity with its unit, enough digits to show the errors, and
// the mode shapes in `ssid modes --json --shapes` checked against independent
// computations (the two-rod closed form; M-orthonormality with the mass matrix
// `ssid assemble` writes).
#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>
#include <unistd.h>

#include "cli_run.hpp"
#include "formats/op4.hpp"
#include "formats/uff.hpp"

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

fs::path scratch() { return cli_scratch("units"); }

const std::string kSamples = std::string(SSID_SOURCE_DIR) + "/samples/";

/// The line of `text` that starts with `prefix` ("" when none).
std::string line_starting(const std::string& text, const std::string& prefix) {
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);)
    if (l.rfind(prefix, 0) == 0) return l;
  return "";
}

}  // namespace

TEST_CASE("ssid estimate: each parameter's unit from the deck, J explained, the frequency error on stdout",
          "[cli][estimate][units]") {
  const auto r = run_ssid("estimate " + kSamples + "mpi_rod.bdf " + kSamples + "estimate/measured.unv --study " +
                          kSamples + "estimate/study.json --quiet");
  INFO(r.err);
  REQUIRE(r.code == 0);
  CHECK(r.err.empty());
  // The rod deck states "$ units: SI (m, kg, N, Pa, s)" on its line 3.
  const std::regex number(R"( +[-0-9.e+]+)");
  auto row = [&](const std::string& name, const std::string& tail) {
    const std::string l = line_starting(r.out, name + " ");
    INFO(l);
    CHECK(std::regex_match(l, std::regex(name + R"( +([-0-9.e+]+ +){5} )" + tail)));
  };
  row("STRUTA", R"(m\^2 +PROD A \(42 cards\))");
  row("BNUTA", R"(m\^2 +PROD A \(42 cards\))");
  row("ECAPA", R"(m\^2 +PROD A \(42 cards\))");
  row("JOINTM", R"(scale factor +CONM2 M \(80 cards\))");
  row("KSUSP", R"(N/m +PELAS K \(1 card\))");
  CHECK_THAT(r.out, Catch::Contains(
                        "  units: SI, as the deck states (" + kSamples + "mpi_rod.bdf:3: \"$ units: SI (m, kg, N, Pa, "
                        "s); no WTMASS needed\"); a parameter has the unit of the fields it designs "
                        "(DVPREL1/DVMREL1), or is a dimensionless scale factor of them when its XINIT is 1 and no "
                        "coefficient is 1\n"));
  CHECK_THAT(r.out, Catch::Contains("  FE mode    FE [Hz]  test mode  test [Hz]  error [%]     MAC\n"));
  CHECK(std::regex_search(r.out, std::regex(R"(\nfrequency error, RMS over the pairs: [0-9]+\.[0-9]{3} % at the estimate )"
                                            R"(\([0-9]+ pairs, largest [0-9]+\.[0-9]{3} %\), [0-9]+\.[0-9]{3} % at the start )"
                                            R"(\([0-9]+ pairs\); mean MAC 0\.[0-9]{3} \(start 0\.[0-9]{3}\)\n)")));
  CHECK(std::regex_search(r.out, std::regex(R"(\nobjective J = [0-9.e+]+ at the estimate \(start [0-9.e+]+\): J = data )"
                                            R"(misfit [0-9.e+]+ \+ prior term [0-9.e+-]+, where the data misfit is the )"
                                            R"(sum of \(\(measured - predicted\) / std\)\^2 over the [0-9]+ measurements)")));
}

TEST_CASE("ssid estimate: a deck that states no units says \"deck units\"", "[cli][estimate][units]") {
  const fs::path dir = scratch(), deck = dir / "no_units.bdf";
  {
    std::string text = cli_slurp(kSamples + "mpi_rod.bdf");
    const auto at = text.find("$ units:");
    REQUIRE(at != std::string::npos);
    text.replace(at, 8, "$ (none)");
    std::ofstream(deck) << text;
  }
  const auto r = run_ssid("estimate " + deck.string() + " " + kSamples + "estimate/measured.unv --study " + kSamples +
                          "estimate/study.json --quiet --json -");
  INFO(r.err);
  REQUIRE(r.code == 0);
  const json j = json::parse(r.out);
  CHECK(j["parameters"][0]["unit"] == "deck units (area)");
  CHECK(j["parameters"][0]["designs"] == "PROD A (42 cards)");
  CHECK(j["parameters"][3]["unit"] == "scale factor");
  CHECK(j["parameters"][4]["unit"] == "deck units (translational stiffness)");
  CHECK(j["units"] == "deck units: the deck states no unit system (a comment \"$ units: SI\" would name them)");
  CHECK(j["objective"]["J"].get<double>() ==
        Approx(j["objective"]["data_misfit"].get<double>() + j["objective"]["prior_term"].get<double>()));
  CHECK(j["frequency_rms_pct"] == j["iterations"].back()["frequency_rms_pct"]);
}

TEST_CASE("--help prints defaults as people write them, and the exit codes", "[cli][units]") {
  const auto r = run_ssid("correlate --help");
  REQUIRE(r.code == 0);
  CHECK_THAT(r.out, Catch::Contains("--min-mac arg (=0.9)") && Catch::Contains("--max-freq-error arg (=10)") &&
                        Catch::Contains("--tol arg (=0)"));
  CHECK(r.out.find("0.90000") == std::string::npos);
  const auto m = run_ssid("modes --help");
  CHECK_THAT(m.out, Catch::Contains("--noise-freq arg (=0)"));
  CHECK_THAT(m.out, Catch::EndsWith(
                        "exit status: 0 success; 1 ssid failed (a bug: please report it); 2 bad input (an option, a "
                        "file, a\nmodel: the message names it; nothing was computed); 3 it ran, but the result is not "
                        "trustworthy (not\nconverged, stopped early: JSON marked \"partial\": true); 130 interrupted "
                        "by Ctrl-C (JSON marked partial)\n"));
}

TEST_CASE("ssid correlate: frequencies in Hz to 7 digits, so that a 1.7 % error does not read as a match",
          "[cli][correlate][units]") {
  // One mode on one node: 0.5042 Hz against 0.4958 Hz is a +1.69 % error; to 0.01 Hz both read 0.50.
  const fs::path dir = scratch();
  auto write = [&](const fs::path& p, double hz) {
    ssid::formats::uff::UffFile f;
    Eigen::MatrixXd v(1, 3);
    v << 1.0, 0.5, 0.25;
    f.datasets.push_back(ssid::formats::uff::NodalData55::normal_mode(1, hz, {7}, v));
    ssid::formats::uff::write_uff(f, p.string());
  };
  const fs::path fe = dir / "fe.unv", test = dir / "test.unv";
  write(fe, 0.5042);
  write(test, 0.4958);
  const auto r = run_ssid("correlate " + fe.string() + " " + test.string());
  INFO(r.err);
  REQUIRE(r.code == 0);
  CHECK_THAT(r.out, Catch::Contains("FEM Frequency (Hz)/#  Test Frequency (Hz)/#"));
  CHECK_THAT(r.out, Catch::Contains("0.5042/1") && Catch::Contains("0.4958/1") && Catch::Contains("1.69(*)"));
}

TEST_CASE("ssid modes --json --shapes: the two-rod shapes match the closed form", "[cli][modes][units]") {
  const auto r = run_ssid("modes " + kSamples + "two_rods.bdf --json - --shapes");
  INFO(r.err);
  REQUIRE(r.code == 0);
  const json j = json::parse(r.out);
  // g-set: grids 1-3, components 1-6.
  REQUIRE(j["shape_dofs"].size() == 18);
  CHECK(j["shape_dofs"][0] == json::array({1, 1}));
  CHECK(j["shape_dofs"][17] == json::array({3, 6}));
  CHECK_THAT(j["shape_convention"]["normalization"].get<std::string>(), Catch::StartsWith("MASS: phi^T M phi = 1"));
  CHECK_THAT(j["shape_convention"]["values"].get<std::string>(),
             Catch::StartsWith("translations in the deck's length unit, rotations in radians"));
  // K = k[2 -1; -1 1], M = m diag(1, 1/2) on (grid 2, grid 3) axial: φ₁ = ∓φ₂/√2,
  // and mass normalisation m φ₁² + (m/2) φ₂² = 1 gives |φ₂| = 1/√m, |φ₁| = 1/√(2m).
  const double m = 7850.0 * 1e-4;
  REQUIRE(j["modes"].size() == 2);
  for (int mode = 0; mode < 2; ++mode) {
    const auto& s = j["modes"][mode]["shape"];
    REQUIRE(s.size() == 18);
    const double sign = s[12].get<double>() > 0 ? 1.0 : -1.0;  // grid 3, T1
    CHECK(sign * s[12].get<double>() == Approx(1 / std::sqrt(m)).epsilon(1e-12));
    CHECK(sign * s[6].get<double>() == Approx((mode == 0 ? 1 : -1) / std::sqrt(2 * m)).epsilon(1e-12));
    for (int i = 0; i < 18; ++i)
      if (i != 6 && i != 12) CHECK(s[i].get<double>() == 0.0);  // grid 1 fixed; the rest without stiffness
  }
  // --shapes needs --json.
  const auto bad = run_ssid("modes " + kSamples + "two_rods.bdf --shapes");
  CHECK(bad.code == 2);
  CHECK(bad.err == "ssid: error: --shapes adds the mode shapes to the JSON: give --json FILE too\n");
}

TEST_CASE("ssid modes --json --shapes: shapes M-orthonormal with the mass matrix of ssid assemble", "[cli][modes][units]") {
  const fs::path dir = scratch(), ops = dir / "ops";
  const std::string deck = kSamples + "mpi_rod.bdf";
  const auto a = run_ssid("assemble " + deck + " -o " + ops.string() + " --no-derivatives");
  INFO(a.err);
  REQUIRE(a.code == 0);
  const json manifest = json::parse(cli_slurp(ops / "manifest.json"));
  const auto r = run_ssid("modes " + deck + " --nmodes 12 --json - --shapes --quiet");
  INFO(r.err);
  REQUIRE(r.code == 0);
  const json j = json::parse(r.out);
  // The a-set DOFs of the OP4 matrices, by (grid, component), into the g-set shape rows.
  std::map<std::pair<long, int>, std::size_t> row;
  for (std::size_t i = 0; i < j["shape_dofs"].size(); ++i)
    row[{j["shape_dofs"][i][0].get<long>(), j["shape_dofs"][i][1].get<int>()}] = i;
  const auto& dofs = manifest["dofs"];
  const auto n = static_cast<Eigen::Index>(dofs.size());
  REQUIRE(n > 0);
  const auto mats = ssid::formats::read_op4((ops / manifest["files"]["M"].get<std::string>()).string());
  REQUIRE(mats.size() == 1);
  const Eigen::MatrixXd M = mats[0].dense_real();
  REQUIRE(M.rows() == n);
  const auto nm = static_cast<Eigen::Index>(j["modes"].size());
  REQUIRE(nm == 12);
  Eigen::MatrixXd Phi(n, nm);
  for (Eigen::Index k = 0; k < nm; ++k)
    for (Eigen::Index i = 0; i < n; ++i)
      Phi(i, k) = j["modes"][k]["shape"][row.at({dofs[i][0].get<long>(), dofs[i][1].get<int>()})].get<double>();
  const Eigen::MatrixXd G = Phi.transpose() * M * Phi;
  CHECK((G - Eigen::MatrixXd::Identity(nm, nm)).cwiseAbs().maxCoeff() < 1e-9);
}
