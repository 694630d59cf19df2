#pragma once
/// \file tam_xor.hpp
/// Test–analysis cross-orthogonality with the mass of a test-analysis model (TAM):
/// Guyan (static condensation) or IRS (Guyan corrected for the omitted DOFs' inertia,
/// O'Callahan) of the deck's K and M onto the test DOFs, `--tam guyan,irs` of
/// `ssid correlate` and `ssid estimate` (docs/correlation.md, "Cross-orthogonality").
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "estimator/study/deck_study.hpp"
#include "translators/assembly/fe_model.hpp"
#include "translators/measurement/sensor_mapping.hpp"

namespace ssid::cli::report {

/// The TAM kinds of a --tam value ("guyan,irs": each once, in the order given). Prints
/// what is wrong and returns false for another word.
bool parse_tams(const std::string& value, std::vector<std::string>& tams);

/// The deck's K and M in coordinates where each test DOF `dofs` (grids, measured
/// directions ±1..±3 in basic) is one coordinate (measurement_coordinates.hpp: a
/// direction not along the grid's displacement frame is a combination of its
/// translations), and those coordinates' rows, in the order of `dofs`: what a
/// test-analysis model condenses onto. Throws InputError saying why not: a rotational
/// test DOF, a test grid whose translations are not in the analysis set (dependent or
/// constrained).
struct TestCoordinates {
  Eigen::SparseMatrix<double> K, M;
  std::vector<Eigen::Index> rows;
};
TestCoordinates test_coordinates(const translators::FeModel& model, const translators::FeOperators& op,
                                 const std::vector<translators::MeasuredDof>& dofs);

/// The reduced mass of a test-analysis model ("guyan" or "irs") on the test DOFs of `tc`.
/// Throws InputError when the reduction fails.
Eigen::MatrixXd tam_mass(const std::string& kind, const TestCoordinates& tc);

/// {"guyan": X, "irs": X} for the kinds `tams`: cross_orthogonality_json (report_data.hpp)
/// of the analysis shapes `fe` (at `dofs`, in their order) against the test shapes `test`
/// with each TAM's mass from the deck's `op` (a-set K and M of `model`), or {"unavailable":
/// why} (also added to `problems` as "--tam KIND: why") when the TAM cannot be built.
nlohmann::json tam_cross_orthogonality_json(const std::vector<std::string>& tams, const translators::FeModel& model,
                                            const translators::FeOperators& op,
                                            const std::vector<translators::MeasuredDof>& dofs, const Eigen::MatrixXd& fe,
                                            const std::vector<int>& fe_numbers, const Eigen::MatrixXd& test,
                                            const std::vector<int>& test_numbers,
                                            const std::vector<std::pair<int, int>>& pairs,
                                            std::vector<std::string>& problems);

/// `ssid estimate --tam`: the same for the first configuration at parameters `r` (the
/// estimate): its analysis shapes at the sensor rows against its measured modes, paired as
/// `pairs` ({"fe_mode", "test_mode"}: the result's pairs), K and M re-assembled at `r`.
/// Throws InputError when the configuration has no deck (a problem file's run).
nlohmann::json estimate_tam_json(const estimator::PreparedConfiguration& configuration, const Eigen::VectorXd& r,
                                 const nlohmann::json& pairs, const std::vector<std::string>& tams,
                                 std::vector<std::string>& problems);

}  // namespace ssid::cli::report
