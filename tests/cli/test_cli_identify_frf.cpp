// `ssid identify frf`: FRFs, coherence and multiple coherence from a universal file's time
// histories, compared with scipy.signal (tests/estimator/identification/welch_reference.py)
// run on the same records as read back from the file.
#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <cmath>
#include <complex>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>

#include "cli/cli_run.hpp"
#include "formats/uff.hpp"
#include "translators/synthetic_modes.hpp"

namespace fs = std::filesystem;
namespace uff = ssid::formats::uff;
using cd = std::complex<double>;

namespace {

fs::path scratch(const std::string& name) { return cli_scratch("idfrf") / name; }

uff::Function58 time_record(std::int64_t id, std::int64_t node, int direction, int ordinate, const char* unit,
                            const Eigen::VectorXd& samples, double dt) {
  uff::Function58 fn;
  fn.function_type = 1;
  fn.function_id = id;
  fn.response_node = node;
  fn.response_direction = direction;
  fn.reference_node = 1;
  fn.reference_direction = 1;
  fn.ordinate_type = 4;
  fn.even = true;
  fn.abscissa_min = 0;
  fn.abscissa_increment = dt;
  fn.axes[0].specific_data_type = 17;
  fn.axes[1].specific_data_type = ordinate;
  fn.axes[1].units = unit;
  for (Eigen::Index k = 0; k < samples.size(); ++k) {
    fn.x.push_back(static_cast<double>(k) * dt);
    fn.y.emplace_back(samples(k));
  }
  return fn;
}

/// ni white forces (nodes 1…ni, +X) and no responses (nodes 11…, +Z): FIR-filtered
/// mixtures of the forces plus independent noise; written as UFF 58 time histories.
fs::path records_file(const std::string& name, Eigen::Index ni, Eigen::Index no, Eigen::Index samples, double dt) {
  ssid::translators::NormalDeviates z(77);
  Eigen::MatrixXd x(samples, ni);
  for (Eigen::Index i = 0; i < x.size(); ++i) x(i) = z();
  const Eigen::Index taps = 6;
  // Each tap sized in place (copying one prototype matrix into the vector trips
  // GCC 12's -Wmaybe-uninitialized inside Eigen at -O3, an error with SSID_WERROR).
  std::vector<Eigen::MatrixXd> b(static_cast<std::size_t>(taps));
  for (auto& m : b) {
    m.resize(no, ni);
    for (Eigen::Index i = 0; i < m.size(); ++i) m(i) = z();
  }
  Eigen::MatrixXd y = Eigen::MatrixXd::Zero(samples, no);
  for (Eigen::Index n = 0; n < samples; ++n) {
    for (Eigen::Index l = 0; l < taps && l <= n; ++l)
      y.row(n) += (b[static_cast<std::size_t>(l)] * x.row(n - l).transpose()).transpose();
    for (Eigen::Index r = 0; r < no; ++r) y(n, r) += 0.4 * z();
  }
  uff::UffFile f;
  for (Eigen::Index r = 0; r < no; ++r) f.datasets.emplace_back(time_record(r + 1, 11 + r, 3, 12, "m/s^2", y.col(r), dt));
  for (Eigen::Index i = 0; i < ni; ++i) f.datasets.emplace_back(time_record(10 + i, 1 + i, 1, 13, "N", x.col(i), dt));
  const fs::path p = scratch(name);
  uff::write_uff(f, p.string(), uff::Precision::Extended);
  return p;
}

/// scipy's spectra, H1, H2, coherences of the records of `file` as ssid reads them back.
nlohmann::json scipy_reference(const fs::path& file, int segment, int overlap, const std::string& window) {
  const uff::UffFile f = uff::read_uff(file.string());
  nlohmann::json j;
  std::vector<const uff::Function58*> forces, responses;
  for (const auto* fn : f.functions()) (fn->axes[1].specific_data_type == 13 ? forces : responses).push_back(fn);
  for (std::size_t k = 0; k < forces.front()->y.size(); ++k) {
    nlohmann::json xr = nlohmann::json::array(), yr = nlohmann::json::array();
    for (const auto* fn : forces) xr.push_back(fn->y[k].real());
    for (const auto* fn : responses) yr.push_back(fn->y[k].real());
    j["x"].push_back(xr);
    j["y"].push_back(yr);
  }
  j["dt"] = forces.front()->abscissa_increment;
  j["nperseg"] = segment;
  j["noverlap"] = overlap;
  j["window"] = window;
  const fs::path in = scratch("ref_in.json"), out = scratch("ref_out.json");
  std::ofstream(in) << j.dump();
  const std::string script = std::string(SSID_SOURCE_DIR) + "/tests/estimator/identification/welch_reference.py";
  REQUIRE(std::system(("/usr/bin/python3 '" + script + "' '" + in.string() + "' '" + out.string() + "'").c_str()) == 0);
  nlohmann::json r;
  std::ifstream(out) >> r;
  return r;
}

bool python_has_scipy() { return std::system("/usr/bin/python3 -c 'import scipy.signal' >/dev/null 2>&1") == 0; }

nlohmann::json read_json(const fs::path& p) {
  std::ifstream in(p);
  nlohmann::json j;
  in >> j;
  return j;
}

}  // namespace

TEST_CASE("ssid identify frf: H1 with two references and its coherences agree with scipy.signal",
          "[cli][identify][frf][scipy]") {
  if (!python_has_scipy()) {
    WARN("/usr/bin/python3 lacks scipy.signal: the comparison with scipy is skipped");
    return;
  }
  const fs::path file = records_file("mimo.unv", 2, 3, 4096, 0.001), json = scratch("mimo.json"),
                 unv = scratch("mimo_frf.unv");
  const CliResult r = run_ssid("identify frf " + file.string() + " --segment 256 --overlap 0.5 --json " +
                               json.string() + " --uff " + unv.string());
  INFO(r.err);
  REQUIRE(r.code == 0);
  CHECK(r.out.find("5 time histories: 3 response(s), 2 force(s), 4096 samples every 0.001 s\n") != std::string::npos);
  CHECK(r.out.find("H1 by Welch: 31 averages of 256 samples (0.256 s), overlap 128 samples, window hann; 129 lines "
                   "every 3.90625 Hz (0 … 500 Hz)") != std::string::npos);
  CHECK(r.out.find("peak |H| (m/s^2)/(N)") != std::string::npos);
  const nlohmann::json j = read_json(json), ref = scipy_reference(file, 256, 128, "hann");
  REQUIRE(j["frequency_hz"].size() == ref["f"].size());
  REQUIRE(j["frfs"].size() == 6);
  double dev_h = 0, dev_c = 0, dev_m = 0;
  for (std::size_t k = 0; k < ref["f"].size(); ++k) {
    CHECK(j["frequency_hz"][k].get<double>() == Approx(ref["f"][k].get<double>()).epsilon(1e-12));
    for (std::size_t i = 0; i < 2; ++i)
      for (std::size_t o = 0; o < 3; ++o) {
        const auto& fr = j["frfs"][o + 3 * i];
        CHECK(fr["response"][0].get<int>() == static_cast<int>(11 + o));
        CHECK(fr["reference"][0].get<int>() == static_cast<int>(1 + i));
        const cd got(fr["re"][k].get<double>(), fr["im"][k].get<double>());
        const cd want(ref["h1"][k][o][i][0].get<double>(), ref["h1"][k][o][i][1].get<double>());
        dev_h = std::max(dev_h, std::abs(got - want) / std::abs(want));
        dev_c = std::max(dev_c, std::abs(fr["coherence"][k].get<double>() - ref["coherence"][k][o][i].get<double>()));
      }
    for (std::size_t o = 0; o < 3; ++o)
      dev_m = std::max(dev_m, std::abs(j["multiple_coherence"][o]["values"][k].get<double>() -
                                       ref["multiple_coherence"][k][o].get<double>()));
  }
  CHECK(dev_h < 1e-10);
  CHECK(dev_c < 1e-12);
  CHECK(dev_m < 1e-12);

  // UFF 58 out: per pair an FRF (type 4) and a coherence (6), per response a multiple coherence (26).
  const uff::UffFile back = uff::read_uff(unv.string());
  REQUIRE(back.functions().size() == 6 * 2 + 3);
  std::map<int, int> types;
  for (const auto* f : back.functions()) ++types[f->function_type];
  CHECK(types[4] == 6);
  CHECK(types[6] == 6);
  CHECK(types[26] == 3);
  const uff::Function58& h = *back.functions()[0];
  CHECK(h.axes[1].specific_data_type == 12);
  CHECK(h.axes[2].specific_data_type == 13);
  const cd want(j["frfs"][0]["re"][40].get<double>(), j["frfs"][0]["im"][40].get<double>());
  CHECK(std::abs(h.y[40] - want) < 1e-10 * std::abs(want));
  const CliResult l = run_ssid("uff list " + unv.string());
  CHECK(l.code == 0);
  CHECK(l.out.find("type 26 (multiple coherence)") != std::string::npos);
  CHECK(l.out.find("type 6 (coherence)") != std::string::npos);
}

TEST_CASE("ssid identify frf: H2 with a flat-top window agrees with scipy.signal", "[cli][identify][frf][scipy]") {
  if (!python_has_scipy()) {
    WARN("/usr/bin/python3 lacks scipy.signal: the comparison with scipy is skipped");
    return;
  }
  const fs::path file = records_file("siso.unv", 1, 2, 3000, 0.002), json = scratch("siso.json");
  const CliResult r = run_ssid("identify frf " + file.string() + " --estimator h2 --window flattop --segment 200 "
                               "--overlap 0.25 --json " + json.string());
  INFO(r.err);
  REQUIRE(r.code == 0);
  const nlohmann::json j = read_json(json), ref = scipy_reference(file, 200, 50, "flattop");
  CHECK(j["averages"] == 19);
  CHECK_FALSE(j.contains("multiple_coherence"));
  double dev = 0;
  for (std::size_t k = 1; k < ref["f"].size(); ++k)
    for (std::size_t o = 0; o < 2; ++o) {
      const cd got(j["frfs"][o]["re"][k].get<double>(), j["frfs"][o]["im"][k].get<double>());
      const cd want(ref["h2"][k][o][0].get<double>(), ref["h2"][k][o][1].get<double>());
      dev = std::max(dev, std::abs(got - want) / std::abs(want));
    }
  CHECK(dev < 1e-10);
}

TEST_CASE("ssid identify frf: bad options and records exit 2 with the reason", "[cli][identify][frf]") {
  const fs::path file = records_file("bad.unv", 2, 1, 512, 0.001);
  const auto err = [](const CliResult& r) {
    CHECK(r.code == 2);
    return r.err;
  };
  CHECK(run_ssid("identify frf --help").code == 0);
  CHECK(err(run_ssid("identify frf " + file.string() + " --estimator h2 --segment 128")) ==
        "ssid: error: " + file.string() +
            ": --estimator h2 with 2 force records (expected 1; use h1 or hv with several references)\n");
  CHECK(err(run_ssid("identify frf " + file.string() + " --window kaiser")) ==
        "ssid: error: --window: expected hann, flattop, force-exp or rect, got \"kaiser\"\n");
  CHECK(err(run_ssid("identify frf " + file.string() + " --exp-decay 5")) ==
        "ssid: error: --force-fraction and --exp-decay shape the impact windows: give --window force-exp too\n");
  CHECK(err(run_ssid("identify frf " + file.string() + " --overlap 1")) ==
        "ssid: error: --overlap: expected a fraction 0 ≤ F < 1, got 1\n");
  CHECK(err(run_ssid("identify frf " + file.string())) ==
        "ssid: error: " + file.string() +
            ": 512 samples per record, fewer than one Welch segment of 1024 (--segment)\n");
  // Impact windows: the exponential's τ from the decay at the segment's end, said on stdout.
  const CliResult ok = run_ssid("identify frf " + file.string() + " --window force-exp --segment 256 --exp-decay 1");
  INFO(ok.err);
  CHECK(ok.code == 0);
  CHECK(ok.out.find("window force-exp (force 10 % of the segment, exponential τ = 0.055") != std::string::npos);
}
