#pragma once
/// \file operator_set.hpp
/// The operator set the estimator needs — K, M and ∂K/∂r_j, ∂M/∂r_j for every
/// parameter r_j — with what makes it usable by other tools: the DOF map,
/// the grid coordinates and the parameter table. On disk (NASDSA output): one
/// OP4 file per matrix and `manifest.json` (docs/assembly.md documents it):
///
///   { "format": "ssid-operators", "version": 1, "source": "...", "set": "a",
///     "dof": n, "dofs": [[grid, component], ...]        (matrix row i ↔ dofs[i]),
///     "grids": [{"id", "x": [x, y, z] (basic), "cp", "cd"}],
///     "parameters": [{"id", "label", "value", "lower", "upper", "designs": [...],
///                     "derivative": {"method": "exact"|"central"|"forward"|"backward"|"given", "step": h}}],
///     "files": {"K": "K.op4", "M": "M.op4", "dK": [...], "dM": [...]},
///     "matrices": {"K": "KAA", "M": "MAA", "dK": [...], "dM": [...]},   (OP4 names)
///     "notes": [...] }
/// Scalar points appear in "dofs" with component 0.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <cstdint>
#include <string>
#include <vector>

#include "formats/op4.hpp"
#include "translators/dof_map.hpp"

namespace ssid::translators {

class FeModel;

struct OperatorParameter {
  std::int64_t id = 0;   ///< DESVAR id (0 when the parameter is not a DESVAR)
  std::string label;
  double value = 0, lower = -1e20, upper = 1e20;
  std::vector<std::string> designs;  ///< what the parameter designs (for people)
  std::string method = "exact";      ///< how ∂/∂r was obtained: exact, central, forward, backward, given
  double step = 0;                   ///< finite-difference step h (0 for exact/given)
};

struct OperatorGrid {
  std::int64_t id = 0;
  Eigen::Vector3d x = Eigen::Vector3d::Zero();  ///< basic coordinates
  std::int64_t cp = 0, cd = 0;
};

struct OperatorSet {
  std::string source;           ///< the deck, or the import spec
  std::string set = "a";        ///< the DOF set of the matrices: "a" (analysis set)
  std::vector<Dof> dofs;        ///< matrix index → (grid, component)
  std::vector<OperatorGrid> grids;
  std::vector<OperatorParameter> parameters;
  Eigen::SparseMatrix<double> K, M;
  std::vector<Eigen::SparseMatrix<double>> dK, dM;  ///< one per parameter, or empty
  std::vector<std::string> notes;
};

/// The a-set operators of a model at DESVAR values x (derivatives exact, element
/// level), with the a-set DOF map, every grid and the DESVAR table (values x).
OperatorSet operators_from_model(const FeModel& model, const Eigen::VectorXd& x, bool derivatives,
                                 const std::string& source);

/// Writes `dir`/K.op4, M.op4, dK_<id>.op4, dM_<id>.op4 (when the set holds
/// derivatives; <id> the DESVAR id, or the parameter's position when 0) and
/// `dir`/manifest.json. Creates `dir`. Throws std::runtime_error on I/O failure.
void write_operator_set(const OperatorSet& set, const std::string& dir, const formats::Op4WriteOptions& op4 = {});

/// Reads a manifest and the OP4 files it names (relative to the manifest's
/// folder). Throws std::runtime_error naming the manifest and the key that is
/// missing or wrong, or the OP4 file that does not match the DOF count.
OperatorSet read_operator_set(const std::string& manifest_path);

}  // namespace ssid::translators
