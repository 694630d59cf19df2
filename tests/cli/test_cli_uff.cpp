#include <catch2/catch.hpp>

#include <Eigen/QR>
#include <nlohmann/json.hpp>
#include <random>
#include <cstring>
#include <unistd.h>

#include "cli_run.hpp"
#include "formats/uff.hpp"

namespace fs = std::filesystem;
namespace uff = ssid::formats::uff;

namespace {

fs::path scratch() { return cli_scratch("uff"); }

const std::string kMixed = std::string(SSID_SOURCE_DIR) + "/tests/data/uff/testlab_mixed.unv";

/// FE modes: 4 orthonormal shapes on nodes 1..6 (3 components each); test modes:
/// FE modes 1, 2 and 4 (scaled, sign-flipped, slightly perturbed) plus a spurious
/// shape, at nodes 1..5 only, numbered 101.. and placed 1 mm off the FE nodes.
void write_pair(const fs::path& fe_path, const fs::path& test_path) {
  std::mt19937 rng(5);
  std::normal_distribution<double> g;
  Eigen::MatrixXd A(18, 18);
  for (Eigen::Index i = 0; i < A.size(); ++i) A(i) = g(rng);
  Eigen::MatrixXd Q = Eigen::HouseholderQR<Eigen::MatrixXd>(A).householderQ();
  uff::UffFile fe, test;
  uff::NodeSet fn, tn;
  fn.dataset = 2411;
  tn.dataset = 15;
  for (int n = 1; n <= 6; ++n) {
    fn.nodes.push_back(uff::Node{n, 0, 0, 1, {double(n), 0.0, 0.0}});
    if (n <= 5) tn.nodes.push_back(uff::Node{100 + n, 0, 0, 1, {n + 0.001, 0.0, 0.0}});
  }
  fe.datasets.push_back(fn);
  test.datasets.push_back(tn);
  const double fe_hz[] = {10.0, 20.0, 30.0, 40.0};
  for (int m = 0; m < 4; ++m) {
    Eigen::MatrixXd v = Eigen::Map<Eigen::MatrixXd>(Q.col(m).data(), 3, 6).transpose();
    fe.datasets.push_back(uff::NodalData55::normal_mode(m + 1, fe_hz[m], {1, 2, 3, 4, 5, 6}, v));
  }
  const int used[] = {0, 1, 3, -1};
  const double test_hz[] = {10.2, 19.5, 33.0, 41.0};
  for (int k = 0; k < 4; ++k) {
    Eigen::VectorXd s = used[k] >= 0 ? Eigen::VectorXd(-2.0 * Q.col(used[k]) + 0.002 * Q.col(10)) : Eigen::VectorXd(Q.col(12));
    Eigen::MatrixXd v = Eigen::Map<Eigen::MatrixXd>(s.data(), 3, 6).transpose().topRows(5);
    test.datasets.push_back(uff::NodalData55::normal_mode(k + 1, test_hz[k], {101, 102, 103, 104, 105}, v));
  }
  uff::write_uff(fe, fe_path.string());
  uff::write_uff(test, test_path.string());
}

}  // namespace

TEST_CASE("ssid uff list: datasets, nodes, modes, functions, JSON", "[cli][uff]") {
  const fs::path json = scratch() / "list.json";
  auto r = run_ssid("uff list " + kMixed + " --json " + json.string());
  CHECK(r.code == 0);
  CHECK_THAT(r.out, Catch::Contains("10 dataset(s)") && Catch::Contains("nodes: 5 (dataset 15: 3, dataset 2411: 2)") &&
                        Catch::Contains("skipped (kept verbatim): none") &&
                        Catch::Contains("trace lines (82): 1") && Catch::Contains("response 3-Y"));
  CHECK_THAT(r.err, Catch::Contains("9 DOF(s) are missing from some modes"));
  auto j = nlohmann::json::parse(cli_slurp(json));
  CHECK(j["datasets"].size() == 10);
  CHECK(j["modes"].size() == 3);
  CHECK(j["modes"][0]["frequency_hz"] == 7.75);
  CHECK(j["modes"][2]["analysis"] == "complex mode");
  CHECK(j["modes"][2]["eigenvalue"][1] == 48.0);
  CHECK(j["nodes"].size() == 5);
  CHECK(j["functions"][1]["response_direction"] == -2);
  CHECK(j["skipped"].empty());
  CHECK(j["datasets"][4]["type"] == "trace line");
  CHECK(j["datasets"][4]["nodes"] == 3);
  CHECK(j["normal_modes"] == 2);
  CHECK(j["complex_modes"] == 1);
  auto help = run_ssid("uff --help");
  CHECK(help.code == 0);
  auto bad = run_ssid("uff list " + (scratch() / "missing.unv").string());
  CHECK(bad.code == 2);
  CHECK_THAT(bad.err, Catch::Contains("missing.unv") && Catch::Contains("not found"));
  std::ofstream(scratch() / "broken.unv") << "    -1\n    55\nA\nB\nC\nD\nE\n         1         2         2         8"
                                             "         2         3\n         2         4         1         1\n"
                                             "  7.7500X+00\n    -1\n";
  auto br = run_ssid("uff list " + (scratch() / "broken.unv").string());
  CHECK(br.code == 2);
  CHECK(br.out.empty());
  CHECK_THAT(br.err, Catch::Contains("broken.unv:10: dataset 55 record 8 field 1"));
}

TEST_CASE("ssid uff list: 58b and 2414 listed, values on request, 2414 modes usable", "[cli][uff]") {
  // A 58b (complex single, even, little endian) built from its bytes, and a 2414 normal mode.
  std::string bytes;
  for (float v : {1.0f, -0.5f, 0.25f, 2.0f}) {
    char b[4];
    std::memcpy(b, &v, 4);
    bytes.append(b, 4);  // the test hosts are little endian (x86-64)
  }
  std::string text =
      "    -1\n    58b     1     2          11          16     0     0           0           0\n"
      "FRF 7+Z/1+Z\nNONE\nNONE\nNONE\nNONE\n"
      "    4         1    0         0 NONE               7   3 NONE               1   3\n"
      "         5         2         1  1.00000E+01  5.00000E-01  0.00000E+00\n"
      "        18    0    0    0 Frequency            Hz                  \n"
      "        12    0    0    0 Acceleration         m/s\xb2"  // Latin-1 superscript two, as VibControl writes it
      "                \n"
      "        13    0    0    0 Force                N                   \n"
      "         0    0    0    0 NONE                 NONE                \n" +
      bytes +
      "    -1\n"
      "    -1\n  2414\n         1\nMode 1\n         1\nA\nB\nC\nD\nE\n"
      "         1         2         2         8         2         3\n"
      "         0         0         1         0         1         1         0         0\n"
      "         0         0\n"
      "  0.00000E+00  4.50000E+00  0.00000E+00  1.00000E+00  2.00000E-02  0.00000E+00\n"
      "  0.00000E+00  0.00000E+00  0.00000E+00  0.00000E+00  0.00000E+00  0.00000E+00\n"
      "         7\n  0.00000E+00  0.00000E+00  1.00000E+00\n"
      "    -1\n";
  const fs::path p = scratch() / "lab.unv";
  std::ofstream(p, std::ios::binary) << text;
  const fs::path json = scratch() / "lab.json";
  auto r = run_ssid("uff list " + p.string() + " --json " + json.string() + " --values");
  CHECK(r.code == 0);
  CHECK_THAT(r.out, Catch::Contains("line 2 (58b): type 4 (frequency response function), response 7+Z, reference 1+Z, "
                                    "2 points, even abscissa, complex single") &&
                        Catch::Contains("real normal modes usable for correlation: 1 at 3 DOF(s)"));
  auto j = nlohmann::json::parse(cli_slurp(json));
  REQUIRE(j["datasets"].size() == 2);
  const auto& f = j["datasets"][0];
  CHECK(f["number"] == 58);
  CHECK(f["binary"] == true);
  CHECK(f["byte_order"] == "little endian");
  CHECK(f["function"] == "frequency response function");
  CHECK(f["spacing"] == "even");
  CHECK(f["ordinate"] == "complex single");
  CHECK(f["ordinate_axis"]["units"] == "m/s\xc2\xb2");  // JSON text is UTF-8
  CHECK(f["points"] == 2);
  CHECK(f["x"] == nlohmann::json::array({10.0, 10.5}));
  CHECK(f["y"] == nlohmann::json::parse("[[1.0, -0.5], [0.25, 2.0]]"));
  CHECK(j["datasets"][1]["number"] == 2414);
  CHECK(j["datasets"][1]["frequency_hz"] == 4.5);
  CHECK(j["modes"][0]["viscous_damping"] == 0.02);
  CHECK(j["normal_modes"] == 1);
  // Without --values the listing carries no values.
  auto plain = run_ssid("uff list " + p.string() + " --json -");
  CHECK(plain.code == 0);
  CHECK_FALSE(nlohmann::json::parse(plain.out)["datasets"][0].contains("x"));
  auto no_json = run_ssid("uff list " + p.string() + " --values");
  CHECK(no_json.code == 2);
  CHECK(no_json.err == "ssid: error: ssid uff list: --values adds the values to the JSON listing; give --json OUT (or "
                       "--json -)\n");
}

TEST_CASE("ssid uff list: node positions in the global system where a coordinate system is given", "[cli][uff]") {
  const fs::path p = scratch() / "cs.unv";
  std::ofstream(p) << "    -1\n    18\n         1         0         0         8         1\nSYS1\n"
                      " -2.40000E+00 -9.50000E-01  0.00000E+00 -3.40000E+00 -9.50000E-01  0.00000E+00\n"
                      " -3.40000E+00 -9.50000E-01 -1.00000E+00\n    -1\n"
                      "    -1\n    15\n        11         1         1         0  1.00000E+00  2.00000E+00  3.00000E+00\n"
                      "        12         0         0         0  1.00000E+00  2.00000E+00  3.00000E+00\n    -1\n"
                      "    -1\n    58\nA\nB\nC\nD\nE\n"
                      "    1         1    0         0 NONE              11   3 NONE              12   1\n"
                      "         2         1         1  0.00000E+00  1.00000E+00  0.00000E+00\n"
                      "         0    0    0    0 NONE                 NONE\n"
                      "         0    0    0    0 NONE                 NONE\n"
                      "         0    0    0    0 NONE                 NONE\n"
                      "         0    0    0    0 NONE                 NONE\n"
                      "  1.00000E+00\n    -1\n";
  auto r = run_ssid("uff list " + p.string() + " --json -");
  CHECK(r.code == 0);
  auto j = nlohmann::json::parse(r.out);
  // SYS1's axes: x = -X, y = +Y, z = -Z from (-2.4, -0.95, 0): (1, 2, 3) is (-3.4, 1.05, -3).
  REQUIRE(j["nodes"][0].contains("xyz_global"));
  CHECK(j["nodes"][0]["xyz_global"][0].get<double>() == Approx(-3.4).margin(1e-12));
  CHECK(j["nodes"][0]["xyz_global"][1].get<double>() == Approx(1.05).margin(1e-12));
  CHECK(j["nodes"][0]["xyz_global"][2].get<double>() == Approx(-3.0).margin(1e-12));
  CHECK_FALSE(j["nodes"][1].contains("xyz_global"));
  // A response measured along +Z of node 11's displacement system SYS1 is global -Z.
  REQUIRE(j["functions"].size() == 1);
  CHECK(j["functions"][0]["response_axis_global"] == nlohmann::json::array({0.0, 0.0, -1.0}));
  CHECK_FALSE(j["functions"][0].contains("reference_axis_global"));
  // A node in a system the file lacks: listed as a problem, no global positions.
  std::ofstream(p, std::ios::app) << "    -1\n    15\n        13         7         0         0  1.00000E+00  2.00000E+00  "
                                     "3.00000E+00\n    -1\n";
  auto m = run_ssid("uff list " + p.string() + " --json -");
  CHECK(m.code == 0);
  auto k = nlohmann::json::parse(m.out);
  CHECK_FALSE(k["nodes"][0].contains("xyz_global"));
  CHECK(k["problems"].back() == "node 13: definition coordinate system 7 is not defined in the file (datasets 18, 2420)");
}

TEST_CASE("ssid correlate: pairing table, unpaired modes, JSON; position mapping", "[cli][correlate]") {
  const fs::path dir = scratch();
  write_pair(dir / "fe.unv", dir / "test.unv");
  // By id the test nodes (101..105) match nothing.
  auto none = run_ssid("correlate " + (dir / "fe.unv").string() + " " + (dir / "test.unv").string());
  CHECK(none.code == 2);
  CHECK_THAT(none.err, Catch::Contains("share no measured DOF"));

  const fs::path json = dir / "c.json";
  auto r = run_ssid("correlate " + (dir / "fe.unv").string() + " " + (dir / "test.unv").string() +
                    " --map position --tol 0.01 --json " + json.string());
  CHECK(r.code == 0);
  CHECK_THAT(r.out, Catch::Contains("FEM Frequency (Hz)/#") && Catch::Contains("compared at 15 common DOF(s)") &&
                        Catch::Contains("10.00/1 ") && Catch::Contains("10.20/1 ") &&
                        Catch::Contains("accepted pairs: 2 of 3 mutual-best"));
  auto j = nlohmann::json::parse(cli_slurp(json));
  REQUIRE(j["pairs"].size() == 3);
  CHECK(j["pairs"][0]["fe_mode"] == 1);
  CHECK(j["pairs"][0]["test_mode"] == 1);
  CHECK(j["pairs"][0]["accepted"] == true);
  CHECK(j["pairs"][0]["mac"].get<double>() > 0.99);
  CHECK(j["pairs"][0]["msf"].get<double>() == Approx(-0.5).epsilon(0.01));
  CHECK(j["pairs"][0]["error_pct"].get<double>() == Approx(100.0 * (10.0 - 10.2) / 10.2));
  CHECK(j["pairs"][1]["fe_mode"] == 2);
  CHECK(j["pairs"][1]["accepted"] == true);
  // FE 4 pairs with test 3 (33 Hz) by shape, but 21 % off in frequency: not accepted.
  CHECK(j["pairs"][2]["fe_mode"] == 4);
  CHECK(j["pairs"][2]["test_mode"] == 3);
  CHECK(j["pairs"][2]["accepted"] == false);
  CHECK(j["unpaired_fe"] == nlohmann::json::array({3, 4}));
  CHECK(j["unpaired_test"] == nlohmann::json::array({3, 4}));
  CHECK(j["dofs"] == 15);
  CHECK(j["mac"].size() == 4);
  CHECK(j["auto_mac_test"][0][0].get<double>() == Approx(1.0));
  CHECK(j["mapping"]["mapped"] == 5);
  // Looser frequency tolerance and the non-squared MAC.
  auto ns = run_ssid("correlate " + (dir / "fe.unv").string() + " " + (dir / "test.unv").string() +
                     " --map position --tol 0.01 --mac ns --max-freq-error 25 --json -");
  CHECK(ns.code == 0);
  auto k = nlohmann::json::parse(ns.out);
  CHECK(k["mac_form"] == "non-squared");
  CHECK(k["pairs"][2]["accepted"] == true);
  CHECK(k["unpaired_fe"] == nlohmann::json::array({3}));
}

TEST_CASE("ssid correlate: a deck is solved first; one with nothing to solve is refused clearly", "[cli][correlate][errors]") {
  const fs::path dir = scratch();
  std::ofstream(dir / "model.bdf") << "GRID    1               0.      0.      0.\n";
  auto r = run_ssid("correlate " + (dir / "model.bdf").string() + " " + kMixed);
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Catch::Contains("the analysis set is empty"));
  // A deck where the test universal file is expected.
  auto t = run_ssid("correlate " + kMixed + " " + (dir / "model.bdf").string());
  CHECK(t.code == 2);
  CHECK_THAT(t.err, Catch::Contains("model.bdf"));
  auto bad = run_ssid("correlate " + kMixed + " " + kMixed + " --mac cubed");
  CHECK(bad.code == 2);
}
