#pragma once
/// \file model_load.hpp
/// Deck → assembled model → modes, shared by the subcommands that start from a
/// NASTRAN deck (modes, assemble, correlate, estimate).
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "estimator/eigen/eigen_solver.hpp"
#include "formats/deck.hpp"
#include "translators/assembly/fe_model.hpp"
#include "translators/measurement/sensor_mapping.hpp"

namespace ssid::cli {

struct LoadedModel {
  std::string path;
  formats::Deck deck;
  std::unique_ptr<translators::FeModel> model;
  std::vector<std::string> warnings;  ///< deck warnings ("file:line: ...")
};

/// Reads, parses, resolves and assembles a deck (translators::assemble_deck). Throws
/// InputError listing the deck's first twenty errors (file:line each), or a ModelError
/// "<file:line>: cannot assemble the model: ..." for what cannot be assembled.
LoadedModel load_model(const std::string& path, const translators::AssemblyOptions& options = {});

/// Writes the deck warnings and the model's notes (ignored cards, AUTOSPC, ...)
/// to stderr as "note: ..." lines.
void print_model_notes(const LoadedModel& m);

/// What to extract: --nmodes N when given (the lowest N), else the selected
/// EIGRL (V1, V2, ND, NORM) or EIGR (F1, F2, NE, ND, NORM), else every mode for a
/// dense-sized a-set and the lowest `default_nd` otherwise. `source` says which.
estimator::EigenOptions eigen_options(const translators::FeModel& model, std::optional<int> nmodes, long n,
                                      std::string& source, int default_nd = 10);

/// Dense solve for n ≤ estimator::kDenseEigenLimit (all modes exist there),
/// Lanczos over CHOLMOD otherwise. A failed solve throws std::runtime_error with
/// the solver's message and, for a mechanism, the DOF (grid, component) where
/// the factorisation failed when `dofs` (the a-set, see a_set_dofs) is given.
estimator::EigenResult solve_model(const translators::FeOperators& op, const estimator::EigenOptions& options,
                                   const std::vector<translators::Dof>& dofs = {});

/// The a-set DOFs of a model (index → grid, component).
std::vector<translators::Dof> a_set_dofs(const translators::FeModel& model);

/// Grids (basic position, displacement frame) as test mapping sees them.
std::vector<translators::GridPosition> grid_positions(const translators::FeModel& model);

}  // namespace ssid::cli
