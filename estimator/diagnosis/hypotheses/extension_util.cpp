#include "estimator/diagnosis/hypotheses/extension_util.hpp"

#include <Eigen/QR>
#include <algorithm>
#include <cassert>
#include <cmath>
#include <stdexcept>

#include "estimator/eigen/eigen_solver.hpp"
#include "formats/text_util.hpp"
#include "translators/constraints.hpp"

namespace ssid::estimator::diagnosis::hypotheses::detail {

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

double density(const formats::BulkModel& bulk, std::int64_t mid) {
  for (const auto& m : bulk.mat1s)
    if (m.mid == mid) return m.rho;
  return 0.0;
}

formats::BulkModel bulk_at_update(const FeModel& nominal, const ExtensionOptions& options) {
  Eigen::VectorXd x = nominal.initial_parameters();
  const auto& ps = nominal.parameters();
  for (std::size_t j = 0; j < ps.size(); ++j)
    if (const auto it = options.updated.find(formats::detail::upper(ps[j].label)); it != options.updated.end())
      x(static_cast<Eigen::Index>(j)) = it->second;
  return nominal.values_at(x);
}

std::string label(const std::string& prefix, std::int64_t id) {
  std::string s = prefix + std::to_string(id);
  if (s.size() > 8) s = prefix.substr(0, 1) + std::to_string(id % 10000000);
  return s.substr(0, 8);
}

std::vector<double> start_frequencies(const ExtensionOptions& options) {
  std::vector<double> f = options.unexplained_hz;
  if (static_cast<int>(f.size()) > options.max_surge_starts) f.resize(static_cast<std::size_t>(options.max_surge_starts));
  return f;
}

Location member_location(const std::string& type, std::int64_t eid, std::int64_t pid, std::int64_t ga, std::int64_t gb) {
  Location l;
  l.grids = {ga, gb};
  l.elements = {eid};
  if (pid) l.properties = {pid};
  l.text = type + " " + std::to_string(eid) + " (grids " + std::to_string(ga) + "-" + std::to_string(gb) + ")";
  return l;
}

Eigen::VectorXd response_at_sensors(const UnexplainedModes& x, double hz, Eigen::VectorXd modal_force) {
  assert(modal_force.size() == x.eigenvalues.size() && x.sensor_shapes.cols() == x.eigenvalues.size());
  const double lam = hz_to_eigenvalue(hz);
  for (Eigen::Index j = 0; j < modal_force.size(); ++j) {
    const double d = x.eigenvalues(j) - lam;  // a mode exactly at ω: its term dominates, as it should, but finitely
    modal_force(j) /= std::abs(d) > 1e-12 * lam ? d : std::copysign(1e-12 * lam, d);
  }
  return x.sensor_shapes * modal_force;
}

double explained_share(const Eigen::MatrixXd& A, const Eigen::VectorXd& t) {
  if (!(A.norm() > 0) || !(t.squaredNorm() > 0)) return 0.0;
  const Eigen::VectorXd fit = A * A.colPivHouseholderQr().solve(t);
  return std::clamp(fit.squaredNorm() / t.squaredNorm(), 0.0, 1.0);
}

}  // namespace ssid::estimator::diagnosis::hypotheses::detail
