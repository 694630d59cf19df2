#include "cli/report/frf_comparison.hpp"

#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <limits>
#include <fmt/format.h>
#include <map>
#include <memory>
#include <set>
#include <stdexcept>

#include "cli/model_load.hpp"
#include "cli/report/report_data.hpp"
#include "estimator/identification/frf_synthesis.hpp"
#include "estimator/reporting/number_text.hpp"
#include "formats/deck.hpp"
#include "formats/parse_error.hpp"

namespace ssid::cli::report {

namespace {

namespace uff = formats::uff;
namespace id = estimator::identification;
using formats::InputError;

/// Per analysis mode, ζ and where it came from (FrfDamping's rule).
std::pair<Eigen::VectorXd, std::vector<std::string>> modal_damping(const Eigen::VectorXd& hz, const FrfDamping& d,
                                                                   const std::string& file) {
  std::vector<double> thz, tz;
  std::vector<int> tno;
  for (std::size_t t = 0; t < d.test_hz.size(); ++t)
    if (t < d.test_zeta.size() && d.test_zeta[t] > 0 && d.test_hz[t] > 0) {
      thz.push_back(d.test_hz[t]);
      tz.push_back(d.test_zeta[t]);
      tno.push_back(t < d.test_numbers.size() ? d.test_numbers[t] : static_cast<int>(t) + 1);
    }
  const bool given = !std::isnan(d.fallback);
  if (thz.empty() && !given)
    throw InputError(file + ": the test modes carry no damping (dataset 55's viscous damping ratio is 0 or absent): "
                            "give the modal damping of the analysis FRFs with --frf-damping Z (0.01 = 1 %)");
  double mean = 0;
  for (double z : tz) mean += z;
  if (!tz.empty()) mean /= static_cast<double>(tz.size());
  Eigen::VectorXd zeta = Eigen::VectorXd::Constant(hz.size(), given ? d.fallback : mean);
  std::vector<std::string> from(static_cast<std::size_t>(hz.size()),
                                given ? "--frf-damping (no damped test mode near)" : "mean of the test modes' damping");
  const auto partner = id::damping_partners(hz, thz, d.pair_tolerance);
  for (std::size_t r = 0; r < partner.size(); ++r)
    if (const auto t = partner[r]) {
      zeta(static_cast<Eigen::Index>(r)) = tz[*t];
      from[r] = fmt::format("test mode {} at {} Hz", tno[*t], estimator::significant(thz[*t], 6));
    }
  return {zeta, from};
}

std::vector<double> to_vector(const Eigen::VectorXd& v) { return {v.data(), v.data() + v.size()}; }

}  // namespace

void add_frf_options(po::options_description& desc, const std::string& frf_help) {
  desc.add_options()("frf", po::value<std::string>(), frf_help.c_str())(
      "frf-damping", po::value<double>(),
      "modal damping ratio of the analysis FRFs' modes no damped test mode lends its damping to (default: the test "
      "modes' mean; needed when they carry none)")(
      "frf-max", po::value<int>()->default_value(6), "draw at most N measured FRFs (drive points first)");
}

std::optional<FrfOptions> frf_options(const po::variables_map& vm) {
  const int max = vm["frf-max"].as<int>();
  if (max < 1) {
    print_error(fmt::format("--frf-max: expected at least 1, got {}", max));
    return std::nullopt;
  }
  double zeta = std::numeric_limits<double>::quiet_NaN();
  if (vm.count("frf-damping")) {
    zeta = vm["frf-damping"].as<double>();
    if (!(zeta >= 0 && zeta < 1)) {
      print_error(fmt::format("--frf-damping: expected a ratio 0 ≤ ζ < 1 (0.01 = 1 %), got {}", zeta));
      return std::nullopt;
    }
  }
  return FrfOptions{zeta, static_cast<std::size_t>(max)};
}

FrfAnalysis deck_analysis(const std::string& label, const translators::FeModel& model,
                          const translators::FeOperators& op, std::vector<std::string>& problems) {
  std::string source;
  estimator::EigenOptions eo = eigen_options(model, std::nullopt, op.K.rows(), source);
  eo.norm = estimator::ModeNormalization::Mass;  // Eq. 2 needs φᵀMφ = 1, whatever the deck's NORM
  const estimator::EigenResult er = solve_model(op, eo, a_set_dofs(model));
  for (const auto& w : er.warnings) problems.push_back(label + ": " + w);
  return {label, &model, er.eigenvalues, er.modes};
}

nlohmann::json frf_comparison_json(const uff::UffFile& measured, std::vector<translators::TestNode> nodes,
                                   const translators::NodeMapOptions& map, const std::vector<FrfAnalysis>& analyses,
                                   const FrfDamping& damping, std::size_t max_frfs, std::vector<std::string>& problems) {
  if (analyses.empty() || !analyses.front().model) throw std::invalid_argument("frf_comparison_json: no analysis model");
  const translators::FeModel& model = *analyses.front().model;
  std::vector<const uff::Function58*> frfs;
  for (const auto* f : measured.functions())
    if (f->function_type == 4) frfs.push_back(f);
  if (frfs.empty()) throw InputError(measured.path + ": no FRF (dataset 58, function type 4) to compare");

  // The FRF file's own nodes join the test file's; by id, a node nobody lists maps to its id.
  std::set<std::int64_t> listed;
  for (const auto& n : nodes) listed.insert(n.id);
  for (const auto& n : translators::test_nodes(measured))
    if (listed.insert(n.id).second) nodes.push_back(n);
  if (map.by == translators::MapBy::Id)
    for (const auto* f : frfs)
      for (const std::int64_t n : {f->response_node, f->reference_node})
        if (listed.insert(n).second) nodes.push_back({n, Eigen::Vector3d::Zero(), 0});
  const std::vector<translators::GridPosition> grids = grid_positions(model);
  const translators::NodeMapping mapping = translators::map_test_nodes(nodes, grids, map);

  // Drive points first (the analyst's first look), then the file's order.
  std::stable_partition(frfs.begin(), frfs.end(), [](const uff::Function58* f) {
    return f->response_node == f->reference_node && std::abs(f->response_direction) == std::abs(f->reference_direction);
  });
  nlohmann::json left_out = nlohmann::json::array();
  std::vector<const uff::Function58*> drawn;
  std::vector<translators::MeasuredDof> dofs;  // response and reference of each drawn FRF, in turn
  for (const auto* f : frfs) {
    const std::string at = f->where.str();
    const bool directions_ok = std::abs(f->response_direction) >= 1 && std::abs(f->response_direction) <= 6 &&
                               std::abs(f->reference_direction) >= 1 && std::abs(f->reference_direction) <= 6;
    if (!directions_ok) {
      left_out.push_back(fmt::format("{}: response direction {}, reference direction {} (expected ±1…±6)", at,
                                     f->response_direction, f->reference_direction));
      continue;
    }
    std::string unmapped;
    for (const std::int64_t n : {f->response_node, f->reference_node})
      if (!mapping.grid_of(n)) {
        const auto why = mapping.why_unmapped.find(n);
        unmapped = fmt::format("test node {}: {}", n, why != mapping.why_unmapped.end() ? why->second : "maps to no grid");
      }
    if (!unmapped.empty()) {
      left_out.push_back(at + ": " + unmapped);
      continue;
    }
    if (drawn.size() == max_frfs) {
      left_out.push_back(fmt::format("{}: beyond the {} FRF(s) drawn (--frf-max)", at, max_frfs));
      continue;
    }
    drawn.push_back(f);
    dofs.push_back({f->response_node, f->response_direction});
    dofs.push_back({f->reference_node, f->reference_direction});
  }
  if (drawn.empty())
    throw InputError(fmt::format("{}: none of its {} FRF(s) can be drawn ({})", measured.path, frfs.size(),
                                 left_out.empty() ? std::string("none maps") : left_out[0].get<std::string>()));

  // Each DOF as a combination of each analysis's DOFs: C_a = C_g T (an extended deck
  // has DOFs of its own; the test grids are the deck's).
  auto observation = [&](const translators::FeModel& m) -> Eigen::SparseMatrix<double> {
    const translators::Observation obs = translators::observe(dofs, mapping, &m == &model ? grids : grid_positions(m));
    return translators::observation_matrix(obs, m.geometry().gset()) * m.reduction().T;
  };
  const Eigen::SparseMatrix<double> Ca = observation(model);

  nlohmann::json out;
  out["file"] = measured.path;
  out["analyses"] = nlohmann::json::array();
  std::vector<Eigen::VectorXd> zetas;
  std::vector<Eigen::MatrixXd> at_dofs;  // C_a Φ_a per analysis
  for (const auto& a : analyses) {
    const Eigen::VectorXd hz = a.eigenvalue.cwiseMax(0.0).cwiseSqrt() / (2 * M_PI);
    auto [zeta, from] = modal_damping(hz, damping, measured.path);
    nlohmann::json modes = nlohmann::json::array();
    for (Eigen::Index r = 0; r < hz.size(); ++r)
      modes.push_back({{"mode", r + 1}, {"hz", hz(r)}, {"zeta", zeta(r)}, {"zeta_from", from[static_cast<std::size_t>(r)]}});
    out["analyses"].push_back({{"label", a.label}, {"modes", modes}});
    zetas.push_back(zeta);
    at_dofs.push_back(a.model == &model ? Eigen::MatrixXd(Ca * a.a_modes) : Eigen::MatrixXd(observation(*a.model) * a.a_modes));
  }

  out["frfs"] = nlohmann::json::array();
  bool noted_quantity = false;
  for (std::size_t k = 0; k < drawn.size(); ++k) {
    const uff::Function58& f = *drawn[k];
    const auto ro = static_cast<Eigen::Index>(2 * k), rd = ro + 1;
    if (Ca.row(rd).norm() == 0) {
      left_out.push_back(f.where.str() + ": the reference DOF is constrained in the model (no force enters there)");
      continue;
    }
    const auto q = id::quantity_of_data_type(f.axes[1].specific_data_type);
    if (!q && !noted_quantity) {
      problems.push_back(fmt::format("{}: ordinate data type {} (not 8, 11 or 12): the analysis FRFs are receptance",
                                     f.where.str(), f.axes[1].specific_data_type));
      noted_quantity = true;
    }
    const id::FrfQuantity quantity = q.value_or(id::FrfQuantity::Displacement);
    // Lines above 0 Hz: a rigid-body mode is infinite at 0 Hz, and a logarithmic plot
    // has no 0 Hz anyway.
    const std::vector<double> x = f.abscissa();
    std::vector<double> hz;
    Eigen::VectorXcd hm(static_cast<Eigen::Index>(x.size()));
    for (std::size_t i = 0; i < x.size() && i < f.y.size(); ++i)
      if (x[i] > 0) {
        hm(static_cast<Eigen::Index>(hz.size())) = f.y[i];
        hz.push_back(x[i]);
      }
    hm.conservativeResize(static_cast<Eigen::Index>(hz.size()));
    if (hz.empty()) {
      left_out.push_back(f.where.str() + ": no line above 0 Hz");
      continue;
    }
    std::vector<double> re(hz.size()), im(hz.size());
    for (std::size_t i = 0; i < hz.size(); ++i) re[i] = hm(static_cast<Eigen::Index>(i)).real(), im[i] = hm(static_cast<Eigen::Index>(i)).imag();
    nlohmann::json rec{{"response", {f.response_node, f.response_direction}},
                       {"reference", {f.reference_node, f.reference_direction}},
                       {"response_grid", *mapping.grid_of(f.response_node)},
                       {"reference_grid", *mapping.grid_of(f.reference_node)},
                       {"at", f.where.str()},
                       {"quantity", id::quantity_name(quantity)},
                       {"unit", std::string(id::quantity_unit(quantity)) + " (the deck's units)"},
                       {"hz", hz},
                       {"measured", {{"re", re}, {"im", im}}},
                       {"analyses", nlohmann::json::array()}};
    const Eigen::Map<const Eigen::VectorXd> lines(hz.data(), static_cast<Eigen::Index>(hz.size()));
    for (std::size_t a = 0; a < analyses.size(); ++a) {
      id::ModalFrfModel mm;
      mm.eigenvalue = analyses[a].eigenvalue;
      mm.zeta = zetas[a];
      mm.response = at_dofs[a].row(ro);
      mm.drive = at_dofs[a].row(rd).transpose();
      const Eigen::VectorXcd h = id::synthesize_frf(lines, mm, quantity).col(0);
      const double frac = id::frf_assurance(h, hm);
      rec["analyses"].push_back({{"label", analyses[a].label},
                                 {"re", to_vector(h.real())},
                                 {"im", to_vector(h.imag())},
                                 {"frac", std::isnan(frac) ? nlohmann::json(nullptr) : nlohmann::json(frac)}});
    }
    out["frfs"].push_back(rec);
  }
  if (out["frfs"].empty())
    throw InputError(fmt::format("{}: none of its {} FRF(s) can be drawn ({})", measured.path, frfs.size(),
                                 left_out.back().get<std::string>()));
  out["left_out"] = left_out;
  if (!left_out.empty())
    problems.push_back(fmt::format("{}: {} FRF(s) not drawn (frf_comparison.left_out)", measured.path, left_out.size()));
  return out;
}

nlohmann::json estimate_frf_comparison(const uff::UffFile& measured, const estimator::PreparedConfiguration& c,
                                       const Eigen::VectorXd& prior_mean, const Eigen::VectorXd& estimate,
                                       double zeta_fallback, std::size_t max_frfs, std::vector<std::string>& problems) {
  if (!c.fe || !c.assemble)
    throw InputError("--frf needs the deck: a problem file's estimate carries no geometry to place the FRFs on");
  // The deck's modes as correlate takes them (its EIGRL, or every mode of a small
  // model), not the estimator's tracked few: a modal sum wants every mode in the band.
  std::vector<FrfAnalysis> analyses;
  for (const auto& [label, r] : {std::pair<const char*, const Eigen::VectorXd*>{"prior mean", &prior_mean},
                                 std::pair<const char*, const Eigen::VectorXd*>{"estimate", &estimate}}) {
    analyses.push_back(deck_analysis(label, *c.fe, operators_at(c, *r), problems));
  }
  std::vector<double> test_hz;
  for (const auto& m : c.test) test_hz.push_back(m.frequency_hz);
  const FrfDamping damping{test_hz, c.test_damping, c.test_numbers, zeta_fallback, 0.1};
  return frf_comparison_json(measured, c.test_nodes, c.node_map, analyses, damping, max_frfs, problems);
}

nlohmann::json diagnosis_frf_comparison(const uff::UffFile& measured, const estimator::diagnosis::ConfigurationInput& c,
                                        const estimator::diagnosis::Diagnosis& dg, const translators::NodeMapOptions& map,
                                        double zeta_fallback, std::size_t max_frfs, std::vector<std::string>& problems) {
  namespace dx = estimator::diagnosis;
  std::vector<std::pair<std::string, std::string>> decks{{"deck", c.deck_text}};  // label, deck text
  for (const dx::Hypothesis& h : dg.ranking)
    if (h.kind == "parameter") decks.emplace_back("parameters updated", dx::deck_at(h.deck_text, c.name, h.estimate));
  if (dg.cause >= 0 && dg.cause_kind != "parameter") decks.emplace_back("cause: " + dg.cause_kind, dg.updated_deck);
  std::vector<std::unique_ptr<translators::FeModel>> models;
  std::vector<FrfAnalysis> analyses;
  for (const auto& [label, text] : decks) {
    const formats::Deck deck = formats::read_deck_text(text, c.name);
    models.push_back(translators::assemble_deck(deck, c.name));
    const translators::FeModel& m = *models.back();
    analyses.push_back(deck_analysis(label, m, m.operators(m.initial_parameters(), false), problems));
  }
  const FrfDamping damping{c.measured.frequency_hz, c.measured.damping, c.measured.numbers, zeta_fallback, 0.1};
  return frf_comparison_json(measured, c.nodes, map, analyses, damping, max_frfs, problems);
}

std::string frf_comparison_text(const nlohmann::json& c) {
  std::string s = fmt::format("FRFs: {} measured FRF(s) of {} against the analysis (modal superposition); FRAC = 1: "
                              "the same shape over the lines\n",
                              c["frfs"].size(), c["file"].get<std::string>());
  s += "response  reference  quantity      lines (Hz)          ";
  std::vector<std::size_t> width;  // a column per analysis, as wide as its heading
  for (const auto& a : c["analyses"]) {
    const std::string head = "FRAC " + a["label"].get<std::string>();
    width.push_back(std::max<std::size_t>(14, head.size()));
    s += fmt::format(" {:>{}}", head, width.back());
  }
  s += "\n";
  for (const auto& f : c["frfs"]) {
    s += fmt::format("{:>8}  {:>9}  {:<12}  {:>8}…{:<10}", fmt::format("{}:{}", f["response"][0].get<long>(), f["response"][1].get<int>()),
                     fmt::format("{}:{}", f["reference"][0].get<long>(), f["reference"][1].get<int>()),
                     f["quantity"].get<std::string>(), estimator::significant(f["hz"].front().get<double>(), 5),
                     estimator::significant(f["hz"].back().get<double>(), 5));
    for (std::size_t a = 0; a < f["analyses"].size(); ++a) {
      const auto& x = f["analyses"][a];
      s += fmt::format(" {:>{}}", x["frac"].is_null() ? std::string("—") : fmt::format("{:.4f}", x["frac"].get<double>()),
                       a < width.size() ? width[a] : 14);
    }
    s += "\n";
  }
  if (!c["left_out"].empty()) s += fmt::format("{} FRF(s) not drawn: see frf_comparison.left_out in the JSON\n", c["left_out"].size());
  return s;
}

}  // namespace ssid::cli::report
