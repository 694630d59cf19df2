#pragma once
/// \file problem_file.hpp
/// The estimator's problem file (the NASSID analogue of the seed report): one
/// versioned file holding everything an estimation needs — per configuration
/// the operators K, M, ∂K/∂r_j, ∂M/∂r_j on the analysis DOFs, the DOF map, the
/// sensor selection and the measured modes; the parameters with their priors
/// and bounds; the pairing and convergence options. It reads back identically
/// (every double bit for bit). The layout is documented in docs/formats.md:
///
///   line 1  "SSIDPROB <version>"
///   line 2  byte length of the JSON header
///   JSON header (names, scalars, and a table of binary blocks)
///   binary blocks, little-endian, each 8-byte aligned: sparse matrices in
///   compressed-column form (int64 column starts, int64 row indices, float64
///   values), dense matrices column-major float64.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <cstdint>
#include <string>
#include <vector>

namespace ssid::formats {

struct ProblemParameter {
  std::string name;            ///< DESVAR label
  std::int64_t desvar = 0;     ///< DESVAR id (0 when the parameter is not a DESVAR)
  double initial = 0;          ///< prior mean
  double prior_std = 0;
  double lower = -1e20, upper = 1e20;
};

struct ProblemMode {
  int id = 0;
  double frequency_hz = 0;
  double frequency_std_hz = 0;
  Eigen::VectorXd shape;  ///< at the sensors; empty when not measured
  double shape_std = 0;
  bool use_frequency = true;
  bool use_shape = true;
};

struct ProblemConfiguration {
  std::string name;
  std::string deck;                                    ///< source deck (informational)
  std::vector<std::pair<std::int64_t, int>> dofs;      ///< analysis DOF k = (point, component)
  std::vector<std::string> sensor_labels;              ///< e.g. "101:3" (test node : direction)
  Eigen::SparseMatrix<double> sensors;                 ///< n_s × n_a
  Eigen::SparseMatrix<double> K, M;
  std::vector<Eigen::SparseMatrix<double>> dK, dM;     ///< one per parameter
  std::vector<ProblemMode> measured;
  int modes = 0;                                       ///< analysis modes to compute
};

struct ProblemOptions {
  int max_iterations = 20;
  double tolerance = 1e-4;
  double mac_min = 0.6;
  double freq_tol_pct = 50.0;
  double track_mac_min = 0.5;
  bool shape_derivatives = true;
  std::string shape_derivative = "nelson";  ///< "nelson" | "modal-sum"
  std::string operators = "taylor";         ///< "taylor" (imported) | "exact" (re-assemble the deck)
};

struct ProblemFile {
  static constexpr int version = 1;
  std::string title;
  std::vector<ProblemParameter> parameters;
  Eigen::MatrixXd prior_correlation;  ///< p × p; empty = identity
  std::vector<ProblemConfiguration> configurations;
  ProblemOptions options;
};

/// Writes; throws std::runtime_error naming the file on I/O failure and
/// std::invalid_argument when sizes disagree (a configuration's dK count, a
/// shape's length, …).
void write_problem(const std::string& path, const ProblemFile& problem);

/// Reads; every inconsistency (bad magic, unknown version, truncated block,
/// sizes that disagree) is a std::runtime_error naming the file and the item.
ProblemFile read_problem(const std::string& path);

}  // namespace ssid::formats
