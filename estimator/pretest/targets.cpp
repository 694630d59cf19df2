#include "estimator/pretest/targets.hpp"

#include <cmath>
#include <iomanip>
#include <map>
#include <set>
#include <sstream>
#include <string>

#include "formats/parse_error.hpp"

namespace ssid::estimator::pretest {

std::vector<Eigen::Index> select_target_modes(const Eigen::Ref<const Eigen::VectorXd>& eigenvalues, int count,
                                              double min_hz) {
  if (count < 1) throw formats::InputError("target modes: expected at least 1, got " + std::to_string(count));
  std::vector<Eigen::Index> out;
  for (Eigen::Index i = 0; i < eigenvalues.size() && static_cast<int>(out.size()) < count; ++i) {
    const double hz = std::sqrt(std::max(eigenvalues(i), 0.0)) / (2.0 * M_PI);
    if (hz > min_hz) out.push_back(i);
  }
  if (static_cast<int>(out.size()) < count)
    throw formats::InputError("target modes: " + std::to_string(count) + " asked above " + std::to_string(min_hz) +
                              " Hz, but the model's solved modes hold only " + std::to_string(out.size()));
  return out;
}

std::vector<CandidateDof> translational_candidates(const std::vector<translators::Dof>& a_set,
                                                   const std::vector<std::int64_t>& grids) {
  const std::set<std::int64_t> wanted(grids.begin(), grids.end());
  std::set<std::int64_t> seen;
  std::vector<CandidateDof> out;
  for (std::size_t i = 0; i < a_set.size(); ++i) {
    const auto& d = a_set[i];
    if (d.component < 1 || d.component > 3) continue;
    if (!wanted.empty() && !wanted.count(d.point)) continue;
    out.push_back({static_cast<Eigen::Index>(i), d, Eigen::Vector3d::Unit(d.component - 1), false});
    seen.insert(d.point);
  }
  for (auto g : grids)
    if (!seen.count(g))
      throw formats::InputError("candidate grid " + std::to_string(g) +
                                ": no translational DOF in the analysis set (no such grid, or all its "
                                "translations constrained)");
  return out;
}

std::string sensor_label(const CandidateDof& c) {
  if (!c.directed) return "T" + std::to_string(c.dof.component);
  std::ostringstream o;
  o << std::setprecision(4) << "(" << c.direction(0) << ", " << c.direction(1) << ", " << c.direction(2) << ")";
  return o.str();
}

std::vector<std::vector<Eigen::Index>> group_by_grid(const std::vector<CandidateDof>& candidates) {
  std::map<std::int64_t, std::size_t> where;
  std::vector<std::vector<Eigen::Index>> groups;
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    const auto g = candidates[i].dof.point;
    auto it = where.find(g);
    if (it == where.end()) {
      it = where.emplace(g, groups.size()).first;
      groups.emplace_back();
    }
    groups[it->second].push_back(static_cast<Eigen::Index>(i));
  }
  return groups;
}

Eigen::MatrixXd take_rows(const Eigen::Ref<const Eigen::MatrixXd>& A, const std::vector<Eigen::Index>& rows) {
  Eigen::MatrixXd out(static_cast<Eigen::Index>(rows.size()), A.cols());
  for (std::size_t i = 0; i < rows.size(); ++i) out.row(static_cast<Eigen::Index>(i)) = A.row(rows[i]);
  return out;
}

}  // namespace ssid::estimator::pretest
