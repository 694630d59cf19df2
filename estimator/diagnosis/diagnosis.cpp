#include "estimator/diagnosis/diagnosis.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <sstream>

#include "estimator/diagnosis/calibration.hpp"
#include "estimator/eigen/eigen_solver.hpp"
#include "estimator/updating/sensitivity.hpp"
#include "formats/deck_writer.hpp"
#include "formats/parse_error.hpp"
#include "formats/text_util.hpp"
#include "estimator/study/study_reader.hpp"

namespace ssid::estimator::diagnosis {

namespace ext = hypotheses;

namespace {

/// Columns `keep` of a mode set.
translators::ModeSet select_modes(const translators::ModeSet& s, const std::vector<std::size_t>& keep) {
  translators::ModeSet out;
  out.dofs = s.dofs;
  out.shapes.resize(s.shapes.rows(), static_cast<Eigen::Index>(keep.size()));
  for (std::size_t k = 0; k < keep.size(); ++k) {
    const auto i = keep[k];
    out.shapes.col(static_cast<Eigen::Index>(k)) = s.shapes.col(static_cast<Eigen::Index>(i));
    out.frequency_hz.push_back(s.frequency_hz[i]);
    if (i < s.numbers.size()) out.numbers.push_back(s.numbers[i]);
    if (i < s.damping.size()) out.damping.push_back(s.damping[i]);
    if (i < s.modal_mass.size()) out.modal_mass.push_back(s.modal_mass[i]);
    if (i < s.frequency_std_hz.size()) out.frequency_std_hz.push_back(s.frequency_std_hz[i]);
    if (i < s.shape_std.size()) out.shape_std.push_back(s.shape_std[i]);
  }
  return out;
}

/// Log-likelihood of a test mode the model does not explain at all.
double miss_loglik(const MeasuredMode& t, double miss_frequency_pct, bool shapes) {
  double ll = 0;
  if (t.use_frequency && t.frequency_std_hz > 0) {
    const double x = t.frequency_hz * miss_frequency_pct / 100.0 / t.frequency_std_hz;
    ll += -0.5 * x * x - 0.5 * std::log(2 * M_PI * t.frequency_std_hz * t.frequency_std_hz);
  }
  if (shapes && t.use_shape && t.shape.size() && t.shape_std > 0) {
    const double s2 = t.shape_std * t.shape_std;
    ll += -0.5 * 2.0 / s2 - 0.5 * static_cast<double>(t.shape.size()) * std::log(2 * M_PI * s2);
  }
  return ll;
}

/// Log-likelihood of paired modes at the model's prediction (no parameters).
double pair_loglik(const std::vector<MeasuredMode>& test, const ModalSolution& sol, const std::vector<UpdatePair>& pairs,
                   bool shapes) {
  double ll = 0;
  for (const auto& p : pairs) {
    const auto& t = test[static_cast<std::size_t>(p.test)];
    if (t.use_frequency && t.frequency_std_hz > 0) {
      const double x = (t.frequency_hz - eigenvalue_to_hz(sol.eigenvalues(p.fem))) / t.frequency_std_hz;
      ll += -0.5 * x * x - 0.5 * std::log(2 * M_PI * t.frequency_std_hz * t.frequency_std_hz);
    }
    if (shapes && t.use_shape && t.shape.size() && t.shape_std > 0) {
      Eigen::VectorXd u = sol.sensor_shapes.col(p.fem).normalized();
      Eigen::VectorXd z = t.shape.normalized();
      if (z.dot(u) < 0) z = -z;
      const double s2 = t.shape_std * t.shape_std;
      ll += -0.5 * (z - u).squaredNorm() / s2 - 0.5 * static_cast<double>(z.size()) * std::log(2 * M_PI * s2);
    }
  }
  return ll;
}

Fit fit_of(const UpdateCycle& c, int measured) {
  Fit f;
  f.freq_rms_pct = c.freq_rms_pct;
  f.mean_mac = c.mean_mac;
  f.paired = static_cast<int>(c.pairs.size());
  f.measured = measured;
  return f;
}

struct Setup {
  std::vector<ConfigurationInput> est;   ///< configurations with the held-back modes removed
  translators::ModeSet held;             ///< held-back modes of the first configuration
};

class Engine {
 public:
  Engine(const std::vector<ConfigurationInput>& configs, const DiagnosisOptions& options) : m_opt(options) {
    if (configs.empty()) throw std::invalid_argument("diagnose: no configuration");
    m_setup.est = configs;
    if (options.hold_back > 0) {
      const auto& s = configs.front().measured;
      const std::size_t n = s.frequency_hz.size();
      if (static_cast<std::size_t>(options.hold_back) + 2 > n)
        throw formats::InputError("diagnose: cannot hold back " + std::to_string(options.hold_back) + " of " +
                                    std::to_string(n) + " test modes");
      std::vector<std::size_t> order(n);
      for (std::size_t i = 0; i < n; ++i) order[i] = i;
      std::sort(order.begin(), order.end(), [&](auto a, auto b) { return s.frequency_hz[a] < s.frequency_hz[b]; });
      std::vector<std::size_t> keep(order.begin(), order.end() - options.hold_back),
          held(order.end() - options.hold_back, order.end());
      std::sort(keep.begin(), keep.end());
      std::sort(held.begin(), held.end());
      m_setup.est.front().measured = select_modes(s, keep);
      m_setup.held = select_modes(s, held);
    }
  }

  /// The estimation problem of one hypothesis: every configuration's deck text
  /// through the study's builder (estimator/study/deck_study), the new
  /// parameters' priors added to the study, the iteration started at the kind's
  /// start values and, for the deck's own parameters, where the ordinary update
  /// ended (the prior is unchanged: each hypothesis then only has to move from
  /// the best fit without it, not repeat the ordinary update's whole path).
  EstimationProblem build_problem(const std::vector<std::string>& texts, const std::vector<ext::NewParameter>& added) const {
    Study study = m_opt.study;
    for (const auto& p : added) {
      PriorSetting ps;
      ps.mean = p.prior_mean;
      ps.std = p.prior_std;
      study.priors[formats::detail::upper(p.label)] = ps;
      if (!study.parameters.empty()) study.parameters.push_back(formats::detail::upper(p.label));
    }
    std::vector<ConfigurationSource> sources;
    for (std::size_t k = 0; k < texts.size(); ++k) {
      const ConfigurationInput& c = m_setup.est[k];
      ConfigurationSource src;
      src.name = c.configuration;
      src.deck = c.name;
      src.deck_text = texts[k];
      src.measured = c.measured_name.empty() ? "measured modes of " + c.name : c.measured_name;
      src.data.modes = c.measured;
      src.data.nodes = c.nodes;
      sources.push_back(std::move(src));
    }
    EstimationProblem pb = prepare_problem(study, sources);
    const auto& names = pb.prior.names;
    pb.options.start = pb.prior.mean;
    for (std::size_t j = 0; j < names.size(); ++j) {
      const auto i = static_cast<Eigen::Index>(j);
      for (const auto& p : added)
        if (formats::detail::upper(p.label) == names[j] && !std::isnan(p.start)) pb.options.start(i) = p.start;
      if (auto it = m_warm.find(names[j]); it != m_warm.end())
        pb.options.start(i) = std::clamp(it->second, pb.prior.lower(i), pb.prior.upper(i));
    }
    return pb;
  }

  /// The analyst's fixed pairs name analysis modes of the deck as given, where
  /// the ordinary update starts. A hypothesis starts elsewhere (the ordinary
  /// update's estimate) and may add DOFs and with them modes: its partner of
  /// test mode i is the mode most like the nominal partner (MAC over the
  /// nominal model's g-set DOFs) at its own start. The first call (the ordinary
  /// update) records the nominal partners and changes nothing.
  void carry_fixed_pairs(EstimationProblem& pb) {
    for (std::size_t k = 0; k < pb.configurations.size(); ++k) {
      PreparedConfiguration& c = pb.configurations[k];
      if (std::none_of(c.test.begin(), c.test.end(), [](const MeasuredMode& t) { return t.fixed_partner >= 0; })) continue;
      c.model->solve(pb.options.start);
      const Eigen::MatrixXd phi = c.fe->expand(c.model->modes());
      const translators::DofMap& gset = c.fe->geometry().gset();
      if (m_reference.size() <= k) {  // the deck as given
        m_reference.resize(k + 1);
        m_reference[k].gset = gset;
        m_reference[k].shapes = phi;
        continue;
      }
      const Reference& ref = m_reference[k];
      std::vector<Eigen::Index> here, there;  // rows of the common DOFs
      for (std::size_t i = 0; i < ref.gset.size(); ++i)
        if (auto j = gset.find(ref.gset.at(i))) {
          there.push_back(static_cast<Eigen::Index>(i));
          here.push_back(static_cast<Eigen::Index>(*j));
        }
      for (auto& t : c.test) {
        if (t.fixed_partner < 0 || t.fixed_partner >= ref.shapes.cols()) continue;
        Eigen::VectorXd a(static_cast<Eigen::Index>(there.size()));
        for (std::size_t r = 0; r < there.size(); ++r) a(static_cast<Eigen::Index>(r)) = ref.shapes(there[r], t.fixed_partner);
        int best = t.fixed_partner;
        double best_mac = -1;
        for (Eigen::Index j = 0; j < phi.cols(); ++j) {
          double ab = 0, bb = 0;
          for (std::size_t r = 0; r < here.size(); ++r) {
            const double b = phi(here[r], j);
            ab += a(static_cast<Eigen::Index>(r)) * b;
            bb += b * b;
          }
          const double mac = bb > 0 ? ab * ab / (a.squaredNorm() * bb) : 0.0;
          if (mac > best_mac) {
            best_mac = mac;
            best = static_cast<int>(j);
          }
        }
        t.fixed_partner = best;
      }
    }
  }

  /// The estimate of a problem (every configuration together).
  UpdateResult estimate(EstimationProblem& pb) const {
    std::vector<Configuration> confs;
    for (auto& c : pb.configurations) confs.push_back({c.name, c.model.get(), c.test});
    return update(confs, pb.prior, pb.options, m_update_progress);
  }

  /// Builds, estimates and scores one hypothesis given the deck text of each configuration.
  Hypothesis evaluate(const std::string& kind, const std::vector<std::string>& texts,
                      const std::vector<ext::NewParameter>& added, EstimationProblem* keep = nullptr) {
    EstimationProblem pb = build_problem(texts, added);
    carry_fixed_pairs(pb);
    UpdateResult res = estimate(pb);
    // A numerical failure after the first cycle fails the hypothesis, as one in
    // the first; an interruption leaves it as far as it got (interrupted()).
    if (!res.stopped.empty() && !res.interrupted) throw formats::NumericalError(res.stopped);
    m_interrupted = res.interrupted;
    // Pairs are made in the first cycle; a mode the new parameters moved next
    // to its test partner only pairs when the estimate is restarted from there.
    for (int again = 0; again < 2 && !m_interrupted; ++again) {
      std::size_t more = 0;
      for (auto& c : pb.configurations) more += pair_for_update(c.test, c.model->solve(res.r), pb.options).size();
      if (more <= res.history.back().pairs.size()) break;
      pb.options.start = res.r;
      UpdateResult next = estimate(pb);
      if (!next.stopped.empty() && !next.interrupted) throw formats::NumericalError(next.stopped);
      m_interrupted = next.interrupted;
      next.history.front() = res.history.front();  // "before" stays the model at its start
      res = std::move(next);
    }
    Hypothesis h;
    h.kind = kind;
    h.added = added;
    h.names = pb.prior.names;
    h.estimate = res.r;
    h.posterior_std = res.posterior_std;
    h.posterior_cov = res.posterior_cov;
    h.prior_mean = pb.prior.mean;
    h.log_evidence = res.log_evidence;
    h.converged = res.converged;
    h.notes = res.notes;
    int measured = 0;
    for (const auto& c : pb.configurations) measured += static_cast<int>(c.test.size());
    h.before = fit_of(res.history.front(), measured);
    h.after = fit_of(res.history.back(), measured);
    h.pairs = res.history.back().pairs;
    const bool shapes = pb.options.shape_derivatives;
    for (std::size_t k = 0; k < pb.configurations.size(); ++k) {
      std::set<int> paired;
      for (const auto& p : res.history.back().pairs)
        if (p.config == static_cast<int>(k)) paired.insert(p.test);
      const auto& test = pb.configurations[k].test;
      for (std::size_t i = 0; i < test.size(); ++i)
        if (!paired.count(static_cast<int>(i))) h.miss_penalty += miss_loglik(test[i], m_opt.miss_frequency_pct, shapes);
    }
    h.score = h.log_evidence + h.miss_penalty;
    h.deck_text = texts.front();
    // Prediction of the held-back modes.
    if (!m_setup.held.frequency_hz.empty()) {
      auto& pc = pb.configurations.front();
      const ModalSolution sol = pc.model->solve(res.r);
      const auto test = measured_at_sensors(m_opt.study, m_setup.held, pc);
      const auto pairs = pair_for_update(test, sol, pb.options);
      double s2 = 0;
      for (const auto& p : pairs) s2 += p.error_pct * p.error_pct;
      h.predicted = static_cast<int>(pairs.size());
      h.prediction_rms_pct = pairs.empty() ? -1 : std::sqrt(s2 / static_cast<double>(pairs.size()));
    }
    if (keep) *keep = std::move(pb);
    m_last = res;
    return h;
  }

  /// Later hypotheses start the deck's parameters at these values (by label).
  void warm_start(const std::vector<std::string>& names, const Eigen::VectorXd& r) {
    for (std::size_t j = 0; j < names.size(); ++j) m_warm[names[j]] = r(static_cast<Eigen::Index>(j));
  }
  const std::map<std::string, double>& warm() const { return m_warm; }
  /// The first configuration's estimation problem for deck `text` with the
  /// priors of the new parameters `added` (no estimate; the other
  /// configurations are not built).
  EstimationProblem problem(const std::string& text, const std::vector<ext::NewParameter>& added) const {
    return build_problem({text}, added);
  }
  /// The measurement σ of the next hypotheses' estimates (the noise the data
  /// imply): frequencies in % of each, shapes in % of the RMS component (an
  /// absolute shape σ of the study gives way to it); modes with σ of the
  /// identification keep theirs, times the scales ŝ_f, ŝ_s (on the σ
  /// assumed, not compounded).
  void set_noise(double frequency_std_pct, double shape_std_pct, double frequency_scale, double shape_scale) {
    m_opt.study.frequency_std_pct = frequency_std_pct;
    m_opt.study.shape_std.reset();
    m_opt.study.shape_std_pct = shape_std_pct;
    m_opt.study.identified_frequency_std_scale = frequency_scale;
    m_opt.study.identified_shape_std_scale = shape_scale;
  }
  /// Where the estimates of the next hypotheses report their cycles.
  void set_update_progress(Progress p) { m_update_progress = std::move(p); }
  /// The last evaluate()'s estimate was interrupted (its hypothesis is as far as it got).
  bool interrupted() const { return m_interrupted; }
  const UpdateResult& last() const { return m_last; }
  const Setup& setup() const { return m_setup; }
  const DiagnosisOptions& options() const { return m_opt; }

 private:
  /// The deck as given at the ordinary update's start, per configuration: its
  /// g-set DOFs and modes (for the fixed pairs, carry_fixed_pairs).
  struct Reference {
    translators::DofMap gset;
    Eigen::MatrixXd shapes;
  };
  std::vector<Reference> m_reference;
  DiagnosisOptions m_opt;
  Progress m_update_progress;
  Setup m_setup;
  UpdateResult m_last;
  std::map<std::string, double> m_warm;
  bool m_interrupted = false;
};

/// First-order screening data at the updated parameters (first configuration).
struct Screen {
  LinearUpdate lin;    ///< weighted residual, prior-scaled sensitivities, row groups and modes
  struct Row { int fem; double f; Eigen::VectorXd u; double norm; double sigma_f, sigma_s; bool use_f, use_s; };
  std::vector<Row> rows;
};

/// Which rows of a paired test mode the update fits: its frequency, its shape.
struct FittedRows {
  bool frequency = false, shape = false;
};
FittedRows fitted_rows(const MeasuredMode& t, const UpdateOptions& opt) {
  return {t.use_frequency && t.frequency_std_hz > 0, opt.shape_derivatives && t.use_shape && t.shape.size() && t.shape_std > 0};
}

Screen prepare_screen(PreparedConfiguration& pb, const ParameterPrior& prior, const Eigen::VectorXd& r,
                      const std::vector<UpdatePair>& all_pairs, const UpdateOptions& opt) {
  Screen sc;
  const ModalSolution sol = pb.model->solve(r);
  const Eigen::VectorXd d = prior.cov.diagonal().array().sqrt();
  std::vector<double> e;
  std::vector<Eigen::VectorXd> w;
  std::vector<const MeasuredMode*> tests;  // each row's test mode
  for (const auto& p : all_pairs) {
    if (p.config != 0) continue;
    const auto& t = pb.test[static_cast<std::size_t>(p.test)];
    tests.push_back(&t);
    Screen::Row row;
    row.fem = p.fem;
    row.f = eigenvalue_to_hz(sol.eigenvalues(p.fem));
    const Eigen::VectorXd phi_s = sol.sensor_shapes.col(p.fem);
    row.norm = phi_s.norm();
    row.u = phi_s / row.norm;
    const FittedRows fitted = fitted_rows(t, opt);
    row.use_f = fitted.frequency;
    row.use_s = fitted.shape;
    row.sigma_f = t.frequency_std_hz;
    row.sigma_s = t.shape_std;
    sc.rows.push_back(row);
  }
  // Every row's sensitivities at once (the model computes them concurrently).
  std::vector<int> modes;
  std::vector<bool> shapes;
  for (const auto& row : sc.rows) modes.push_back(row.fem), shapes.push_back(row.use_s);
  const std::vector<ModeSensitivity> sens = pb.model->sensitivities(modes, shapes);
  for (std::size_t k = 0; k < sc.rows.size(); ++k) {
    const MeasuredMode& t = *tests[k];
    const Screen::Row& row = sc.rows[k];
    const ModeSensitivity& s = sens[k];
    if (row.use_f) {
      e.push_back((t.frequency_hz - row.f) / row.sigma_f);
      w.push_back((s.d_eigenvalue / (8 * M_PI * M_PI * row.f)).cwiseProduct(d) / row.sigma_f);
      sc.lin.group.push_back(kFrequencyRows);
      sc.lin.block.push_back(static_cast<int>(k));
    }
    if (row.use_s) {
      Eigen::VectorXd z = t.shape.normalized();
      if (z.dot(row.u) < 0) z = -z;
      const Eigen::MatrixXd du = (s.d_sensor_shape - row.u * (row.u.transpose() * s.d_sensor_shape)) / row.norm;
      for (Eigen::Index k2 = 0; k2 < z.size(); ++k2) {
        e.push_back((z(k2) - row.u(k2)) / row.sigma_s);
        w.push_back(du.row(k2).transpose().cwiseProduct(d) / row.sigma_s);
        sc.lin.group.push_back(kShapeRows);
        sc.lin.block.push_back(static_cast<int>(k));
      }
    }
  }
  const auto m = static_cast<Eigen::Index>(e.size());
  sc.lin.e = Eigen::Map<Eigen::VectorXd>(e.data(), m);
  sc.lin.W.resize(m, d.size());
  for (Eigen::Index k = 0; k < m; ++k) sc.lin.W.row(k) = w[static_cast<std::size_t>(k)].transpose();
  sc.lin.theta = ((r - prior.mean).array() / d.array()).matrix();
  return sc;
}

/// The prior-scaled weighted sensitivity σ_β S_ee^{-1/2} ∂u/∂β of one new
/// parameter from its ∂K, ∂M (∂λ exact, ∂φ by modal summation): the rows of `sc`.
Eigen::VectorXd screen_column(const Screen& sc, const OperatorModel& model, const Eigen::VectorXd& lambdas,
                              const SparseMatrix& C, const SparseMatrix& dK, const SparseMatrix& dM, double prior_std) {
  const Eigen::MatrixXd& Phi = model.modes();
  std::vector<double> t;
  t.reserve(static_cast<std::size_t>(sc.lin.e.size()));
  for (const auto& row : sc.rows) {
    const double lam = lambdas(row.fem);
    const Eigen::VectorXd phi = Phi.col(row.fem);
    if (row.use_f) t.push_back(eigenvalue_derivative(dK, dM, lam, phi) / (8 * M_PI * M_PI * row.f) / row.sigma_f);
    if (row.use_s) {
      const Eigen::VectorXd dphi = modal_sum_derivative(Phi, lambdas, row.fem, dK, dM);
      const Eigen::VectorXd ds = C * dphi;
      const Eigen::VectorXd du = (ds - row.u * row.u.dot(ds)) / row.norm;
      for (Eigen::Index k = 0; k < du.size(); ++k) t.push_back(du(k) / row.sigma_s);
    }
  }
  return prior_std * Eigen::Map<const Eigen::VectorXd>(t.data(), static_cast<Eigen::Index>(t.size()));
}

/// The updated model's modes (`sol`, the model's last solve) and, for each
/// unexplained test mode (the evidence's order), its sensor shape and the
/// analysis mode most like it at the sensors (highest MAC within ±30 % in
/// frequency; any frequency when none; the nearest in frequency when the test
/// has no shapes).
ext::UnexplainedModes unexplained_modes(PreparedConfiguration& pb, const ModalSolution& sol, const Evidence& ev) {
  ext::UnexplainedModes out;
  const Eigen::MatrixXd& phi = pb.model->modes();
  out.eigenvalues = sol.eigenvalues;
  out.sensor_shapes = sol.sensor_shapes;
  if (phi.cols() > 0) out.g_shapes = pb.fe->expand(phi);
  for (const auto& u : ev.unpaired_test) {
    const MeasuredMode* t = nullptr;
    for (const auto& m : pb.test)
      if (m.id == u.id) t = &m;
    if (!t || !t->shape.size() || phi.cols() == 0) {  // frequencies only: the analysis mode nearest in frequency
      Eigen::Index nearest = -1;
      double gap = std::numeric_limits<double>::infinity();
      for (Eigen::Index j = 0; j < sol.eigenvalues.size(); ++j)
        if (const double d = std::abs(eigenvalue_to_hz(sol.eigenvalues(j)) - u.frequency_hz); d < gap) {
          gap = d;
          nearest = j;
        }
      out.test_shapes.emplace_back();
      out.neighbour.push_back(phi.cols() > 0 ? static_cast<int>(nearest) : -1);
      continue;
    }
    int best = -1;
    double best_mac = -1;
    for (int pass = 0; pass < 2 && best < 0; ++pass)
      for (Eigen::Index j = 0; j < sol.sensor_shapes.cols(); ++j) {
        const double f = eigenvalue_to_hz(sol.eigenvalues(j));
        if (pass == 0 && std::abs(f - u.frequency_hz) > 0.3 * u.frequency_hz) continue;
        const Eigen::VectorXd s = sol.sensor_shapes.col(j);
        const double d = s.squaredNorm() * t->shape.squaredNorm();
        const double mac = d > 0 ? std::pow(s.dot(t->shape), 2) / d : 0.0;
        if (mac > best_mac) { best_mac = mac; best = static_cast<int>(j); }
      }
    out.test_shapes.push_back(t->shape);
    out.neighbour.push_back(best);
  }
  return out;
}

/// The noise the comparisons of fits use: σ of a frequency [% of it] and of a
/// component of a unit shape; per test mode (configuration, test index) where
/// its σ is the identification's (Study::std_from), else the uniform values.
struct FitNoise {
  double frequency_pct = 1, shape_unit = 1;
  std::map<std::pair<int, int>, std::pair<double, double>> per_mode;  ///< (σ_f %, σ_s)
  std::map<std::pair<int, int>, int> rows;  ///< data rows of a test mode: its frequency and its shape's components
  double alpha = 0.01;                      ///< the chance of vetoing a right hypothesis (worse_fit)
  std::pair<double, double> of(int config, int test) const {
    const auto it = per_mode.find({config, test});
    return it != per_mode.end() ? it->second : std::make_pair(frequency_pct, shape_unit);
  }
  int rows_of(int config, int test) const {
    const auto it = rows.find({config, test});
    return it != rows.end() ? it->second : 1;
  }
};

/// The pairs of `h` whose test mode `ref` leaves unpaired.
std::vector<const UpdatePair*> new_pairs(const Hypothesis& h, const Hypothesis& ref) {
  std::set<std::pair<int, int>> theirs;
  for (const auto& p : ref.pairs) theirs.insert({p.config, p.test});
  std::vector<const UpdatePair*> out;
  for (const auto& p : h.pairs)
    if (!theirs.count({p.config, p.test})) out.push_back(&p);
  return out;
}

/// How far the χ² of one group of the modes both pair may rise when h pairs the
/// modes `fresh` that `ref` does not, before the rise says H is wrong rather
/// than pulled by their rows. Why (docs/diagnosis.md, "Not worse"): linearised,
/// whitened and prior-scaled, with H right and its new rows fitting to the
/// noise, the new rows move H's estimate from its fit to the common rows by
/// d ~ N(0, Σ_c − Σ_h), of rank m ≤ min(new rows, H's parameters), and the
/// common rows' penalised misfit (χ² plus the prior's term) rises by dᵀΣ_c⁻¹d,
/// stochastically below χ²(m). That bound is proven for all common rows and
/// the penalised misfit; for each group's χ² alone, prior included, it was
/// checked numerically (test_calibration.cpp). A right H exceeds the (1 − α/2)
/// point in a group with probability at most α/2. With no new rows, 1 (a
/// likelihood ratio of e^{−1/2}: within it the difference is the noise's).
double allowed_rise(const Hypothesis& h, const std::vector<const UpdatePair*>& fresh, const FitNoise& noise) {
  long new_rows = 0;
  for (const UpdatePair* p : fresh) new_rows += noise.rows_of(p->config, p->test);
  const long m = std::min<long>(new_rows, h.estimate.size());
  return m > 0 ? std::max(1.0, chi2_quantile_upper(0.5 * noise.alpha, static_cast<double>(m))) : 1.0;
}

/// "" when `h` fits the test modes that both pair no worse than `ref`, pairs
/// no fewer modes and predicts held-back modes no worse; otherwise why not.
/// Worse: the frequency or the shape χ² of the common pairs, in units of the
/// noise, χ²_f = Σ (Δf %/σ_f)², χ²_s = Σ ‖z − u‖²/σ_s² = Σ (2 − 2√MAC)/σ_s²,
/// grows by more than allowed_rise: 1 when h pairs the same modes, more when
/// it pairs new ones, whose rows pull its estimate; and the new modes'
/// frequencies must fit within the noise. Each of the three checks vetoes a
/// right hypothesis with probability at most α/2: at most 3α/2 in all.
std::string worse_fit(const Hypothesis& h, const Hypothesis& ref, const FitNoise& noise) {
  if (h.after.paired < ref.after.paired)
    return "pairs fewer test modes (" + std::to_string(h.after.paired) + " vs " + std::to_string(ref.after.paired) + ")";
  std::map<std::pair<int, int>, const UpdatePair*> mine;
  for (const auto& p : h.pairs) mine[{p.config, p.test}] = &p;
  double e2h = 0, e2r = 0, mach = 0, macr = 0, df = 0, ds = 0;
  int n = 0;
  for (const auto& p : ref.pairs) {
    const auto it = mine.find({p.config, p.test});
    if (it == mine.end()) continue;
    const auto [sf, ss] = noise.of(p.config, p.test);
    e2h += it->second->error_pct * it->second->error_pct;
    e2r += p.error_pct * p.error_pct;
    df += (it->second->error_pct * it->second->error_pct - p.error_pct * p.error_pct) / (sf * sf);
    mach += it->second->mac;
    macr += p.mac;
    ds += (std::sqrt(std::clamp(p.mac, 0.0, 1.0)) - std::sqrt(std::clamp(it->second->mac, 0.0, 1.0))) * 2.0 / (ss * ss);
    ++n;
  }
  const std::vector<const UpdatePair*> fresh = new_pairs(h, ref);
  if (n > 0) {
    const double allowed = allowed_rise(h, fresh, noise);
    const std::string on = " on the " + std::to_string(n) + " modes both pair",
                      limit = allowed > 1.0 ? ", above the " + significant(allowed, 3) + " the new pairs' pull explains" : "";
    if (df > allowed)
      return "makes the frequency fit worse (RMS error " + fixed(std::sqrt(e2h / n), 3) + " % vs " + fixed(std::sqrt(e2r / n), 3) +
             " %" + on + ": chi^2 up by " + significant(df, 3) + limit + ")";
    if (ds > allowed)
      return "makes the shape fit worse (mean MAC " + fixed(mach / n, 5) + " vs " + fixed(macr / n, 5) + on +
             ": chi^2 up by " + significant(ds, 3) + limit + ")";
  }
  // The modes only h pairs: fitted, their frequency residuals are below the
  // noise's, χ²(k) for k of them, when H is right. (Not their shapes: a mode the
  // model lacked — a strut's bending, a spring's surge — hardly moves the
  // sensors, and what the test shows of it there is mostly its coupling to the
  // rest, which the extension's few values place only roughly; the sweep's
  // right local modes and surges miss the shape noise there by 5× in χ².)
  int k = 0;
  double x = 0, worst = 0;
  for (const UpdatePair* p : fresh) {
    const double sf = noise.of(p->config, p->test).first;
    ++k;
    x += p->error_pct * p->error_pct / (sf * sf);
    if (std::abs(p->error_pct) > std::abs(worst)) worst = p->error_pct;
  }
  if (const double limit = k > 0 ? chi2_quantile_upper(0.5 * noise.alpha, k) : 0.0; k > 0 && x > limit)
    return "pairs its new mode(s) outside the frequency noise (error up to " + fixed(worst, 3) + " %: chi^2 " +
           significant(x, 3) + " for " + std::to_string(k) + " mode(s), above " + significant(limit, 3) + ")";
  if (h.prediction_rms_pct >= 0 && ref.prediction_rms_pct >= 0 && h.prediction_rms_pct > ref.prediction_rms_pct)
    return "predicts the held-back modes worse (RMS " + fixed(h.prediction_rms_pct, 3) + " % vs " +
           fixed(ref.prediction_rms_pct, 3) + " %)";
  return "";
}

/// "" when extension `h` may be named against the ordinary update `P`
/// (diagnosis.hpp, step 4); otherwise the first reason it may not.
std::string why_not_named(const Hypothesis& h, const Hypothesis& P, const ResidualTest& rt, double alpha, double margin,
                          const FitNoise& noise) {
  if (h.screening_column >= 0) {
    if (!(h.false_alarm <= alpha))
      return "false-alarm probability " + significant(h.false_alarm, 2) + " (" + std::to_string(h.exceed) + " of " +
             std::to_string(rt.replicates) + " noise replicates reach its first-order gain of " + fixed(h.screening, 2) +
             " nats) is above " + significant(alpha, 2);
    if (!(h.held_out.total() > 0))
      return "does not predict held-out modes better (leave-one-mode-out gain " + significant(h.held_out.total(), 3) +
             ": frequencies " + significant(h.held_out.gain[kFrequencyRows], 3) + ", shapes " +
             significant(h.held_out.gain[kShapeRows], 3) + ")";
  } else if (rt.consistent) {
    return "the ordinary update's residuals are consistent with the noise: nothing is left to explain";
  }
  if (h.score - P.score < margin)
    return fixed(h.score - P.score, 1) + " nats above the ordinary update, below the " + fixed(margin, 1) + "-nat margin";
  return worse_fit(h, P, noise);
}

/// Is anything left to explain after the ordinary update? Fills dg.residual
/// from the noise report, the pairs of `param` and the calibrated screening;
/// `where(column)` names a screened candidate.
void residual_test(Diagnosis& dg, const Hypothesis& param, const Screening& screen, const CalibrationOptions& opt,
                   const std::function<std::string(int)>& where) {
  ResidualTest& rt = dg.residual;
  const NoiseScale& ns = dg.noise.scale;
  const char* group_name[kRowGroups] = {"frequency", "shape"};
  for (int g = 0; g < kRowGroups; ++g) rt.chi2_p[g] = ns.rows[g] ? chi2_upper_tail(ns.chi2[g], ns.dof[g]) : 1.0;
  rt.unpaired = param.after.measured - param.after.paired;
  rt.candidates = screen.candidate_count();
  rt.replicates = static_cast<int>(screen.maxima().size());
  std::vector<std::string> left;
  if (rt.unpaired > 0) left.push_back(std::to_string(rt.unpaired) + " test mode(s) have no analysis partner");
  std::string gain_text;
  if (rt.candidates > 0 && rt.replicates > 0) {
    Eigen::Index best = 0;
    rt.statistic = screen.gains().maxCoeff(&best);
    rt.exceed = screen.exceedances(rt.statistic);
    rt.p = screen.false_alarm(rt.statistic);
    rt.p_upper = tail_upper_bound(rt.exceed, rt.replicates);
    gain_text = "the largest first-order gain of the " + std::to_string(rt.candidates) + " candidates screened, " +
                fixed(rt.statistic, 2) + " nats (" + where(static_cast<int>(best)) + "), is reached by " +
                std::to_string(rt.exceed) + " of " + std::to_string(rt.replicates) +
                " replicates of noise alone (false-alarm p = " + significant(rt.p, 2) + ")";
    if (rt.p <= opt.false_alarm) left.push_back(gain_text);
  }
  if (!opt.estimate_noise)
    for (int g = 0; g < kRowGroups; ++g)
      if (ns.rows[g] && rt.chi2_p[g] <= opt.false_alarm)
        left.push_back(std::string(group_name[g]) + " residuals exceed the given noise (chi^2 = " + significant(ns.chi2[g], 4) +
                       " on " + significant(ns.dof[g], 4) + " degrees of freedom, p = " + significant(rt.chi2_p[g], 2) + ")");
  const bool structure_known = !gain_text.empty() || !opt.estimate_noise;
  rt.consistent = left.empty() && structure_known;
  if (rt.consistent)
    rt.text = "nothing is left to explain: every test mode has a partner" +
              (gain_text.empty() ? std::string(" and the residuals fit the given noise")
                                 : " and " + gain_text + ", above " + significant(opt.false_alarm, 2));
  else if (left.empty())
    rt.text = "cannot tell whether anything is left to explain: no candidate has a first-order screening";
  else {
    rt.text = "something is left to explain: ";
    for (std::size_t k = 0; k < left.size(); ++k) rt.text += (k ? "; " : "") + left[k];
  }
}

}  // namespace

void read_diagnosis_section(const Study& study, DiagnosisOptions& options) {
  const nlohmann::json& d = study.diagnosis;
  if (d.is_null()) return;
  const StudyReader rd(study.source);
  rd.keys(d, "diagnosis",
          {"kinds", "shortlist", "decision_margin", "hold_back", "mass_prior_fraction", "stiffness_prior_fraction",
           "miss_frequency_pct", "noise", "replicates", "false_alarm", "comment"});
  if (d.contains("kinds")) {
    const auto& k = d["kinds"];
    if (!k.is_array()) rd.fail("diagnosis.kinds", "expected an array of extension kinds, got " + StudyReader::shown(k));
    options.kinds.clear();
    for (std::size_t i = 0; i < k.size(); ++i)
      options.kinds.push_back(rd.text(k[i], "diagnosis.kinds[" + std::to_string(i) + "]"));
  }
  if (d.contains("shortlist")) options.shortlist = rd.integer(d["shortlist"], "diagnosis.shortlist");
  if (d.contains("decision_margin"))
    options.decision_margin = rd.number(d["decision_margin"], "diagnosis.decision_margin", false, true);
  if (d.contains("hold_back")) options.hold_back = rd.integer(d["hold_back"], "diagnosis.hold_back", 0);
  if (d.contains("mass_prior_fraction"))
    options.extension.mass_prior_fraction = rd.number(d["mass_prior_fraction"], "diagnosis.mass_prior_fraction", true);
  if (d.contains("stiffness_prior_fraction"))
    options.extension.stiffness_prior_fraction =
        rd.number(d["stiffness_prior_fraction"], "diagnosis.stiffness_prior_fraction", true);
  if (d.contains("miss_frequency_pct"))
    options.miss_frequency_pct = rd.number(d["miss_frequency_pct"], "diagnosis.miss_frequency_pct", true);
  if (d.contains("noise")) {
    options.calibration.estimate_noise = rd.choice(d["noise"], "diagnosis.noise", {"estimated", "given"}) == "estimated";
  }
  if (d.contains("replicates")) options.calibration.replicates = rd.integer(d["replicates"], "diagnosis.replicates");
  if (d.contains("false_alarm"))
    options.calibration.false_alarm = rd.number(d["false_alarm"], "diagnosis.false_alarm", true);
}

std::string deck_at(const std::string& deck_text, const std::string& name, const Eigen::VectorXd& x) {
  formats::Deck deck = formats::read_deck_text(deck_text, name);
  const std::unique_ptr<translators::FeModel> fe = translators::assemble_deck(deck, name);
  formats::BulkModel values = fe->values_at(x);
  const auto& params = fe->parameters();
  for (std::size_t j = 0; j < params.size(); ++j)
    for (auto& d : values.desvars)
      if (d.id == params[j].id) d.xinit = x(static_cast<Eigen::Index>(j));
  for (auto& [card, vals] : formats::write_bulk(values)) deck.set_values(card, std::move(vals));
  return formats::render_file(deck, 0);
}

namespace {

/// One diagnosis, one phase per member function (docs/diagnosis.md §1–5):
/// ordinary_update (with implied_noise), gather, nominal_likelihood,
/// prepare_screening, list_candidates, screen, calibrate, make_shortlist,
/// test_shortlist, keep_best_per_place, decide, second_effect,
/// summarise_decision. run() calls them in that order.
class Diagnoser {
 public:
  Diagnoser(const std::vector<ConfigurationInput>& configurations, const DiagnosisOptions& options)
      : m_options(options), m_engine(configurations, options), m_est(m_engine.setup().est) {}

  Diagnosis run() {
    ordinary_update();
    gather();
    nominal_likelihood();
    m_dg.ranking.push_back(m_param);
    // Phases 2 and 3 stop at an interruption; the decision is then made among the
    // hypotheses tested so far. `m_stage` says where, for the partial reason.
    try {
      if (m_dg.interrupted) throw Interrupted(m_dg.partial_reason);
      prepare_screening();
      list_candidates();
      screen();
      calibrate();
      make_shortlist();
      test_shortlist();
    } catch (const Interrupted& ex) {
      if (!m_dg.interrupted) {
        m_dg.interrupted = true;
        m_dg.partial_reason = std::string(ex.what()) + " " + m_stage;
      }
    }
    keep_best_per_place();
    decide();
    second_effect();
    summarise_decision();
    const Hypothesis& C = m_dg.cause >= 0 ? m_dg.ranking[static_cast<std::size_t>(m_dg.cause)] : m_dg.nominal;
    m_dg.updated_deck = deck_at(C.deck_text, m_est.front().name, C.estimate);
    if (!m_dg.interrupted) report(m_options.progress, "done", 1.0);
    return std::move(m_dg);
  }

 private:
  struct Shortlisted {
    const ext::ModelExtension* kind;
    ext::Candidate cand;
    double screening;
    double look;
    int column;  ///< its screening column (−1: not screened)
  };
  /// A candidate's rank within its kind: its first-order gain (`column` ≥ 0,
  /// known after calibrate()) or its priority / the misfit at its grids.
  struct Scored {
    double value;
    std::size_t i;
    int column;
  };

  const DiagnosisOptions& m_options;
  Engine m_engine;
  const std::vector<ConfigurationInput>& m_est;
  Diagnosis m_dg;
  std::vector<std::string> m_base_texts;
  EstimationProblem m_base;
  UpdateResult m_base_res;
  Hypothesis m_param;
  std::string m_stage;
  ext::ExtensionOptions m_eo;
  Screen m_screen;
  ModalSolution m_sol_star;
  std::vector<std::unique_ptr<ext::ModelExtension>> m_kinds;
  std::vector<std::vector<ext::Candidate>> m_cands;
  std::vector<std::vector<Scored>> m_scored;  ///< per kind
  std::vector<Eigen::VectorXd> m_columns;     ///< screening columns until calibrate() takes them
  std::vector<std::pair<std::size_t, std::size_t>> m_column_of;  ///< screening column -> (kind, candidate)
  std::optional<Screening> m_screening;       ///< the calibrated screening (the second effect screens again)
  std::vector<Shortlisted> m_shortlist;

  /// An estimate's cycles, reported as items of `phase` (also to the caller's own
  /// update_progress, which sees every solve of every estimate).
  Progress forward_cycles(const std::string& phase, long done, long total, const std::string& item, double f0,
                          double f1) const {
    const DiagnosisOptions& options = m_options;
    return [&options, phase, done, total, item, f0, f1](const ProgressEvent& e) {
      if (options.update_progress) options.update_progress(e);
      if (!options.progress) return;
      ProgressEvent out = e;
      out.fraction = e.fraction >= 0 ? f0 + (f1 - f0) * e.fraction : -1.0;
      if (total >= 0) {  // a count of hypotheses: the cycle is a detail of the one at hand
        out.phase = phase;
        out.done = done;
        out.total = total;
        out.total_is_bound = false;
        out.detail = item + ", cycle " + std::to_string(e.done) + (e.detail.empty() ? "" : ": " + e.detail);
      } else {
        out.phase = phase;
      }
      options.progress(out);
    };
  }

  /// Between the phases that stop with what they have: a report that is answered
  /// by Interrupted stops the diagnosis after this phase, with the update done.
  void between_phases(const std::string& phase, double fraction) {
    try {
      report(m_options.progress, phase, fraction);
    } catch (const Interrupted& ex) {
      if (m_dg.interrupted) return;
      m_dg.interrupted = true;
      m_dg.partial_reason = std::string(ex.what()) + " after the ordinary update: no extension tested";
    }
  }

  /// 1. The ordinary update of the deck's own parameters ("parameter"), at the
  /// noise the data imply (implied_noise).
  void ordinary_update() {
    report(m_options.progress, "ordinary update of the deck's parameters", 0.0);
    m_engine.set_update_progress(forward_cycles("ordinary update: cycle", -1, -1, "", 0.0, 0.1));
    for (const auto& c : m_est) m_base_texts.push_back(c.deck_text);
    m_param = m_engine.evaluate("parameter", m_base_texts, {}, &m_base);
    implied_noise();
    if (m_engine.interrupted()) {
      m_dg.interrupted = true;
      m_dg.partial_reason = m_engine.last().stopped + " during the ordinary update (after " +
                            std::to_string(m_engine.last().history.size()) + " cycle(s)): no extension tested";
    }
    m_base_res = m_engine.last();
    m_engine.warm_start(m_param.names, m_base_res.r);
    m_param.description = "the deck's own parameters re-estimated";
    m_param.location.text = "deck parameters";
  }

  /// 1b. The noise the data imply, from the ordinary update at the assumed σ;
  /// estimated, every estimate from here on uses it (the update is redone).
  void implied_noise() {
    Diagnosis& dg = m_dg;
    const DiagnosisOptions& options = m_options;
    dg.noise.estimated = options.calibration.estimate_noise;
    dg.noise.assumed_frequency_pct = dg.noise.frequency_pct = options.study.frequency_std_pct;
    dg.noise.assumed_shape_pct = dg.noise.shape_pct = assumed_shape_pct();
    dg.noise.std_from = m_base.measurement_std;
    for (const auto& c : m_base.configurations)
      for (const auto& f : c.std_from) dg.noise.identified = dg.noise.identified || f == "identification";
    if (m_engine.interrupted()) return;
    const UpdateResult& first = m_engine.last();
    const Screen s1 =
        prepare_screen(m_base.configurations.front(), m_base.prior, first.r, first.history.back().pairs, m_base.options);
    dg.noise.scale = estimate_noise(s1.lin, s1.lin.e, options.calibration.estimate_noise, options.calibration.min_dof);
    if (options.calibration.estimate_noise) {
      dg.noise.frequency_pct = dg.noise.assumed_frequency_pct * dg.noise.scale.scale[kFrequencyRows];
      dg.noise.shape_pct = dg.noise.assumed_shape_pct * dg.noise.scale.scale[kShapeRows];
    }
    try {
      if (options.calibration.estimate_noise && dg.noise.identified)
        report(options.progress,
               "ordinary update at the noise the data imply (the identification's sigma times " +
                   significant(dg.noise.scale.scale[kFrequencyRows], 3) + " for frequencies" +
                   (dg.noise.scale.rows[kShapeRows] > 0
                        ? ", times " + significant(dg.noise.scale.scale[kShapeRows], 3) + " for shapes)"
                        : "; no shapes measured)"),
               0.05);
      else if (options.calibration.estimate_noise)
        report(options.progress,
               "ordinary update at the noise the data imply (frequencies " + significant(dg.noise.frequency_pct, 3) +
                   (dg.noise.scale.rows[kShapeRows] > 0
                        ? " %, shapes " + significant(dg.noise.shape_pct, 3) + " % of the RMS component)"
                        : " %; no shapes measured)"),
               0.05);
    } catch (const Interrupted& ex) {  // the update at the assumed σ stands: a partial diagnosis
      dg.interrupted = true;
      dg.partial_reason = std::string(ex.what()) + " after the ordinary update: no extension tested";
    }
    if (options.calibration.estimate_noise && !dg.interrupted) {
      m_engine.warm_start(m_param.names, first.r);
      m_engine.set_noise(dg.noise.frequency_pct, dg.noise.shape_pct, dg.noise.scale.scale[kFrequencyRows],
                         dg.noise.scale.scale[kShapeRows]);
      const Fit before = m_param.before;  // the deck as given, not the warm start
      m_param = m_engine.evaluate("parameter", m_base_texts, {}, &m_base);
      m_param.before = before;
    }
  }

  /// 1. The evidence: what the updated model gets wrong.
  void gather() {
    between_phases("evidence: what the updated model gets wrong", 0.1);
    m_dg.evidence = gather_evidence(m_base.configurations.front(), m_base_res.r, [&] {
      std::vector<UpdatePair> v;
      for (const auto& p : m_base_res.history.back().pairs)
        if (p.config == 0) v.push_back(p);
      return v;
    }());
  }
  /// The nominal model (no estimate): likelihood at the prior mean, pairs of cycle 0.
  void nominal_likelihood() {
    between_phases("the deck as given: its likelihood", 0.1);
    Hypothesis& h = m_dg.nominal;
    h.kind = "none";
    h.description = "the deck as given";
    h.names = m_param.names;
    h.estimate = m_base.prior.mean;
    h.prior_mean = h.estimate;
    h.before = h.after = m_param.before;
    const bool shapes = m_base.options.shape_derivatives;
    double ll = 0;
    for (auto& c : m_base.configurations) {
      const ModalSolution sol = c.model->solve(m_base.prior.mean);
      std::vector<UpdatePair> pairs = pair_for_update(c.test, sol, m_base.options);
      ll += pair_loglik(c.test, sol, pairs, shapes);
      std::set<int> paired;
      for (const auto& p : pairs) paired.insert(p.test);
      for (std::size_t i = 0; i < c.test.size(); ++i)
        if (!paired.count(static_cast<int>(i))) h.miss_penalty += miss_loglik(c.test[i], m_options.miss_frequency_pct, shapes);
    }
    h.log_evidence = ll;
    h.score = ll + h.miss_penalty;
    h.deck_text = m_base_texts.front();
  }

  /// 2. What the screening needs at the updated parameters: the weighted
  /// residual and sensitivities, the analysis modes nearest the unexplained ones.
  void prepare_screening() {
    m_stage = "while listing the candidates";
    m_eo = m_options.extension;
    m_eo.unexplained_hz.clear();
    for (const auto& u : m_dg.evidence.unpaired_test) m_eo.unexplained_hz.push_back(u.frequency_hz);
    const auto& measured_hz = m_est.front().measured.frequency_hz;
    m_eo.lowest_test_hz = *std::min_element(measured_hz.begin(), measured_hz.end());
    m_eo.highest_test_hz = *std::max_element(measured_hz.begin(), measured_hz.end());
    if (!(m_eo.total_mass > 0)) m_eo.total_mass = ext::total_mass(*m_base.configurations.front().fe);
    report(m_options.progress, "screening: sensitivities of the " + std::to_string(m_base_res.history.back().pairs.size()) +
                                   " paired modes at the updated parameters",
           0.1);
    m_screen = prepare_screen(m_base.configurations.front(), m_base.prior, m_base_res.r, m_base_res.history.back().pairs,
                              m_base.options);
    m_sol_star = m_base.configurations.front().model->solve(m_base_res.r);
    m_eo.unexplained = unexplained_modes(m_base.configurations.front(), m_sol_star, m_dg.evidence);
    m_eo.updated = m_engine.warm();
  }

  /// 2. Every kind's candidates first, so that the screening is counted over all of them.
  void list_candidates() {
    const translators::FeModel& nominal = *m_base.configurations.front().fe;
    for (auto& kind : ext::standard_extensions(m_eo))
      if (m_options.kinds.empty() ||
          std::find(m_options.kinds.begin(), m_options.kinds.end(), kind->kind()) != m_options.kinds.end())
        m_kinds.push_back(std::move(kind));
    m_cands.assign(m_kinds.size(), {});
    for (std::size_t q = 0; q < m_kinds.size(); ++q) {
      report(m_options.progress, "listing candidates", static_cast<long>(q), static_cast<long>(m_kinds.size()),
             m_kinds[q]->kind(), 0.1);
      try {
        m_cands[q] = m_kinds[q]->candidates(nominal);
      } catch (const formats::InputError& ex) {  // a deck this kind cannot extend (e.g. cards in an INCLUDE)
        m_dg.notes.push_back(m_kinds[q]->kind() + ": no candidates (" + ex.what() + ")");
      }
    }
  }

  /// 2. First-order screening of each candidate: a screening column for the
  /// kinds that add no DOF, the others ranked by their priority or the misfit
  /// at their grids.
  void screen() {
    const translators::FeModel& nominal = *m_base.configurations.front().fe;
    std::map<std::int64_t, double> grid_weight;
    for (const auto& g : m_dg.evidence.grid_misfit) grid_weight[g.grid] += g.share;
    for (const auto& u : m_dg.evidence.unpaired_test)
      for (const auto& g : u.moves) grid_weight[g.grid] += g.share;
    long total = 0, screened_so_far = 0;
    for (std::size_t q = 0; q < m_kinds.size(); ++q) total += static_cast<long>(m_cands[q].size());
    m_stage = "while screening the candidates";

    m_scored.assign(m_kinds.size(), {});
    for (std::size_t q = 0; q < m_kinds.size(); ++q) {
      const auto& kind = m_kinds[q];
      for (std::size_t i = 0; i < m_cands[q].size(); ++i, ++screened_so_far) {
        report(m_options.progress, "screening candidates", screened_so_far, total, kind->kind(),
               0.1 + 0.05 * static_cast<double>(screened_so_far) / static_cast<double>(total));
        auto deriv = kind->screening(nominal, m_cands[q][i]);
        if (deriv) {
          m_columns.push_back(screen_column(m_screen, *m_base.configurations.front().model, m_sol_star.eigenvalues, m_base.configurations.front().sensors,
                                            deriv->dK[0], deriv->dM[0], deriv->prior_std.at(0)));
          m_column_of.push_back({q, i});
          m_scored[q].push_back({0.0, i, static_cast<int>(m_columns.size()) - 1});
        } else if (!std::isnan(m_cands[q][i].priority)) {
          m_scored[q].push_back({m_cands[q][i].priority, i, -1});
        } else {
          double w = 0;
          for (auto g : m_cands[q][i].location.grids)
            if (auto it = grid_weight.find(g); it != grid_weight.end()) w += it->second;
          m_scored[q].push_back({w, i, -1});
        }
      }
    }
    report(m_options.progress, "screening candidates", total, total, "", 0.15);
  }

  /// 2b. Calibration: the screening's gains with the noise re-estimated, replayed
  /// on data simulated from the ordinary update's model; the residual test.
  void calibrate() {
    m_stage = "while calibrating the screening";
    Eigen::MatrixXd U(m_screen.lin.e.size(), static_cast<Eigen::Index>(m_columns.size()));
    for (std::size_t k = 0; k < m_columns.size(); ++k) U.col(static_cast<Eigen::Index>(k)) = m_columns[k];
    m_columns.clear();
    m_screening.emplace(m_screen.lin, std::move(U), m_options.calibration);
    if (m_screening->candidate_count() > 0)
      report(m_options.progress, "calibrating: " + std::to_string(m_options.calibration.replicates) +
                                     " replicates of the screening on simulated noise",
             0.15);
    m_screening->bootstrap();
    for (auto& v : m_scored)
      for (auto& x : v)
        if (x.column >= 0) x.value = m_screening->gains()(x.column);
    residual_test(m_dg, m_param, *m_screening, m_options.calibration, [&](int column) {
      const auto& [q, i] = m_column_of[static_cast<std::size_t>(column)];
      return m_kinds[q]->kind() + " at " + m_cands[q][i].location.text;
    });
  }

  /// 2. The shortlist: each kind's best candidates by gain (or rank).
  void make_shortlist() {
    const auto a_size = m_base.configurations.front().fe->reduction().a_to_g.size();
    for (std::size_t q = 0; q < m_kinds.size(); ++q) {
      const auto& kind = m_kinds[q];
      if (m_cands[q].empty()) continue;
      std::set<std::string> places;
      for (const auto& c : m_cands[q]) places.insert(c.location.text);
      m_dg.searched[kind->kind()] = static_cast<int>(places.size());
      const double look = std::log(static_cast<double>(places.size()));
      auto& sq = m_scored[q];
      const bool screened = std::any_of(sq.begin(), sq.end(), [](const Scored& x) { return x.column >= 0; });
      std::stable_sort(sq.begin(), sq.end(), [](const Scored& a, const Scored& b) { return a.value > b.value; });
      std::size_t n = static_cast<std::size_t>(m_options.shortlist);
      if (!screened && m_cands[q].size() <= static_cast<std::size_t>(m_options.exhaustive_limit) && a_size < 3000)
        n = m_cands[q].size();
      else if (!screened) n = static_cast<std::size_t>(2 * m_options.shortlist);
      // Kinds with several candidates per place (start values): keep all starts of the chosen places.
      for (std::size_t k = 0; k < std::min(n, sq.size()); ++k)
        m_shortlist.push_back(
            {kind.get(), m_cands[q][sq[k].i], sq[k].column >= 0 ? sq[k].value : 0.0, look, sq[k].column});
    }
  }

  /// 3. Exact re-estimation of the shortlist.
  void test_shortlist() {
    const translators::FeModel& nominal = *m_base.configurations.front().fe;
    const auto n_short = static_cast<long>(m_shortlist.size());
    for (std::size_t k = 0; k < m_shortlist.size(); ++k) {
      const auto& s = m_shortlist[k];
      const std::string item = s.kind->kind() + " at " + s.cand.location.text;
      const double f0 = 0.15 + 0.8 * static_cast<double>(k) / static_cast<double>(n_short),
                   f1 = 0.15 + 0.8 * static_cast<double>(k + 1) / static_cast<double>(n_short);
      m_stage = "while testing candidates (" + std::to_string(k) + " of " + std::to_string(n_short) + " tested)";
      report(m_options.progress, "testing candidates", static_cast<long>(k), n_short, item, f0);
      m_engine.set_update_progress(forward_cycles("testing candidates", static_cast<long>(k), n_short, item, f0, f1));
      try {
        std::vector<std::string> texts;
        std::vector<ext::NewParameter> added;
        std::string description;
        for (const auto& c : m_est) {
          ext::ExtendedDeck xd = s.kind->apply(c.deck_text, c.name, nominal, s.cand);
          texts.push_back(xd.text);
          added = xd.parameters;
          description = xd.description;
        }
        Hypothesis h = m_engine.evaluate(s.kind->kind(), texts, added);
        if (m_engine.interrupted()) throw Interrupted(m_engine.last().stopped);  // half-estimated: not ranked
        h.location = s.cand.location;
        h.description = description;
        h.screening = s.screening;
        h.screening_column = s.column;
        if (s.column >= 0) {
          h.exceed = m_screening->exceedances(s.screening);
          h.false_alarm = m_screening->false_alarm(s.screening);
          h.held_out = m_screening->held_out(s.column);
          h.held_out_known = true;
        }
        h.look_elsewhere = s.look;
        h.score -= h.look_elsewhere;
        m_dg.ranking.push_back(std::move(h));
      } catch (const formats::InputError& ex) {  // the extended deck cannot be built or solved
        m_dg.notes.push_back(item + ": not tested (" + ex.what() + ")");
      } catch (const formats::NumericalError& ex) {  // its estimate failed
        m_dg.notes.push_back(item + ": not tested (" + ex.what() + ")");
      }
    }
    if (n_short > 0) report(m_options.progress, "testing candidates", n_short, n_short, "", 0.95);
  }

  /// Same place tried from several starts: keep its best.
  void keep_best_per_place() {
    std::stable_sort(m_dg.ranking.begin(), m_dg.ranking.end(),
                     [](const Hypothesis& a, const Hypothesis& b) { return a.score > b.score; });
    std::set<std::string> seen;
    std::vector<Hypothesis> unique;
    for (auto& h : m_dg.ranking)
      if (seen.insert(h.kind + "|" + h.location.text).second) unique.push_back(std::move(h));
    m_dg.ranking = std::move(unique);
  }

  /// The noise the comparisons of fits use: the estimates' σ.
  /// The assumed shape σ in % of the RMS component: the study's, or its
  /// absolute σ on the unit shape of the first configuration's sensors
  /// (deck_study.hpp: σ = (pct/100)/√n_s).
  double assumed_shape_pct() const {
    const Study& st = m_options.study;
    if (!st.shape_std) return st.shape_std_pct;
    const auto ns = static_cast<double>(m_base.configurations.front().dofs.size());
    return *st.shape_std * 100.0 * std::sqrt(std::max(ns, 1.0));
  }

  FitNoise fit_noise() const {
    FitNoise n;
    n.frequency_pct = m_dg.noise.frequency_pct;
    const auto ns = static_cast<double>(m_base.configurations.front().dofs.size());  // the sensors the shapes have
    n.shape_unit = m_dg.noise.shape_pct / 100.0 / std::sqrt(std::max(ns, 1.0));
    n.alpha = m_options.calibration.false_alarm;
    for (std::size_t c = 0; c < m_base.configurations.size(); ++c) {
      const auto& test = m_base.configurations[c].test;
      for (std::size_t t = 0; t < test.size(); ++t) {
        const FittedRows fitted = fitted_rows(test[t], m_base.options);
        n.rows[{static_cast<int>(c), static_cast<int>(t)}] =
            (fitted.frequency ? 1 : 0) + (fitted.shape ? static_cast<int>(test[t].shape.size()) : 0);
      }
    }
    // Modes with the identification's σ: those the estimates used (scaled by
    // the estimated noise when it is estimated: m_base is the re-run update's).
    for (std::size_t c = 0; c < m_base.configurations.size(); ++c) {
      const auto& pc = m_base.configurations[c];
      for (std::size_t t = 0; t < pc.test.size() && t < pc.std_from.size(); ++t)
        if (pc.std_from[t] == "identification")
          n.per_mode[{static_cast<int>(c), static_cast<int>(t)}] = {
              100.0 * pc.test[t].frequency_std_hz / pc.test[t].frequency_hz,
              pc.test[t].shape_std > 0 ? pc.test[t].shape_std : n.shape_unit};
    }
    return n;
  }

  /// 4. Every extension's verdict and the cause (diagnosis.hpp).
  void decide() {
    Diagnosis& dg = m_dg;
    const DiagnosisOptions& options = m_options;
    const FitNoise noise = fit_noise();
    const double alpha = options.calibration.false_alarm;
    int ip = -1, ie = -1;
    for (std::size_t i = 0; i < dg.ranking.size(); ++i) {
      if (dg.ranking[i].kind == "parameter" && ip < 0) ip = static_cast<int>(i);
      if (dg.ranking[i].kind != "parameter" && ie < 0) ie = static_cast<int>(i);
    }
    const Hypothesis& P = dg.ranking[static_cast<std::size_t>(ip)];
    int eligible = -1;
    for (std::size_t i = 0; i < dg.ranking.size(); ++i) {
      Hypothesis& h = dg.ranking[i];
      if (h.kind == "parameter") continue;
      h.verdict = why_not_named(h, P, dg.residual, alpha, options.decision_margin, noise);
      if (h.verdict.empty()) {
        h.verdict = eligible < 0 ? "named" : "passes every test, but scores below the cause";
        if (eligible < 0) eligible = static_cast<int>(i);
      }
    }
    if (eligible >= 0) {
      dg.cause = eligible;
      dg.margin = dg.ranking[static_cast<std::size_t>(eligible)].score - P.score;
    } else if (P.score - dg.nominal.score >= options.decision_margin) {
      dg.cause = ip;
      dg.margin = P.score - std::max(dg.nominal.score, ie >= 0 ? dg.ranking[static_cast<std::size_t>(ie)].score : -INFINITY);
    } else {
      dg.cause = -1;
      dg.margin = dg.nominal.score - P.score;
    }
  }

  /// 5. After a screened cause, the screening again with the cause's model
  /// (linearised at its estimate) as the null; both are named when the best
  /// other candidate passes the same tests and the pair's exact estimate beats
  /// the cause alone.
  void second_effect() {
    Diagnosis& dg = m_dg;
    const DiagnosisOptions& options = m_options;
    Engine& engine = m_engine;
    const std::vector<ConfigurationInput>& est = m_est;
    const FitNoise noise = fit_noise();
    const double alpha = options.calibration.false_alarm;
    const auto& kinds = m_kinds;
    const auto& cands = m_cands;
    const auto& column_of = m_column_of;
    const translators::FeModel* nominal = m_base.configurations.front().fe.get();
    if (dg.cause >= 0 && !dg.interrupted && m_screening &&
        dg.ranking[static_cast<std::size_t>(dg.cause)].screening_column >= 0) {
      try {
        const Hypothesis first = dg.ranking[static_cast<std::size_t>(dg.cause)];
        const int c1 = first.screening_column;
        // The cause's model at its estimate, linearised there, is the null of the
        // second search (the cause's parameter is one of its own); every other
        // screened candidate gets its column at that model.
        report(options.progress, "a second effect: screening at the cause's model", 0.95);
        EstimationProblem ep1 = engine.problem(first.deck_text, first.added);
        PreparedConfiguration& pb1 = ep1.configurations.front();
        std::vector<UpdatePair> pairs1;
        for (const auto& p : first.pairs)
          if (p.config == 0) pairs1.push_back(p);
        const Screen sc1 = prepare_screen(pb1, ep1.prior, first.estimate, pairs1, ep1.options);
        const ModalSolution sol1 = pb1.model->solve(first.estimate);
        std::vector<int> kept;
        std::vector<Eigen::VectorXd> cols;
        for (std::size_t c = 0; c < column_of.size(); ++c) {
          const auto& [q, i] = column_of[c];
          if (cands[q][i].location.text == first.location.text) continue;
          auto deriv = kinds[q]->screening(*nominal, cands[q][i]);
          cols.push_back(screen_column(sc1, *pb1.model, sol1.eigenvalues, pb1.sensors, deriv->dK[0], deriv->dM[0],
                                       deriv->prior_std.at(0)));
          kept.push_back(static_cast<int>(c));
        }
        Eigen::MatrixXd U1(sc1.lin.e.size(), static_cast<Eigen::Index>(cols.size()));
        for (std::size_t k = 0; k < cols.size(); ++k) U1.col(static_cast<Eigen::Index>(k)) = cols[k];
        cols.clear();
        report(options.progress, "a second effect: " + std::to_string(options.calibration.replicates) +
                                     " replicates of the screening on simulated noise",
               0.96);
        Screening ext_screen(sc1.lin, std::move(U1), options.calibration);
        ext_screen.bootstrap();
        dg.noise.frequency_pct_cause = dg.noise.frequency_pct * ext_screen.noise().scale[kFrequencyRows];
        dg.noise.shape_pct_cause = dg.noise.shape_pct * ext_screen.noise().scale[kShapeRows];
        SecondEffect& se = dg.second;
        se.tested = true;
        int best = -1;
        for (int j = 0; j < ext_screen.candidate_count(); ++j) {
          if (best < 0 || ext_screen.gains()(j) > ext_screen.gains()(best)) best = j;
        }
        if (best < 0) {
          se.text = "no other candidate to test";
        } else {
          const auto& [q2, i2] = column_of[static_cast<std::size_t>(kept[static_cast<std::size_t>(best)])];
          const auto& [q1, i1] = column_of[static_cast<std::size_t>(c1)];
          se.kind = kinds[q2]->kind();
          se.location = cands[q2][i2].location;
          se.gain = ext_screen.gains()(best);
          se.false_alarm = ext_screen.false_alarm(se.gain);
          se.held_out = ext_screen.held_out(best);
          const std::string what = se.kind + " at " + se.location.text + ": first-order gain " + fixed(se.gain, 2) +
                                   " nats, false-alarm p = " + significant(se.false_alarm, 2) + ", held-out gain " +
                                   significant(se.held_out.total(), 3);
          if (se.false_alarm > alpha) {
            se.text = "none: the best, " + what + " (above " + significant(alpha, 2) + ")";
          } else if (!(se.held_out.total() > 0)) {
            se.text = "none: the best, " + what + ", does not predict held-out modes better";
          } else {
            std::vector<std::string> texts;
            std::vector<ext::NewParameter> added;
            for (const auto& c : est) {
              const ext::ExtendedDeck x1 = kinds[q1]->apply(c.deck_text, c.name, *nominal, cands[q1][i1]);
              const ext::ExtendedDeck x2 = kinds[q2]->apply(x1.text, c.name, *nominal, cands[q2][i2]);
              texts.push_back(x2.text);
              added = x1.parameters;
              added.insert(added.end(), x2.parameters.begin(), x2.parameters.end());
            }
            engine.set_update_progress(
                forward_cycles("testing two effects", 0, 1, "the cause and a second effect", 0.97, 1.0));
            engine.warm_start(first.names, first.estimate);  // the first cause starts at its estimate
            Hypothesis h = engine.evaluate(first.kind + " + " + se.kind, texts, added);
            if (engine.interrupted()) throw Interrupted(engine.last().stopped);
            h.location = first.location;
            h.location.text = first.location.text + " and " + se.location.text;
            for (auto g : se.location.grids) h.location.grids.push_back(g);
            for (auto e : se.location.elements) h.location.elements.push_back(e);
            for (auto pr : se.location.properties) h.location.properties.push_back(pr);
            h.description = first.description + "; " + se.kind + " at " + se.location.text;
            h.look_elsewhere = first.look_elsewhere + std::log(static_cast<double>(std::max(1, dg.searched[se.kind])));
            h.score -= h.look_elsewhere;
            h.screening = se.gain;
            h.false_alarm = se.false_alarm;
            h.exceed = ext_screen.exceedances(se.gain);
            h.held_out = se.held_out;
            h.held_out_known = true;
            std::string no;
            if (h.score - first.score < options.decision_margin)
              no = fixed(h.score - first.score, 1) + " nats above the first cause alone, below the " +
                   fixed(options.decision_margin, 1) + "-nat margin";
            else
              no = worse_fit(h, first, noise);
            if (no.empty()) {
              se.named = true;
              se.text = "named: " + what;
              h.verdict = "named (two effects)";
              for (const auto& x : dg.ranking)
                if (x.kind == "parameter") dg.margin = h.score - x.score;
              dg.ranking.insert(dg.ranking.begin(), std::move(h));
              dg.cause = 0;
            } else {
              se.text = "none: " + what + ", but the model with both " + no;
              h.verdict = no;
              dg.ranking.push_back(std::move(h));  // at the end: the cause's index holds
            }
          }
        }
      } catch (const Interrupted& ex) {
        dg.interrupted = true;
        dg.partial_reason = std::string(ex.what()) + " while testing a second effect";
      } catch (const formats::InputError& ex) {
        dg.second.text = "not tested (" + std::string(ex.what()) + ")";
      } catch (const formats::NumericalError& ex) {
        dg.second.text = "not tested (" + std::string(ex.what()) + ")";
      }
    }
  }

  /// The decision in a sentence, with its figures (dg.cause_kind, dg.summary).
  void summarise_decision() {
    Diagnosis& dg = m_dg;
    const DiagnosisOptions& options = m_options;
    const Hypothesis& C = dg.cause >= 0 ? dg.ranking[static_cast<std::size_t>(dg.cause)] : dg.nominal;
    const Hypothesis* param = nullptr;
    for (const auto& h : dg.ranking)
      if (h.kind == "parameter") param = &h;
    const Hypothesis& P = *param;
    dg.cause_kind = C.kind;
    // The best extension that was not named, and why (for "parameter" and "none").
    std::string best_other = "none tested";
    for (const auto& h : dg.ranking)
      if (h.kind != "parameter") {
        best_other = h.kind + " at " + h.location.text + ": " + h.verdict;
        break;
      }
    const std::string left = dg.residual.consistent ? "; " + dg.residual.text : "";
    if (C.kind == "none") {
      dg.summary = "no change explains the test better than the deck as given (the update gains " +
                   fixed(P.score - dg.nominal.score, 1) + " nats, below the " + fixed(options.decision_margin, 1) +
                   "-nat margin)" + left;
    } else if (C.kind == "parameter") {
      dg.summary = "the deck's parameters were wrong" +
                   (dg.residual.consistent ? left : "; no model-form extension passes (best: " + best_other + ")");
    } else {
      std::string values;
      const auto p0 = C.names.size() - C.added.size();
      for (std::size_t j = 0; j < C.added.size(); ++j) {
        values += (j ? ", " : "") + C.added[j].meaning + " = " + significant(C.estimate(static_cast<Eigen::Index>(p0 + j)), 5) +
                  " +- " + significant(C.posterior_std(static_cast<Eigen::Index>(p0 + j)), 2);
      }
      dg.summary = C.kind + " at " + C.location.text + " (" + values + "), " + fixed(dg.margin, 1) +
                   " nats above the ordinary update";
      if (!std::isnan(C.false_alarm))
        dg.summary += ", false-alarm probability " + significant(C.false_alarm, 2) + " (" + std::to_string(C.exceed) +
                      " of " + std::to_string(dg.residual.replicates) + " noise replicates reach its first-order gain of " +
                      fixed(C.screening, 2) + " nats), held-out gain " + significant(C.held_out.total(), 3);
    }
  }
};

}  // namespace

namespace {
/// "use at least N": the replicates a false-alarm target p needs, 1/p − 1, or
/// why no count will do (replicates is an int).
std::string replicates_needed(double p) {
  const double n = std::ceil(1.0 / p - 1.0 - 1e-9);
  if (n > static_cast<double>(std::numeric_limits<int>::max()))
    return "no replicate count can (it would need " + significant(n, 3) + ")";
  return "use at least " + std::to_string(static_cast<long long>(n));
}
}  // namespace

Diagnosis diagnose(const std::vector<ConfigurationInput>& configurations, const DiagnosisOptions& options) {
  const CalibrationOptions& cal = options.calibration;
  if (!(cal.false_alarm > 0 && cal.false_alarm < 1))
    throw formats::InputError("diagnose: the false-alarm target must lie between 0 and 1, got " + significant(cal.false_alarm, 3));
  if (smallest_p(cal.replicates) > cal.false_alarm)
    throw formats::InputError("diagnose: " + std::to_string(cal.replicates) +
                              " bootstrap replicates cannot show a false-alarm probability of " + significant(cal.false_alarm, 3) +
                              " or less (the smallest is 1/(replicates + 1)); " + replicates_needed(cal.false_alarm));
  return Diagnoser(configurations, options).run();
}

}  // namespace ssid::estimator::diagnosis
