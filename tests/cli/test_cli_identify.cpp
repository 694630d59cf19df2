// `ssid identify modes`: FRFs of a 3-DOF chain written as UFF 58, modes back as JSON and
// UFF 55, compared with the chain's exact modes (dense eigen-solve).
#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "cli/cli_run.hpp"
#include "estimator/identification/chain_model.hpp"
#include "formats/uff.hpp"

namespace fs = std::filesystem;
namespace uff = ssid::formats::uff;
using cd = std::complex<double>;

namespace {

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("ssid_identify_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir / name;
}

/// Receptance FRFs of the chain (Rayleigh damping) from DOF 0 to every DOF, 0 … 500 Hz
/// every 0.25 Hz, as dataset 58 (complex double); nodes 1, 2, 3 in +X.
fs::path chain_frf_file(const ident_test::ChainModel& model) {
  uff::UffFile f;
  for (int o = 0; o < 3; ++o) {
    uff::Function58 fn;
    fn.function_type = 4;
    fn.function_id = o + 1;
    fn.response_node = o + 1;
    fn.response_direction = 1;
    fn.reference_node = 1;
    fn.reference_direction = 1;
    fn.ordinate_type = 6;
    fn.even = true;
    fn.abscissa_min = 0;
    fn.abscissa_increment = 0.25;
    for (int k = 0; k <= 2000; ++k) {
      const double w = 2 * M_PI * 0.25 * k;
      const Eigen::MatrixXcd H =
          (model.K.cast<cd>() - w * w * model.M.cast<cd>() + cd(0, w) * model.C.cast<cd>()).inverse();
      fn.x.push_back(0.25 * k);
      fn.y.push_back(H(o, 0));
    }
    f.datasets.emplace_back(fn);
  }
  const fs::path p = scratch("chain_frf.unv");
  uff::write_uff(f, p.string(), uff::Precision::Extended);
  return p;
}

}  // namespace

TEST_CASE("ssid identify modes --method era: the chain's three modes from its FRFs", "[cli][identify]") {
  const auto model = ident_test::chain_model(true, {0});
  const fs::path in = chain_frf_file(model);
  const fs::path json = scratch("modes.json"), out55 = scratch("modes.unv");
  const auto r = run_ssid("identify modes " + in.string() + " --method era --json " + json.string() + " --uff " +
                          out55.string());
  INFO(r.err);
  REQUIRE(r.code == 0);
  CHECK_THAT(r.out, Catch::StartsWith("3 FRF(s): 3 response(s) × 1 reference(s), 2001 lines every 0.25 Hz; ERA orders 2…40\n"));
  nlohmann::json j;
  std::ifstream(json) >> j;
  REQUIRE(j["modes"].size() == 3);
  std::vector<cd> poles;
  std::vector<Eigen::VectorXcd> shapes;
  model.exact(poles, shapes);
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> ges(model.K, model.M);
  double worst_f = 0, worst_z = 0, worst_mac = 1;
  for (std::size_t m = 0; m < 3; ++m) {
    const auto& mode = j["modes"][m];
    const double f = std::abs(poles[m]) / (2 * M_PI), z = -poles[m].real() / std::abs(poles[m]);
    worst_f = std::max(worst_f, std::abs(mode["hz"].get<double>() - f) / f);
    worst_z = std::max(worst_z, std::abs(mode["zeta"].get<double>() - z) / z);
    CHECK(mode["hz_std"].get<double>() >= 0);
    CHECK(mode["zeta_std"].get<double>() >= 0);
    REQUIRE(mode["shape"].size() == 3);
    Eigen::Vector3d phi;
    for (int o = 0; o < 3; ++o) {
      const auto& row = mode["shape"][static_cast<std::size_t>(o)];
      CHECK(row[0].get<int>() == o + 1);
      CHECK(row[1].get<int>() == 1);
      phi(o) = row[2].get<double>();
    }
    const Eigen::Vector3d exact = ges.eigenvectors().col(static_cast<Eigen::Index>(m));
    worst_mac = std::min(worst_mac, std::pow(phi.dot(exact), 2) / (phi.squaredNorm() * exact.squaredNorm()));
  }
  INFO("vs exact: frequency " << worst_f << ", damping " << worst_z << ", MAC " << worst_mac);
  CHECK(worst_f < 1e-6);  // measured 5e-8
  CHECK(worst_z < 1e-4);  // measured 9e-7
  CHECK(worst_mac > 0.9999);
  // UFF 55 back: three real normal modes at the same frequencies.
  const uff::UffFile back = uff::read_uff(out55.string());
  const auto modes55 = back.nodal_data();
  REQUIRE(modes55.size() == 3);
  for (std::size_t m = 0; m < 3; ++m) {
    CHECK(modes55[m]->is_normal_mode());
    CHECK(modes55[m]->frequency_hz() == Approx(j["modes"][m]["hz"].get<double>()).epsilon(1e-5));
  }
}

TEST_CASE("ssid identify: bad input exits 2 with the cause", "[cli][identify]") {
  const auto model = ident_test::chain_model(true, {0});
  const fs::path in = chain_frf_file(model);
  const auto m = run_ssid("identify modes " + in.string() + " --method armax");
  CHECK(m.code == 2);
  CHECK(m.err == "ssid: error: --method: expected era, got \"armax\" (armax and plscf are not available yet)\n");
  const auto o = run_ssid("identify modes " + in.string() + " --max-order 7");
  CHECK(o.code == 2);
  CHECK(o.err == "ssid: error: --max-order: expected an even number ≥ 2, got 7\n");
  // A file without FRFs: only a mode (dataset 55).
  uff::UffFile f;
  f.datasets.emplace_back(uff::NodalData55::normal_mode(1, 10.0, {1}, Eigen::MatrixXd::Ones(1, 3)));
  const fs::path none = scratch("no_frf.unv");
  uff::write_uff(f, none.string());
  const auto n = run_ssid("identify modes " + none.string());
  CHECK(n.code == 2);
  CHECK(n.err == "ssid: error: " + none.string() + ": no frequency response functions (dataset 58, function type 4)\n");
  const auto u = run_ssid("identify frobnicate");
  CHECK(u.code == 2);
  CHECK_THAT(u.err, Catch::StartsWith("ssid identify: unknown subcommand 'frobnicate'\n"));
  const auto h = run_ssid("identify --help");
  CHECK(h.code == 0);
  CHECK_THAT(h.out, Catch::StartsWith("usage: ssid identify <modes> ...\n"));
}
