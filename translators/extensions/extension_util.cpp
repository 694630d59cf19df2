#include "translators/extensions/extension_util.hpp"

#include <stdexcept>

#include "translators/constraints.hpp"

namespace ssid::translators::extensions::detail {

Eigen::SparseMatrix<double> to_aset(const FeModel& model, const std::vector<Eigen::Triplet<double>>& g_triplets) {
  const auto n = static_cast<Eigen::Index>(model.geometry().gset().size());
  Eigen::SparseMatrix<double> A(n, n);
  A.setFromTriplets(g_triplets.begin(), g_triplets.end());
  return reduce(A, model.reduction());
}

double young_modulus(const formats::BulkModel& bulk, std::int64_t mid) {
  for (const auto& m : bulk.mat1s)
    if (m.mid == mid) return m.e;
  throw std::invalid_argument("MAT1 " + std::to_string(mid) + " not found");
}

std::string label(const std::string& prefix, std::int64_t id) {
  std::string s = prefix + std::to_string(id);
  if (s.size() > 8) s = prefix.substr(0, 1) + std::to_string(id % 10000000);
  return s.substr(0, 8);
}

}  // namespace ssid::translators::extensions::detail
