#include "estimator/updating/updating.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>

#include "estimator/eigen/eigen_solver.hpp"
#include "estimator/reporting/number_text.hpp"
#include "formats/parse_error.hpp"

namespace ssid::estimator {

namespace {


/// z, u, T and σ of one cycle, in physical parameter units.
struct Residuals {
  Eigen::VectorXd z, u, sigma;
  Eigen::MatrixXd T;
};

void fill_pair_stats(const std::vector<MeasuredMode>& test, const ModalSolution& fem, std::vector<UpdatePair>& pairs) {
  for (auto& p : pairs) {
    p.test_hz = test[static_cast<std::size_t>(p.test)].frequency_hz;
    p.fem_hz = eigenvalue_to_hz(fem.eigenvalues(p.fem));
    p.error_pct = p.test_hz > 0 ? (p.fem_hz - p.test_hz) / p.test_hz * 100.0 : 0.0;
    const auto& shape = test[static_cast<std::size_t>(p.test)].shape;
    p.mac = shape.size() ? mac_matrix(shape, fem.sensor_shapes.col(p.fem))(0, 0) : 0.0;
  }
}

/// Follows each pair's analysis mode from the previous cycle to this one by
/// MAC on the tracking shapes; a pair whose partner cannot be followed, or whose
/// new partner no longer matches the test shape, is dropped with a note.
std::vector<UpdatePair> track_pairs(const std::vector<UpdatePair>& previous, const Eigen::MatrixXd& previous_shapes,
                                  const std::vector<MeasuredMode>& test, const ModalSolution& fem,
                                  const UpdateOptions& options, int cycle, std::vector<std::string>& notes,
                                  std::vector<DroppedMode>& dropped) {
  const Eigen::MatrixXd tmac = mac_matrix(previous_shapes, fem.tracking_shapes);
  std::vector<UpdatePair> out;
  std::vector<bool> taken(static_cast<std::size_t>(fem.eigenvalues.size()), false);
  for (const auto& p : previous) {
    Eigen::Index best = -1;
    const double best_mac = tmac.row(p.fem).maxCoeff(&best);
    const auto& t = test[static_cast<std::size_t>(p.test)];
    std::string why;
    if (best_mac < options.track_mac_min)
      why = "its analysis mode " + std::to_string(p.fem + 1) + " could not be followed (tracking MAC " +
            std::to_string(best_mac) + ")";
    else if (taken[static_cast<std::size_t>(best)])
      why = "analysis mode " + std::to_string(best + 1) + " is claimed by another test mode";
    else if (t.fixed_partner < 0 && t.shape.size() && mac_matrix(t.shape, fem.sensor_shapes.col(best))(0, 0) < options.mac_min)
      why = "its partner, analysis mode " + std::to_string(best + 1) + ", no longer matches the test shape";
    if (!why.empty()) {
      notes.push_back("cycle " + std::to_string(cycle) + ": test mode " + std::to_string(t.id) +
                      " left the update: " + why);
      dropped.push_back({p.config, p.test, cycle, why});
      continue;
    }
    taken[static_cast<std::size_t>(best)] = true;
    UpdatePair q = p;
    q.fem = static_cast<int>(best);
    out.push_back(q);
  }
  fill_pair_stats(test, fem, out);
  return out;
}

/// z, u, σ of the pairs and, with `with_T`, the sensitivities T (the costly part:
/// a trial point of the line search needs only the objective).
Residuals residuals(ModalModel& model, const std::vector<MeasuredMode>& test, const ModalSolution& fem,
                    const std::vector<UpdatePair>& pairs, const UpdateOptions& options, bool with_T = true) {
  const int p = model.parameter_count();
  std::vector<double> z, u, sigma;
  std::vector<Eigen::VectorXd> rows;
  auto uses = [&](const UpdatePair& pair) {
    const auto& t = test[static_cast<std::size_t>(pair.test)];
    const bool use_f = t.use_frequency && t.frequency_std_hz > 0;
    const bool use_s = options.shape_derivatives && t.use_shape && t.shape.size() > 0 && t.shape_std > 0;
    return std::pair{use_f, use_s};
  };
  // The sensitivities of every used pair at once (the model may compute them concurrently).
  std::vector<ModeSensitivity> sens;
  if (with_T) {
    std::vector<int> modes;
    std::vector<bool> shapes;
    for (const auto& pair : pairs) {
      const auto [use_f, use_s] = uses(pair);
      if (!use_f && !use_s) continue;
      modes.push_back(pair.fem);
      shapes.push_back(use_s);
    }
    sens = model.sensitivities(modes, shapes);
  }
  std::size_t used = 0;
  for (const auto& pair : pairs) {
    const auto& t = test[static_cast<std::size_t>(pair.test)];
    const auto [use_f, use_s] = uses(pair);
    if (!use_f && !use_s) continue;
    const ModeSensitivity s = with_T ? std::move(sens[used++]) : ModeSensitivity{Eigen::VectorXd::Zero(p), Eigen::MatrixXd()};
    if (use_f) {
      const double f = eigenvalue_to_hz(fem.eigenvalues(pair.fem));
      if (f <= 0) throw formats::NumericalError("test mode " + std::to_string(t.id) + " is paired with a zero-frequency analysis mode");
      z.push_back(t.frequency_hz);
      u.push_back(f);
      sigma.push_back(t.frequency_std_hz);
      rows.push_back(s.d_eigenvalue / (4.0 * M_PI * M_PI * 2.0 * f));
    }
    if (use_s) {
      const Eigen::VectorXd phi = fem.sensor_shapes.col(pair.fem);
      const double n = phi.norm();
      const Eigen::VectorXd un = phi / n;
      Eigen::VectorXd zn = t.shape / t.shape.norm();
      if (zn.dot(un) < 0) zn = -zn;
      // d(φ/‖φ‖) = (I − û ûᵀ) dφ / ‖φ‖
      const Eigen::MatrixXd d = with_T ? Eigen::MatrixXd((s.d_sensor_shape - un * (un.transpose() * s.d_sensor_shape)) / n)
                                       : Eigen::MatrixXd::Zero(un.size(), p);
      for (Eigen::Index k = 0; k < un.size(); ++k) {
        z.push_back(zn(k));
        u.push_back(un(k));
        sigma.push_back(t.shape_std);
        rows.push_back(d.row(k).transpose());
      }
    }
  }
  Residuals r;
  const auto m = static_cast<Eigen::Index>(z.size());
  r.z = Eigen::Map<Eigen::VectorXd>(z.data(), m);
  r.u = Eigen::Map<Eigen::VectorXd>(u.data(), m);
  r.sigma = Eigen::Map<Eigen::VectorXd>(sigma.data(), m);
  r.T.resize(m, p);
  for (Eigen::Index k = 0; k < m; ++k) r.T.row(k) = rows[static_cast<std::size_t>(k)].transpose();
  return r;
}

void summarise(UpdateCycle& c) {
  double sum2 = 0, mac = 0;
  int nmac = 0;
  for (const auto& p : c.pairs) {
    sum2 += p.error_pct * p.error_pct;
    if (p.mac > 0) { mac += p.mac; ++nmac; }
  }
  c.freq_rms_pct = c.pairs.empty() ? 0.0 : std::sqrt(sum2 / static_cast<double>(c.pairs.size()));
  c.mean_mac = nmac ? mac / nmac : 0.0;
}

}  // namespace

std::vector<UpdatePair> pair_for_update(const std::vector<MeasuredMode>& test, const ModalSolution& fem,
                                 const UpdateOptions& options) {
  const auto m = fem.eigenvalues.size();
  struct Candidate { int t, f; double mac; };
  std::vector<Candidate> candidates;
  std::vector<bool> test_done(test.size(), false), fem_done(static_cast<std::size_t>(m), false);
  std::vector<UpdatePair> pairs;
  for (std::size_t i = 0; i < test.size(); ++i) {
    const int j = test[i].fixed_partner;
    if (j < 0) continue;
    if (j >= m)
      throw formats::InputError("test mode " + std::to_string(test[i].id) + " is paired with analysis mode " +
                                std::to_string(j + 1) + ", but only " + std::to_string(m) + " were solved");
    if (fem_done[static_cast<std::size_t>(j)])
      throw formats::InputError("analysis mode " + std::to_string(j + 1) + " is paired with two test modes");
    test_done[i] = fem_done[static_cast<std::size_t>(j)] = true;
    UpdatePair q;
    q.test = static_cast<int>(i);
    q.fem = j;
    pairs.push_back(q);
  }
  for (std::size_t i = 0; i < test.size(); ++i) {
    if (!test[i].shape.size() || test_done[i]) continue;
    if (test[i].shape.size() != fem.sensor_shapes.rows())
      throw std::invalid_argument("test mode " + std::to_string(test[i].id) + " has " +
                                  std::to_string(test[i].shape.size()) + " shape components, the sensors " +
                                  std::to_string(fem.sensor_shapes.rows()));
    const Eigen::MatrixXd mac = mac_matrix(test[i].shape, fem.sensor_shapes);
    for (Eigen::Index j = 0; j < m; ++j) {
      const double err = std::abs(eigenvalue_to_hz(fem.eigenvalues(j)) - test[i].frequency_hz) / test[i].frequency_hz * 100.0;
      if (mac(0, j) >= options.mac_min && err <= options.freq_tol_pct)
        candidates.push_back({static_cast<int>(i), static_cast<int>(j), mac(0, j)});
    }
  }
  std::stable_sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) { return a.mac > b.mac; });
  for (const auto& c : candidates) {
    if (test_done[static_cast<std::size_t>(c.t)] || fem_done[static_cast<std::size_t>(c.f)]) continue;
    test_done[static_cast<std::size_t>(c.t)] = fem_done[static_cast<std::size_t>(c.f)] = true;
    UpdatePair q;
    q.test = c.t;
    q.fem = c.f;
    pairs.push_back(q);
  }
  for (std::size_t i = 0; i < test.size(); ++i) {
    if (test[i].shape.size() || test_done[i]) continue;
    int best = -1;
    double best_err = options.freq_tol_pct;
    for (Eigen::Index j = 0; j < m; ++j) {
      if (fem_done[static_cast<std::size_t>(j)]) continue;
      const double err = std::abs(eigenvalue_to_hz(fem.eigenvalues(j)) - test[i].frequency_hz) / test[i].frequency_hz * 100.0;
      if (err <= best_err) { best_err = err; best = static_cast<int>(j); }
    }
    if (best >= 0) {
      fem_done[static_cast<std::size_t>(best)] = true;
      UpdatePair q;
      q.test = static_cast<int>(i);
      q.fem = best;
      pairs.push_back(q);
    }
  }
  std::sort(pairs.begin(), pairs.end(), [](const UpdatePair& a, const UpdatePair& b) { return a.test < b.test; });
  fill_pair_stats(test, fem, pairs);
  return pairs;
}

UpdateResult update(ModalModel& model, const std::vector<MeasuredMode>& test, const ParameterPrior& prior,
                    const UpdateOptions& options, const Progress& progress) {
  return update(std::vector<Configuration>{{"", &model, test}}, prior, options, progress);
}

ParameterPrior posterior_as_prior(const UpdateResult& result, const ParameterPrior& prior) {
  ParameterPrior next = prior;
  next.mean = result.r;
  next.cov = result.posterior_cov;
  return next;
}

UpdateResult update(const std::vector<Configuration>& configurations, const ParameterPrior& prior,
                    const UpdateOptions& options, const Progress& progress) {
  const auto p = prior.mean.size();
  if (prior.cov.rows() != p || prior.cov.cols() != p || prior.lower.size() != p || prior.upper.size() != p)
    throw std::invalid_argument("update: the prior's mean, covariance and bounds disagree in size");
  if (configurations.empty()) throw std::invalid_argument("update: no configuration");
  for (const auto& c : configurations) {
    if (!c.model) throw std::invalid_argument("update: configuration '" + c.name + "' has no model");
    if (c.model->parameter_count() >= 0 && c.model->parameter_count() != p)
      throw std::invalid_argument("update: the model of '" + c.name + "' has " +
                                  std::to_string(c.model->parameter_count()) + " parameters, the prior " +
                                  std::to_string(p));
    if (c.test.empty()) throw std::invalid_argument("update: configuration '" + c.name + "' has no measured modes");
  }
  const std::size_t nc = configurations.size();
  auto label = [&](std::size_t k) {
    return configurations[k].name.empty() ? std::string() : " of '" + configurations[k].name + "'";
  };

  // Work in θ = D⁻¹ (r − r₀), D = diag(prior σ): all parameters of order one.
  const Eigen::VectorXd d = prior.cov.diagonal().array().sqrt();
  if ((d.array() <= 0).any()) throw formats::InputError("update: every parameter needs a positive prior variance");
  const Eigen::MatrixXd cov_theta = d.asDiagonal().inverse() * prior.cov * d.asDiagonal().inverse();
  const Eigen::VectorXd lo = ((prior.lower - prior.mean).array() / d.array()).matrix();
  const Eigen::VectorXd hi = ((prior.upper - prior.mean).array() / d.array()).matrix();
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(p);

  UpdateResult result;
  Eigen::VectorXd theta = Eigen::VectorXd::Zero(p);
  if (options.start.size()) {
    if (options.start.size() != p) throw std::invalid_argument("update: the start point and the prior disagree in size");
    theta = ((options.start - prior.mean).array() / d.array()).matrix().cwiseMax(lo).cwiseMin(hi);
  }
  std::vector<std::vector<UpdatePair>> pairs(nc);
  std::vector<Eigen::MatrixXd> tracking(nc);
  // Line search: the Gauss–Newton step of Eq. (7) is a descent direction of J;
  // a step that raises J (the linearisation overshot: far from the answer, or
  // along a poorly informed direction) is halved, from the last accepted point.
  Eigen::LLT<Eigen::MatrixXd> prior_llt(cov_theta);
  auto objective = [&](const Eigen::VectorXd& th, const Residuals& res) {
    const Eigen::VectorXd e = ((res.z - res.u).array() / res.sigma.array()).matrix();
    return e.squaredNorm() + th.dot(prior_llt.solve(th));
  };
  double J_accepted = INFINITY;
  Eigen::VectorXd theta_accepted = theta;
  std::vector<std::vector<UpdatePair>> pairs_accepted;
  std::vector<Eigen::MatrixXd> tracking_accepted;
  int halvings = 0;  // trials rejected since the last accepted point
  constexpr int max_halvings = 12;
  // Levenberg–Marquardt damping of the step from the last accepted point: raised
  // ×10 at each rejected trial (from 0.1), lowered ×10 at each accepted one (0 below 0.1).
  double mu = 0;
  Eigen::MatrixXd T_accepted;
  Residuals res_accepted;
  // A report counted in cycles done (cycle 0, the model at the start, is the
  // first) of at most max_iterations + 1. A tick (a solve starting) shows
  // nothing new; it lets the caller stop the run there.
  auto report_cycle = [&](int done, const std::string& detail, bool tick = false) {
    if (!progress) return;
    ProgressEvent e;
    e.phase = "cycle";
    e.done = done;
    e.total = options.max_iterations + 1;
    e.total_is_bound = true;
    e.detail = detail;
    e.tick = tick;
    e.fraction = static_cast<double>(e.done) / static_cast<double>(e.total);
    progress(e);
  };
  // A rejected trial: the next one is the accepted point's step with more
  // damping, and the trial's pairs, notes and dropped modes are undone.
  auto reject = [&](int cycle, const std::string& why, std::size_t notes_before, std::size_t dropped_before) {
    ++halvings;
    mu = mu > 0 ? 10 * mu : 0.1;
    theta = bayes_step(theta_accepted, zero, cov_theta, res_accepted.z, res_accepted.u, T_accepted, res_accepted.sigma,
                       lo, hi, mu)
                .r_next;
    report_cycle(cycle, "trial point rejected (" + why + "); step damped, mu = " + significant(mu, 3));
    pairs = pairs_accepted;
    tracking = tracking_accepted;
    result.notes.resize(notes_before);
    result.dropped.resize(dropped_before);
  };
  // The posterior at an accepted cycle's r (the mode, once converged): what the
  // result holds at the end, or when the iteration stops early.
  struct Accepted {
    Eigen::VectorXd r;
    BayesStep step;
    Eigen::VectorXd sigma;
    Eigen::MatrixXd T_theta;
    std::size_t notes = 0, dropped = 0;
  };
  std::optional<Accepted> accepted;
  auto finish = [&](const Accepted& a) {
    result.r = a.r;
    result.posterior_cov = d.asDiagonal() * a.step.posterior_cov * d.asDiagonal();
    result.posterior_std = result.posterior_cov.diagonal().array().sqrt();
    // log det S* − log det S_rr is the same in θ and r: the D² factors cancel.
    result.log_evidence = laplace_log_evidence(a.step.objective, a.sigma, cov_theta, a.step.posterior_cov);
    result.identifiability = identifiability(a.T_theta, a.sigma, cov_theta, a.step.posterior_cov);
    if (a.step.clipped) result.notes.push_back("a parameter bound is active at the solution");
  };
  // A stop before the end: the last accepted cycle's result, or (none yet) the exception.
  auto stop_early = [&](const std::string& why, bool interrupted) {
    result.notes.resize(accepted->notes);
    result.dropped.resize(accepted->dropped);
    finish(*accepted);
    result.converged = false;
    result.stopped = why;
    result.interrupted = interrupted;
    result.notes.push_back("stopped after " + std::to_string(result.history.size()) + " cycle(s): " + why);
    return result;
  };
  try {
    for (int cycle = 0;;) {
      const Eigen::VectorXd r = prior.mean + d.cwiseProduct(theta);
      const std::size_t notes_before = result.notes.size(), dropped_before = result.dropped.size();
      std::vector<Residuals> parts;
      std::vector<ModalSolution> solutions;
      UpdateCycle c;
      c.cycle = cycle;
      c.r = r;
      bool unsolvable = false;
      for (std::size_t k = 0; k < nc; ++k) {
        const auto& conf = configurations[k];
        report_cycle(cycle, "solving" + label(k), true);
        ModalSolution fem;
        try {
          fem = conf.model->solve(r);
        } catch (const formats::InputError& ex) {
          // A trial point where the model cannot be solved (a designed area
          // driven through zero: an element or a factorisation refuses it, …) is
          // a step too far, like one that raises J.
          if (cycle == 0 || halvings >= max_halvings) throw;
          reject(cycle, std::string("no solution at the trial point (") + ex.what() + ")", notes_before, dropped_before);
          unsolvable = true;
          break;
        } catch (const formats::NumericalError& ex) {
          if (cycle == 0 || halvings >= max_halvings) throw;
          reject(cycle, std::string("no solution at the trial point (") + ex.what() + ")", notes_before, dropped_before);
          unsolvable = true;
          break;
        }
        if (cycle == 0) {
          pairs[k] = pair_for_update(conf.test, fem, options);
          if (pairs[k].empty()) throw formats::InputError("update: no test mode" + label(k) + " pairs with an analysis mode");
          for (std::size_t i = 0; i < conf.test.size(); ++i)
            if (std::none_of(pairs[k].begin(), pairs[k].end(), [&](const UpdatePair& q) { return q.test == static_cast<int>(i); }))
              result.notes.push_back("test mode " + std::to_string(conf.test[i].id) + label(k) + " has no analysis partner");
        } else {
          std::vector<UpdatePair> previous;
          Eigen::MatrixXd prev(tracking[k].rows(), static_cast<Eigen::Index>(pairs[k].size()));
          for (std::size_t q = 0; q < pairs[k].size(); ++q) {
            prev.col(static_cast<Eigen::Index>(q)) = tracking[k].col(pairs[k][q].fem);
            previous.push_back(pairs[k][q]);
            previous.back().fem = static_cast<int>(q);
          }
          pairs[k] = track_pairs(previous, prev, conf.test, fem, options, cycle, result.notes, result.dropped);
          if (pairs[k].empty()) throw formats::NumericalError("update: every test mode" + label(k) + " lost its analysis partner");
        }
        for (auto& q : pairs[k]) q.config = static_cast<int>(k);
        tracking[k] = fem.tracking_shapes;
        solutions.push_back(fem);
        c.pairs.insert(c.pairs.end(), pairs[k].begin(), pairs[k].end());
      }
      if (unsolvable) continue;
      // Trial point: accept when J did not grow with the same pairs. A step that
      // loses pairs overshot too (a test mode whose partner the step moved away
      // is data the step stopped fitting; J over fewer pairs is not comparable),
      // so it is rejected as well, until max_halvings: then the pairs that remain
      // are accepted (a partner that is really gone stays gone).
      if (cycle > 0) {
        bool same = true, lost = false;
        for (std::size_t k = 0; k < nc; ++k) {
          lost = lost || pairs[k].size() < pairs_accepted[k].size();
          same = same && pairs[k].size() == pairs_accepted[k].size();
          for (std::size_t q = 0; same && q < pairs[k].size(); ++q) same = pairs[k][q].test == pairs_accepted[k][q].test;
        }
        if (lost && halvings < max_halvings) {
          reject(cycle, "the step loses pairs", notes_before, dropped_before);
          continue;
        }
        double J_trial = 0;
        if (same) {
          Residuals trial;
          std::vector<double> z, u, sg;
          for (std::size_t k = 0; k < nc; ++k) {
            const Residuals part = residuals(*configurations[k].model, configurations[k].test, solutions[k], pairs[k], options, false);
            z.insert(z.end(), part.z.data(), part.z.data() + part.z.size());
            u.insert(u.end(), part.u.data(), part.u.data() + part.u.size());
            sg.insert(sg.end(), part.sigma.data(), part.sigma.data() + part.sigma.size());
          }
          const auto len = static_cast<Eigen::Index>(z.size());
          trial.z = Eigen::Map<Eigen::VectorXd>(z.data(), len);
          trial.u = Eigen::Map<Eigen::VectorXd>(u.data(), len);
          trial.sigma = Eigen::Map<Eigen::VectorXd>(sg.data(), len);
          J_trial = objective(theta, trial);
        }
        // At the minimum as far as the steps can see: after repeated damping the
        // trial still raises J, by less than 1e-6 of itself. With approximate
        // sensitivities (modal summation) the Gauss–Newton steps point to a
        // point near, not at, J's minimum, and the iteration would go on
        // trading rejected trials for tiny gains until the cycle limit; the
        // accepted point is the answer to far better than the data resolve.
        if (same && halvings >= 2 && J_trial > J_accepted * (1 + 1e-9) && J_trial <= J_accepted * (1 + 1e-6)) {
          result.notes.resize(accepted->notes);
          result.dropped.resize(accepted->dropped);
          finish(*accepted);
          result.converged = true;
          result.notes.push_back("converged after " + std::to_string(result.history.size()) +
                                 " cycle(s): a damped step changes J by less than 1e-6 of it");
          return result;
        }
        // J equal within what the eigen-solve resolves (at the minimum) is not growth.
        if (same && J_trial > J_accepted * (1 + 1e-9) && halvings < max_halvings) {
          reject(cycle, "J = " + significant(J_trial, 10) + " > " + significant(J_accepted, 10), notes_before,
                 dropped_before);
          continue;
        }
      }
      c.step_halvings = halvings;
      if (halvings >= max_halvings) mu = 0;  // the damped steps ended at the accepted point: start afresh
      halvings = 0;
      for (std::size_t k = 0; k < nc; ++k)
        parts.push_back(residuals(*configurations[k].model, configurations[k].test, solutions[k], pairs[k], options));
      Residuals res;
      Eigen::Index m = 0;
      result.final_solutions = std::move(solutions);
      for (const auto& part : parts) m += part.z.size();
      res.z.resize(m);
      res.u.resize(m);
      res.sigma.resize(m);
      res.T.resize(m, p);
      Eigen::Index at = 0;
      for (const auto& part : parts) {
        const auto len = part.z.size();
        res.z.segment(at, len) = part.z;
        res.u.segment(at, len) = part.u;
        res.sigma.segment(at, len) = part.sigma;
        res.T.middleRows(at, len) = part.T;
        at += len;
      }
      if (m == 0) throw formats::InputError("update: no measurement with a positive standard deviation");
      const Eigen::MatrixXd T_theta = res.T * d.asDiagonal();
      // Convergence and the posterior come from the undamped step of Eq. (7); the
      // next point from the damped one while the damping lasts.
      const BayesStep step = bayes_step(theta, zero, cov_theta, res.z, res.u, T_theta, res.sigma, lo, hi);
      // The damping that just succeeded after rejections is kept for the next
      // step (lowering it at once had the next trial rejected again, every
      // second solve wasted); after a step accepted at once it is lowered.
      if (c.step_halvings == 0) mu = mu >= 0.1 ? mu / 10 : 0.0;
      const Eigen::VectorXd theta_next =
          mu > 0 ? bayes_step(theta, zero, cov_theta, res.z, res.u, T_theta, res.sigma, lo, hi, mu).r_next : step.r_next;

      c.objective = step.objective;
      c.misfit = step.misfit;
      c.clipped = step.clipped;
      summarise(c);
      result.history.push_back(c);
      result.measurements = static_cast<int>(m);
      accepted = Accepted{r, step, res.sigma, T_theta, result.notes.size(), result.dropped.size()};
      report_cycle(cycle + 1, "J = " + significant(step.objective, 6) + " (data misfit " + significant(step.misfit, 6) +
                              ", prior " + significant(step.objective - step.misfit, 4) + "), frequency RMS error " +
                              significant(c.freq_rms_pct, 4) + " %, " + std::to_string(c.pairs.size()) + " pairs");

      const double move = (step.r_next - theta).cwiseAbs().maxCoeff();
      const bool last = cycle >= options.max_iterations;
      if (move < options.tolerance || last) {
        finish(*accepted);
        result.converged = move < options.tolerance;
        if (!result.converged)
          result.notes.push_back("not converged after " + std::to_string(result.history.size()) +
                                 " cycle(s) (last move " + significant(move, 3) + " prior standard deviations)");
        return result;
      }
      J_accepted = step.objective;
      theta_accepted = theta;
      pairs_accepted = pairs;
      tracking_accepted = tracking;
      T_accepted = T_theta;
      res_accepted = res;
      theta = theta_next;
      ++cycle;
    }
  } catch (const Interrupted& ex) {
    if (!accepted) throw;
    return stop_early(ex.what(), true);
  } catch (const formats::NumericalError& ex) {
    if (!accepted) throw;
    return stop_early(ex.what(), false);
  }
}

}  // namespace ssid::estimator
