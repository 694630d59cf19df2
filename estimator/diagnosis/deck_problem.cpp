#include "estimator/diagnosis/deck_problem.hpp"

#include <cmath>
#include <limits>
#include <set>
#include <stdexcept>

#include "estimator/eigen/eigen_solver.hpp"
#include "formats/bulk_model.hpp"
#include "formats/parse_error.hpp"
#include "translators/measurement/sensor_mapping.hpp"

namespace ssid::estimator::diagnosis {

std::vector<MeasuredMode> measured_modes(const translators::ModeSet& set, const DeckProblemOptions& options) {
  std::vector<MeasuredMode> out;
  const auto ns = set.shapes.rows();
  for (std::size_t i = 0; i < set.frequency_hz.size(); ++i) {
    MeasuredMode m;
    m.id = i < set.numbers.size() ? set.numbers[i] : static_cast<int>(i + 1);
    m.frequency_hz = set.frequency_hz[i];
    m.frequency_std_hz = m.frequency_hz * options.frequency_std_pct / 100.0;
    if (ns > 0) {
      m.shape = set.shapes.col(static_cast<Eigen::Index>(i));
      m.shape_std = options.shape_std_pct / 100.0 / std::sqrt(static_cast<double>(ns));
    }
    out.push_back(m);
  }
  return out;
}

DeckProblem make_deck_problem(const std::string& deck_text, const std::string& name,
                              const translators::ModeSet& measured, const DeckProblemOptions& options,
                              const std::map<std::string, PriorOverride>& priors) {
  DeckProblem pb;
  pb.name = name;
  pb.deck = std::make_unique<formats::Deck>(formats::read_deck_text(deck_text, name));
  pb.fe = translators::assemble_deck(*pb.deck, name);
  const translators::FeModel& fe = *pb.fe;

  // Test DOFs onto the model: grids by id.
  std::vector<translators::GridPosition> grids;
  for (const auto& g : fe.geometry().grids()) grids.push_back({g.id, g.x, g.frame});
  std::set<std::int64_t> ids;
  for (const auto& d : measured.dofs) ids.insert(d.node);
  std::vector<translators::TestNode> nodes;
  for (auto id : ids) nodes.push_back({id, Eigen::Vector3d::Zero(), 0});
  const translators::NodeMapping mapping = translators::map_test_nodes(nodes, grids, {});
  for (const auto& p : mapping.problems) pb.problems.push_back(p);
  translators::require_mapped(measured.dofs, mapping, "", "the deck " + name);
  const translators::Observation obs = translators::observe(measured.dofs, mapping, grids);
  if (obs.rows.empty()) throw formats::InputError(name + ": no measured DOF lies on a grid of the model");
  for (const auto& row : obs.rows) pb.dofs.push_back(row.measured);
  const SparseMatrix Cg = translators::observation_matrix(obs, fe.geometry().gset());
  pb.sensors = (Cg * fe.reduction().T).pruned();
  const translators::ModeSet kept = translators::restrict_to(measured, pb.dofs);
  pb.test = measured_modes(kept, options);

  // Prior from the DESVARs.
  const auto& params = fe.parameters();
  const auto p = static_cast<Eigen::Index>(params.size());
  if (p == 0) throw formats::InputError(name + ": the deck has no DESVAR (nothing to estimate)");
  pb.prior.mean.resize(p);
  pb.prior.cov = Eigen::MatrixXd::Zero(p, p);
  pb.prior.lower.resize(p);
  pb.prior.upper.resize(p);
  pb.start.resize(p);
  for (Eigen::Index j = 0; j < p; ++j) {
    const auto& d = params[static_cast<std::size_t>(j)];
    pb.prior.names.push_back(d.label);
    double mean = d.initial, sd = options.prior_rel_std * std::abs(d.initial), start = d.initial;
    if (auto it = priors.find(d.label); it != priors.end()) {
      mean = it->second.mean;
      sd = it->second.std;
      start = std::isnan(it->second.start) ? mean : it->second.start;
    }
    if (!(sd > 0)) throw formats::InputError(name + ": DESVAR " + d.label + " needs a positive prior standard deviation");
    pb.prior.mean(j) = mean;
    pb.prior.cov(j, j) = sd * sd;
    pb.prior.lower(j) = d.lower <= -1e20 ? -INFINITY : d.lower;
    pb.prior.upper(j) = d.upper >= 1e20 ? INFINITY : d.upper;
    pb.start(j) = start;
  }

  // The modal model: exact re-assembly, one CHOLMOD analysis reused.
  const auto a = static_cast<int>(fe.reduction().a_to_g.size());
  pb.nmodes = std::min(a - 1, 2 * static_cast<int>(pb.test.size()) + options.extra_modes);
  auto solver = std::make_shared<EigenSolver>();
  const translators::FeModel* fep = pb.fe.get();
  auto assemble = [fep](const Eigen::VectorXd& r) {
    translators::FeOperators o = fep->operators(r, true);
    Operators ops;
    ops.K = std::move(o.K);
    ops.M = std::move(o.M);
    ops.dK = std::move(o.dK);
    ops.dM = std::move(o.dM);
    return ops;
  };
  double f_max = 0;
  for (const auto& t : pb.test) f_max = std::max(f_max, t.frequency_hz);
  const double f_band = options.band_factor * f_max;
  const int max_modes = std::min(a - 1, std::max(options.max_modes, pb.nmodes));
  auto eigensolve = [solver, name, f_band, max_modes](const SparseMatrix& K, const SparseMatrix& M, int nmodes) {
    // The lowest `nmodes`; when they do not reach the band's top, the lowest `max_modes`.
    solver->options().nd = nmodes;
    EigenResult r = solver->solve(K, M);
    if (r.ok() && r.size() > 0 && r.cycles(r.size() - 1) < f_band && nmodes < max_modes) {
      solver->options().nd = max_modes;
      r = solver->solve(K, M);
    }
    if (!r.ok()) throw_solve_failure(r, name + ": eigen-solve failed: " + r.message);
    return std::make_pair(r.eigenvalues, r.modes);
  };
  pb.model = std::make_unique<OperatorModel>(
      assemble, eigensolve, pb.sensors, pb.nmodes,
      a > options.nelson_max_dofs ? ShapeDerivative::ModalSum : ShapeDerivative::Nelson);
  pb.tracked = std::make_unique<SensorTracked>(*pb.model);
  return pb;
}

UpdateResult estimate(std::vector<DeckProblem*> problems, const DeckProblemOptions& options) {
  if (problems.empty()) throw std::invalid_argument("estimate: no problem");
  std::vector<Configuration> confs;
  for (auto* pb : problems) {
    if (pb->prior.names != problems.front()->prior.names)
      throw std::invalid_argument("estimate: configuration " + pb->name + " has other parameters than " +
                                  problems.front()->name);
    confs.push_back({pb->name, pb->tracked.get(), pb->test});
  }
  UpdateOptions uo = options.update;
  uo.start = problems.front()->start;
  return update(confs, problems.front()->prior, uo, options.update_progress);
}

}  // namespace ssid::estimator::diagnosis
