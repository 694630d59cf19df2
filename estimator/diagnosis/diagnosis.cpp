#include "estimator/diagnosis/diagnosis.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>

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
  Eigen::VectorXd e;   ///< weighted residual
  Eigen::MatrixXd W;   ///< weighted, prior-scaled sensitivities of the existing parameters
  Eigen::MatrixXd Hinv_Wt;  ///< H⁻¹ Wᵀ
  struct Row { int fem; double f; Eigen::VectorXd u; double norm; double sigma_f, sigma_s; bool use_f, use_s; };
  std::vector<Row> rows;
};

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
    row.use_f = t.use_frequency && t.frequency_std_hz > 0;
    row.use_s = opt.shape_derivatives && t.use_shape && t.shape.size() && t.shape_std > 0;
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
    }
    if (row.use_s) {
      Eigen::VectorXd z = t.shape.normalized();
      if (z.dot(row.u) < 0) z = -z;
      const Eigen::MatrixXd du = (s.d_sensor_shape - row.u * (row.u.transpose() * s.d_sensor_shape)) / row.norm;
      for (Eigen::Index k = 0; k < z.size(); ++k) {
        e.push_back((z(k) - row.u(k)) / row.sigma_s);
        w.push_back(du.row(k).transpose().cwiseProduct(d) / row.sigma_s);
      }
    }
  }
  const auto m = static_cast<Eigen::Index>(e.size());
  sc.e = Eigen::Map<Eigen::VectorXd>(e.data(), m);
  sc.W.resize(m, d.size());
  for (Eigen::Index k = 0; k < m; ++k) sc.W.row(k) = w[static_cast<std::size_t>(k)].transpose();
  const Eigen::MatrixXd H = Eigen::MatrixXd::Identity(d.size(), d.size()) + sc.W.transpose() * sc.W;
  sc.Hinv_Wt = H.ldlt().solve(sc.W.transpose());
  return sc;
}

/// ΔlogZ of one new parameter from its ∂K, ∂M (first order).
double screen_score(const Screen& sc, const OperatorModel& model, const Eigen::VectorXd& lambdas, const SparseMatrix& C,
                    const SparseMatrix& dK, const SparseMatrix& dM, double prior_std) {
  const Eigen::MatrixXd& Phi = model.modes();
  std::vector<double> t;
  t.reserve(static_cast<std::size_t>(sc.e.size()));
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
  const Eigen::Map<const Eigen::VectorXd> tv(t.data(), static_cast<Eigen::Index>(t.size()));
  const Eigen::VectorXd Wt = sc.W.transpose() * tv;
  const double s = tv.squaredNorm() - Wt.dot(sc.Hinv_Wt * tv);
  const double g = tv.dot(sc.e);
  const double v = prior_std * prior_std;
  return 0.5 * g * g / (std::max(s, 0.0) + 1.0 / v) - 0.5 * std::log1p(v * std::max(s, 0.0));
}

/// For each unexplained test mode (the evidence's order), the g-set shape of
/// the analysis mode of `sol` (the model's last solve) most like it at the
/// sensors (highest MAC within ±30 % in frequency; any frequency when none).
std::vector<Eigen::VectorXd> neighbours_of_unexplained(PreparedConfiguration& pb, const ModalSolution& sol, const Evidence& ev) {
  std::vector<Eigen::VectorXd> out;
  const Eigen::MatrixXd& phi = pb.model->modes();
  for (const auto& u : ev.unpaired_test) {
    const MeasuredMode* t = nullptr;
    for (const auto& m : pb.test)
      if (m.id == u.id) t = &m;
    if (!t || !t->shape.size() || phi.cols() == 0) {
      out.emplace_back();
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
    out.push_back(best >= 0 ? Eigen::VectorXd(pb.fe->expand(phi.col(best))) : Eigen::VectorXd());
  }
  return out;
}

}  // namespace

void read_diagnosis_section(const Study& study, DiagnosisOptions& options) {
  const nlohmann::json& d = study.diagnosis;
  if (d.is_null()) return;
  const StudyReader rd(study.source);
  rd.keys(d, "diagnosis",
          {"kinds", "shortlist", "decision_margin", "hold_back", "mass_prior_fraction", "stiffness_prior_fraction",
           "miss_frequency_pct", "comment"});
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

/// One diagnosis, one phase per member function (docs/diagnosis.md §1–4):
/// ordinary_update, gather, nominal_likelihood, prepare_screening,
/// list_candidates, screen, test_shortlist, keep_best_per_place, decide.
/// run() calls them in that order.
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
      test_shortlist();
    } catch (const Interrupted& ex) {
      if (!m_dg.interrupted) {
        m_dg.interrupted = true;
        m_dg.partial_reason = std::string(ex.what()) + " " + m_stage;
      }
    }
    keep_best_per_place();
    decide();
    if (!m_dg.interrupted) report(m_options.progress, "done", 1.0);
    return std::move(m_dg);
  }

 private:
  struct Shortlisted {
    const ext::ModelExtension* kind;
    ext::Candidate cand;
    double screening;
    double look;
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

  /// 1. The ordinary update of the deck's own parameters ("parameter").
  void ordinary_update() {
    report(m_options.progress, "ordinary update of the deck's parameters", 0.0);
    m_engine.set_update_progress(forward_cycles("ordinary update: cycle", -1, -1, "", 0.0, 0.1));
    for (const auto& c : m_est) m_base_texts.push_back(c.deck_text);
    m_param = m_engine.evaluate("parameter", m_base_texts, {}, &m_base);
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
    m_eo.unexplained_neighbours = neighbours_of_unexplained(m_base.configurations.front(), m_sol_star, m_dg.evidence);
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

  /// 2. First-order screening of each candidate (kinds that add no DOF), the
  /// others ranked by their priority or the misfit at their grids; the shortlist.
  void screen() {
    const translators::FeModel& nominal = *m_base.configurations.front().fe;
    const Screen& sc = m_screen;
    const ModalSolution& sol_star = m_sol_star;
    std::map<std::int64_t, double> grid_weight;
    for (const auto& g : m_dg.evidence.grid_misfit) grid_weight[g.grid] += g.share;
    for (const auto& u : m_dg.evidence.unpaired_test)
      for (const auto& g : u.moves) grid_weight[g.grid] += g.share;
    const auto a_size = nominal.reduction().a_to_g.size();
    long total = 0, screened_so_far = 0;
    for (std::size_t q = 0; q < m_kinds.size(); ++q) total += static_cast<long>(m_cands[q].size());
    m_stage = "while screening the candidates";

    for (std::size_t q = 0; q < m_kinds.size(); ++q) {
      const auto& kind = m_kinds[q];
      if (m_cands[q].empty()) continue;
      std::set<std::string> places;
      for (const auto& c : m_cands[q]) places.insert(c.location.text);
      m_dg.searched[kind->kind()] = static_cast<int>(places.size());
      const double look = std::log(static_cast<double>(places.size()));
      std::vector<std::pair<double, std::size_t>> scored;
      bool screened = false;
      for (std::size_t i = 0; i < m_cands[q].size(); ++i, ++screened_so_far) {
        report(m_options.progress, "screening candidates", screened_so_far, total, kind->kind(),
               0.1 + 0.05 * static_cast<double>(screened_so_far) / static_cast<double>(total));
        auto deriv = kind->screening(nominal, m_cands[q][i]);
        if (deriv) {
          screened = true;
          const double sd = deriv->prior_std.at(0);
          scored.push_back({screen_score(sc, *m_base.configurations.front().model, sol_star.eigenvalues, m_base.configurations.front().sensors,
                                         deriv->dK[0], deriv->dM[0], sd),
                            i});
        } else if (!std::isnan(m_cands[q][i].priority)) {
          scored.push_back({m_cands[q][i].priority, i});
        } else {
          double w = 0;
          for (auto g : m_cands[q][i].location.grids)
            if (auto it = grid_weight.find(g); it != grid_weight.end()) w += it->second;
          scored.push_back({w, i});
        }
      }
      std::stable_sort(scored.begin(), scored.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
      std::size_t n = static_cast<std::size_t>(m_options.shortlist);
      if (!screened && m_cands[q].size() <= static_cast<std::size_t>(m_options.exhaustive_limit) && a_size < 3000)
        n = m_cands[q].size();
      else if (!screened) n = static_cast<std::size_t>(2 * m_options.shortlist);
      // Kinds with several candidates per place (start values): keep all starts of the chosen places.
      for (std::size_t k = 0; k < std::min(n, scored.size()); ++k)
        m_shortlist.push_back({kind.get(), m_cands[q][scored[k].second], screened ? scored[k].first : 0.0, look});
    }
    report(m_options.progress, "screening candidates", total, total, "", 0.15);
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

  /// 4. Decision.
  void decide() {
    Diagnosis& dg = m_dg;
    const DiagnosisOptions& options = m_options;
    int ip = -1, ie = -1;
    for (std::size_t i = 0; i < dg.ranking.size(); ++i) {
      if (dg.ranking[i].kind == "parameter" && ip < 0) ip = static_cast<int>(i);
      if (dg.ranking[i].kind != "parameter" && ie < 0) ie = static_cast<int>(i);
    }
    const Hypothesis& P = dg.ranking[static_cast<std::size_t>(ip)];
    if (ie >= 0 && dg.ranking[static_cast<std::size_t>(ie)].score - P.score >= options.decision_margin) {
      dg.cause = ie;
      dg.margin = dg.ranking[static_cast<std::size_t>(ie)].score - P.score;
    } else if (P.score - dg.nominal.score >= options.decision_margin) {
      dg.cause = ip;
      dg.margin = P.score - std::max(dg.nominal.score, ie >= 0 ? dg.ranking[static_cast<std::size_t>(ie)].score : -INFINITY);
    } else {
      dg.cause = -1;
      dg.margin = dg.nominal.score - P.score;
    }
    const Hypothesis& C = dg.cause >= 0 ? dg.ranking[static_cast<std::size_t>(dg.cause)] : dg.nominal;
    dg.cause_kind = C.kind;
    if (C.kind == "none") {
      dg.summary = "no change explains the test better than the deck as given (the update gains " +
                   fixed(P.score - dg.nominal.score, 1) + " nats, below the " + fixed(options.decision_margin, 1) +
                   "-nat margin)";
    } else if (C.kind == "parameter") {
      dg.summary = "the deck's parameters were wrong; no model-form extension beats the ordinary update (best: " +
                   (ie >= 0 ? dg.ranking[static_cast<std::size_t>(ie)].kind + " at " +
                                  dg.ranking[static_cast<std::size_t>(ie)].location.text + ", " +
                                  fixed(dg.ranking[static_cast<std::size_t>(ie)].score - P.score, 1) + " nats"
                            : std::string("none tested")) +
                   ")";
    } else {
      std::string values;
      const auto p0 = C.names.size() - C.added.size();
      for (std::size_t j = 0; j < C.added.size(); ++j) {
        values += (j ? ", " : "") + C.added[j].meaning + " = " +
                  significant(C.estimate(static_cast<Eigen::Index>(p0 + j)), 5) + " +- " +
                  significant(C.posterior_std(static_cast<Eigen::Index>(p0 + j)), 2);
      }
      dg.summary = C.kind + " at " + C.location.text + " (" + values + "), " + fixed(dg.margin, 1) +
                   " nats above the ordinary update";
    }
    dg.updated_deck = deck_at(C.deck_text, m_est.front().name, C.estimate);
  }
};

}  // namespace

Diagnosis diagnose(const std::vector<ConfigurationInput>& configurations, const DiagnosisOptions& options) {
  return Diagnoser(configurations, options).run();
}

}  // namespace ssid::estimator::diagnosis
