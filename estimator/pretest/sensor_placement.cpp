#include "estimator/pretest/sensor_placement.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "estimator/pretest/targets.hpp"
#include "formats/parse_error.hpp"

namespace ssid::estimator::pretest {

std::string method_name(PlacementMethod m) {
  switch (m) {
    case PlacementMethod::EffectiveIndependence: return "ei";
    case PlacementMethod::KineticEnergy: return "ke";
    case PlacementMethod::AverageKineticEnergy: return "ake";
    case PlacementMethod::EigenvectorProduct: return "evp";
    case PlacementMethod::EigenvectorSum: return "evp-sum";
  }
  return "?";
}

FisherSummary fisher_summary(const Eigen::Ref<const Eigen::MatrixXd>& Phi_s) {
  FisherSummary f;
  if (Phi_s.cols() == 0) return f;
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(Phi_s);
  const Eigen::VectorXd s = svd.singularValues();
  const double tol = std::max(Phi_s.rows(), Phi_s.cols()) * std::numeric_limits<double>::epsilon() *
                     (s.size() ? s(0) : 0.0);
  f.rank = static_cast<int>((s.array() > tol).count());
  if (Phi_s.rows() < Phi_s.cols() || f.rank < Phi_s.cols()) {
    f.determinant = 0;
    f.log10_determinant = -std::numeric_limits<double>::infinity();
    f.condition_number = std::numeric_limits<double>::infinity();
    return f;
  }
  // det F = Π σ_i², summed in logs so that a large mode count neither overflows nor underflows.
  f.log10_determinant = 2.0 * s.array().log10().sum();
  f.determinant = std::pow(10.0, f.log10_determinant);
  const double r = s(0) / s(s.size() - 1);
  f.condition_number = r * r;
  return f;
}

namespace {

std::vector<std::vector<Eigen::Index>> singletons(Eigen::Index c) {
  std::vector<std::vector<Eigen::Index>> g(static_cast<std::size_t>(c));
  for (Eigen::Index i = 0; i < c; ++i) g[static_cast<std::size_t>(i)] = {i};
  return g;
}

/// F⁻¹ and E for the rows still alive (E of a dead row is left 0).
bool refresh(const Eigen::MatrixXd& Phi, const std::vector<char>& alive, Eigen::MatrixXd& Finv, Eigen::VectorXd& E) {
  const Eigen::Index m = Phi.cols();
  Eigen::MatrixXd F = Eigen::MatrixXd::Zero(m, m);
  for (Eigen::Index i = 0; i < Phi.rows(); ++i)
    if (alive[static_cast<std::size_t>(i)]) F.noalias() += Phi.row(i).transpose() * Phi.row(i);
  Eigen::LLT<Eigen::MatrixXd> llt(F);
  if (llt.info() != Eigen::Success) return false;
  Finv = llt.solve(Eigen::MatrixXd::Identity(m, m));
  E = ((Phi * Finv).array() * Phi.array()).rowwise().sum();
  for (Eigen::Index i = 0; i < Phi.rows(); ++i)
    if (!alive[static_cast<std::size_t>(i)]) E(i) = 0;
  return true;
}

void finish(Placement& p, const Eigen::Ref<const Eigen::MatrixXd>& Phi_c,
            const std::vector<std::vector<Eigen::Index>>& groups) {
  p.selected.clear();
  for (auto g : p.groups_kept)
    for (auto r : groups[static_cast<std::size_t>(g)]) p.selected.push_back(r);
  std::sort(p.selected.begin(), p.selected.end());
  p.fisher = fisher_summary(take_rows(Phi_c, p.selected));
}

}  // namespace

Placement effective_independence(const Eigen::Ref<const Eigen::MatrixXd>& Phi_c, int keep,
                                 const std::vector<std::vector<Eigen::Index>>& groups_in) {
  const Eigen::Index c = Phi_c.rows(), m = Phi_c.cols();
  const bool grouped = !groups_in.empty();
  const auto groups = grouped ? groups_in : singletons(c);
  const auto ng = static_cast<int>(groups.size());
  if (keep < 1 || keep > ng)
    throw formats::InputError("effective independence: cannot keep " + std::to_string(keep) + " of " +
                              std::to_string(ng) + (grouped ? " candidate grids" : " candidate DOFs"));
  if (!grouped && keep < m)
    throw formats::InputError("effective independence: " + std::to_string(keep) + " sensors cannot resolve " +
                              std::to_string(m) + " target modes (the Fisher information would be singular)");
  const Eigen::MatrixXd Phi = Phi_c;
  std::vector<char> alive(static_cast<std::size_t>(c), 0), group_alive(static_cast<std::size_t>(ng), 1);
  for (const auto& g : groups)
    for (auto r : g) alive[static_cast<std::size_t>(r)] = 1;
  Eigen::MatrixXd Finv;
  Eigen::VectorXd E;
  if (!refresh(Phi, alive, Finv, E))
    throw formats::InputError("effective independence: the " + std::to_string(m) +
                              " target modes are not independent on the " + std::to_string(c) +
                              " candidate DOFs (the Fisher information is singular)");
  long rows_alive = static_cast<long>(std::count(alive.begin(), alive.end(), 1));
  long rows_at_refresh = rows_alive;
  constexpr double kEssential = 1e-8;  // 1 − E_i below this: the row is essential (E_i = 1)
  Placement p;
  p.method = PlacementMethod::EffectiveIndependence;
  p.grouped = grouped;
  int groups_alive = ng;
  // The groups' rows in one flat array (group g: flat[start[g] … start[g+1])): the
  // scan below visits every live group every step, and a list per group (25 000
  // of them for single DOFs) made that scan cost more than the update itself
  // (docs/performance.md "Pretest").
  std::vector<Eigen::Index> flat;
  std::vector<std::size_t> start{0};
  for (const auto& g : groups) {
    flat.insert(flat.end(), g.begin(), g.end());
    start.push_back(flat.size());
  }
  std::vector<std::pair<double, int>> order;
  order.reserve(static_cast<std::size_t>(ng));
  while (groups_alive > keep) {
    // The live groups' summed E; groups holding an essential row are passed over.
    order.clear();
    int smallest = -1;
    for (int g = 0; g < ng; ++g) {
      if (!group_alive[static_cast<std::size_t>(g)]) continue;
      double sum = 0;
      bool ess = false;
      for (std::size_t k = start[static_cast<std::size_t>(g)]; k < start[static_cast<std::size_t>(g) + 1]; ++k) {
        const double e = E(flat[k]);
        sum += e;
        ess = ess || 1.0 - e < kEssential;
      }
      if (ess) continue;
      order.emplace_back(sum, g);
      if (smallest < 0 || sum < order[static_cast<std::size_t>(smallest)].first)
        smallest = static_cast<int>(order.size()) - 1;
    }
    int victim = -1;
    Eigen::MatrixXd V, Sinv;
    // Tries group g; true when it can go (rows left ≥ m and F stays non-singular).
    auto try_group = [&](int g) {
      const auto& rows = groups[static_cast<std::size_t>(g)];
      if (rows_alive - static_cast<long>(rows.size()) < m) return false;
      const Eigen::MatrixXd G = take_rows(Phi, rows);
      V = Finv * G.transpose();
      const Eigen::MatrixXd S = Eigen::MatrixXd::Identity(G.rows(), G.rows()) - G * V;
      Eigen::FullPivLU<Eigen::MatrixXd> lu(S);
      // det S = det F_after / det F_before: ~0 means the group is jointly essential.
      if (std::abs(lu.determinant()) < kEssential) return false;
      Sinv = lu.inverse();
      return true;
    };
    // The smallest sum nearly always goes; sort only when it cannot (O(c) a step, not O(c log c)).
    if (smallest >= 0 && try_group(order[static_cast<std::size_t>(smallest)].second)) {
      victim = order[static_cast<std::size_t>(smallest)].second;
    } else {
      std::sort(order.begin(), order.end());
      for (const auto& ranked : order)
        if (try_group(ranked.second)) {
          victim = ranked.second;
          break;
        }
    }
    if (victim < 0)
      throw formats::InputError("effective independence: every remaining " +
                                std::string(grouped ? "grid" : "DOF") +
                                " is essential to the independence of the target modes; cannot go below " +
                                std::to_string(groups_alive));
    const auto& rows = groups[static_cast<std::size_t>(victim)];
    for (auto r : rows) alive[static_cast<std::size_t>(r)] = 0;
    group_alive[static_cast<std::size_t>(victim)] = 0;
    --groups_alive;
    rows_alive -= static_cast<long>(rows.size());
    if (2 * rows_alive <= rows_at_refresh) {
      refresh(Phi, alive, Finv, E);
      rows_at_refresh = rows_alive;
      continue;
    }
    // Woodbury (Sherman–Morrison for one row): O(c m k), no determinant recomputed.
    const Eigen::MatrixXd W = Phi * V;  // c x k, w_j = Vᵀ φ_j
    E += ((W * Sinv).array() * W.array()).rowwise().sum().matrix();
    for (auto r : rows) E(r) = 0;
    Finv += V * Sinv * V.transpose();
  }
  refresh(Phi, alive, Finv, E);
  for (int g = 0; g < ng; ++g) {
    if (!group_alive[static_cast<std::size_t>(g)]) continue;
    p.groups_kept.push_back(g);
    bool ess = false;
    for (auto r : groups[static_cast<std::size_t>(g)]) ess = ess || 1.0 - E(r) < kEssential;
    if (grouped && ess) ++p.protected_groups;
  }
  finish(p, Phi_c, groups);
  p.score.resize(static_cast<Eigen::Index>(p.selected.size()));
  for (std::size_t i = 0; i < p.selected.size(); ++i) p.score(static_cast<Eigen::Index>(i)) = E(p.selected[i]);
  return p;
}

Eigen::MatrixXd kinetic_energy_fractions(const Eigen::Ref<const Eigen::MatrixXd>& Phi,
                                         const Eigen::SparseMatrix<double>& M, const std::vector<Eigen::Index>& rows) {
  if (M.rows() != Phi.rows() || M.cols() != Phi.rows())
    throw formats::InputError("kinetic energy: the mass matrix is " + std::to_string(M.rows()) + " x " +
                              std::to_string(M.cols()) + ", the modes have " + std::to_string(Phi.rows()) + " DOFs");
  const Eigen::MatrixXd MPhi = M * Phi;
  const Eigen::VectorXd gm = (Phi.array() * MPhi.array()).colwise().sum().transpose();
  Eigen::MatrixXd ke(static_cast<Eigen::Index>(rows.size()), Phi.cols());
  for (std::size_t i = 0; i < rows.size(); ++i)
    ke.row(static_cast<Eigen::Index>(i)) =
        (Phi.row(rows[i]).array() * MPhi.row(rows[i]).array()) / gm.transpose().array();
  return ke;
}

Eigen::VectorXd placement_metric(PlacementMethod method, const Eigen::Ref<const Eigen::MatrixXd>& Phi_c,
                                 const Eigen::Ref<const Eigen::MatrixXd>& ke) {
  switch (method) {
    case PlacementMethod::KineticEnergy: return ke.rowwise().maxCoeff();
    case PlacementMethod::AverageKineticEnergy: return ke.rowwise().mean();
    case PlacementMethod::EigenvectorProduct: return Phi_c.rowwise().prod().cwiseAbs();
    case PlacementMethod::EigenvectorSum: {
      Eigen::RowVectorXd scale = Phi_c.cwiseAbs().colwise().maxCoeff();
      for (Eigen::Index j = 0; j < scale.size(); ++j)
        if (scale(j) == 0) scale(j) = 1;
      return (Phi_c.cwiseAbs().array().rowwise() / scale.array()).rowwise().sum();
    }
    case PlacementMethod::EffectiveIndependence: break;
  }
  throw std::invalid_argument("placement_metric: effective independence has no one-shot metric");
}

Placement rank_placement(PlacementMethod method, const Eigen::Ref<const Eigen::MatrixXd>& Phi_c,
                         const Eigen::Ref<const Eigen::VectorXd>& metric, int keep,
                         const std::vector<std::vector<Eigen::Index>>& groups_in) {
  const bool grouped = !groups_in.empty();
  const auto groups = grouped ? groups_in : singletons(Phi_c.rows());
  const auto ng = static_cast<int>(groups.size());
  if (keep < 1 || keep > ng)
    throw formats::InputError(method_name(method) + " placement: cannot keep " + std::to_string(keep) + " of " +
                              std::to_string(ng) + (grouped ? " candidate grids" : " candidate DOFs"));
  std::vector<double> sum(static_cast<std::size_t>(ng), 0.0);
  for (int g = 0; g < ng; ++g)
    for (auto r : groups[static_cast<std::size_t>(g)]) sum[static_cast<std::size_t>(g)] += metric(r);
  std::vector<int> order(static_cast<std::size_t>(ng));
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](int a, int b) { return sum[static_cast<std::size_t>(a)] > sum[static_cast<std::size_t>(b)]; });
  Placement p;
  p.method = method;
  p.grouped = grouped;
  p.groups_kept.assign(order.begin(), order.begin() + keep);
  std::sort(p.groups_kept.begin(), p.groups_kept.end());
  finish(p, Phi_c, groups);
  p.score.resize(static_cast<Eigen::Index>(p.selected.size()));
  for (std::size_t i = 0; i < p.selected.size(); ++i) p.score(static_cast<Eigen::Index>(i)) = metric(p.selected[i]);
  return p;
}

}  // namespace ssid::estimator::pretest
