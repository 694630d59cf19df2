/// \file cmd_diagnose.cpp
/// `ssid diagnose DECK MEASURED.unv [--study FILE] [--json FILE] [-o DIR]`:
/// what the model gets wrong, which model-form extension explains it, the
/// gain, and the extended, updated deck (docs/diagnosis.md).
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <set>
#include <sstream>

#include "cli/cli_util.hpp"
#include "cli/exit_codes.hpp"
#include "cli/progress_lines.hpp"
#include "cli/report/frf_comparison.hpp"
#include "cli/report/report_data.hpp"
#include "estimator/diagnosis/diagnosis.hpp"
#include "estimator/reporting/number_text.hpp"
#include "estimator/study/deck_study.hpp"
#include "formats/parse_error.hpp"
#include "formats/uff.hpp"

namespace ssid::cli {

namespace {

namespace dx = estimator::diagnosis;

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw formats::InputError(path + ": cannot open");
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// One configuration as the diagnosis takes it: the deck's text and the
/// measured data read as `ssid estimate` reads them (deck_study's read_measured).
dx::ConfigurationInput load_configuration(const estimator::ConfigurationSource& src) {
  dx::ConfigurationInput c;
  c.name = src.deck;
  c.deck_text = read_text(src.deck);
  c.measured = src.data.modes;
  c.nodes = src.data.nodes;
  c.measured_name = src.measured;
  c.configuration = src.name;
  for (const auto& n : src.data.notes) std::cerr << "warning: " << n << "\n";
  return c;
}

nlohmann::json location_json(const estimator::diagnosis::hypotheses::Location& l) {
  return {{"grids", l.grids}, {"elements", l.elements}, {"properties", l.properties}, {"text", l.text}};
}

/// NaN (a figure that was not computed) as JSON null.
nlohmann::json nan_null(double x) { return std::isnan(x) ? nlohmann::json(nullptr) : nlohmann::json(x); }

nlohmann::json fit_json(const dx::Fit& f) {
  return {{"freq_rms_pct", f.freq_rms_pct}, {"mean_mac", f.mean_mac}, {"paired", f.paired}, {"measured", f.measured}};
}


/// The command line's options.
void add_diagnose_options(po::options_description& desc) {
  desc.add_options()("deck", po::value<std::string>()->required(), "the nominal deck with its DESVAR parameters")(
      "measured", po::value<std::string>()->required(),
      "measured modes: universal file (dataset 55), the JSON of ssid identify modes (modes with their sigma), or frequencies only (.csv, .txt, .json: docs/estimation.md)")(
      "study", po::value<std::string>(),
      "study file (JSON, docs/estimation.md; its \"diagnosis\" section: docs/diagnosis.md): noise, priors, pairs, kinds, configurations")(
      "json", po::value<std::string>(), "write the diagnosis as JSON to this file ('-' for stdout)")(
      "output,o", po::value<std::string>(), "write the extended, updated deck into this folder")(
      "report", po::value<std::string>(), "write an HTML report (residuals, ranking, the cause on the structure, the gain) to this file")(
      "also", po::value<std::vector<std::string>>()->composing(),
      "another tested configuration sharing the parameters: DECK=MEASURED.unv (repeatable)")(
      "kinds", po::value<std::string>(), "comma-separated extension kinds to try (default: all)")(
      "freq-std", po::value<double>(),
      "measured frequency standard deviation, % (default 1; study \"measurement\": {\"frequency_std_pct\"})")(
      "shape-std", po::value<double>(),
      "measured shape standard deviation, % of the RMS component (default 5; study \"measurement\": {\"shape_std_pct\"})")(
      "prior-std", po::value<double>(),
      "prior standard deviation of the deck's parameters, relative to XINIT (default: half the distance to the "
      "nearer DESVAR bound; study \"prior_std_pct\")")(
      "frequencies-only", "use the measured frequencies only, not the shapes (study \"measurement\": {\"frequencies_only\": true})")(
      "shortlist", po::value<int>(), "candidates per kind re-estimated exactly (default 3)")(
      "margin", po::value<double>(), "decision margin in nats (default 3)")(
      "noise", po::value<std::string>(), "the measurement noise: 'estimated' from the data (default) or 'given' (the assumed sigma)")(
      "replicates", po::value<int>(), "bootstrap replicates of the screening that calibrate the decision (default 199)")(
      "false-alarm", po::value<double>(), "the largest false-alarm probability of a named cause (default 0.01)")(
      "hold-back", po::value<int>(), "hold back the N highest test modes and report their prediction")(
      "quiet,q", "no progress lines on stderr (phases, counts of candidates, the time left)");
  report::add_frf_options(desc,
                          "measured FRFs (universal file, dataset 58) to lay over them the FRFs of the deck as given, "
                          "of the ordinary update and of the named cause's extended deck (first configuration; JSON "
                          "frf_comparison, the report's FRF figures)");
}

/// The diagnosis options from the study file (its estimation settings and its
/// "diagnosis" section) and the flags (flags win), and the configurations
/// (the study's, the command line's DECK MEASURED, --also). Returns false with
/// the exit code in `rc` for a --noise other than estimated/given, an unknown
/// kind or a malformed --also.
bool diagnosis_options(const po::variables_map& vm, dx::DiagnosisOptions& opt,
                       std::vector<dx::ConfigurationInput>& configs, int& rc) {
  // Assigned, not chosen by ?: (GCC 12 then warns of a maybe-uninitialized Study).
  estimator::Study study;
  if (vm.count("study")) study = estimator::read_study(vm["study"].as<std::string>());
  dx::read_diagnosis_section(study, opt);
  std::string noise = opt.calibration.estimate_noise ? "estimated" : "given";
  // The flags that override the study's estimation settings.
  if (vm.count("freq-std")) study.frequency_std_pct = vm["freq-std"].as<double>();
  if (vm.count("shape-std")) {
    study.shape_std.reset();
    study.shape_std_pct = vm["shape-std"].as<double>();
  }
  if (vm.count("prior-std")) study.prior_std_pct = 100.0 * vm["prior-std"].as<double>();
  if (vm.count("frequencies-only")) study.frequencies_only = true;
  for (const char* flag : {"freq-std", "shape-std", "prior-std"})
    if (vm.count(flag) && !(vm[flag].as<double>() > 0))
      throw formats::InputError(std::string("--") + flag + ": expected a positive number");
  if (vm.count("shortlist")) opt.shortlist = vm["shortlist"].as<int>();
  if (vm.count("margin")) opt.decision_margin = vm["margin"].as<double>();
  if (vm.count("hold-back")) opt.hold_back = vm["hold-back"].as<int>();
  if (vm.count("noise")) noise = vm["noise"].as<std::string>();
  if (vm.count("replicates")) opt.calibration.replicates = vm["replicates"].as<int>();
  if (vm.count("false-alarm")) opt.calibration.false_alarm = vm["false-alarm"].as<double>();
  if (noise != "estimated" && noise != "given") {
    print_error("--noise: expected \"estimated\" or \"given\", got \"" + noise + "\"");
    rc = kExitBadInput;
    return false;
  }
  opt.calibration.estimate_noise = noise == "estimated";
  if (vm.count("kinds")) {
    opt.kinds.clear();
    std::stringstream ss(vm["kinds"].as<std::string>());
    for (std::string k; std::getline(ss, k, ',');) opt.kinds.push_back(k);
  }
  // The kinds the library has (a new kind needs no change here).
  std::set<std::string> kinds;
  std::string kind_list;
  for (const auto& x : estimator::diagnosis::hypotheses::standard_extensions({})) {
    kinds.insert(x->kind());
    kind_list += (kind_list.empty() ? "" : ", ") + x->kind();
  }
  for (const auto& k : opt.kinds)
    if (!kinds.count(k)) {
      print_error("unknown extension kind \"" + k + "\" (" + kind_list + ")");
      rc = kExitBadInput;
      return false;
    }
  std::vector<std::pair<std::string, std::string>> also;
  if (vm.count("also"))
    for (const auto& a : vm["also"].as<std::vector<std::string>>()) {
      const auto eq = a.find('=');
      if (eq == std::string::npos) {
        print_error("--also: expected DECK=MEASURED.unv, got \"" + a + "\"");
        rc = kExitBadInput;
        return false;
      }
      also.emplace_back(a.substr(0, eq), a.substr(eq + 1));
    }
  for (const auto& src : estimator::load_configurations(study, vm["deck"].as<std::string>(), vm["measured"].as<std::string>()))
    configs.push_back(load_configuration(src));
  for (const auto& [d, m] : also) {
    estimator::ConfigurationSource src;
    src.name = d;
    src.deck = d;
    src.measured = m;
    src.data = estimator::read_measured(m, study.frequencies_only);
    configs.push_back(load_configuration(src));
  }
  opt.study = std::move(study);
  return true;
}

/// Writes the extended, updated deck into the -o folder; returns its path ("" without -o).
std::string write_diagnosed_deck(const po::variables_map& vm, const dx::ConfigurationInput& first, const dx::Diagnosis& dg) {
  std::string deck_path;
  if (vm.count("output")) {
    const std::filesystem::path dir = vm["output"].as<std::string>();
    std::filesystem::create_directories(dir);
    const auto stem = std::filesystem::path(first.name).stem().string();
    deck_path = (dir / (stem + "_diagnosed.bdf")).string();
    std::ofstream out(deck_path, std::ios::binary);
    out << dg.updated_deck;
    if (!out) throw formats::InputError(deck_path + ": cannot write");
  }
  return deck_path;
}

/// The diagnosis as JSON (docs/diagnosis.md), without "partial"; `opt` gives the
/// false-alarm target the residual test reports.
nlohmann::json diagnosis_json(const dx::Diagnosis& dg, const dx::Hypothesis& cause, const dx::DiagnosisOptions& opt,
                              const std::string& deck_path) {
  nlohmann::json j;
  {
    nlohmann::json c;
    c["kind"] = dg.cause_kind;
    c["location"] = location_json(cause.location);
    const auto p0 = cause.names.size() - cause.added.size();
    if (!cause.added.empty()) {
      c["value"] = cause.estimate(static_cast<Eigen::Index>(p0));
      c["std"] = cause.posterior_std(static_cast<Eigen::Index>(p0));
      c["parameters"] = nlohmann::json::array();
      for (std::size_t k = 0; k < cause.added.size(); ++k)
        c["parameters"].push_back({{"name", cause.added[k].label},
                                   {"meaning", cause.added[k].meaning},
                                   {"estimate", cause.estimate(static_cast<Eigen::Index>(p0 + k))},
                                   {"std", cause.posterior_std(static_cast<Eigen::Index>(p0 + k))}});
    } else {
      c["value"] = nullptr;
      c["std"] = nullptr;
    }
    c["summary"] = dg.summary;
    c["margin_nats"] = dg.margin;
    c["false_alarm_p"] = nan_null(cause.false_alarm);
    c["held_out_gain"] = cause.held_out_known ? nlohmann::json(cause.held_out.total()) : nlohmann::json(nullptr);
    c["why"] = cause.verdict;
    j["cause"] = c;
  }
  j["ranking"] = nlohmann::json::array();
  for (const auto& h : dg.ranking) {
    nlohmann::json r = {{"kind", h.kind},
                        {"location", location_json(h.location)},
                        {"log_evidence", h.score},
                        {"laplace_log_evidence", h.log_evidence},
                        {"unpaired_penalty", h.miss_penalty},
                        {"look_elsewhere", h.look_elsewhere},
                        {"freq_rms_pct", h.after.freq_rms_pct},
                        {"mean_mac", h.after.mean_mac},
                        {"paired", h.after.paired},
                        {"converged", h.converged}};
    if (h.prediction_rms_pct >= 0) r["prediction_rms_pct"] = h.prediction_rms_pct;
    if (h.screening != 0) r["screening_nats"] = h.screening;
    r["false_alarm_p"] = nan_null(h.false_alarm);
    if (h.exceed >= 0) r["false_alarm_exceed"] = h.exceed;
    if (h.held_out_known)
      r["held_out_gain"] = {{"frequency", h.held_out.gain[dx::kFrequencyRows]},
                            {"shape", h.held_out.gain[dx::kShapeRows]},
                            {"total", h.held_out.total()}};
    if (!h.verdict.empty()) r["verdict"] = h.verdict;
    const auto p0 = h.names.size() - h.added.size();
    r["parameters"] = nlohmann::json::array();
    for (std::size_t k = 0; k < h.added.size(); ++k)
      r["parameters"].push_back({{"name", h.added[k].label},
                                 {"estimate", h.estimate(static_cast<Eigen::Index>(p0 + k))},
                                 {"std", h.posterior_std(static_cast<Eigen::Index>(p0 + k))}});
    // Every parameter (the deck's, then the new ones) with its posterior: the
    // "parameter" row is what `ssid estimate` gives on the same study.
    r["all_parameters"] = nlohmann::json::array();
    for (std::size_t k = 0; k < h.names.size(); ++k)
      r["all_parameters"].push_back({{"name", h.names[k]},
                                     {"estimate", h.estimate(static_cast<Eigen::Index>(k))},
                                     {"std", h.posterior_std(static_cast<Eigen::Index>(k))}});
    r["posterior_covariance"] = nlohmann::json::array();
    for (Eigen::Index a = 0; a < h.posterior_cov.rows(); ++a) {
      std::vector<double> row(static_cast<std::size_t>(h.posterior_cov.cols()));
      for (Eigen::Index b = 0; b < h.posterior_cov.cols(); ++b) row[static_cast<std::size_t>(b)] = h.posterior_cov(a, b);
      r["posterior_covariance"].push_back(row);
    }
    j["ranking"].push_back(r);
  }
  j["gain"] = {{"before", fit_json(dg.nominal.before)}, {"after", fit_json(cause.after)}};
  j["nominal"] = {{"log_evidence", dg.nominal.score}};
  j["searched"] = dg.searched;
  {
    const auto& n = dg.noise;
    auto group = [&](int g, double assumed, double implied, double with_cause) {
      return nlohmann::json{{"assumed_pct", assumed}, {"implied_pct", implied},
                            {"implied_with_cause_pct", nan_null(with_cause)}, {"scale", n.scale.scale[g]},
                            {"chi2", n.scale.chi2[g]}, {"dof", n.scale.dof[g]}, {"rows", n.scale.rows[g]},
                            {"chi2_p", dg.residual.chi2_p[g]}};
    };
    j["noise"] = {{"mode", n.estimated ? "estimated" : "given"},
                  {"pooled", n.scale.pooled},
                  {"std_from", n.std_from},
                  {"identified", n.identified},
                  {"frequency", group(dx::kFrequencyRows, n.assumed_frequency_pct, n.frequency_pct, n.frequency_pct_cause)},
                  {"shape", group(dx::kShapeRows, n.assumed_shape_pct, n.shape_pct, n.shape_pct_cause)}};
    const auto& r = dg.residual;
    j["residual_test"] = {{"consistent", r.consistent},     {"text", r.text},
                          {"unpaired", r.unpaired},         {"candidates", r.candidates},
                          {"statistic_nats", nan_null(r.statistic)}, {"p", nan_null(r.p)},
                          {"p_upper_95", nan_null(r.p_upper)},     {"exceed", r.exceed},
                          {"replicates", r.replicates},     {"false_alarm_target", opt.calibration.false_alarm}};
    const auto& se = dg.second;
    j["second_effect"] = {{"tested", se.tested}, {"named", se.named}, {"text", se.text}};
    if (se.tested && !se.kind.empty()) {
      j["second_effect"]["kind"] = se.kind;
      j["second_effect"]["location"] = location_json(se.location);
      j["second_effect"]["first_order_gain"] = se.gain;
      j["second_effect"]["false_alarm_p"] = se.false_alarm;
      j["second_effect"]["held_out_gain"] = se.held_out.total();
    }
  }
  {
    nlohmann::json e;
    e["findings"] = dg.evidence.findings;
    e["unpaired_test"] = nlohmann::json::array();
    for (const auto& u : dg.evidence.unpaired_test) {
      nlohmann::json moves = nlohmann::json::array();
      for (const auto& g : u.moves) moves.push_back({{"grid", g.grid}, {"share", g.share}});
      e["unpaired_test"].push_back({{"test_mode", u.id}, {"hz", u.frequency_hz}, {"mems_error", u.mems_error}, {"moves", moves}});
    }
    e["unpaired_fe"] = nlohmann::json::array();
    for (const auto& u : dg.evidence.unpaired_fe) e["unpaired_fe"].push_back({{"fe_mode", u.mode}, {"hz", u.frequency_hz}});
    e["modes"] = nlohmann::json::array();
    for (const auto& m : dg.evidence.modes)
      e["modes"].push_back({{"test_mode", m.test_id}, {"test_hz", m.test_hz}, {"fe_mode", m.fem}, {"fe_hz", m.fem_hz},
                            {"error_pct", m.error_pct}, {"mac", m.mac}, {"mems_error", m.mems_error}});
    e["frequency_error"] = {{"mean_pct", dg.evidence.mean_error_pct}, {"rms_pct", dg.evidence.rms_error_pct},
                            {"slope_pct_per_hz", dg.evidence.error_slope_pct_per_hz}};
    e["grid_misfit"] = nlohmann::json::array();
    for (std::size_t k = 0; k < std::min<std::size_t>(10, dg.evidence.grid_misfit.size()); ++k)
      e["grid_misfit"].push_back({{"grid", dg.evidence.grid_misfit[k].grid}, {"share", dg.evidence.grid_misfit[k].share}});
    j["evidence"] = e;
  }
  j["notes"] = dg.notes;
  j["deck"] = deck_path.empty() ? nlohmann::json(nullptr) : nlohmann::json(deck_path);
  return j;
}

/// Why the result is not to be trusted ("" when it is): stopped early, or the
/// cause's own estimate did not converge.
std::string untrusted_reason(const dx::Diagnosis& dg, const dx::Hypothesis& cause) {
  std::string untrusted = dg.partial_reason;
  if (untrusted.empty() && cause.kind != "none" && !cause.converged)
    untrusted = "the estimate of the cause (" + cause.kind + (cause.kind == "parameter" ? "" : " at " + cause.location.text) +
                ") did not converge";
  return untrusted;
}

/// The exit code, with its message on stderr when the result is not trusted.
int exit_code(const dx::Diagnosis& dg, const std::string& untrusted, const std::string& json_path) {
  if (untrusted.empty()) return static_cast<int>(kExitSuccess);
  const std::string marked =
    json_path.empty() || json_path == "-" ? "" : "; " + json_path + " is marked \"partial\": true";
  print_error("diagnose: " + untrusted + ": " +
            (dg.interrupted ? "the ranking holds the hypotheses tested so far"
                            : "the diagnosis is not trustworthy (more cycles: \"max_iterations\" in --study)") +
            marked);
  return static_cast<int>(dg.interrupted ? kExitInterrupted : kExitUntrusted);
}

/// The report on stdout: evidence, hypotheses, cause and gain.
void print_report(const dx::Diagnosis& dg, const dx::Hypothesis& cause, const std::vector<dx::ConfigurationInput>& configs,
                  const std::string& measured, const std::string& untrusted, const std::string& deck_path) {
  std::cout << "ssid diagnose: " << configs.front().name << " against " << measured;
  if (configs.size() > 1) std::cout << " (+" << configs.size() - 1 << " configuration(s))";
  std::cout << "\n";
  if (!untrusted.empty()) std::cout << "PARTIAL RESULT (" << untrusted << ")\n";
  std::cout << "\n1. What the updated model gets wrong (after the ordinary update):\n";
  for (const auto& f : dg.evidence.findings) std::cout << "   - " << f << "\n";
  // Frequencies to 7 significant digits: any error the error column shows is visible in them.
  {
    const auto& n = dg.noise;
    // Frequency-only data has no shape rows: no shape noise to imply or test.
    const bool shapes = n.scale.rows[dx::kShapeRows] > 0;
    if (n.identified) {  // per-mode σ of the identification: the scales on them
      std::cout << "   - noise " << (n.estimated ? "the data imply" : "(given)") << ": the assumed sigma times "
                << estimator::significant(n.scale.scale[dx::kFrequencyRows], 3) << " (frequencies)";
      if (shapes) std::cout << " and " << estimator::significant(n.scale.scale[dx::kShapeRows], 3) << " (shapes)";
      if (n.estimated)
        std::cout << " (" << estimator::significant(n.scale.dof[dx::kFrequencyRows], 3)
                  << (shapes ? " and " + estimator::significant(n.scale.dof[dx::kShapeRows], 4) : std::string())
                  << " degrees of freedom" << (n.scale.pooled ? ", one scale for both" : "") << ")";
      std::cout << "\n   - assumed sigma: " << n.std_from;
    } else {
      std::cout << "   - noise " << (n.estimated ? "the data imply" : "(given)") << ": frequencies "
                << estimator::significant(n.frequency_pct, 3) << " %";
      if (shapes) std::cout << ", shapes " << estimator::significant(n.shape_pct, 3) << " % of the RMS component";
      if (n.estimated && shapes)
        std::cout << " (assumed " << estimator::significant(n.assumed_frequency_pct, 3) << " % and "
                  << estimator::significant(n.assumed_shape_pct, 3) << " %; " << estimator::significant(n.scale.dof[dx::kFrequencyRows], 3)
                  << " and " << estimator::significant(n.scale.dof[dx::kShapeRows], 4) << " degrees of freedom"
                  << (n.scale.pooled ? ", one scale for both" : "") << ")";
      else if (n.estimated)
        std::cout << " (assumed " << estimator::significant(n.assumed_frequency_pct, 3) << " %; "
                  << estimator::significant(n.scale.dof[dx::kFrequencyRows], 3) << " degrees of freedom; no shapes measured)";
    }
    std::cout << "\n   - against the assumed noise: frequency chi^2 " << estimator::significant(n.scale.chi2[dx::kFrequencyRows], 4)
              << " (p = " << estimator::significant(dg.residual.chi2_p[dx::kFrequencyRows], 2) << ")";
    if (shapes)
      std::cout << ", shape chi^2 " << estimator::significant(n.scale.chi2[dx::kShapeRows], 4) << " (p = "
                << estimator::significant(dg.residual.chi2_p[dx::kShapeRows], 2) << ")";
    std::cout << "\n";
    std::cout << "   - anything left to explain? " << (dg.residual.text.empty() ? "not tested" : dg.residual.text) << "\n";
  }
  std::cout << "\n   test mode   test [Hz]  FE mode      FE [Hz]  error [%]    MAC   MEMS e^2\n";
  for (const auto& m : dg.evidence.modes) {
    std::cout << "   " << std::setw(9) << m.test_id << std::setw(12) << estimator::significant(m.test_hz, 7);
    if (m.fem) std::cout << std::setw(9) << m.fem << std::setw(13) << estimator::significant(m.fem_hz, 7) << std::setw(11)
                         << estimator::fixed(m.error_pct, 3) << std::setw(7) << estimator::fixed(m.mac, 3);
    else std::cout << std::setw(40) << "(no partner)";
    std::cout << std::setw(11) << estimator::fixed(m.mems_error, 3) << "\n";
  }
  std::cout << "\n2-3. Hypotheses tested (searched:";
  for (const auto& [k, n] : dg.searched) std::cout << " " << k << " " << n;
  std::cout << " locations)\n   score = Laplace log-evidence + unpaired-mode penalty - log(#locations)\n";
  std::cout << "   false-alarm p: probability that noise alone gives a first-order gain as large (" << dg.residual.replicates
            << " replicates); held-out: leave-one-mode-out gain over the ordinary update\n";
  std::cout << "   rank  kind               location                                  score [nats]  freq RMS %  mean MAC  paired"
               "  false-alarm p  held-out\n";
  std::cout << "      -  none               deck as given                            " << std::setw(13)
            << estimator::fixed(dg.nominal.score, 1) << std::setw(12) << estimator::fixed(dg.nominal.before.freq_rms_pct, 3) << std::setw(10)
            << estimator::fixed(dg.nominal.before.mean_mac, 4) << std::setw(8) << dg.nominal.before.paired << "\n";
  for (std::size_t i = 0; i < dg.ranking.size() && i < 12; ++i) {
    const auto& h = dg.ranking[i];
    std::string loc = h.location.text;
    if (loc.size() > 40) loc = loc.substr(0, 37) + "...";
    std::cout << "   " << std::setw(4) << i + 1 << "  " << std::left << std::setw(19) << h.kind << std::setw(41) << loc
              << std::right << std::setw(13) << estimator::fixed(h.score, 1) << std::setw(12) << estimator::fixed(h.after.freq_rms_pct, 3)
              << std::setw(10) << estimator::fixed(h.after.mean_mac, 4) << std::setw(8) << h.after.paired << std::setw(15)
              << (std::isnan(h.false_alarm) ? std::string("-") : estimator::significant(h.false_alarm, 2)) << std::setw(10)
              << (h.held_out_known ? estimator::significant(h.held_out.total(), 3) : std::string("-"));
    if (h.prediction_rms_pct >= 0) std::cout << "  held-back RMS " << estimator::fixed(h.prediction_rms_pct, 2) << " %";
    std::cout << (static_cast<int>(i) == dg.cause ? "  <- cause" : "") << "\n";
  }
  std::cout << "\n4. Cause: " << dg.cause_kind << " — " << dg.summary << "\n";
  for (const auto& h : dg.ranking)  // why the best extension not named was not
    if (h.kind != "parameter" && static_cast<int>(&h - dg.ranking.data()) != dg.cause) {
      std::cout << "   not named: " << h.kind << " at " << h.location.text << ": " << h.verdict << "\n";
      break;
    }
  if (!std::isnan(dg.noise.frequency_pct_cause))
  {
    std::cout << "   noise the data imply with the cause in the model: frequencies "
              << estimator::significant(dg.noise.frequency_pct_cause, 3) << " %";
    if (dg.noise.scale.rows[dx::kShapeRows] > 0)
      std::cout << ", shapes " << estimator::significant(dg.noise.shape_pct_cause, 3) << " %";
    std::cout << "\n";
  }
  if (dg.second.tested) std::cout << "   a second effect: " << dg.second.text << "\n";
  std::cout << "\n5. Gain:              before     after\n";
  std::cout << "   freq RMS error %  " << std::setw(8) << estimator::fixed(dg.nominal.before.freq_rms_pct, 3) << std::setw(10)
            << estimator::fixed(cause.after.freq_rms_pct, 3) << "\n";
  std::cout << "   mean MAC          " << std::setw(8) << estimator::fixed(dg.nominal.before.mean_mac, 4) << std::setw(10)
            << estimator::fixed(cause.after.mean_mac, 4) << "\n";
  std::cout << "   paired modes      " << std::setw(8) << dg.nominal.before.paired << std::setw(10) << cause.after.paired << " of "
            << cause.after.measured << "\n";
  std::cout << "   log evidence      " << std::setw(8) << estimator::fixed(dg.nominal.score, 1) << std::setw(10) << estimator::fixed(cause.score, 1)
            << "\n";
  for (const auto& n : dg.notes) std::cout << "note: " << n << "\n";
  if (!deck_path.empty()) std::cout << "\nextended, updated deck: " << deck_path << "\n";
}

}  // namespace

int cmd_diagnose(const Args& args) {
  po::options_description desc("ssid diagnose options");
  add_diagnose_options(desc);
  po::positional_options_description pos;
  pos.add("deck", 1).add("measured", 1);
  po::variables_map vm;
  int rc = 0;
  if (!parse_options(args, "ssid diagnose DECK MEASURED.unv [--study FILE] [--json FILE] [-o DIR]", desc, pos, vm, rc))
    return rc;

  dx::DiagnosisOptions opt;
  std::vector<dx::ConfigurationInput> configs;
  if (!diagnosis_options(vm, opt, configs, rc)) return rc;
  const std::optional<report::FrfOptions> frf_opt = report::frf_options(vm);
  if (!frf_opt) return kExitBadInput;
  // The measured FRFs before the search: a bad file is reported before minutes of work.
  std::optional<formats::uff::UffFile> frf_file;
  if (vm.count("frf")) frf_file = formats::uff::read_uff(vm["frf"].as<std::string>());
  const std::string json_path = vm.count("json") ? vm["json"].as<std::string>() : "";
  const bool quiet_json = json_path == "-";
  // Candidates can number hundreds: their counts at most every 2 s.
  ProgressLines lines("ssid diagnose", vm.count("quiet") != 0, 2.0);
  opt.progress = lines.callback();

  const InterruptFlag interrupt;
  dx::Diagnosis dg;
  try {
    dg = dx::diagnose(configs, opt);
  } catch (const estimator::Interrupted& e) {
    const std::string why = std::string(e.what()) + " before the ordinary update's first cycle was complete";
    if (!json_path.empty())
      write_json(json_path, {{"partial", true}, {"partial_reason", why}, {"cause", nullptr}, {"ranking", nlohmann::json::array()}});
    print_error("diagnose: " + why + ": no diagnosis" +
                (json_path.empty() || quiet_json ? "" : " (" + json_path + " is marked \"partial\": true)"));
    return kExitInterrupted;
  }
  const dx::Hypothesis& cause = dg.cause >= 0 ? dg.ranking[static_cast<std::size_t>(dg.cause)] : dg.nominal;
  const std::string deck_path = write_diagnosed_deck(vm, configs.front(), dg);
  nlohmann::json j = diagnosis_json(dg, cause, opt, deck_path);
  const std::string untrusted = untrusted_reason(dg, cause);
  j["partial"] = !untrusted.empty();
  if (!untrusted.empty()) j["partial_reason"] = untrusted;
  if (frf_file) {
    std::vector<std::string> notes;
    j["frf_comparison"] = report::diagnosis_frf_comparison(*frf_file, configs.front(), dg,
                                                           {opt.study.map_by, opt.study.map_tolerance},
                                                           frf_opt->zeta_fallback, frf_opt->max_frfs, notes);
    for (const auto& n : notes) std::cerr << "note: " << n << "\n";
  }
  if (vm.count("report")) report::write_diagnosis_report(vm["report"].as<std::string>(), args, vm, j);
  if (quiet_json) {
    write_json("-", j);
    return exit_code(dg, untrusted, json_path);
  }
  print_report(dg, cause, configs, vm["measured"].as<std::string>(), untrusted, deck_path);
  if (j.contains("frf_comparison")) std::cout << "\n" << report::frf_comparison_text(j["frf_comparison"]);
  if (!json_path.empty()) write_json(json_path, j);
  return exit_code(dg, untrusted, json_path);
}

}  // namespace ssid::cli
