// ssid modes: NASTRAN's eigenvalue table against closed forms, the JSON
// layout, checks, EIGRL handling, refusals, and the synthetic test (--uff).
#include <catch2/catch.hpp>

#include <cmath>
#include <nlohmann/json.hpp>
#include <sstream>
#include <unistd.h>

#include "cli_run.hpp"
#include "formats/uff.hpp"
#include "translators/measurement/mode_set.hpp"

namespace fs = std::filesystem;

namespace {

fs::path scratch() { return cli_scratch("modes"); }

/// Fixed-free chain of n CRODs of length L/n along X (no J: AUTOSPC takes the torsion).
std::string rod_chain(int n, double L, const std::string& eig, const std::string& extra = "",
                      const std::string& prod = "PROD,1,2,1.0E-4\n") {
  std::ostringstream s;
  s << "SOL 103\nCEND\nSPC = 1\nMETHOD = 1\nDISPLACEMENT = ALL\nBEGIN BULK\n";
  for (int i = 0; i <= n; ++i) s << "GRID," << i + 1 << ",," << L * i / n << ",0.,0.\n";
  for (int i = 0; i < n; ++i) s << "CROD," << 100 + i << ",1," << i + 1 << "," << i + 2 << "\n";
  s << prod << "MAT1,2,7.0E10,,0.3,2700.\nSPC1,1,123456,1\n" << eig << extra << "ENDDATA\n";
  return s.str();
}

fs::path write(const fs::path& p, const std::string& text) {
  std::ofstream(p) << text;
  return p;
}

/// Lumped fixed-free chain: λ_j = 4k/m sin²((2j − 1)π / 4n), k = EA/h, m = ρAh.
double chain_lambda(int n, double L, int j) {
  const double h = L / n, k = 7.0e10 * 1e-4 / h, m = 2700.0 * 1e-4 * h;
  const double s = std::sin((2 * j - 1) * M_PI / (4.0 * n));
  return 4 * k / m * s * s;
}

}  // namespace

TEST_CASE("ssid modes: table and JSON match the closed form of a lumped rod chain", "[cli][modes]") {
  const fs::path dir = scratch();
  const int n = 40;
  const fs::path deck = write(dir / "chain.bdf", rod_chain(n, 2.0, "EIGRL,1,,,4\n", "FORCE,9,41,,1.,1.,0.,0.\n"));
  const fs::path json = dir / "chain.json";
  auto r = run_ssid("modes " + deck.string() + " --json " + json.string());
  INFO(r.err);
  REQUIRE(r.code == 0);
  CHECK_THAT(r.out, Catch::Contains("R E A L   E I G E N V A L U E S"));
  CHECK_THAT(r.out, Catch::Contains("GENERALIZED"));
  CHECK_THAT(r.err, Catch::Contains("1 FORCE card ignored"));
  CHECK_THAT(r.err, Catch::Contains("case control output requests ignored (they do not change K or M): DISPLACEMENT"));
  auto j = nlohmann::json::parse(cli_slurp(json));
  CHECK(j.size() == 3);
  CHECK(j["partial"] == false);  // the band's Sturm count agrees with the modes found
  CHECK(j["dof"] == n);
  REQUIRE(j["modes"].size() == 4);
  for (int i = 0; i < 4; ++i) {
    const auto& m = j["modes"][i];
    CHECK(m.size() == 6);
    CHECK(m["mode"] == i + 1);
    const double lam = chain_lambda(n, 2.0, i + 1);
    CHECK(m["eigenvalue"].get<double>() == Approx(lam).epsilon(1e-10));
    CHECK(m["radians"].get<double>() == Approx(std::sqrt(lam)).epsilon(1e-10));
    CHECK(m["cycles"].get<double>() == Approx(std::sqrt(lam) / (2 * M_PI)).epsilon(1e-10));
    CHECK(m["generalized_mass"].get<double>() == Approx(1.0).epsilon(1e-12));
    CHECK(m["generalized_stiffness"].get<double>() == Approx(lam).epsilon(1e-10));
  }
  // The first line of the table in NASTRAN's layout: I9, I10, 5 × (7X, 1PE13.6).
  char line[160];
  const auto& m0 = j["modes"][0];
  std::snprintf(line, sizeof line, "%9d%10d%20.6E%20.6E%20.6E%20.6E%20.6E", 1, 1, m0["eigenvalue"].get<double>(),
                m0["radians"].get<double>(), m0["cycles"].get<double>(), m0["generalized_mass"].get<double>(),
                m0["generalized_stiffness"].get<double>());
  CHECK_THAT(r.out, Catch::Contains(line));
  // Residual and orthogonality checks are printed.
  CHECK_THAT(r.out, Catch::Contains("M-orthogonality"));

  // --nmodes overrides EIGRL; the continuous rod's first frequency c/4L is approached.
  auto r2 = run_ssid("modes " + deck.string() + " --nmodes 2 --json -");
  REQUIRE(r2.code == 0);
  auto j2 = nlohmann::json::parse(r2.out);
  CHECK(j2["modes"].size() == 2);
  const double f1 = std::sqrt(7.0e10 / 2700.0) / (4 * 2.0);
  CHECK(j2["modes"][0]["cycles"].get<double>() == Approx(f1).epsilon(1e-3));
}

TEST_CASE("ssid modes: a large chain goes through the Lanczos solver with the same answer", "[cli][modes]") {
  const fs::path dir = scratch();
  const int n = 300;  // a-set above the dense limit
  const fs::path deck = write(dir / "long.bdf", rod_chain(n, 3.0, "EIGRL,1,,,3\n"));
  auto r = run_ssid("modes " + deck.string() + " --json -");
  INFO(r.err);
  REQUIRE(r.code == 0);
  auto j = nlohmann::json::parse(r.out);
  CHECK(j["dof"] == n);
  REQUIRE(j["modes"].size() == 3);
  for (int i = 0; i < 3; ++i)
    CHECK(j["modes"][i]["eigenvalue"].get<double>() == Approx(chain_lambda(n, 3.0, i + 1)).epsilon(1e-9));
}

TEST_CASE("ssid modes: massless torsion DOFs in a large model (Lanczos path)", "[cli][modes]") {
  const fs::path dir = scratch();
  const int n = 150;  // J given: 2n a-set DOFs, the n torsion ones massless (lumped rod mass)
  const fs::path deck = write(dir / "torsion.bdf", rod_chain(n, 3.0, "EIGRL,1,,,4\n", "", "PROD,1,2,1.0E-4,2.0E-8\n"));
  auto r = run_ssid("modes " + deck.string() + " --json -");
  INFO(r.err);
  REQUIRE(r.code == 0);
  auto j = nlohmann::json::parse(r.out);
  CHECK(j["dof"] == 2 * n);
  REQUIRE(j["modes"].size() == 4);
  for (int i = 0; i < 4; ++i)
    CHECK(j["modes"][i]["eigenvalue"].get<double>() == Approx(chain_lambda(n, 3.0, i + 1)).epsilon(1e-9));
}

TEST_CASE("ssid modes: every mode of the two-rod sample (dense fallback)", "[cli][modes]") {
  auto r = run_ssid("modes " + std::string(SSID_SOURCE_DIR) + "/samples/two_rods.bdf --json -");
  INFO(r.err);
  REQUIRE(r.code == 0);
  auto j = nlohmann::json::parse(r.out);
  CHECK(j["dof"] == 2);
  REQUIRE(j["modes"].size() == 2);  // EIGRL asks 3; the torsion DOFs have no stiffness
  // K = k[2 −1; −1 1], M = m diag(1, 1/2): λ = (2 ∓ √2) k/m.
  const double k = 2.1e11 * 1e-4, m = 7850.0 * 1e-4;
  CHECK(j["modes"][0]["eigenvalue"].get<double>() == Approx((2 - std::sqrt(2.0)) * k / m).epsilon(1e-12));
  CHECK(j["modes"][1]["eigenvalue"].get<double>() == Approx((2 + std::sqrt(2.0)) * k / m).epsilon(1e-12));
}

TEST_CASE("ssid modes: refuses a card it cannot assemble, names it", "[cli][modes]") {
  const fs::path dir = scratch();
  const fs::path deck = write(dir / "quad.bdf", rod_chain(2, 1.0, "EIGRL,1,,,2\n", "CQUAD4,7,1,1,2,3,3\n"));
  auto r = run_ssid("modes " + deck.string());
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Catch::Contains("CQUAD4") && Catch::Contains("cannot assemble"));
  auto u = run_ssid("modes " + deck.string() + " --seed 3");
  CHECK(u.code == 2);
  CHECK_THAT(u.err, Catch::Contains("need --uff"));
}

TEST_CASE("ssid modes --uff: synthetic test read back; noise reproducible by seed", "[cli][modes][synthetic]") {
  const fs::path dir = scratch();
  const fs::path deck = write(dir / "chain8.bdf", rod_chain(8, 2.0, "EIGRL,1,,,3\n"));
  const fs::path clean = dir / "clean.unv";
  auto r = run_ssid("modes " + deck.string() + " --json - --uff " + clean.string() + " --sensors 3,5:7,9");
  INFO(r.err);
  REQUIRE(r.code == 0);
  auto j = nlohmann::json::parse(r.out);
  auto t = ssid::translators::modes_from_uff(ssid::formats::uff::read_uff(clean.string()));
  REQUIRE(t.frequency_hz.size() == 3);
  CHECK(t.dofs.size() == 5 * 3);
  for (int i = 0; i < 3; ++i) CHECK(t.frequency_hz[i] == j["modes"][i]["cycles"].get<double>());
  // Mass-normalised axial shape of a lumped chain: φ(x_i) ∝ sin((2j−1)π i / 2n); Y and Z are zero.
  for (int mode = 0; mode < 3; ++mode) {
    const double scale = t.shapes(12, mode) / std::sin((2 * mode + 1) * M_PI * 8 / 16.0);
    for (int s = 0; s < 5; ++s) {
      const int grid = static_cast<int>(t.dofs[3 * s].node), i = grid - 1;
      CHECK(t.shapes(3 * s, mode) == Approx(scale * std::sin((2 * mode + 1) * M_PI * i / 16.0)).margin(1e-9 * std::abs(scale)));
      CHECK(t.shapes(3 * s + 1, mode) == 0.0);
    }
  }
  const fs::path a = dir / "a.unv", b = dir / "b.unv", c = dir / "c.unv";
  const std::string noisy = " --noise-freq 1 --noise-shape 3 --uff ";
  REQUIRE(run_ssid("modes " + deck.string() + noisy + a.string() + " --seed 11").code == 0);
  REQUIRE(run_ssid("modes " + deck.string() + noisy + b.string() + " --seed 11").code == 0);
  REQUIRE(run_ssid("modes " + deck.string() + noisy + c.string() + " --seed 12").code == 0);
  CHECK(cli_slurp(a) == cli_slurp(b));
  CHECK(cli_slurp(a) != cli_slurp(c));
  auto ta = ssid::translators::modes_from_uff(ssid::formats::uff::read_uff(a.string()));
  CHECK(ta.shapes.cols() == 3);
  CHECK(ta.dofs.size() == 9 * 3);  // default: every grid
  CHECK(ta.frequency_hz[0] != j["modes"][0]["cycles"].get<double>());
  CHECK(ta.frequency_hz[0] == Approx(j["modes"][0]["cycles"].get<double>()).epsilon(0.05));
}

TEST_CASE("ssid modes --weight: grid point weight of the frame sample against hand sums", "[cli][modes][weight]") {
  // samples/frame.bdf: lumped mass, each element's mass at its mid-point on average.
  const double rho = 2700.0, a_tube = M_PI * (0.02 * 0.02 - 0.015 * 0.015), a_rod = 2.0e-4;
  const double m_bar = rho * a_tube * 1.0, m_bat = rho * a_rod * 0.5, m_diag = rho * a_rod * std::sqrt(1.25);
  const double total = 6.0 + 12 * m_bar + 12 * m_bat + 12 * m_diag;
  const double xcg = (18 * m_bar + 24 * m_bat + 18 * m_diag + 18.0) / total;
  auto r = run_ssid("modes " + std::string(SSID_SOURCE_DIR) + "/samples/frame.bdf --nmodes 1 --weight");
  INFO(r.err);
  REQUIRE(r.code == 0);
  CHECK_THAT(r.out, Catch::Contains("O U T P U T   F R O M   G R I D   P O I N T   W E I G H T"));
  // Direction Y row: mass, X-C.G., Y-C.G. (0: not seen by a Y mass), Z-C.G.
  const auto at = r.out.find("                                  Y    ");
  REQUIRE(at != std::string::npos);
  std::istringstream row(r.out.substr(at + 36, 80));
  double m = 0, x = 0, y = 0, z = 0;
  row >> m >> x >> y >> z;
  CHECK(m == Approx(total).epsilon(1e-6));
  CHECK(x == Approx(xcg).epsilon(1e-6));
  CHECK(y == 0.0);
  CHECK(z == Approx(0.25).epsilon(1e-6));
  // Without --weight and without PARAM GRDPNT: no weight output.
  auto q = run_ssid("modes " + std::string(SSID_SOURCE_DIR) + "/samples/frame.bdf --nmodes 1");
  CHECK(q.out.find("W E I G H T") == std::string::npos);
}

TEST_CASE("ssid modes: a mechanism names its DOF", "[cli][modes][errors]") {
  // Without AUTOSPC the rods' rotations have neither stiffness nor mass.
  const fs::path dir = scratch();
  const fs::path deck = write(dir / "mech.bdf", rod_chain(3, 1.0, "EIGRL,1,,,2\n", "PARAM,AUTOSPC,NO\n"));
  auto r = run_ssid("modes " + deck.string());
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Catch::Contains("not positive definite") && Catch::Contains(" component ") && Catch::Contains("(grid "));
}

TEST_CASE("ssid modes --uff: sensor file, rotations, bad sensors", "[cli][modes][synthetic]") {
  const fs::path dir = scratch();
  const std::string deck = std::string(SSID_SOURCE_DIR) + "/samples/frame.bdf";
  const fs::path sensors = write(dir / "sensors.txt", "# tip station\n31 THRU 34\n21, 22\n");
  const fs::path out = dir / "rot.unv";
  auto r = run_ssid("modes " + deck + " --nmodes 3 --uff " + out.string() + " --sensor-file " + sensors.string() +
                    " --rotations");
  INFO(r.err);
  REQUIRE(r.code == 0);
  auto t = ssid::translators::modes_from_uff(ssid::formats::uff::read_uff(out.string()));
  CHECK(t.dofs.size() == 6 * 6);
  CHECK(t.dofs[0].node == 31);
  CHECK(t.dofs[5].direction == 6);
  CHECK(t.dofs[30].node == 22);
  auto bad = run_ssid("modes " + deck + " --nmodes 3 --uff " + out.string() + " --sensors 31,99");
  CHECK(bad.code == 2);
  CHECK_THAT(bad.err, Catch::Contains("sensor grid 99 is not a grid of the model"));
  auto both = run_ssid("modes " + deck + " --uff " + out.string() + " --sensors 31 --sensor-file " + sensors.string());
  CHECK(both.code == 2);
}

TEST_CASE("ssid modes honours EIGRL V1/V2 bands and EIGR", "[cli][modes]") {
  const fs::path dir = scratch();
  const int n = 40;
  // Band [f2, f4] (widened by 1e-6): exactly modes 2..4 of the closed form.
  const double f2 = std::sqrt(chain_lambda(n, 2.0, 2)) / (2 * M_PI), f4 = std::sqrt(chain_lambda(n, 2.0, 4)) / (2 * M_PI);
  char eig[128];
  std::snprintf(eig, sizeof eig, "EIGRL,1,%.9g,%.9g\n", f2 * (1 - 1e-6), f4 * (1 + 1e-6));
  auto r = run_ssid("modes " + write(dir / "band.bdf", rod_chain(n, 2.0, eig)).string() + " --json -");
  INFO(r.err);
  REQUIRE(r.code == 0);
  auto j = nlohmann::json::parse(r.out);
  REQUIRE(j["modes"].size() == 3);
  CHECK(j["modes"][0]["eigenvalue"].get<double>() == Approx(chain_lambda(n, 2.0, 2)).epsilon(1e-10));
  CHECK(j["modes"][2]["eigenvalue"].get<double>() == Approx(chain_lambda(n, 2.0, 4)).epsilon(1e-10));
  // EIGR: SID, METHOD, F1, F2, NE, ND.
  auto e = run_ssid("modes " + write(dir / "eigr.bdf", rod_chain(n, 2.0, "EIGR,1,LAN,,,,5\n")).string() + " --json -");
  INFO(e.err);
  REQUIRE(e.code == 0);
  CHECK(nlohmann::json::parse(e.out)["modes"].size() == 5);
}

namespace {

/// Runs ssid modes on `deck` with the default solver and with --method multilevel
/// and checks the frequencies of modes first..nmodes-1 agree to `eps` (relative).
void check_multilevel_matches_direct(const std::string& deck, int nmodes, int first, double eps) {
  const std::string args = "modes " + deck + " --nmodes " + std::to_string(nmodes);
  const CliResult direct = run_ssid(args + " --json -");
  const CliResult ml = run_ssid(args + " --method multilevel --json -");
  REQUIRE(direct.code == 0);
  INFO(ml.err);
  REQUIRE(ml.code == 0);
  const auto jd = nlohmann::json::parse(direct.out), jm = nlohmann::json::parse(ml.out);
  REQUIRE(jm["modes"].size() == static_cast<std::size_t>(nmodes));
  for (int i = first; i < nmodes; ++i)
    CHECK(jm["modes"][i]["cycles"].get<double>() == Approx(jd["modes"][i]["cycles"].get<double>()).epsilon(eps));
}

}  // namespace

TEST_CASE("ssid modes --method multilevel: a free 3D frame gives the direct solver's frequencies", "[cli][modes]") {
  // 6 x 5 x 4 grids 1 m apart, every lattice edge a CBAR: 720 DOFs, free-free.
  std::ostringstream s;
  s << "SOL 103\nCEND\nBEGIN BULK\n";
  auto id = [](int i, int j, int k) { return 1 + i + 6 * (j + 5 * k); };
  for (int k = 0; k < 4; ++k)
    for (int j = 0; j < 5; ++j)
      for (int i = 0; i < 6; ++i) s << "GRID," << id(i, j, k) << ",," << i << "." << "," << j << ".," << k << ".\n";
  int eid = 1;
  for (int k = 0; k < 4; ++k)
    for (int j = 0; j < 5; ++j)
      for (int i = 0; i < 6; ++i) {
        if (i + 1 < 6) s << "CBAR," << eid++ << ",1," << id(i, j, k) << "," << id(i + 1, j, k) << ",0.,1.,0.\n";
        if (j + 1 < 5) s << "CBAR," << eid++ << ",1," << id(i, j, k) << "," << id(i, j + 1, k) << ",1.,0.,0.\n";
        if (k + 1 < 4) s << "CBAR," << eid++ << ",1," << id(i, j, k) << "," << id(i, j, k + 1) << ",1.,0.,0.\n";
      }
  s << "PBAR,1,2,1.0E-3,1.0E-6,2.0E-6,2.0E-6\nMAT1,2,2.1E11,8.1E10,,7850.\nENDDATA\n";
  const fs::path deck = write(scratch() / "frame_ml.bdf", s.str());
  check_multilevel_matches_direct(deck.string(), 14, 6, 1e-9);  // elastic modes (the first six are rigid)
  const CliResult text = run_ssid("modes " + deck.string() + " --nmodes 14 --method multilevel");
  CHECK(text.out.find("Multilevel solver") != std::string::npos);
  const CliResult bad = run_ssid("modes " + deck.string() + " --method cholesky");
  CHECK(bad.code == 2);
  CHECK(bad.err.find("--method") != std::string::npos);
}

TEST_CASE("ssid modes --method multilevel on the MPI truss beam sample agrees with the direct solver", "[cli][modes][slow]") {
  // A real model: RBE2 spiders at the balls, CONM2s, suspension springs (modes at
  // 0.3-0.6 Hz), 8.5k a-set DOFs. Seen: 3.5e-9 relative at most over 35 modes.
  const std::string deck = std::string(SSID_SOURCE_DIR) + "/samples/mpi_beam.bdf";
  check_multilevel_matches_direct(deck, 35, 0, 1e-7);
}
