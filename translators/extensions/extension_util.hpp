#pragma once
/// \file extension_util.hpp
/// Helpers shared by the extension kinds (internal).
#include <Eigen/SparseCore>
#include <string>
#include <vector>

#include "translators/assembly/fe_model.hpp"

namespace ssid::translators::extensions::detail {

/// A g-set matrix given by triplets, reduced to the a-set: Tᵀ A T.
Eigen::SparseMatrix<double> to_aset(const FeModel& model, const std::vector<Eigen::Triplet<double>>& g_triplets);

/// Young's modulus of MAT1 `mid` (throws when absent).
double young_modulus(const formats::BulkModel& bulk, std::int64_t mid);

/// Short DESVAR label (≤ 8 characters): prefix + id.
std::string label(const std::string& prefix, std::int64_t id);

}  // namespace ssid::translators::extensions::detail
