#pragma once
/// \file correlate.hpp
/// Correlation of an analysis mode set with a test mode set at their common
/// measured DOFs: the pairing table, MAC matrices and auto-MACs in one call.
/// The analysis set can come from a UFF 55 file (FE modes written at sensors) or,
/// once a deck is assembled, from C Φ (translators::observation_matrix times the
/// eigenvectors) — the function does not care where the shapes came from.
#include <vector>

#include "estimator/correlation/measures.hpp"
#include "translators/measurement/mode_set.hpp"

namespace ssid::estimator {

struct Correlation {
  std::vector<translators::MeasuredDof> dofs;  ///< common DOFs the shapes were compared on
  translators::ModeSet fe, test;               ///< both sets restricted to `dofs`
  Pairing pairing;
  Eigen::MatrixXd auto_mac_fe, auto_mac_test;  ///< in options.form
};

/// Compares `fe` with `test` on the DOFs both hold (order of `test`).
/// Throws std::invalid_argument when they share no DOF.
Correlation correlate(const translators::ModeSet& fe, const translators::ModeSet& test,
                      const PairingOptions& options = {});

}  // namespace ssid::estimator
