// Issue 22's end-to-end proof: a modal test of the MPI truss simulated in the
// time domain, then the whole test-to-update chain through the CLI.
//
// The truth is the rod-form truss with a strut-area error (STRUTA +5 %) and a
// 2 kg mass hidden at the optics-boom tip ball (grid 29); its modes come from
// the truss generator's own reference assembler (not ssid's deck assembly).
// Two shakers drive it with independent white-noise forces (σ = 10 N) in the
// directions that excite the band's modes best; triaxial accelerometers sit at
// every ball. Each mode k (every one below 100 Hz, suspension modes included)
// carries modal damping ζ_k drawn from 0.5–2 % and is integrated exactly over
// each sample with the force held (zero-order hold): the sampled responses are
// those of the continuous structure, with the structure's own poles. Noise of
// 3 % of each record's RMS is added to the accelerations and 1 % to the forces.
//
// The records go to a binary universal file (58b, single precision: what
// Test.Lab writes by default). ssid then identifies the modes from the time
// data (ERA and pLSCF on H1 FRFs by Welch, Hann, 20 averages of 4096 samples),
// every mode of the band within 0.1 % of the truth, and `ssid estimate` and
// `ssid diagnose` take the identified modes with their σ. They must reach what
// they reach from the exact modes (the same truth's modes at the sensors with
// the library tests' noise, written as UFF 55): with parameter errors only, the
// strut area and joint mass recovered within 3σ; with the hidden mass, the
// mass named at grid 29 with its value and the strut area recovered.
//
// ARMAX is not run on this test: its step 3 holds p³ × samples values (8.9 TB for
// the 240 records), and the order its rule needs (s = 2N/p for the ~70 modes
// under the anti-aliasing cut-off) is far beyond the paper's few outputs and
// modes; ssid refuses it with that figure (checked below) and `--responses`
// chooses a few records (docs/identification.md).
#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>

#include "formats/uff.hpp"
#include "tests/cli/cli_run.hpp"
#include "tests/estimator/diagnosis/truss_cases.hpp"

namespace fs = std::filesystem;
using json = nlohmann::json;
using namespace ssid;
using namespace ssid::test_support;
namespace uff = ssid::formats::uff;

namespace {

/// The FRFs' line spacing: Welch segments of 4096 samples at 256 Hz.
constexpr double kLineHz = 256.0 / 4096;

/// The simulated test's settings.
struct ShakerTest {
  double sample_hz = 256.0;      ///< Nyquist 128 Hz
  Eigen::Index samples = 43008;  ///< 168 s: 20 Welch segments of 4096 at half overlap
  double mode_cutoff_hz = 100.0; ///< modes above are left out (the anti-aliasing filter's work)
  double force_std = 10.0;       ///< N
  double response_noise = 0.03;  ///< σ of the added noise / the record's RMS
  double force_noise = 0.01;
  double zeta_min = 0.005, zeta_max = 0.02;
  unsigned seed = 2201;
};

/// Time histories: forces (2 × N, N) and accelerations (p × N, m/s²) at `dofs`.
struct TimeData {
  std::vector<std::pair<int, int>> force_dofs, dofs;  ///< (grid, direction 1..3)
  Eigen::MatrixXd forces, responses;
  std::vector<double> zeta;  ///< per simulated mode
  std::vector<double> band_hz, band_zeta;  ///< the truth's modes in the band, and their damping
};

/// Modal displacement q and velocity of one mode under a held force:
/// x_{n+1} = Φ x_n + Γ p_n, the exact solution of q̈ + 2ζω q̇ + ω² q = p over Δt
/// with p constant (Φ = e^{AΔt}, Γ = A⁻¹(Φ − I)B for A = [0 1; −ω² −2ζω], B = [0; 1]).
struct ModeStep {
  Eigen::Matrix2d phi;
  Eigen::Vector2d gamma;
};
ModeStep mode_step(double w, double zeta, double dt) {
  const double s = zeta * w, wd = w * std::sqrt(1 - zeta * zeta), e = std::exp(-s * dt);
  const double c = std::cos(wd * dt), sn = std::sin(wd * dt);
  ModeStep m;
  m.phi << e * (c + s / wd * sn), e * sn / wd, -e * w * w / wd * sn, e * (c - s / wd * sn);
  m.gamma << -2 * zeta / w * m.phi(0, 1) - (m.phi(1, 1) - 1) / (w * w), m.phi(0, 1);
  return m;
}

/// Of the sensors' DOFs, the two whose drive excites the band's modes best: the
/// pair maximising the smallest (over modes in the band) of φ_k(r1)² + φ_k(r2)²,
/// each mode's shape scaled to unit largest sensor component.
std::pair<std::size_t, std::size_t> shaker_dofs(const Eigen::MatrixXd& phi_band) {
  Eigen::MatrixXd s = phi_band;
  for (Eigen::Index k = 0; k < s.cols(); ++k) s.col(k) /= s.col(k).cwiseAbs().maxCoeff();
  double best = -1;
  std::pair<std::size_t, std::size_t> out{0, 1};
  for (Eigen::Index a = 0; a < s.rows(); ++a)
    for (Eigen::Index b = a + 1; b < s.rows(); ++b) {
      const double worst = (s.row(a).array().square() + s.row(b).array().square()).minCoeff();
      if (worst > best) {
        best = worst;
        out = {static_cast<std::size_t>(a), static_cast<std::size_t>(b)};
      }
    }
  return out;
}

TimeData simulate(const tr::TrussCards& truth, const ShakerTest& spec, double band_low, double band_high) {
  const tr::ReferenceModes rm = tr::reference_modes(truth, 120);
  std::map<int, Eigen::Index> index;
  for (std::size_t i = 0; i < rm.grid_ids.size(); ++i) index[rm.grid_ids[i]] = static_cast<Eigen::Index>(i);
  TimeData t;
  for (const auto& g : truth.grids)
    if (g.kind == "ball")
      for (int c = 1; c <= 3; ++c) t.dofs.push_back({g.id, c});
  const auto p = static_cast<Eigen::Index>(t.dofs.size());
  std::vector<Eigen::Index> modes;
  for (std::size_t j = 0; j < rm.frequency_hz.size(); ++j)
    if (rm.frequency_hz[j] > 0.05 && rm.frequency_hz[j] < spec.mode_cutoff_hz) modes.push_back(static_cast<Eigen::Index>(j));
  REQUIRE(rm.frequency_hz.back() > spec.mode_cutoff_hz);  // every mode below the cut-off is in
  Eigen::MatrixXd phi(p, static_cast<Eigen::Index>(modes.size()));
  for (Eigen::Index i = 0; i < p; ++i)
    for (Eigen::Index k = 0; k < phi.cols(); ++k)
      phi(i, k) = rm.shapes(6 * index.at(t.dofs[static_cast<std::size_t>(i)].first) + t.dofs[static_cast<std::size_t>(i)].second - 1,
                            modes[static_cast<std::size_t>(k)]);
  std::vector<Eigen::Index> band;
  for (Eigen::Index k = 0; k < phi.cols(); ++k) {
    const double f = rm.frequency_hz[static_cast<std::size_t>(modes[static_cast<std::size_t>(k)])];
    if (f >= band_low && f <= band_high) band.push_back(k);
  }
  Eigen::MatrixXd phi_band(p, static_cast<Eigen::Index>(band.size()));
  for (std::size_t k = 0; k < band.size(); ++k) phi_band.col(static_cast<Eigen::Index>(k)) = phi.col(band[k]);
  const auto [r1, r2] = shaker_dofs(phi_band);
  t.force_dofs = {t.dofs[r1], t.dofs[r2]};

  std::mt19937 rng(spec.seed);
  std::normal_distribution<double> n01(0.0, 1.0);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  const Eigen::Index n = spec.samples;
  const double dt = 1.0 / spec.sample_hz;
  t.forces.resize(2, n);
  for (Eigen::Index s = 0; s < n; ++s)
    for (int r = 0; r < 2; ++r) t.forces(r, s) = spec.force_std * n01(rng);
  // Modal forces p_k = φ_k(r1) F1 + φ_k(r2) F2; accelerations q̈ = p − 2ζω q̇ − ω² q.
  Eigen::MatrixXd qdd(phi.cols(), n);
  for (Eigen::Index k = 0; k < phi.cols(); ++k) {
    const double w = 2 * M_PI * rm.frequency_hz[static_cast<std::size_t>(modes[static_cast<std::size_t>(k)])];
    const double zeta = spec.zeta_min + (spec.zeta_max - spec.zeta_min) * u01(rng);
    t.zeta.push_back(zeta);
    const ModeStep st = mode_step(w, zeta, dt);
    Eigen::Vector2d x = Eigen::Vector2d::Zero();
    for (Eigen::Index s = 0; s < n; ++s) {
      const double pk = phi(static_cast<Eigen::Index>(r1), k) * t.forces(0, s) + phi(static_cast<Eigen::Index>(r2), k) * t.forces(1, s);
      qdd(k, s) = pk - 2 * zeta * w * x(1) - w * w * x(0);
      x = st.phi * x + st.gamma * pk;
    }
  }
  t.responses = phi * qdd;
  for (const Eigen::Index k : band) {
    t.band_hz.push_back(rm.frequency_hz[static_cast<std::size_t>(modes[static_cast<std::size_t>(k)])]);
    t.band_zeta.push_back(t.zeta[static_cast<std::size_t>(k)]);
  }
  auto add_noise = [&](Eigen::MatrixXd& m, double level) {
    for (Eigen::Index i = 0; i < m.rows(); ++i) {
      const double rms = m.row(i).norm() / std::sqrt(static_cast<double>(n));
      for (Eigen::Index s = 0; s < n; ++s) m(i, s) += level * rms * n01(rng);
    }
  };
  add_noise(t.responses, spec.response_noise);
  add_noise(t.forces, spec.force_noise);
  return t;
}

/// The records as a binary universal file (58b, little endian, 4-byte reals):
/// forces typed 13 (excitation force), accelerations 12, reference = the first shaker.
void write_time_file(const TimeData& t, double dt, const fs::path& path) {
  uff::UffFile f;
  std::int64_t id = 0;
  auto record = [&](const std::pair<int, int>& dof, const Eigen::Ref<const Eigen::RowVectorXd>& v, bool force) {
    uff::Function58 fn;
    fn.id_lines = {force ? "Shaker force" : "Acceleration", "simulated MPI modal test", "NONE", "NONE", "NONE"};
    fn.function_type = 1;
    fn.function_id = ++id;
    fn.response_node = dof.first;
    fn.response_direction = dof.second;
    fn.reference_node = t.force_dofs[0].first;
    fn.reference_direction = t.force_dofs[0].second;
    fn.ordinate_type = 2;
    fn.even = true;
    fn.abscissa_min = 0;
    fn.abscissa_increment = dt;
    fn.axes[0] = {18, 0, 0, 0, "Time", "s"};
    fn.axes[1] = force ? uff::Axis58{13, 0, 1, 0, "Force", "N"} : uff::Axis58{12, 1, 0, 0, "Acceleration", "m/s^2"};
    fn.binary = true;
    for (Eigen::Index s = 0; s < v.size(); ++s) fn.y.emplace_back(v(s), 0.0);
    f.datasets.emplace_back(std::move(fn));
  };
  for (std::size_t r = 0; r < t.force_dofs.size(); ++r) record(t.force_dofs[r], t.forces.row(static_cast<Eigen::Index>(r)), true);
  for (std::size_t i = 0; i < t.dofs.size(); ++i) record(t.dofs[i], t.responses.row(static_cast<Eigen::Index>(i)), false);
  uff::write_uff(f, path.string());
}

json read_json(const fs::path& p) {
  json j;
  std::ifstream(p) >> j;
  return j;
}

/// A parameter of a list by name: (estimate, std); ssid estimate's JSON names the
/// posterior's σ "posterior_std", a diagnosis hypothesis's "std".
std::pair<double, double> parameter(const json& list, const std::string& name, const std::string& std_key = "std") {
  for (const auto& q : list)
    if (q["name"] == name) return {q["estimate"].get<double>(), q[std_key].get<double>()};
  FAIL("no parameter " << name);
  return {0, 0};
}

/// A nominal DESVAR's XINIT.
double nominal_value(const Case& c, const std::string& label) {
  for (const auto& d : c.fe.desvars)
    if (d.label == label) return d.init;
  FAIL("no DESVAR " << label);
  return 0;
}

/// The test as a universal file of time histories, in `dir`.
struct SimulatedTest {
  fs::path file;
  TimeData data;
};
SimulatedTest simulated_test(const Case& truth, const fs::path& dir, unsigned seed) {
  ShakerTest spec;
  spec.seed = seed;
  const TestSpec band;  // 2–66 Hz, the band of the library's diagnosis tests
  SimulatedTest out{dir / "time.unv", simulate(truth.fe, spec, band.f_low, band.f_high)};
  write_time_file(out.data, 1.0 / spec.sample_hz, out.file);
  return out;
}

/// `ssid identify modes` on the time histories; the modes JSON. Checks that every
/// mode of the truth in the band was found once, and nothing else: within 0.1 % in
/// frequency (the floor of the σ ssid estimate gives an identified frequency is
/// 0.05 %), and in damping within 25 % where the lines resolve the peak by ssid
/// identify check's own pass (the half-power band 2ζf spans ≥ 3 lines of 0.0625 Hz);
/// a peak less resolved is widened by the Hann window's leakage: ζ is then only
/// required between the truth's and twice it.
fs::path identify(const SimulatedTest& test, const std::string& method, const fs::path& dir) {
  const fs::path id = dir / (method + ".json");
  const auto r = run_ssid("identify modes " + test.file.string() + " --method " + method +
                          " --min-hz 2 --max-hz 66 --segment 4096 --max-order 80 --json " + id.string());
  INFO(method << ": " << r.out << r.err);
  REQUIRE(r.code == 0);
  const json modes = read_json(id)["modes"];
  REQUIRE(modes.size() == test.data.band_hz.size());
  for (std::size_t k = 0; k < modes.size(); ++k) {
    const double hz = modes[k]["hz"], zeta = modes[k]["zeta"];
    CAPTURE(method, k, hz, test.data.band_hz[k], zeta, test.data.band_zeta[k]);
    CHECK(std::abs(hz / test.data.band_hz[k] - 1) < 1e-3);
    const double lines = 2 * test.data.band_zeta[k] * test.data.band_hz[k] / kLineHz;
    CAPTURE(lines);
    if (lines >= 3) {
      CHECK(std::abs(zeta / test.data.band_zeta[k] - 1) < 0.25);
    } else {
      CHECK(zeta > 0.75 * test.data.band_zeta[k]);
      CHECK(zeta < 2 * test.data.band_zeta[k]);
    }
    CHECK(modes[k]["shape"].size() == test.data.dofs.size());
  }
  return id;
}

/// The truth's modes at every ball with the library tests' noise (0.2 % frequency, 2 %
/// of the RMS shape component), as UFF 55: the "exact modes" the identified ones face.
fs::path exact_modes(const Case& truth, const fs::path& dir, unsigned seed) {
  TestSpec exact;
  exact.seed = seed;
  const fs::path p = dir / "exact.unv";
  formats::uff::write_uff(translators::mode_set_to_uff(synthetic_test(truth.fe, exact)), p.string());
  return p;
}

/// A case's scratch folder, with the nominal rod deck ssid is given written in it.
fs::path case_folder(const std::string& tag, const Case& nominal) {
  const fs::path dir = cli_scratch(tag);
  std::ofstream(dir / "rod.bdf") << deck_text(nominal.t, nominal.fe);
  return dir;
}

}  // namespace

TEST_CASE("a simulated MPI shaker test: ssid estimate recovers the parameters from the identified modes",
          "[cli][identify][estimate][mpi_test][slow]") {
  const Case nominal = rod_case();
  const fs::path dir = case_folder("mpi_shaker_estimate", nominal);
  Case truth = rod_case();
  perturb(truth.fe, "STRUTA", 1.05);
  perturb(truth.fe, "JOINTM", 0.95);
  const SimulatedTest test = simulated_test(truth, dir, 2201);
  INFO("shakers at " << test.data.force_dofs[0].first << ":" << test.data.force_dofs[0].second << " and "
                     << test.data.force_dofs[1].first << ":" << test.data.force_dofs[1].second);
  const fs::path exact = exact_modes(truth, dir, 2202);

  for (const std::string source : {"exact", "era", "plscf"}) {
    const fs::path modes = source == "exact" ? exact : identify(test, source, dir);
    const fs::path out = dir / ("e_" + source + ".json");
    const auto e = run_ssid("estimate " + (dir / "rod.bdf").string() + " " + modes.string() + " -q --json " + out.string());
    INFO(source << ": " << e.out << e.err);
    REQUIRE(e.code == 0);
    const json j = read_json(out);
    for (const auto& [name, factor] : {std::pair<std::string, double>{"STRUTA", 1.05}, {"JOINTM", 0.95}}) {
      const double truth_value = factor * nominal_value(nominal, name);
      const auto [value, sd] = parameter(j["parameters"], name, "posterior_std");
      CAPTURE(source, name, value, sd, truth_value);
      CHECK(std::abs(value - truth_value) < 3 * sd);
      // The test resolves the error (else the check above would hold for the nominal too).
      CHECK(sd < std::abs(truth_value - nominal_value(nominal, name)));
    }
  }
  fs::remove_all(dir);
}

TEST_CASE("a simulated MPI shaker test: ssid diagnose names the hidden mass from the identified modes",
          "[cli][identify][diagnose][mpi_test][slow]") {
  const Case nominal = rod_case();
  const fs::path dir = case_folder("mpi_shaker_diagnose", nominal);
  Case truth = rod_case();
  perturb(truth.fe, "STRUTA", 1.05);
  const int grid = 29;     // the optics-boom tip ball
  const double mass = 2.0; // kg, about 1 % of the truss
  truth.fe.masses.push_back({9001, grid, mass, 0.0, "hidden"});
  const SimulatedTest test = simulated_test(truth, dir, 2203);
  const fs::path exact = exact_modes(truth, dir, 2204);

  const double strut_area = 1.05 * nominal_value(nominal, "STRUTA");
  for (const std::string source : {"exact", "era", "plscf"}) {
    const fs::path modes = source == "exact" ? exact : identify(test, source, dir);
    const fs::path out = dir / ("d_" + source + ".json");
    const auto d = run_ssid("diagnose " + (dir / "rod.bdf").string() + " " + modes.string() + " -q --json " + out.string());
    INFO(source << ": " << d.out << d.err);
    REQUIRE(d.code == 0);
    const json j = read_json(out);
    REQUIRE(j["cause"]["kind"] == "missing_mass");
    CHECK(j["cause"]["location"]["grids"] == json::array({grid}));
    const double value = j["cause"]["value"], sd = j["cause"]["std"];
    CAPTURE(source, value, sd);
    CHECK(std::abs(value - mass) < 3 * sd);
    CHECK(sd < 0.1 * mass);
    int rows = 0;
    for (const auto& h : j["ranking"])
      if (h["kind"] == "missing_mass" && h["location"]["grids"] == json::array({grid})) {
        ++rows;
        const auto [area, area_sd] = parameter(h["all_parameters"], "STRUTA");
        CAPTURE(area, area_sd, strut_area);
        CHECK(std::abs(area - strut_area) < 3 * area_sd);
      }
    CHECK(rows == 1);
  }

  // ARMAX's step 3 grows as p³: on the 240 records it is refused before it
  // starts, naming what would do, rather than ended by the allocator.
  const auto a = run_ssid("identify modes " + test.file.string() + " --method armax");
  CHECK(a.code == 2);
  CHECK_THAT(a.err, Catch::Contains("--method armax on 240 response record(s) at AR order 1 would hold") &&
                        Catch::Contains("choose a few records with --responses"));
  fs::remove_all(dir);
}
