#pragma once
/// Synthetic measured data for the estimation tests: MPI truss rod decks from
/// the generator, and "measured" modes of a truth deck written as UFF 55 at a
/// sensor set, with seeded noise. (A local helper: the FE modes come from the
/// same assembly and eigen-solver the estimator uses, written through the
/// formats layer's UFF writer and read back by the estimator like any test file.)
#include <Eigen/Core>
#include <cctype>
#include <filesystem>
#include <map>
#include <random>
#include <string>
#include <unistd.h>
#include <vector>

#include "estimator/eigen/eigen_solver.hpp"
#include "formats/bulk_model.hpp"
#include "formats/deck_writer.hpp"
#include "formats/uff.hpp"
#include "translators/assembly/fe_model.hpp"
#include "translators/measurement/mode_set.hpp"
#include "translators/truss/configurations.hpp"
#include "translators/truss/truss_cards.hpp"
#include "translators/truss/truss_deck.hpp"

namespace estimate_test {

namespace fs = std::filesystem;

inline std::string to_upper(std::string s) {
  for (auto& c : s) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return s;
}

inline fs::path scratch(const std::string& name) {
  const fs::path p = fs::temp_directory_path() / ("ssid_estimate_" + std::to_string(::getpid())) / name;
  fs::create_directories(p);
  return p;
}

/// Writes the generator's rod deck of `configs` to `path`.
inline void write_rod_deck(const std::vector<std::string>& configs, const fs::path& path) {
  namespace truss = ssid::translators::truss;
  const truss::TrussModel t = truss::build_configured(configs);
  const truss::TrussCards fe = truss::build_truss_cards(t, truss::ModelForm::Rod);
  const ssid::formats::Deck deck = truss::to_deck(t, fe, "test", path.filename().string());
  if (fs::exists(path)) fs::remove(path);
  ssid::formats::write_deck(deck, path.string());
}

/// A deck with its assembly.
struct DeckModel {
  ssid::formats::Deck deck;
  std::unique_ptr<ssid::translators::FeModel> fe;
};

inline DeckModel load(const fs::path& path) {
  DeckModel d{ssid::formats::read_deck(path.string()), nullptr};
  ssid::formats::BulkModel bulk = ssid::formats::parse_bulk(d.deck);
  ssid::formats::resolve(d.deck, bulk);
  d.fe = std::make_unique<ssid::translators::FeModel>(d.deck, std::move(bulk));
  return d;
}

struct Synthetic {
  std::vector<std::int64_t> sensors;  ///< grids measured in X, Y, Z
  int modes = 18;                     ///< lowest analysis modes computed
  double min_hz = 0;                  ///< modes below are not "measured"
  double freq_noise_pct = 0;          ///< σ of the frequency noise, % of f
  double shape_noise = 0;             ///< σ added to each component of the unit-normalised shape
  unsigned seed = 1;
  double scale = -3.7;                ///< arbitrary test scaling and sign
};

/// The "measured" modes of `model` at parameters x (DESVAR order), as a universal file
/// (2411 nodes + one 55 per mode, extended precision). Returns the exact frequencies.
inline std::vector<double> write_measured(const DeckModel& model, const Eigen::VectorXd& x, const Synthetic& s,
                                          const fs::path& uff_path) {
  namespace tr = ssid::translators;
  const auto& fe = *model.fe;
  const tr::FeOperators ops = fe.operators(x, false);
  ssid::estimator::EigenOptions eo;
  eo.nd = s.modes;
  const auto res = ssid::estimator::solve_modes(ops.K, ops.M, eo);
  if (!res.ok()) throw std::runtime_error("synthetic data: eigen-solve failed: " + res.message);
  const Eigen::MatrixXd g = fe.expand(res.modes);
  std::mt19937_64 rng(s.seed);
  std::normal_distribution<double> normal;
  tr::ModeSet set;
  std::vector<ssid::formats::uff::Node> nodes;
  for (auto id : s.sensors) {
    const auto& gp = fe.geometry().grid(id, "sensor");
    ssid::formats::uff::Node n;
    n.id = id;
    n.xyz = {gp.x(0), gp.x(1), gp.x(2)};
    nodes.push_back(n);
    for (int c = 1; c <= 3; ++c) set.dofs.push_back({id, c});
  }
  std::vector<double> exact;
  std::vector<Eigen::VectorXd> cols;
  for (int m = 0; m < res.size(); ++m) {
    const double f = std::sqrt(std::max(res.eigenvalues(m), 0.0)) / (2 * M_PI);
    if (f < s.min_hz) continue;
    Eigen::VectorXd shape(static_cast<Eigen::Index>(3 * s.sensors.size()));
    for (std::size_t k = 0; k < s.sensors.size(); ++k) {
      const auto& gp = fe.geometry().grid(s.sensors[k], "sensor");
      Eigen::Vector3d u_cd;
      for (int c = 0; c < 3; ++c) u_cd(c) = g(static_cast<Eigen::Index>(gp.dofs[static_cast<std::size_t>(c)]), m);
      shape.segment<3>(static_cast<Eigen::Index>(3 * k)) = gp.frame * u_cd;
    }
    shape /= shape.norm();
    for (Eigen::Index k = 0; k < shape.size(); ++k) shape(k) += s.shape_noise * normal(rng);
    exact.push_back(f);
    set.frequency_hz.push_back(f * (1.0 + s.freq_noise_pct / 100.0 * normal(rng)));
    set.numbers.push_back(m + 1);
    set.damping.push_back(0.0);
    set.modal_mass.push_back(0.0);
    cols.push_back(s.scale * shape);
  }
  set.shapes.resize(static_cast<Eigen::Index>(set.dofs.size()), static_cast<Eigen::Index>(cols.size()));
  for (std::size_t k = 0; k < cols.size(); ++k) set.shapes.col(static_cast<Eigen::Index>(k)) = cols[k];
  const auto file = tr::mode_set_to_uff(set, nodes);
  ssid::formats::uff::write_uff(file, uff_path.string(), ssid::formats::uff::Precision::Extended);
  return exact;
}

/// DESVAR values by label with some replaced.
inline Eigen::VectorXd parameters_with(const DeckModel& model, const std::map<std::string, double>& values) {
  Eigen::VectorXd x = model.fe->initial_parameters();
  const auto& params = model.fe->parameters();
  for (const auto& [label, v] : values)
    for (std::size_t j = 0; j < params.size(); ++j)
      if (to_upper(params[j].label) == to_upper(label)) x(static_cast<Eigen::Index>(j)) = v;
  return x;
}

/// Every other ball of the 80 (a realistic triaxial sensor set: 40 nodes, 120 DOFs).
inline std::vector<std::int64_t> ball_sensors() {
  std::vector<std::int64_t> s;
  for (int b = 1; b <= 80; b += 2) s.push_back(b);
  return s;
}

}  // namespace estimate_test
