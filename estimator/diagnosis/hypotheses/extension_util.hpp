#pragma once
/// \file extension_util.hpp
/// Helpers shared by the extension kinds (internal).
#include <Eigen/SparseCore>
#include <string>
#include <vector>

#include "translators/assembly/fe_model.hpp"
#include "estimator/diagnosis/hypotheses/model_extension.hpp"

namespace ssid::estimator::diagnosis::hypotheses::detail {

/// A g-set matrix given by triplets, reduced to the a-set: Tᵀ A T.
Eigen::SparseMatrix<double> to_aset(const FeModel& model, const std::vector<Eigen::Triplet<double>>& g_triplets);

/// Young's modulus of MAT1 `mid` (throws when absent).
double young_modulus(const formats::BulkModel& bulk, std::int64_t mid);

/// Density of MAT1 `mid`, 0 when absent (a member without a MAT1 carries no mass of its own).
double density(const formats::BulkModel& bulk, std::int64_t mid);

/// The deck's cards at the parameters the hypotheses start from
/// (ExtensionOptions::updated; the deck's own values for the others).
formats::BulkModel bulk_at_update(const FeModel& nominal, const ExtensionOptions& options);

/// Short DESVAR label (≤ 8 characters): prefix + id.
std::string label(const std::string& prefix, std::int64_t id);

/// The unexplained test frequencies a kind starts its new mode at (the first
/// `max_surge_starts`); empty when every test mode has a partner.
std::vector<double> start_frequencies(const ExtensionOptions& options);

/// The location of a two-grid member: its grids, element, property (when
/// `pid` > 0) and "TYPE eid (grids a-b)".
Location member_location(const std::string& type, std::int64_t eid, std::int64_t pid, std::int64_t ga, std::int64_t gb);

/// The shape at the sensors with which the structure answers, at frequency
/// `hz`, a force F whose modal components are `modal_force` (φ_jᵀF, one per
/// analysis mode of `x`): u = Σ_j φ_j (φ_jᵀF) / (λ_j − ω²), over the updated
/// model's mass-normalised modes. A kind that adds a local mode near ω ranks
/// its places by how well this shape (its force on the structure) gives the
/// unexplained test mode's.
Eigen::VectorXd response_at_sensors(const UnexplainedModes& x, double hz, Eigen::VectorXd modal_force);

/// The share of `t` that the columns of `A` span, ‖A A⁺ t‖² / ‖t‖² ∈ [0, 1]
/// (least squares; for one column the MAC of the two); 0 when A or t is zero.
double explained_share(const Eigen::MatrixXd& A, const Eigen::VectorXd& t);

}  // namespace ssid::estimator::diagnosis::hypotheses::detail
