#include "estimator/pretest/exciter_placement.hpp"

#include <cmath>
#include <stdexcept>

#include "estimator/pretest/mif.hpp"
#include "formats/parse_error.hpp"

namespace ssid::estimator::pretest {

DropoffModel::DropoffModel(const Eigen::Ref<const Eigen::MatrixXd>& Phi, const Eigen::Ref<const Eigen::VectorXd>& eigenvalues,
                           const std::vector<Eigen::Index>& sensors, const std::vector<CandidateDof>& candidates,
                           const std::vector<std::vector<Eigen::Index>>& groups, const std::vector<Eigen::Index>& targets,
                           double zeta)
    : DropoffModel(Phi, eigenvalues, take_rows(Phi, sensors), candidates, groups, targets, zeta) {}

DropoffModel::DropoffModel(const Eigen::Ref<const Eigen::MatrixXd>& Phi, const Eigen::Ref<const Eigen::VectorXd>& eigenvalues,
                           const Eigen::Ref<const Eigen::MatrixXd>& Phi_o, const std::vector<CandidateDof>& candidates,
                           const std::vector<std::vector<Eigen::Index>>& groups, const std::vector<Eigen::Index>& targets,
                           double zeta)
    : m_candidates(candidates), m_groups(groups) {
  if (eigenvalues.size() != Phi.cols() || Phi_o.cols() != Phi.cols())
    throw std::invalid_argument("DropoffModel: eigenvalues, modes and output rows differ in mode count");
  if (zeta <= 0) throw formats::InputError("damping ratio: expected > 0, got " + std::to_string(zeta));
  std::vector<Eigen::Index> rows;
  for (const auto& c : candidates) rows.push_back(c.row);
  m_Phi_in = take_rows(Phi, rows);
  for (auto t : targets) {
    const double w = std::sqrt(std::max(eigenvalues(t), 0.0));
    // Columns of A_t are the modes' contributions at ω_t: H = A_t Γ for any input.
    m_A.push_back(modal_frf(Phi_o, Eigen::MatrixXd::Identity(Phi.cols(), Phi.cols()), eigenvalues, zeta, w));
  }
}

Eigen::VectorXd DropoffModel::dropoff(const Exciter& e) const {
  Eigen::VectorXd gamma = Eigen::VectorXd::Zero(m_Phi_in.cols());
  for (auto p : m_groups.at(static_cast<std::size_t>(e.group))) {
    const int c = m_candidates[static_cast<std::size_t>(p)].dof.component;
    gamma += e.direction(c - 1) * m_Phi_in.row(p).transpose();
  }
  const Eigen::VectorXcd g = gamma.cast<std::complex<double>>();
  Eigen::VectorXd d(targets());
  for (int t = 0; t < targets(); ++t) d(t) = multivariate_mif(m_A[static_cast<std::size_t>(t)] * g)(0);
  return d;
}

Eigen::MatrixXd DropoffModel::dropoffs(const std::vector<Exciter>& exciters) const {
  Eigen::MatrixXd D(targets(), static_cast<Eigen::Index>(exciters.size()));
  for (std::size_t e = 0; e < exciters.size(); ++e) D.col(static_cast<Eigen::Index>(e)) = dropoff(exciters[e]);
  return D;
}

double exciter_objective(const Eigen::Ref<const Eigen::MatrixXd>& dropoffs, const ObjectiveOptions& o) {
  double j = 0;
  for (Eigen::Index t = 0; t < dropoffs.rows(); ++t) {
    const double v = dropoffs.row(t).minCoeff();
    if (v > o.target_minimum) j += std::expm1(o.rate * (v - o.target_minimum));
  }
  return j;
}

namespace {

std::vector<Exciter> decode(const Design& d) {
  std::vector<Exciter> ex;
  for (std::size_t e = 0; e < d.discrete.size(); ++e) {
    Eigen::Vector3d v(d.continuous[3 * e], d.continuous[3 * e + 1], d.continuous[3 * e + 2]);
    const double n = v.norm();
    ex.push_back({d.discrete[e], n > 1e-12 ? Eigen::Vector3d(v / n) : Eigen::Vector3d::UnitX()});
  }
  return ex;
}

}  // namespace

ExciterPlacement place_exciters(const DropoffModel& model, int count, const GeneticOptions& ga,
                                const ObjectiveOptions& objective) {
  if (count < 1) throw formats::InputError("exciters: expected at least 1, got " + std::to_string(count));
  GeneticProblem p;
  for (int e = 0; e < count; ++e) {
    p.discrete_sizes.push_back(model.groups());
    for (int k = 0; k < 3; ++k) p.continuous_bounds.emplace_back(-1.0, 1.0);
  }
  ExciterPlacement out;
  out.ga = genetic_minimize(
      p, [&](const Design& d) { return exciter_objective(model.dropoffs(decode(d)), objective); }, ga);
  out.exciters = decode(out.ga.best);
  out.dropoffs = model.dropoffs(out.exciters);
  out.objective = exciter_objective(out.dropoffs, objective);
  return out;
}

}  // namespace ssid::estimator::pretest
