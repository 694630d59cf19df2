/// \file cmd_identify.cpp
/// `ssid identify modes FILE.unv --method armax|era|plscf`: modes from the records of a
/// universal file (dataset 58) as a table, JSON and UFF 55. FRFs (function type 4) go to ERA
/// (Markov parameters by inverse FFT, ERA over model orders, the stabilisation diagram's
/// physical modes) or to pLSCF (poles over model orders, the stabilisation diagram, LSFD for
/// the shapes); time histories (function type 1, the forces told by their ordinate type) go
/// to the multistage ARMAX with its subset order rule, or to ERA or pLSCF through H1 FRFs
/// (Welch). `ssid identify frf` turns time histories into FRFs, coherences and multiple
/// coherences (UFF 58 types 4, 6, 26); `ssid identify check` judges a test's data
/// (reciprocity, linearity, coherence, resolution against damping) with a verdict per check.
/// docs/identification.md describes the methods and the rule for force records.
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
#include <optional>
#include <unsupported/Eigen/FFT>
#include <set>
#include <sstream>
#include <utility>
#include <variant>
#include <unistd.h>

#include "cli/cli_util.hpp"
#include "cli/progress_lines.hpp"
#include "cli/report/html_report.hpp"
#include "cli/report/report_data.hpp"
#include "estimator/identification/armax_order.hpp"
#include "estimator/identification/data_checks.hpp"
#include "estimator/identification/era.hpp"
#include "estimator/identification/frf.hpp"
#include "estimator/identification/modal_indicators.hpp"
#include "estimator/identification/frf_synthesis.hpp"
#include "estimator/identification/plscf.hpp"
#include "estimator/identification/stabilisation.hpp"
#include "formats/parse_error.hpp"
#include "formats/uff.hpp"
#include "translators/measurement/mode_set.hpp"

namespace ssid::cli {

namespace {

namespace uff = formats::uff;
namespace id = estimator::identification;
using Dof = std::pair<std::int64_t, int>;  // node, direction (±1 … ±6)

std::string dof_text(const Dof& d) { return fmt::format("{}:{}", d.first, d.second); }

/// The FRFs of a file as lines of no × ni matrices, with their DOFs.
struct FrfSet {
  std::vector<Dof> responses, references;
  std::vector<Eigen::MatrixXcd> lines;
  double df = 0;
  std::string unit;  ///< the ordinate's unit as the records' axis labels it ("" when they do not)
};

/// The frequency of each line, k·df (Hz).
Eigen::VectorXd line_hz(const FrfSet& s) {
  Eigen::VectorXd hz(static_cast<Eigen::Index>(s.lines.size()));
  for (Eigen::Index k = 0; k < hz.size(); ++k) hz(k) = static_cast<double>(k) * s.df;
  return hz;
}

/// A record's ordinate unit as its axis labels it ("" when it does not).
std::string record_unit(const uff::Function58& f) {
  const std::string& u = f.axes[1].units;
  return u.empty() || u == "NONE" ? "" : u;
}

FrfSet read_frfs(const uff::UffFile& file, const std::vector<const uff::Function58*>& frfs) {
  FrfSet s;
  const auto* first = frfs.front();
  for (const auto* f : frfs) {
    const std::string at = f->where.str() + ": dataset 58";
    if (!f->even) throw formats::InputError(at + ": uneven abscissa (expected evenly spaced frequency lines)");
    if (f->abscissa_min != 0)
      throw formats::InputError(fmt::format("{}: first line at {} Hz (expected lines from 0 Hz)", at, f->abscissa_min));
    if (f->y.size() != first->y.size() || f->abscissa_increment != first->abscissa_increment)
      throw formats::InputError(fmt::format("{}: {} lines every {} Hz (expected {} every {} Hz as at {})", at,
                                            f->y.size(), f->abscissa_increment, first->y.size(),
                                            first->abscissa_increment, first->where.str()));
    const Dof r{f->response_node, f->response_direction}, q{f->reference_node, f->reference_direction};
    if (std::find(s.responses.begin(), s.responses.end(), r) == s.responses.end()) s.responses.push_back(r);
    if (std::find(s.references.begin(), s.references.end(), q) == s.references.end()) s.references.push_back(q);
  }
  if (!(first->abscissa_increment > 0))
    throw formats::InputError(fmt::format("{}: dataset 58: frequency increment {} Hz (expected > 0)",
                                          first->where.str(), first->abscissa_increment));
  s.df = first->abscissa_increment;
  s.unit = record_unit(*first);
  const auto no = static_cast<Eigen::Index>(s.responses.size()), ni = static_cast<Eigen::Index>(s.references.size());
  s.lines.assign(first->y.size(), Eigen::MatrixXcd::Zero(no, ni));
  std::vector<std::vector<bool>> seen(static_cast<std::size_t>(no), std::vector<bool>(static_cast<std::size_t>(ni)));
  for (const auto* f : frfs) {
    const auto o = std::find(s.responses.begin(), s.responses.end(), Dof{f->response_node, f->response_direction}) -
                   s.responses.begin();
    const auto i = std::find(s.references.begin(), s.references.end(), Dof{f->reference_node, f->reference_direction}) -
                   s.references.begin();
    seen[static_cast<std::size_t>(o)][static_cast<std::size_t>(i)] = true;
    for (std::size_t k = 0; k < f->y.size(); ++k) s.lines[k](o, i) = f->y[k];
  }
  for (Eigen::Index o = 0; o < no; ++o)
    for (Eigen::Index i = 0; i < ni; ++i)
      if (!seen[static_cast<std::size_t>(o)][static_cast<std::size_t>(i)])
        throw formats::InputError(fmt::format(
            "{}: no FRF of response {}:{} to reference {}:{} (every response needs one per reference)", file.path,
            s.responses[static_cast<std::size_t>(o)].first, s.responses[static_cast<std::size_t>(o)].second,
            s.references[static_cast<std::size_t>(i)].first, s.references[static_cast<std::size_t>(i)].second));
  return s;
}

/// The time histories of a file (dataset 58, function type 1) as columns sampled every
/// dt: the forces (inputs) and the responses, each with its DOF.
struct TimeSet {
  std::vector<Dof> responses, forces;
  Eigen::MatrixXd y;  ///< samples × responses
  Eigen::MatrixXd x;  ///< samples × forces
  double dt = 0;      ///< s
};

/// Which time records are forces (docs/identification.md, "Time histories"): those whose
/// ordinate (record 9, field 1) is of type 13, excitation force, dataset 58's code for a
/// force channel; in a file that marks none so, those whose response DOF is their reference
/// DOF (a channel that is its own reference). The reference fields alone cannot decide: a
/// driving-point accelerometer has the force's DOF as both. The others are responses.
bool is_force_record(const std::vector<const uff::Function58*>& records, const uff::Function58& f) {
  constexpr int kExcitationForce = 13;
  const bool typed = std::any_of(records.begin(), records.end(), [](const uff::Function58* r) {
    return r->axes[1].specific_data_type == kExcitationForce;
  });
  return typed ? f.axes[1].specific_data_type == kExcitationForce
               : f.response_node == f.reference_node && f.response_direction == f.reference_direction;
}

/// With `free_decays`, a file without a force record is read too (TimeSet::forces empty).
TimeSet read_time_histories(const uff::UffFile& file, const std::vector<const uff::Function58*>& records,
                            bool free_decays = false) {
  TimeSet s;
  std::vector<const uff::Function58*> in, out;
  const auto* first = records.front();
  for (const auto* f : records) {
    const std::string at = f->where.str() + ": dataset 58";
    if (!f->even) throw formats::InputError(at + ": uneven abscissa (expected evenly spaced time samples)");
    if (f->is_complex()) throw formats::InputError(at + ": complex ordinate (expected a real time history)");
    if (f->y.size() != first->y.size() || f->abscissa_increment != first->abscissa_increment)
      throw formats::InputError(fmt::format("{}: {} samples every {} s (expected {} every {} s as at {})", at,
                                            f->y.size(), f->abscissa_increment, first->y.size(),
                                            first->abscissa_increment, first->where.str()));
    const bool force = is_force_record(records, *f);
    const Dof d{f->response_node, f->response_direction};
    auto& dofs = force ? s.forces : s.responses;
    if (std::find(dofs.begin(), dofs.end(), d) != dofs.end())
      throw formats::InputError(fmt::format("{}: a second {} record at {}:{}", at, force ? "force" : "response",
                                            d.first, d.second));
    dofs.push_back(d);
    (force ? in : out).push_back(f);
  }
  if (!(first->abscissa_increment > 0))
    throw formats::InputError(fmt::format("{}: dataset 58: time increment {} s (expected > 0)", first->where.str(),
                                          first->abscissa_increment));
  if (in.empty() && !free_decays)
    throw formats::InputError(file.path +
                              ": no force record among the time histories (expected dataset 58 of ordinate type 13, "
                              "excitation force, or one whose response DOF is its reference DOF)");
  if (out.empty())
    throw formats::InputError(file.path + ": no response record among the time histories (every one is a force)");
  s.dt = first->abscissa_increment;
  const auto fill = [&](const std::vector<const uff::Function58*>& fs, Eigen::MatrixXd& m) {
    m.resize(static_cast<Eigen::Index>(first->y.size()), static_cast<Eigen::Index>(fs.size()));
    for (std::size_t c = 0; c < fs.size(); ++c)
      for (std::size_t k = 0; k < fs[c]->y.size(); ++k)
        m(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(c)) = fs[c]->y[k].real();
  };
  fill(in, s.x);
  fill(out, s.y);
  return s;
}

/// H1 FRFs of time histories by Welch averaging (Hann window, half overlap).
FrfSet h1_frfs(const uff::UffFile& file, const TimeSet& t, Eigen::Index segment) {
  if (t.y.rows() < segment)
    throw formats::InputError(fmt::format("{}: {} samples per record, fewer than one Welch segment of {} (--segment)",
                                          file.path, t.y.rows(), segment));
  id::WelchOptions wo;
  wo.segment_length = segment;
  const id::FrfEstimate est = id::estimate_frf(t.x, t.y, t.dt, wo, id::FrfEstimator::H1);
  FrfSet s;
  s.responses = t.responses;
  s.references = t.forces;
  s.lines = est.h;
  s.df = 1.0 / (static_cast<double>(segment) * t.dt);
  for (std::size_t k = 0; k < s.lines.size(); ++k)
    if (!s.lines[k].allFinite())
      throw formats::InputError(fmt::format(
          "{}: H1 undefined at {} Hz: the force records do not excite that line (zero, or fully correlated)",
          file.path, est.frequency_hz(static_cast<Eigen::Index>(k))));
  return s;
}

/// Modes of one method, ready for the table, the JSON and UFF 55.
struct Identified {
  struct Mode {
    double hz = 0, zeta = 0, hz_std = 0, zeta_std = 0;
    Eigen::VectorXcd shape;  ///< at `responses`, unit norm, rotated to its best real line
    std::string columns;     ///< the method's own table columns
    nlohmann::json extra;    ///< the method's own JSON fields
    /// σ of each component of the unit shape, RMS over the components (the
    /// spread of the cluster's shapes across orders); NaN: the method gives none.
    double shape_std = std::numeric_limits<double>::quiet_NaN();
  };
  std::string columns_header;  ///< heads `Mode::columns`
  std::vector<Mode> modes;
  std::map<std::string, int> rejected;  ///< poles not kept, per reason
  nlohmann::json summary = nlohmann::json::object();  ///< the method's own top-level JSON fields
  std::vector<std::string> notes;                     ///< for stderr
  /// ERA's or pLSCF's stabilisation diagram (stabilisation_json), null for ARMAX.
  nlohmann::json stabilisation;
  /// ERA, pLSCF: LSFD with the modes' poles over the band, the modal model whose FRFs
  /// the report lays over the measured ones (absent when LSFD could not be made: `fit_note`).
  std::optional<id::LsfdResult> fit;
  std::string fit_note;
};

/// The diagram of `st` over `orders` as JSON: {"criteria", "orders", "poles": [{"order",
/// "hz", "zeta", "class" (o f d v s x: pole_class_symbol), "reason", "mode" (1-based,
/// null when in none)}]}, and "frf_sum" {"hz", "magnitude"}: Σ |H_ij| over every FRF
/// at each line, the curve drawn behind the diagram.
nlohmann::json stabilisation_json(const id::StabilisationResult& st, const std::vector<Eigen::Index>& orders,
                                  const id::StabilisationOptions& so, const nlohmann::json& background) {
  nlohmann::json poles = nlohmann::json::array();
  for (const auto& d : st.diagram)
    poles.push_back({{"order", d.order},
                     {"hz", d.hz},
                     {"zeta", d.zeta},
                     {"class", std::string(1, id::pole_class_symbol(d.cls))},
                     {"reason", id::reject_reason_text(d.reason)},
                     {"mode", d.mode >= 0 ? nlohmann::json(d.mode + 1) : nlohmann::json(nullptr)}});
  return {{"criteria",
           {{"freq_tol", so.freq_tol},
            {"damping_tol", so.damping_tol},
            {"mac_min", so.mac_min},
            {"zeta_max", so.zeta_max},
            {"mpc_min", so.mpc_min},
            {"mpd_max_deg", so.mpd_max_deg},
            {"min_fraction", so.min_fraction}}},
          {"orders", orders},
          {"poles", poles},
          {"frf_sum", background}};
}

/// Σ|H_ij| over every FRF at each line: the curve behind the diagram.
nlohmann::json frf_sum(const FrfSet& s) {
  const Eigen::VectorXd hz = line_hz(s);
  nlohmann::json mag = nlohmann::json::array();
  for (const auto& h : s.lines) mag.push_back(h.cwiseAbs().sum());
  return {{"hz", std::vector<double>(hz.data(), hz.data() + hz.size())}, {"magnitude", mag}, {"of", "FRFs"}};
}

/// For free decays: Σ|Y_i(f)| over the records' discrete Fourier transforms (times dt,
/// lines 0 … N/2), which peak at the modes as FRFs do.
nlohmann::json decay_spectrum_sum(const TimeSet& t) {
  const Eigen::Index n = t.y.rows(), lines = n / 2 + 1;
  Eigen::FFT<double> fft;
  Eigen::VectorXd sum = Eigen::VectorXd::Zero(lines);
  for (Eigen::Index c = 0; c < t.y.cols(); ++c) {
    const Eigen::VectorXd in = t.y.col(c);
    Eigen::VectorXcd spec;
    fft.fwd(spec, in);
    sum += spec.head(lines).cwiseAbs() * t.dt;
  }
  nlohmann::json hz = nlohmann::json::array(), mag = nlohmann::json::array();
  for (Eigen::Index k = 0; k < lines; ++k) {
    hz.push_back(static_cast<double>(k) / (static_cast<double>(n) * t.dt));
    mag.push_back(sum(k));
  }
  return {{"hz", hz}, {"magnitude", mag}, {"of", "free-decay spectra"}};
}

/// ERA at the orders 2, 4, … max_order of Markov parameters `Y` sampled every `dt`, the
/// stabilisation diagram's modes, and the diagram drawn over `background`.
Identified era_identified(const std::vector<Eigen::MatrixXd>& Y, double dt, int max_order,
                          const id::StabilisationOptions& so, const nlohmann::json& background,
                          std::vector<id::OrderPoles>& poles, id::StabilisationResult& st) {
  id::EraOptions eo;
  eo.dt = dt;
  std::vector<Eigen::Index> orders;
  for (int n = 2; n <= max_order; n += 2) orders.push_back(n);
  const std::vector<id::EraResult> realizations = id::era_orders(Y, eo, orders);
  poles = id::order_poles(realizations);
  st = id::stabilise(poles, so);
  Identified r;
  // Exact (noise-free) data of a model of order n give no realization above n, so no pole
  // can recur across orders: say so rather than leave "no mode" unexplained.
  if (st.modes.empty() && !realizations.empty()) {
    const Eigen::VectorXd& sv = realizations.front().singular_values;
    const auto rank = (sv.array() > sv(0) * 1e-13).count();
    if (rank < max_order)
      r.notes.push_back(fmt::format(
          "the records' Hankel matrix has numerical rank {} (below the largest order {}): data without noise of a "
          "model of order {}; no pole recurs across orders above it, which the stabilisation diagram needs",
          rank, max_order, rank));
  }
  r.columns_header = "     MPC  orders";
  for (const auto& d : st.diagram)
    if (d.reason != id::RejectReason::None) ++r.rejected[id::reject_reason_text(d.reason)];
  for (const id::ClusteredMode& md : st.modes) {
    r.modes.push_back({md.hz, md.zeta, md.hz_std, md.zeta_std, id::rotate_to_real(md.shape),
                       fmt::format(" {:7.4f} {:7d}", md.mpc, md.poles), {{"mpc", md.mpc}, {"orders", md.poles}}});
    // On the unit shape, as the estimator's σ is (deck_study.hpp).
    if (md.shape_std.size() && md.shape.norm() > 0)
      r.modes.back().shape_std =
          md.shape_std.norm() / std::sqrt(static_cast<double>(md.shape_std.size())) / md.shape.norm();
  }
  r.stabilisation = stabilisation_json(st, orders, so, background);
  return r;
}

/// ERA on FRFs: the impulse response over one period (markov_from_frf), its first half
/// (the least wrap-around) from its second sample on; then LSFD with the modes' poles
/// for their FRFs. The first sample is left out because it holds the FRF's direct
/// term: an accelerance tends to a constant (the mass line) above its modes, an
/// impulse at t = 0 that is no C AᵏB, and a Hankel matrix holding it realizes
/// nothing but over-damped poles. From the second on, Y[k] = C Aᵏ⁻¹ (A B): the same
/// poles and output shapes (the participations gain each pole's e^{λΔt}, a factor
/// LSFD's residues absorb).
Identified era_modes(const FrfSet& s, int max_order, const id::PlscfOptions& band, const id::StabilisationOptions& so) {
  const auto Y = id::markov_from_frf(s.lines, s.df);
  const double dt = 1.0 / (static_cast<double>(Y.size()) * s.df);
  const std::vector<Eigen::MatrixXd> head(Y.begin() + 1, Y.begin() + static_cast<std::ptrdiff_t>(Y.size() / 2));
  std::vector<id::OrderPoles> poles;
  id::StabilisationResult st;
  Identified r = era_identified(head, dt, max_order, so, frf_sum(s), poles, st);
  // The FRFs of the identified modes: ERA's poles and participation factors, their
  // residues and the residual terms by LSFD over the band (the table keeps ERA's shapes).
  if (!st.modes.empty()) {
    try {
      r.fit = id::lsfd(line_hz(s), s.lines, id::mode_poles(st, poles), band);
    } catch (const formats::InputError& e) {
      r.fit_note = e.what();
    }
  }
  return r;
}

/// For the report: the test geometry of `g` (nodes in global, trace lines of dataset 82)
/// as j["geometry"] {"grids", "lines": [], "test_lines"}, and each identified mode's shape
/// (the real part of the unit shape, each measured direction turned to global by its
/// node's displacement system) at the measured nodes as j["identified_shapes"]
/// [{"mode", "hz", "points": [[node, dx, dy, dz]]}]; j["geometry_note"] says why not, when
/// the geometry has no nodes or no trace lines.
void add_test_geometry(nlohmann::json& j, const uff::UffFile& g, const Identified& r, const std::vector<Dof>& responses) {
  const std::vector<uff::Node> nodes = g.nodes_in_global();
  const translators::NodeSegments traces = translators::trace_segments(g);
  if (nodes.empty() || traces.empty()) {
    j["geometry_note"] = fmt::format("{}: {}; the identified shapes are not drawn (--geometry FILE.unv names a "
                                     "universal file with the test's nodes, dataset 15 or 2411, and trace lines, 82)",
                                     g.path, nodes.empty() ? "no nodes" : "no trace lines");
    return;
  }
  std::set<std::int64_t> ids;
  nlohmann::json grids = nlohmann::json::array(), lines = nlohmann::json::array();
  for (const auto& n : nodes) {
    ids.insert(n.id);
    grids.push_back({n.id, n.xyz[0], n.xyz[1], n.xyz[2]});
  }
  // Nodes of the originals (displacement systems), for direction_in_global.
  std::map<std::int64_t, uff::Node> original;
  for (const auto& n : g.nodes()) original[n.id] = n;
  for (const auto& [a, b] : traces)
    if (ids.count(a) && ids.count(b)) lines.push_back({a, b});
  j["geometry"] = {{"grids", grids}, {"lines", nlohmann::json::array()}, {"test_lines", lines}};
  nlohmann::json shapes = nlohmann::json::array();
  for (std::size_t m = 0; m < r.modes.size(); ++m) {
    std::map<std::int64_t, Eigen::Vector3d> at;
    for (std::size_t o = 0; o < responses.size(); ++o) {
      const auto [node, dir] = responses[o];
      const auto it = original.find(node);
      if (it == original.end() || std::abs(dir) < 1 || std::abs(dir) > 3) continue;
      const auto e = g.direction_in_global(it->second, dir);  // a −X response counts along −X
      const double v = r.modes[m].shape(static_cast<Eigen::Index>(o)).real();
      auto& p = at.try_emplace(node, Eigen::Vector3d::Zero()).first->second;
      p += v * Eigen::Vector3d(e[0], e[1], e[2]);
    }
    nlohmann::json points = nlohmann::json::array();
    for (const auto& [node, p] : at) points.push_back({node, p.x(), p.y(), p.z()});
    shapes.push_back({{"mode", m + 1}, {"hz", r.modes[m].hz}, {"points", points}});
  }
  j["identified_shapes"] = shapes;
}

/// ERA on free decays: every response record together as one decay, Markov parameters
/// Y[k] = y(k·dt) (no × 1; markov_from_records), the diagram over the records' spectra.
Identified era_decay_modes(const TimeSet& t, int max_order, const id::StabilisationOptions& so) {
  std::vector<id::OrderPoles> poles;
  id::StabilisationResult st;
  return era_identified(id::markov_from_records(t.y), t.dt, max_order, so, decay_spectrum_sum(t), poles, st);
}

/// pLSCF at the polynomial orders 1 … max_order over the band, the stabilisation diagram's
/// modes, and their shapes by LSFD (with lower and upper residuals) over the same band. A
/// mode's frequency and damping are its pole at the highest order of its cluster (mode_poles),
/// the ± its cluster's spread over the orders.
Identified plscf_modes(const FrfSet& s, int max_order, const id::PlscfOptions& band,
                       const id::StabilisationOptions& so, const estimator::Progress& progress) {
  const Eigen::VectorXd hz = line_hz(s);
  std::vector<Eigen::Index> orders;
  for (int p = 1; p <= max_order; ++p) orders.push_back(p);
  const std::vector<id::OrderPoles> poles = id::plscf_orders(hz, s.lines, band, orders, progress);
  const id::StabilisationResult st = id::stabilise(poles, so);
  Identified r;
  r.columns_header = "     MPC     MPD  orders";
  for (const auto& d : st.diagram)
    if (d.reason != id::RejectReason::None) ++r.rejected[id::reject_reason_text(d.reason)];
  r.stabilisation = stabilisation_json(st, orders, so, frf_sum(s));
  if (st.modes.empty()) return r;
  const id::LsfdResult fit = id::lsfd(hz, s.lines, id::mode_poles(st, poles), band);
  for (std::size_t m = 0; m < st.modes.size(); ++m) {
    const id::ClusteredMode& md = st.modes[m];
    const id::IdentifiedPole& p = fit.modes[m];
    r.modes.push_back({p.hz, p.zeta, md.hz_std, md.zeta_std, id::rotate_to_real(p.shape.normalized()),
                       fmt::format(" {:7.4f} {:7.2f} {:7d}", p.mpc, p.mpd, md.poles),
                       {{"mpc", p.mpc}, {"mpd", p.mpd}, {"orders", md.poles}}});
    // The spread of the cluster's shapes over the orders, on the unit shape (as ERA's).
    if (md.shape_std.size() && md.shape.norm() > 0)
      r.modes.back().shape_std =
          md.shape_std.norm() / std::sqrt(static_cast<double>(md.shape_std.size())) / md.shape.norm();
  }
  r.summary["lsfd_fit_error"] = fit.fit_error;
  r.fit = fit;
  return r;
}

/// The measured FRFs against those of the identified modal model (LSFD, lsfd_synthesis)
/// over the band's lines (above 0 Hz): {"model", "fit_error", "band_hz": [first, last line],
/// "unit", "records": [{"response": [node, dir], "reference": [node, dir], "frac"}]}, and
/// with `curves` the lines ("hz") and each record's "measured" and "synthesized" {"re", "im"}.
nlohmann::json frf_fit_json(const FrfSet& s, const id::LsfdResult& fit, const id::PlscfOptions& band, bool curves) {
  const Eigen::VectorXd all = line_hz(s);
  std::vector<Eigen::Index> lines;
  for (Eigen::Index k = 0; k < all.size(); ++k)
    if (all(k) > 0 && all(k) >= band.hz_min && all(k) <= band.hz_max) lines.push_back(k);
  Eigen::VectorXd hz(static_cast<Eigen::Index>(lines.size()));
  for (std::size_t k = 0; k < lines.size(); ++k) hz(static_cast<Eigen::Index>(k)) = all(lines[k]);
  const std::vector<Eigen::MatrixXcd> model = id::lsfd_synthesis(hz, fit);
  nlohmann::json j{{"model", "LSFD on the identified poles with lower and upper residuals"},
                   {"fit_error", fit.fit_error},
                   {"band_hz", {hz(0), hz(hz.size() - 1)}},
                   {"unit", s.unit},
                   {"records", nlohmann::json::array()}};
  if (curves) j["hz"] = std::vector<double>(hz.data(), hz.data() + hz.size());
  for (std::size_t o = 0; o < s.responses.size(); ++o)
    for (std::size_t i = 0; i < s.references.size(); ++i) {
      const auto oi = static_cast<Eigen::Index>(o), ii = static_cast<Eigen::Index>(i);
      Eigen::VectorXcd measured(hz.size()), synthesized(hz.size());
      for (std::size_t k = 0; k < lines.size(); ++k) {
        measured(static_cast<Eigen::Index>(k)) = s.lines[static_cast<std::size_t>(lines[k])](oi, ii);
        synthesized(static_cast<Eigen::Index>(k)) = model[k](oi, ii);
      }
      const double frac = id::frf_assurance(measured, synthesized);
      nlohmann::json rec{{"response", {s.responses[o].first, s.responses[o].second}},
                         {"reference", {s.references[i].first, s.references[i].second}},
                         {"frac", std::isfinite(frac) ? nlohmann::json(frac) : nlohmann::json(nullptr)}};
      if (curves) {
        auto parts = [](const Eigen::VectorXcd& v) {
          std::vector<double> re(static_cast<std::size_t>(v.size())), im(re.size());
          for (Eigen::Index k = 0; k < v.size(); ++k) re[static_cast<std::size_t>(k)] = v(k).real(), im[static_cast<std::size_t>(k)] = v(k).imag();
          return nlohmann::json{{"re", re}, {"im", im}};
        };
        rec["measured"] = parts(measured);
        rec["synthesized"] = parts(synthesized);
      }
      j["records"].push_back(rec);
    }
  return j;
}

/// One line on the FRFs of the identified modes: the worst and mean FRAC.
void print_frf_fit(std::ostream& o, const nlohmann::json& fit) {
  double worst = 2, sum = 0;
  int n = 0;
  const nlohmann::json* at = nullptr;
  for (const auto& r : fit["records"]) {
    if (r["frac"].is_null()) continue;
    const double v = r["frac"];
    sum += v;
    ++n;
    if (v < worst) worst = v, at = &r;
  }
  if (!at) return;
  o << fmt::format("FRFs of the identified modes (LSFD with residuals, {:g}…{:g} Hz): FRAC mean {:.4f}, lowest {:.4f} "
                   "(response {}:{}, reference {}:{}); {:.3g} of the FRFs unexplained (relative Frobenius norm)\n",
                   fit["band_hz"][0].get<double>(), fit["band_hz"][1].get<double>(), sum / n, worst,
                   (*at)["response"][0].get<long>(), (*at)["response"][1].get<int>(), (*at)["reference"][0].get<long>(),
                   (*at)["reference"][1].get<int>(), fit["fit_error"].get<double>());
}

/// `--subsets "N:D,N:D;N:D"`: subsets of the response records named by their DOFs
/// (semicolon between subsets, comma within), as 0-based columns of `responses`;
/// `option` names the option in messages (--responses gives one subset this way).
std::vector<std::vector<int>> parse_subsets(const std::string& text, const std::vector<Dof>& responses,
                                            const std::string& option = "--subsets") {
  std::vector<std::vector<int>> out;
  std::stringstream all(text);
  for (std::string item; std::getline(all, item, ';');) {
    std::vector<int> subset;
    std::stringstream one(item);
    for (std::string dof; std::getline(one, dof, ',');) {
      const auto colon = dof.find(':');
      long node = 0;
      int dir = 0;
      try {
        std::size_t a = 0, b = 0;
        if (colon == std::string::npos) throw std::invalid_argument("no colon");
        node = std::stol(dof.substr(0, colon), &a);
        dir = std::stoi(dof.substr(colon + 1), &b);
        if (a != colon || b != dof.size() - colon - 1) throw std::invalid_argument("trailing text");
      } catch (const std::logic_error&) {
        throw formats::InputError(fmt::format("{}: \"{}\": expected NODE:DIRECTION, e.g. 12:3", option, dof));
      }
      const auto it = std::find(responses.begin(), responses.end(), Dof{node, dir});
      if (it == responses.end())
        throw formats::InputError(fmt::format("{}: {}:{} is not a response record of the file", option, node, dir));
      const int col = static_cast<int>(it - responses.begin());
      if (std::find(subset.begin(), subset.end(), col) != subset.end())
        throw formats::InputError(fmt::format("{}: {}:{} twice in one subset", option, node, dir));
      subset.push_back(col);
    }
    if (subset.empty()) throw formats::InputError(option + ": an empty subset in \"" + text + "\"");
    out.push_back(subset);
  }
  if (out.empty()) throw formats::InputError(option + ": no subset given");
  return out;
}

/// The ARMAX runs: all p responses at (s, m), then each subset of q responses at
/// (⌈s·p/q⌉, ⌈m·p/q⌉), which keeps the AR parameters per run as the paper's single-response
/// runs at (p·s, p·m) do; without subsets, each response alone.
std::vector<id::ArmaxRun> armax_runs(int p, const id::ArmaxOptions& all, const std::vector<std::vector<int>>& subsets) {
  if (subsets.empty()) return id::single_output_runs(p, all);
  std::vector<id::ArmaxRun> runs{{{}, all}};
  for (int j = 0; j < p; ++j) runs[0].outputs.push_back(j);
  for (const auto& sub : subsets) {
    const int q = static_cast<int>(sub.size());
    id::ArmaxRun r{sub, all};
    r.options.ar_order = (all.ar_order * p + q - 1) / q;
    r.options.arx_order = (all.arx_order * p + q - 1) / q;
    runs.push_back(r);
  }
  return runs;
}

/// The spread of a recurring mode's shape over the runs, on the unit shape (as ERA's and
/// pLSCF's shape_std): each run of two or more responses gives the shape at its responses,
/// scaled onto the all-responses run's by least squares over them; per response the
/// sample standard deviation of the values the runs give it (the all-responses run's
/// included), RMS over the responses that two or more runs give. NaN when no run but the
/// first has two responses (single-response runs carry no shape information: their one
/// component scales onto anything).
double armax_shape_spread(const id::ArmaxOrderResult& res, const id::RecurringMode& md) {
  using cd = std::complex<double>;
  const auto& ref_outputs = res.runs.front().outputs;
  const Eigen::VectorXcd ref = md.shape / md.shape.norm();
  std::vector<std::vector<cd>> values(ref_outputs.size());
  for (std::size_t o = 0; o < ref_outputs.size(); ++o) values[o].push_back(ref(static_cast<Eigen::Index>(o)));
  for (std::size_t k = 1; k < res.runs.size() && k < md.pole.size(); ++k) {
    const auto& outs = res.runs[k].outputs;
    if (outs.size() < 2) continue;
    const Eigen::VectorXcd& psi = res.models[k].poles.at(md.pole[k]).shape;
    Eigen::VectorXcd target(static_cast<Eigen::Index>(outs.size()));
    std::vector<std::size_t> at(outs.size());
    for (std::size_t i = 0; i < outs.size(); ++i) {
      at[i] = static_cast<std::size_t>(std::find(ref_outputs.begin(), ref_outputs.end(), outs[i]) - ref_outputs.begin());
      target(static_cast<Eigen::Index>(i)) = ref(static_cast<Eigen::Index>(at[i]));
    }
    const cd den = psi.squaredNorm();
    if (std::abs(den) == 0) continue;
    const cd c = psi.dot(target) / den;  // ψᴴ target / ψᴴψ
    for (std::size_t i = 0; i < outs.size(); ++i) values[at[i]].push_back(c * psi(static_cast<Eigen::Index>(i)));
  }
  double sum = 0;
  int n = 0;
  for (const auto& v : values) {
    if (v.size() < 2) continue;
    cd mean = 0;
    for (const auto& x : v) mean += x;
    mean /= static_cast<double>(v.size());
    double var = 0;
    for (const auto& x : v) var += std::norm(x - mean);
    sum += var / static_cast<double>(v.size() - 1);
    ++n;
  }
  return n > 0 ? std::sqrt(sum / n) : std::numeric_limits<double>::quiet_NaN();
}

/// The multistage ARMAX's `runs` (armax_runs: all responses at (s, m), then each alone at
/// (p·s, p·m) or the subsets): the modes found in every run (armax_model_order), within
/// [hz_min, hz_max].
Identified armax_modes(const TimeSet& t, const std::vector<id::ArmaxRun>& runs, const id::StabilisationOptions& so,
                       std::vector<std::string>& warnings) {
  const id::ArmaxOrderResult res = id::armax_model_order(t.y, t.x, t.dt, runs, {});
  for (std::size_t k = 0; k < res.models.size(); ++k)
    if (!res.models[k].converged)
      warnings.push_back(fmt::format("ARMAX run {} did not converge in {} passes (its best pass is used)", k + 1,
                                     res.models[k].iterations));
  Identified r;
  r.columns_header = "  runs";
  r.summary["armax_runs"] = nlohmann::json::array();
  for (const auto& run : res.runs) {
    nlohmann::json outs = nlohmann::json::array();
    for (int c : run.outputs)
      outs.push_back({t.responses[static_cast<std::size_t>(c)].first, t.responses[static_cast<std::size_t>(c)].second});
    r.summary["armax_runs"].push_back(
        {{"responses", outs}, {"ar_order", run.options.ar_order}, {"arx_order", run.options.arx_order}});
  }
  for (const auto& p : res.rejected) ++r.rejected[p.reason];
  for (const id::RecurringMode& md : res.modes) {
    if (md.hz_mean < so.hz_min || md.hz_mean > so.hz_max) {
      ++r.rejected["outside --min-hz/--max-hz"];
      continue;
    }
    r.modes.push_back({md.hz_mean, md.zeta_mean, md.hz_std, md.zeta_std, id::rotate_to_real(md.shape.normalized()),
                       fmt::format(" {:5d}", res.models.size()), {{"runs", res.models.size()}}});
    r.modes.back().shape_std = armax_shape_spread(res, md);
  }
  return r;
}

/// `--method armax` on time histories `t` (read from `path`): the records --responses
/// names (default all), the runs of the order rule (all of them at s, m, then --subsets
/// or each alone), refused before it starts when a run would hold more than half this
/// machine's memory; the modes into `r`, their DOFs into `responses`.
void armax_modes_of(const TimeSet& all_records, const po::variables_map& vm, const std::string& path,
                    std::ostream& text, Identified& r, std::vector<Dof>& responses,
                    const id::StabilisationOptions& so, std::vector<std::string>& warnings) {
  TimeSet t = all_records;
  if (vm.count("responses")) {
    const auto chosen = parse_subsets(vm["responses"].as<std::string>(), all_records.responses, "--responses");
    if (chosen.size() != 1)
      throw formats::InputError("--responses: one list of records (comma between them), got " +
                                std::to_string(chosen.size()) + " (';' separates --subsets' lists)");
    t.responses.clear();
    t.y.resize(all_records.y.rows(), static_cast<Eigen::Index>(chosen[0].size()));
    for (std::size_t k = 0; k < chosen[0].size(); ++k) {
      t.responses.push_back(all_records.responses[static_cast<std::size_t>(chosen[0][k])]);
      t.y.col(static_cast<Eigen::Index>(k)) = all_records.y.col(chosen[0][k]);
    }
    text << fmt::format("ARMAX on {} of them (--responses); ", t.responses.size());
  }
  responses = t.responses;
  const auto p = static_cast<int>(t.responses.size());
  if (p < 2)
    throw formats::InputError(path + ": --method armax needs at least two response records (the order rule "
                                     "compares the identification from all of them with each one's)");
  const int s = vm.count("ar-order") ? vm["ar-order"].as<int>() : (12 + p - 1) / p;
  const int m = vm.count("arx-order") ? vm["arx-order"].as<int>() : (90 + p - 1) / p;
  std::vector<std::vector<int>> subsets;
  if (vm.count("subsets")) subsets = parse_subsets(vm["subsets"].as<std::string>(), t.responses);
  id::ArmaxOptions options;
  options.ar_order = s;
  options.arx_order = m;
  const std::vector<id::ArmaxRun> runs = armax_runs(p, options, subsets);
  // A run that cannot fit is refused now, with what would, rather than ended by the
  // allocator (or the kernel) after minutes.
  const double memory = static_cast<double>(::sysconf(_SC_PHYS_PAGES)) * static_cast<double>(::sysconf(_SC_PAGE_SIZE));
  for (const auto& run : runs) {
    const double need = id::armax_memory_bytes(t.y.rows(), static_cast<Eigen::Index>(run.outputs.size()),
                                               static_cast<Eigen::Index>(t.forces.size()), run.options.ar_order);
    if (memory > 0 && need > memory / 2)
      throw formats::InputError(fmt::format(
          "{}: --method armax on {} response record(s) at AR order {} would hold {:.1f} GiB in its step 3 (it grows as "
          "p³ × samples; this machine has {:.1f} GiB): choose a few records with --responses (the paper used 1 or 2), "
          "or identify all of them with --method era or plscf",
          path, run.outputs.size(), run.options.ar_order, need / 1073741824.0, memory / 1073741824.0));
  }
  if (subsets.empty()) {
    text << fmt::format("ARMAX orders s = {}, m = {} on all responses, then {}, {} on each\n", s, m,
                        runs.back().options.ar_order, runs.back().options.arx_order);
  } else {
    text << fmt::format("ARMAX orders s = {}, m = {} on all responses, then on {} subset(s):", s, m, subsets.size());
    for (std::size_t k = 1; k < runs.size(); ++k) {
      std::string names;
      for (int c : runs[k].outputs) names += (names.empty() ? "" : ",") + dof_text(t.responses[static_cast<std::size_t>(c)]);
      text << fmt::format(" {{{}}} at {}, {};", names, runs[k].options.ar_order, runs[k].options.arx_order);
    }
    text << "\n";
  }
  try {
    r = armax_modes(t, runs, so, warnings);
  } catch (const formats::InputError& e) {
    // The estimator names the records by column; the file is what the user can act on.
    throw formats::InputError(path + ": " + e.what());
  }
}

int identify_modes(const Args& args) {
  po::options_description desc("ssid identify modes options");
  desc.add_options()("file", po::value<std::string>()->required(),
                     "universal file with FRFs (dataset 58, type 4) or time histories (type 1)")(
      "method", po::value<std::string>()->default_value("era"),
      "identification method: armax (time histories), era or plscf")(
      "json", po::value<std::string>(), "write the modes as JSON to this file ('-' for stdout)")(
      "uff", po::value<std::string>(), "write the modes as real normal modes, UFF dataset 55")(
      "svg", po::value<std::string>(), "era, plscf: write the stabilisation diagram as SVG to this file")(
      "report", po::value<std::string>(),
      "write an HTML report (stabilisation diagram, the modes' table, the FRF overlays, the shapes on the test "
      "geometry) to this file (docs/report.md)")(
      "geometry", po::value<std::string>(),
      "--report: universal file with the test geometry (nodes: 15/2411, trace lines: 82, coordinate systems: "
      "18/2420) to draw the identified shapes on (default: the input file's own)")(
      "max-order", po::value<int>()->default_value(40),
      "largest model order: era: state dimension, even; plscf: polynomial order")(
      "segment", po::value<int>()->default_value(1024), "era, plscf on time histories: Welch segment, samples")(
      "ar-order", po::value<int>(), "armax: AR order s with all p responses (default ⌈12/p⌉)")(
      "arx-order", po::value<int>(), "armax: prior ARX order m with all p responses (default ⌈90/p⌉)")(
      "responses", po::value<std::string>(),
      "armax: the response records it uses, e.g. \"1:1,2:1,3:3\" (NODE:DIRECTION; default: all). Its step 3 "
      "grows as p³ in memory: a few responses, not a test's hundreds; the shapes are then at these DOFs only")(
      "subsets", po::value<std::string>(),
      "armax: the order rule's runs besides all responses, as subsets of the response records, e.g. "
      "\"1:1,2:1;2:1,3:1\" (NODE:DIRECTION, ';' between subsets); a subset of q records runs at orders "
      "⌈s·p/q⌉, ⌈m·p/q⌉ (default: each record alone)")(
      "min-hz", po::value<double>()->default_value(0.0, "0"),
      "keep modes from this frequency, Hz (plscf: also the fitted band's start)")(
      "max-hz", po::value<double>(),
      "keep modes up to this frequency, Hz (default: all; plscf: also the fitted band's end)");
  po::positional_options_description pos;
  pos.add("file", 1);
  po::variables_map vm;
  int rc = 0;
  if (!parse_options(args,
                     "ssid identify modes FILE.unv [--method armax|era|plscf] [--json OUT] [--uff OUT] [--svg OUT.svg] "
                     "[--report OUT.html] [--geometry GEOMETRY.unv] [--max-order N] [--segment N] [--ar-order S] [--arx-order M] [--responses LIST] [--subsets LIST] [--min-hz F] [--max-hz F]",
                     desc, pos, vm, rc))
    return rc;
  const std::string method = vm["method"].as<std::string>();
  if (method != "era" && method != "armax" && method != "plscf") {
    print_error("--method: expected armax, era or plscf, got \"" + method + "\"");
    return 2;
  }
  const int max_order = vm["max-order"].as<int>();
  if (method == "plscf" ? max_order < 1 : (max_order < 2 || max_order % 2)) {
    print_error(fmt::format("--max-order: expected {}, got {}",
                            method == "plscf" ? "an order ≥ 1" : "an even number ≥ 2", max_order));
    return 2;
  }
  const int segment = vm["segment"].as<int>();
  if (segment < 8) {
    print_error(fmt::format("--segment: expected at least 8 samples, got {}", segment));
    return 2;
  }
  for (const char* name : {"ar-order", "arx-order"})
    if (vm.count(name) && vm[name].as<int>() < 1) {
      print_error(fmt::format("--{}: expected an order ≥ 1, got {}", name, vm[name].as<int>()));
      return 2;
    }
  if (vm.count("responses") && method != "armax") {
    print_error("--responses: chooses ARMAX's records (--method armax); era and plscf use every response");
    return 2;
  }
  if (vm.count("subsets") && method != "armax") {
    print_error("--subsets: the order rule's runs are ARMAX's (--method armax)");
    return 2;
  }
  if (vm.count("svg") && method == "armax") {
    print_error("--svg: the stabilisation diagram is ERA's and pLSCF's (--method era|plscf); ARMAX's modes come from "
                "runs, not orders");
    return 2;
  }
  id::StabilisationOptions so;
  so.hz_min = vm["min-hz"].as<double>();
  if (vm.count("max-hz")) so.hz_max = vm["max-hz"].as<double>();
  id::PlscfOptions band;
  band.hz_min = so.hz_min;
  if (vm.count("max-hz")) band.hz_max = so.hz_max;
  // With --json -, stdout carries the JSON alone (as every command's --json -): no table.
  TextOut text_out(vm);
  std::ostream& text = text_out.stream();
  ProgressLines progress_lines("ssid identify", false, 2.0, 2.0);
  // ERA or pLSCF on FRFs, with the text that ends the input's description line.
  const auto frf_method = [&](const FrfSet& s) {
    if (method == "plscf") {
      text << fmt::format("pLSCF orders 1…{}\n", max_order);
      return plscf_modes(s, max_order, band, so, progress_lines.callback());
    }
    text << fmt::format("ERA orders 2…{}\n", max_order);
    return era_modes(s, max_order, band, so);
  };

  const uff::UffFile file = uff::read_uff(vm["file"].as<std::string>());
  std::vector<const uff::Function58*> frf_records, time_records;
  for (const auto* f : file.functions()) {
    if (f->function_type == 4) frf_records.push_back(f);
    if (f->function_type == 1) time_records.push_back(f);
  }
  if (frf_records.empty() && time_records.empty())
    throw formats::InputError(file.path +
                              ": no frequency response functions or time histories (dataset 58, function type 4 or 1)");
  if (!frf_records.empty() && !time_records.empty())
    throw formats::InputError(fmt::format(
        "{}: both FRFs ({}, first at {}) and time histories ({}, first at {}); expected one kind", file.path,
        frf_records.size(), frf_records.front()->where.str(), time_records.size(), time_records.front()->where.str()));
  if (method == "armax" && time_records.empty())
    throw formats::InputError(file.path + ": --method armax needs time histories (dataset 58, function type 1); "
                                          "the file has FRFs only");

  Identified r;
  std::vector<Dof> responses;
  std::vector<std::string> warnings;
  std::optional<FrfSet> frfs;  // the FRFs ERA or pLSCF identified from
  if (time_records.empty()) {
    const FrfSet& s = frfs.emplace(read_frfs(file, frf_records));
    text << fmt::format("{} FRF(s): {} response(s) × {} reference(s), {} lines every {} Hz; ",
                             s.responses.size() * s.references.size(), s.responses.size(), s.references.size(),
                             s.lines.size(), s.df);
    r = frf_method(s);
    responses = s.responses;
  } else {
    const TimeSet t = read_time_histories(file, time_records, true);
    responses = t.responses;
    const auto p = static_cast<int>(t.responses.size());
    if (t.forces.empty()) {
      // Free decays (no record is a force): ERA on the records themselves.
      if (method != "era")
        throw formats::InputError(fmt::format(
            "{}: no force record among the time histories (expected dataset 58 of ordinate type 13, excitation force, "
            "or one whose response DOF is its reference DOF): free decays, which --method {} cannot use without the "
            "forces; --method era identifies free decays",
            file.path, method));
      text << fmt::format("{} time histories: {} response(s), no force: free decays, {} samples every {} s; ERA orders 2…{}\n",
                          time_records.size(), p, t.y.rows(), t.dt, max_order);
      r = era_decay_modes(t, max_order, so);
    } else if (method != "armax") {
      text << fmt::format("{} time histories: {} response(s), {} force(s), {} samples every {} s; ",
                          time_records.size(), p, t.forces.size(), t.y.rows(), t.dt);
      const FrfSet& s = frfs.emplace(h1_frfs(file, t, segment));
      text << fmt::format("H1 by Welch ({} samples, Hann, half overlap): {} lines every {} Hz; ", segment,
                               s.lines.size(), s.df);
      r = frf_method(s);
    } else {
      text << fmt::format("{} time histories: {} response(s), {} force(s), {} samples every {} s; ",
                          time_records.size(), p, t.forces.size(), t.y.rows(), t.dt);
      armax_modes_of(t, vm, file.path, text, r, responses, so, warnings);
    }
  }

  text << "mode   frequency (Hz)      ± (Hz)   damping (%)     ± (%)" << r.columns_header << "\n";
  std::vector<std::int64_t> nodes;
  for (const auto& d : responses)
    if (std::find(nodes.begin(), nodes.end(), d.first) == nodes.end()) nodes.push_back(d.first);
  nlohmann::json modes = nlohmann::json::array();
  uff::UffFile out;
  bool rotations_dropped = false;
  for (std::size_t m = 0; m < r.modes.size(); ++m) {
    const Identified::Mode& md = r.modes[m];
    text << fmt::format("{:4d} {:16.6f} {:11.3e} {:13.4f} {:9.3e}{}\n", m + 1, md.hz, md.hz_std, 100 * md.zeta,
                             100 * md.zeta_std, md.columns);
    nlohmann::json shape = nlohmann::json::array();
    Eigen::MatrixXd values = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(nodes.size()), 3);
    for (std::size_t o = 0; o < responses.size(); ++o) {
      const auto [node, dir] = responses[o];
      const double sign = dir < 0 ? -1.0 : 1.0;
      const std::complex<double> v = sign * md.shape(static_cast<Eigen::Index>(o));
      shape.push_back({node, std::abs(dir), v.real(), v.imag()});
      if (std::abs(dir) >= 1 && std::abs(dir) <= 3) {
        const auto row = std::find(nodes.begin(), nodes.end(), node) - nodes.begin();
        values(row, std::abs(dir) - 1) = v.real();
      } else {
        rotations_dropped = true;
      }
    }
    nlohmann::json j = {
        {"hz", md.hz}, {"zeta", md.zeta}, {"hz_std", md.hz_std}, {"zeta_std", md.zeta_std}, {"shape", shape}};
    if (std::isfinite(md.shape_std)) j["shape_std"] = md.shape_std;
    j.update(md.extra);
    if (!j.contains("mpc")) j["mpc"] = id::modal_phase_collinearity(md.shape);
    j["mpd_deg"] = id::mean_phase_deviation(md.shape);
    modes.push_back(j);
    out.datasets.emplace_back(uff::NodalData55::normal_mode(static_cast<std::int64_t>(m + 1), md.hz, nodes, values,
                                                            0.0, md.zeta));
  }
  if (r.modes.empty())
    text << (method == "armax" ? "(no mode found in every run)\n" : "(no mode stable across the orders)\n");
  std::cerr << "note: poles not kept:";
  for (const auto& [reason, count] : r.rejected) std::cerr << " " << reason << " " << count << ";";
  std::cerr << "\n";
  for (const auto& n : r.notes) std::cerr << "note: " << n << "\n";
  for (const auto& w : warnings) std::cerr << "warning: " << w << "\n";
  if (rotations_dropped) std::cerr << "warning: rotational responses are in the JSON only (UFF 55 gets X, Y, Z)\n";

  nlohmann::json j;
  j["modes"] = modes;
  j["method"] = method;
  j["rejected"] = r.rejected;
  j.update(r.summary);
  if (!r.stabilisation.is_null()) j["stabilisation"] = r.stabilisation;
  if (frfs && r.fit) {
    j["frf_fit"] = frf_fit_json(*frfs, *r.fit, band, vm.count("report") > 0);
    print_frf_fit(text, j["frf_fit"]);
  } else if (frfs && !r.fit_note.empty()) {
    std::cerr << "note: no FRFs of the identified modes: " << r.fit_note << "\n";
  }
  if (vm.count("report")) {
    std::vector<std::string> inputs{vm["file"].as<std::string>()};
    const uff::UffFile* geometry = &file;
    uff::UffFile other;
    if (vm.count("geometry")) {
      other = uff::read_uff(vm["geometry"].as<std::string>());
      geometry = &other;
      inputs.push_back(other.path);
    }
    add_test_geometry(j, *geometry, r, responses);
    j["run"] = report::run_json("identify modes", args, inputs);
  }
  if (vm.count("json")) write_json(vm["json"].as<std::string>(), j);
  if (vm.count("svg")) {
    const std::string path = vm["svg"].as<std::string>();
    std::ofstream o(path, std::ios::binary);
    o << report::stabilisation_svg(j, true);
    if (!o) throw formats::InputError("cannot write " + path);
  }
  if (vm.count("report")) report::write_report(vm["report"].as<std::string>(), j);
  if (vm.count("uff")) {
    out.path = vm["uff"].as<std::string>();
    uff::write_uff(out, out.path);
  }
  return 0;
}

/// `ssid identify frf`: FRFs, coherence and multiple coherence from time histories.
int identify_frf(const Args& args) {
  po::options_description desc("ssid identify frf options");
  desc.add_options()("file", po::value<std::string>()->required(),
                     "universal file with time histories (dataset 58, function type 1), forces marked as for "
                     "ssid identify modes")(
      "estimator", po::value<std::string>()->default_value("h1"),
      "h1 (noise on the responses; several references), h2 (noise on the force; one reference) or hv (both)")(
      "window", po::value<std::string>()->default_value("hann"),
      "hann, flattop, rect, or force-exp (impact: force window on the forces, exponential on the responses)")(
      "segment", po::value<int>()->default_value(1024), "Welch segment length, samples")(
      "overlap", po::value<double>(), "overlap of the segments, a fraction in [0, 1) (default 0.5; force-exp: 0)")(
      "force-fraction", po::value<double>()->default_value(0.1, "0.1"),
      "force-exp: the share of each segment the force window keeps, (0, 1]")(
      "exp-decay", po::value<double>()->default_value(1.0, "1"),
      "force-exp: the exponential window's value at the segment's end, % (0 < P < 100)")(
      "uff", po::value<std::string>(),
      "write the FRFs (function type 4), coherences (6) and multiple coherences (26) as UFF 58")(
      "json", po::value<std::string>(), "write the FRFs and coherences as JSON ('-' for stdout)");
  po::positional_options_description pos;
  pos.add("file", 1);
  po::variables_map vm;
  int rc = 0;
  if (!parse_options(args,
                     "ssid identify frf FILE.unv [--estimator h1|h2|hv] [--window hann|flattop|force-exp|rect] "
                     "[--segment N] [--overlap F] [--force-fraction F] [--exp-decay P] [--uff OUT.unv] [--json OUT]",
                     desc, pos, vm, rc))
    return rc;
  TextOut text_out(vm);
  std::ostream& text = text_out.stream();
  const std::string est = vm["estimator"].as<std::string>(), win = vm["window"].as<std::string>();
  id::FrfEstimator estimator = id::FrfEstimator::H1;
  if (est == "h2") estimator = id::FrfEstimator::H2;
  else if (est == "hv") estimator = id::FrfEstimator::Hv;
  else if (est != "h1") {
    print_error("--estimator: expected h1, h2 or hv, got \"" + est + "\"");
    return 2;
  }
  if (win != "hann" && win != "flattop" && win != "rect" && win != "force-exp") {
    print_error("--window: expected hann, flattop, force-exp or rect, got \"" + win + "\"");
    return 2;
  }
  const int segment = vm["segment"].as<int>();
  if (segment < 8) {
    print_error(fmt::format("--segment: expected at least 8 samples, got {}", segment));
    return 2;
  }
  const double overlap = vm.count("overlap") ? vm["overlap"].as<double>() : (win == "force-exp" ? 0.0 : 0.5);
  if (!(overlap >= 0 && overlap < 1)) {
    print_error(fmt::format("--overlap: expected a fraction 0 ≤ F < 1, got {}", overlap));
    return 2;
  }
  const double force_fraction = vm["force-fraction"].as<double>(), decay = vm["exp-decay"].as<double>();
  if (win != "force-exp" && (!vm["force-fraction"].defaulted() || !vm["exp-decay"].defaulted())) {
    print_error("--force-fraction and --exp-decay shape the impact windows: give --window force-exp too");
    return 2;
  }
  if (!(force_fraction > 0 && force_fraction <= 1)) {
    print_error(fmt::format("--force-fraction: expected 0 < F ≤ 1, got {}", force_fraction));
    return 2;
  }
  if (!(decay > 0 && decay < 100)) {
    print_error(fmt::format("--exp-decay: expected a percentage 0 < P < 100, got {}", decay));
    return 2;
  }

  const uff::UffFile file = uff::read_uff(vm["file"].as<std::string>());
  std::vector<const uff::Function58*> time_records;
  for (const auto* f : file.functions())
    if (f->function_type == 1) time_records.push_back(f);
  if (time_records.empty())
    throw formats::InputError(file.path + ": no time histories (dataset 58, function type 1)");
  const TimeSet t = read_time_histories(file, time_records);
  if (t.y.rows() < segment)
    throw formats::InputError(fmt::format("{}: {} samples per record, fewer than one Welch segment of {} (--segment)",
                                          file.path, t.y.rows(), segment));
  if (estimator == id::FrfEstimator::H2 && t.forces.size() != 1)
    throw formats::InputError(fmt::format("{}: --estimator h2 with {} force records (expected 1; use h1 or hv with "
                                          "several references)",
                                          file.path, t.forces.size()));

  id::WelchOptions wo;
  wo.segment_length = segment;
  wo.overlap = static_cast<Eigen::Index>(std::floor(overlap * segment));
  double tau = 0;
  if (win == "force-exp") {
    // The exponential window falls to P % at the segment's end: exp(−N Δt/τ) = P/100.
    tau = -static_cast<double>(segment) * t.dt / std::log(decay / 100);
    wo.reference_window = {id::WindowKind::Force, force_fraction, 1.0};
    wo.response_window = {id::WindowKind::Exponential, 0.1, tau};
  } else {
    const id::WindowKind k = win == "hann" ? id::WindowKind::Hann
                             : win == "flattop" ? id::WindowKind::FlatTop
                                                : id::WindowKind::Rectangular;
    wo.reference_window = wo.response_window = {k, 0.1, 1.0};
  }
  const id::FrfEstimate e = id::estimate_frf(t.x, t.y, t.dt, wo, estimator);
  const auto lines = e.frequency_hz.size();
  const double df = 1.0 / (static_cast<double>(segment) * t.dt);
  const auto no = static_cast<Eigen::Index>(t.responses.size()), ni = static_cast<Eigen::Index>(t.forces.size());

  // Units of H from the records' labels: response unit / force unit.
  std::string uy, ux;
  for (const auto* f : time_records) {
    std::string& u = is_force_record(time_records, *f) ? ux : uy;
    if (u.empty()) u = record_unit(*f);
  }
  const std::string unit = fmt::format("({})/({})", uy.empty() ? "response unit" : uy, ux.empty() ? "force unit" : ux);

  text << fmt::format("{} time histories: {} response(s), {} force(s), {} samples every {} s\n",
                           time_records.size(), no, ni, t.y.rows(), t.dt);
  text << fmt::format("{} by Welch: {} averages of {} samples ({} s), overlap {} samples, window {}{}; {} lines "
                           "every {} Hz (0 … {} Hz)\n",
                           est == "h1" ? "H1" : est == "h2" ? "H2" : "Hv", e.segments, segment,
                           static_cast<double>(segment) * t.dt, wo.overlap, win,
                           win == "force-exp" ? fmt::format(" (force {} % of the segment, exponential τ = {} s)",
                                                            100 * force_fraction, tau)
                                              : "",
                           lines, df, e.frequency_hz(lines - 1));
  if (e.segments < 4)
    std::cerr << fmt::format("warning: {} average(s) only: the coherence of fewer than about 4 is biased towards 1 "
                             "(a longer record or a shorter --segment gives more)\n",
                             e.segments);
  // A line where G_xx is singular has no FRF: written as 0 (and its coherences 0), said here.
  std::vector<double> undefined;
  for (Eigen::Index k = 0; k < lines; ++k)
    if (!e.h[static_cast<std::size_t>(k)].allFinite()) undefined.push_back(e.frequency_hz(k));
  if (!undefined.empty())
    std::cerr << fmt::format("warning: {} line(s) where the forces' spectral matrix is singular (first at {} Hz): FRF "
                             "and coherences written as 0 there\n",
                             undefined.size(), undefined.front());
  const auto finite = [](double v) { return std::isfinite(v) ? v : 0.0; };
  const auto finite_c = [](std::complex<double> v) {
    return std::isfinite(v.real()) && std::isfinite(v.imag()) ? v : std::complex<double>(0, 0);
  };

  text << fmt::format("response  reference   peak |H| {}   at (Hz)   coherence: mean    min   lines < 0.9\n", unit);
  nlohmann::json j;
  j["estimator"] = est;
  j["window"] = win;
  j["segment"] = segment;
  j["overlap_samples"] = wo.overlap;
  j["averages"] = e.segments;
  j["df_hz"] = df;
  j["unit"] = unit;
  if (win == "force-exp") j["exponential_tau_s"] = tau;
  j["frequency_hz"] = std::vector<double>(e.frequency_hz.data(), e.frequency_hz.data() + lines);
  j["frfs"] = nlohmann::json::array();
  uff::UffFile out;
  std::int64_t fid = 0;
  const auto record = [&](int type, const Dof& resp, const Dof& ref, bool complex, const std::string& what) {
    uff::Function58 fn;
    fn.id_lines = {what, "ssid identify frf of " + file.path,
                   fmt::format("{}, {} averages of {} samples, window {}", est, e.segments, segment, win), "NONE",
                   "NONE"};
    fn.function_type = type;
    fn.function_id = ++fid;
    fn.response_node = resp.first;
    fn.response_direction = resp.second;
    fn.reference_node = ref.first;
    fn.reference_direction = ref.second;
    fn.ordinate_type = complex ? 6 : 4;
    fn.even = true;
    fn.abscissa_min = 0;
    fn.abscissa_increment = df;
    fn.axes[0].specific_data_type = 18;  // frequency
    fn.axes[0].label = "Frequency";
    fn.axes[0].units = "Hz";
    for (Eigen::Index k = 0; k < lines; ++k) fn.x.push_back(e.frequency_hz(k));
    return fn;
  };
  for (Eigen::Index i = 0; i < ni; ++i)
    for (Eigen::Index o = 0; o < no; ++o) {
      const Dof resp = t.responses[static_cast<std::size_t>(o)], ref = t.forces[static_cast<std::size_t>(i)];
      Eigen::VectorXcd h(lines);
      Eigen::VectorXd coh(lines);
      for (Eigen::Index k = 0; k < lines; ++k) {
        h(k) = finite_c(e.h[static_cast<std::size_t>(k)](o, i));
        coh(k) = finite(e.coherence(k, o + no * i));
      }
      Eigen::Index peak = 0;
      h.tail(lines - 1).cwiseAbs().maxCoeff(&peak);  // above 0 Hz
      ++peak;
      const Eigen::VectorXd c = coh.tail(lines - 1);
      text << fmt::format("{:>8} {:>10} {:>18.6e} {:9.3f} {:18.4f} {:6.4f} {:13d}\n",
                               fmt::format("{}:{}", resp.first, resp.second), fmt::format("{}:{}", ref.first, ref.second),
                               std::abs(h(peak)), e.frequency_hz(peak), c.mean(), c.minCoeff(),
                               (c.array() < 0.9).count());
      std::vector<double> re(static_cast<std::size_t>(lines)), im(re.size());
      for (Eigen::Index k = 0; k < lines; ++k) re[static_cast<std::size_t>(k)] = h(k).real(), im[static_cast<std::size_t>(k)] = h(k).imag();
      j["frfs"].push_back({{"response", {resp.first, resp.second}},
                           {"reference", {ref.first, ref.second}},
                           {"re", re},
                           {"im", im},
                           {"coherence", std::vector<double>(coh.data(), coh.data() + lines)}});
      uff::Function58 fh = record(4, resp, ref, true, fmt::format("FRF {} {}:{} / {}:{}", est, resp.first, resp.second,
                                                                 ref.first, ref.second));
      for (const auto* f : time_records)  // the response record's ordinate axis (type, unit)
        if (f->response_node == resp.first && f->response_direction == resp.second &&
            !is_force_record(time_records, *f))
          fh.axes[1] = f->axes[1];
      fh.axes[2].specific_data_type = 13;  // excitation force
      fh.axes[2].force_exponent = 1;
      fh.axes[2].label = "force";
      for (Eigen::Index k = 0; k < lines; ++k) fh.y.push_back(h(k));
      out.datasets.emplace_back(fh);
      uff::Function58 fc = record(6, resp, ref, false, fmt::format("coherence {}:{} / {}:{}", resp.first, resp.second,
                                                                  ref.first, ref.second));
      for (Eigen::Index k = 0; k < lines; ++k) fc.y.emplace_back(coh(k));
      out.datasets.emplace_back(fc);
    }
  if (ni > 1) {
    j["multiple_coherence"] = nlohmann::json::array();
    for (Eigen::Index o = 0; o < no; ++o) {
      const Dof resp = t.responses[static_cast<std::size_t>(o)];
      std::vector<double> mc;
      for (Eigen::Index k = 0; k < lines; ++k) mc.push_back(finite(e.multiple_coherence(k, o)));
      j["multiple_coherence"].push_back({{"response", {resp.first, resp.second}}, {"values", mc}});
      // Reference fields: the first force (a multiple coherence is with all of them).
      uff::Function58 fm = record(26, resp, t.forces.front(), false,
                                  fmt::format("multiple coherence {}:{} with {} forces", resp.first, resp.second, ni));
      for (double v : mc) fm.y.emplace_back(v);
      out.datasets.emplace_back(fm);
    }
  }
  if (vm.count("json")) write_json(vm["json"].as<std::string>(), j);
  if (vm.count("uff")) {
    out.path = vm["uff"].as<std::string>();
    uff::write_uff(out, out.path, uff::Precision::Standard);
    std::cerr << fmt::format("wrote {}: {} FRF(s) (dataset 58 type 4), {} coherence(s) (type 6){}\n", out.path, no * ni,
                             no * ni, ni > 1 ? fmt::format(", {} multiple coherence(s) (type 26)", no) : "");
  }
  return 0;
}

/// FRFs of one record set for the checks: measured (dataset 58 type 4, with their
/// coherences of type 6 where the file has them) or H1 from time histories.
struct CheckSet {
  FrfSet frf;
  Eigen::VectorXd f;                        ///< Hz, the lines
  std::map<std::pair<Dof, Dof>, Eigen::VectorXd> coherence;  ///< (response, reference) → per line
  std::string what;                         ///< how the FRFs were obtained, for the header
};

CheckSet check_set(const std::string& path, int segment) {
  const uff::UffFile file = uff::read_uff(path);
  std::vector<const uff::Function58*> frf_records, time_records, coh_records;
  for (const auto* f : file.functions()) {
    if (f->function_type == 4) frf_records.push_back(f);
    if (f->function_type == 1) time_records.push_back(f);
    if (f->function_type == 6) coh_records.push_back(f);
  }
  if (frf_records.empty() && time_records.empty())
    throw formats::InputError(path + ": no frequency response functions or time histories (dataset 58, type 4 or 1)");
  if (!frf_records.empty() && !time_records.empty())
    throw formats::InputError(fmt::format("{}: both FRFs ({}) and time histories ({}); expected one kind", path,
                                          frf_records.size(), time_records.size()));
  CheckSet c;
  if (!frf_records.empty()) {
    c.frf = read_frfs(file, frf_records);
    c.f.resize(static_cast<Eigen::Index>(c.frf.lines.size()));
    for (Eigen::Index k = 0; k < c.f.size(); ++k) c.f(k) = static_cast<double>(k) * c.frf.df;
    for (const auto* h : coh_records) {
      if (h->y.size() != c.frf.lines.size())
        throw formats::InputError(fmt::format("{}: dataset 58 (coherence): {} lines (expected {} as the FRFs)",
                                              h->where.str(), h->y.size(), c.frf.lines.size()));
      Eigen::VectorXd v(c.f.size());
      for (Eigen::Index k = 0; k < v.size(); ++k) v(k) = h->y[static_cast<std::size_t>(k)].real();
      c.coherence[{{h->response_node, h->response_direction}, {h->reference_node, h->reference_direction}}] = v;
    }
    c.what = fmt::format("{} FRF(s) and {} coherence(s) from {}", frf_records.size(), coh_records.size(), path);
    return c;
  }
  const TimeSet t = read_time_histories(file, time_records);
  if (t.y.rows() < segment)
    throw formats::InputError(fmt::format("{}: {} samples per record, fewer than one Welch segment of {} (--segment)",
                                          path, t.y.rows(), segment));
  id::WelchOptions wo;
  wo.segment_length = segment;
  const id::FrfEstimate e = id::estimate_frf(t.x, t.y, t.dt, wo, id::FrfEstimator::H1);
  c.frf.responses = t.responses;
  c.frf.references = t.forces;
  c.frf.df = 1.0 / (static_cast<double>(segment) * t.dt);
  c.f = e.frequency_hz;
  c.frf.lines = e.h;
  const auto no = static_cast<Eigen::Index>(t.responses.size());
  for (std::size_t i = 0; i < t.forces.size(); ++i)
    for (std::size_t o = 0; o < t.responses.size(); ++o)
      c.coherence[{t.responses[o], t.forces[i]}] =
          e.coherence.col(static_cast<Eigen::Index>(o) + no * static_cast<Eigen::Index>(i));
  c.what = fmt::format("H1 of {} time histories of {} (Welch, {} averages of {} samples, Hann)", time_records.size(),
                       path, e.segments, segment);
  return c;
}

/// The FRF of response r to reference q in `s` (directions' signs turned to +), if measured.
std::optional<Eigen::VectorXcd> frf_of(const CheckSet& s, const Dof& r, const Dof& q) {
  const auto same = [](const Dof& a, const Dof& b) { return a.first == b.first && std::abs(a.second) == std::abs(b.second); };
  const auto o = std::find_if(s.frf.responses.begin(), s.frf.responses.end(), [&](const Dof& d) { return same(d, r); });
  const auto i = std::find_if(s.frf.references.begin(), s.frf.references.end(), [&](const Dof& d) { return same(d, q); });
  if (o == s.frf.responses.end() || i == s.frf.references.end()) return std::nullopt;
  const double sign = (o->second < 0 ? -1.0 : 1.0) * (i->second < 0 ? -1.0 : 1.0);
  Eigen::VectorXcd h(static_cast<Eigen::Index>(s.frf.lines.size()));
  for (std::size_t k = 0; k < s.frf.lines.size(); ++k)
    h(static_cast<Eigen::Index>(k)) = sign * s.frf.lines[k](o - s.frf.responses.begin(), i - s.frf.references.begin());
  return h;
}


/// Verdict of a figure against its pass and warn limits (smaller is better, or larger when `larger_better`).
std::string verdict(double v, double pass, double warn, bool larger_better = false) {
  if (std::isnan(v)) return "fail";
  if (larger_better) return v >= pass ? "pass" : v >= warn ? "warn" : "fail";
  return v <= pass ? "pass" : v <= warn ? "warn" : "fail";
}

int rank(const std::string& v) { return v == "fail" ? 3 : v == "warn" ? 2 : v == "pass" ? 1 : 0; }

/// `ssid identify check` on free decays: the dominant frequency of overlapping segments.
int check_decays(const uff::UffFile& file, const std::vector<const uff::Function58*>& records, int segment,
                 double overlap, const std::string& json_path) {
  TextOut text_out(json_path);
  std::ostream& text = text_out.stream();
  const auto* first = records.front();
  for (const auto* f : records) {
    const std::string at = f->where.str() + ": dataset 58";
    if (!f->even) throw formats::InputError(at + ": uneven abscissa (expected evenly spaced time samples)");
    if (f->is_complex()) throw formats::InputError(at + ": complex ordinate (expected a real time history)");
    if (f->y.size() != first->y.size() || f->abscissa_increment != first->abscissa_increment)
      throw formats::InputError(fmt::format("{}: {} samples every {} s (expected {} every {} s as at {})", at,
                                            f->y.size(), f->abscissa_increment, first->y.size(),
                                            first->abscissa_increment, first->where.str()));
  }
  const double dt = first->abscissa_increment;
  const auto n = static_cast<Eigen::Index>(first->y.size());
  Eigen::MatrixXd y(n, static_cast<Eigen::Index>(records.size()));
  for (std::size_t c = 0; c < records.size(); ++c)
    for (Eigen::Index k = 0; k < n; ++k) y(k, static_cast<Eigen::Index>(c)) = records[c]->y[static_cast<std::size_t>(k)].real();
  const Eigen::Index seg = segment > 0 ? segment : n / 4;
  if (seg < 16 || seg > n)
    throw formats::InputError(fmt::format("{}: decay segments of {} samples in records of {} (expected 16 … {}; "
                                          "--decay-segment)",
                                          file.path, seg, n, n));
  const Eigen::Index step = std::max<Eigen::Index>(1, static_cast<Eigen::Index>(std::lround((1 - overlap) * seg)));
  const auto segs = id::decay_segments(y, dt, seg, step);
  text << fmt::format("{} free decay(s) (no force record) of {}: {} samples every {} s; ERA (order ≤ 8) on {} "
                           "segments of {} samples every {} samples\n",
                           records.size(), file.path, n, dt, segs.size(), seg, step);
  text << "segment  start (s)   RMS (record unit)   dominant (Hz)   damping (%)\n";
  nlohmann::json items = nlohmann::json::array();
  std::vector<double> hz;
  for (std::size_t k = 0; k < segs.size(); ++k) {
    const auto& d = segs[k];
    text << fmt::format("{:7d} {:10.4f} {:19.6e} {:15.6f} {:13.4f}\n", k + 1, d.start_s, d.rms, d.hz,
                             100 * d.zeta);
    items.push_back({{"start_s", d.start_s}, {"rms", d.rms}, {"hz", std::isnan(d.hz) ? nlohmann::json() : nlohmann::json(d.hz)},
                     {"zeta", std::isnan(d.zeta) ? nlohmann::json() : nlohmann::json(d.zeta)}});
    if (!std::isnan(d.hz)) hz.push_back(d.hz);
  }
  std::string v = "n/a", figure = "fewer than two segments with a dominant mode";
  if (hz.size() >= 2) {
    std::vector<double> sorted = hz;
    std::sort(sorted.begin(), sorted.end());
    const double median = sorted[sorted.size() / 2];
    const double spread = (sorted.back() - sorted.front()) / median;
    v = verdict(spread, 0.005, 0.01);
    figure = fmt::format("dominant frequency {:.6f} Hz in the first segment, {:.6f} Hz in the last: spread {:.3f} % over {} "
                         "segments (pass ≤ 0.5 %, warn ≤ 1 %)",
                         hz.front(), hz.back(), 100 * spread, hz.size());
  }
  nlohmann::json checks = nlohmann::json::array();
  text << "\ncheck        verdict\n";
  text << fmt::format("{:<12} {:<5} {}\n", "linearity", v, figure);
  checks.push_back({{"check", "linearity"}, {"verdict", v}, {"figure", figure}, {"items", items}});
  for (const char* name : {"reciprocity", "coherence", "resolution"}) {
    text << fmt::format("{:<12} {:<5} {}\n", name, "n/a", "free decays: no FRF");
    checks.push_back({{"check", name}, {"verdict", "n/a"}, {"figure", "free decays: no FRF"}, {"items", nlohmann::json::array()}});
  }
  text << "\noverall: " << v << "\n";
  if (!json_path.empty()) write_json(json_path, {{"checks", checks}, {"overall", v}});
  return 0;
}

/// `ssid identify check`: reciprocity, linearity, coherence, resolution against damping.
int identify_check(const Args& args) {
  po::options_description desc("ssid identify check options");
  desc.add_options()("file", po::value<std::string>()->required(),
                     "universal file with FRFs (dataset 58 type 4, coherences type 6) or time histories (type 1)")(
      "second", po::value<std::string>(),
      "the same measurement at another force level (linearity): FRFs or time histories")(
      "segment", po::value<int>()->default_value(1024), "time histories: Welch segment for H1, samples")(
      "coherence-min", po::value<double>()->default_value(0.9, "0.9"), "coherence below this is low")(
      "band", po::value<std::string>(), "check the lines in F1:F2 only, Hz (default: all above 0 Hz)")(
      "modes-from", po::value<std::string>(),
      "the JSON of ssid identify modes: the peaks' damping from the identified modes (else from the FRFs' "
      "half-power bandwidth)")(
      "decay-segment", po::value<int>(), "free decays: ERA segment, samples (default a quarter of the record)")(
      "decay-overlap", po::value<double>()->default_value(0.5, "0.5"), "free decays: overlap of the segments, [0, 1)")(
      "json", po::value<std::string>(), "write the verdicts and figures as JSON ('-' for stdout)");
  po::positional_options_description pos;
  pos.add("file", 1);
  po::variables_map vm;
  int rc = 0;
  if (!parse_options(args,
                     "ssid identify check FILE.unv [--second FILE2.unv] [--segment N] [--coherence-min C] "
                     "[--band F1:F2] [--modes-from IDENTIFIED.json] [--decay-segment N] [--decay-overlap F] "
                     "[--json OUT]",
                     desc, pos, vm, rc))
    return rc;
  TextOut text_out(vm);
  std::ostream& text = text_out.stream();
  const int segment = vm["segment"].as<int>();
  if (segment < 8) {
    print_error(fmt::format("--segment: expected at least 8 samples, got {}", segment));
    return 2;
  }
  const double cmin = vm["coherence-min"].as<double>();
  if (!(cmin > 0 && cmin < 1)) {
    print_error(fmt::format("--coherence-min: expected 0 < C < 1, got {}", cmin));
    return 2;
  }
  double lo = 0, hi = std::numeric_limits<double>::infinity();
  if (vm.count("band")) {
    const std::string b = vm["band"].as<std::string>();
    const auto colon = b.find(':');
    std::size_t u1 = 0, u2 = 0;
    try {
      if (colon != std::string::npos) {
        lo = std::stod(b.substr(0, colon), &u1);
        hi = std::stod(b.substr(colon + 1), &u2);
      }
    } catch (const std::exception&) {
      u1 = 0;
    }
    if (colon == std::string::npos || u1 != colon || u2 != b.size() - colon - 1 || !(lo >= 0) || !(hi > lo)) {
      print_error("--band: expected F1:F2 in Hz with 0 ≤ F1 < F2, got \"" + b + "\"");
      return 2;
    }
  }
  std::vector<std::pair<double, double>> identified;
  if (vm.count("modes-from")) {
    const std::string path = vm["modes-from"].as<std::string>();
    std::ifstream in(path);
    if (!in) throw formats::InputError(path + ": cannot open the identified modes (--modes-from)");
    nlohmann::json j;
    try {
      in >> j;
    } catch (const nlohmann::json::exception& e) {
      throw formats::InputError(fmt::format("{}: not JSON ({})", path, e.what()));
    }
    if (!j.contains("modes") || !j["modes"].is_array())
      throw formats::InputError(path + ": no \"modes\" array (expected the JSON of ssid identify modes)");
    for (std::size_t k = 0; k < j["modes"].size(); ++k) {
      const auto& m = j["modes"][k];
      if (!m.contains("hz") || !m.contains("zeta") || !m["hz"].is_number() || !m["zeta"].is_number())
        throw formats::InputError(fmt::format("{}: modes[{}] has no numeric \"hz\" and \"zeta\"", path, k));
      identified.emplace_back(m["hz"].get<double>(), m["zeta"].get<double>());
    }
  }

  const double decay_overlap = vm["decay-overlap"].as<double>();
  if (!(decay_overlap >= 0 && decay_overlap < 1)) {
    print_error(fmt::format("--decay-overlap: expected a fraction 0 ≤ F < 1, got {}", decay_overlap));
    return 2;
  }
  {
    // Free decays (time histories, none of them a force): linearity from the dominant
    // frequency of overlapping segments; the FRF checks do not apply.
    const uff::UffFile file = uff::read_uff(vm["file"].as<std::string>());
    std::vector<const uff::Function58*> time_records;
    bool other = false;
    for (const auto* f : file.functions()) {
      if (f->function_type == 1) time_records.push_back(f);
      if (f->function_type == 4) other = true;
    }
    if (!time_records.empty() && !other &&
        std::none_of(time_records.begin(), time_records.end(),
                     [&](const uff::Function58* f) { return is_force_record(time_records, *f); })) {
      if (vm.count("second"))
        throw formats::InputError(file.path + ": free decays (no force record): --second compares FRFs at two force "
                                              "levels, which free decays do not have");
      return check_decays(file, time_records, vm.count("decay-segment") ? vm["decay-segment"].as<int>() : 0,
                          decay_overlap, vm.count("json") ? vm["json"].as<std::string>() : "");
    }
  }
  const CheckSet a = check_set(vm["file"].as<std::string>(), segment);
  std::optional<CheckSet> b;
  if (vm.count("second")) b = check_set(vm["second"].as<std::string>(), segment);
  // The lines checked: in the band, above 0 Hz (a force has no DC content to speak of).
  std::vector<Eigen::Index> keep;
  for (Eigen::Index k = 0; k < a.f.size(); ++k)
    if (a.f(k) > 0 && a.f(k) >= lo && a.f(k) <= hi) keep.push_back(k);
  if (keep.size() < 3)
    throw formats::InputError(fmt::format("{}: {} line(s) in the band checked (expected at least 3)",
                                          vm["file"].as<std::string>(), keep.size()));
  const auto pick = [&](const Eigen::VectorXcd& v) {
    Eigen::VectorXcd o(static_cast<Eigen::Index>(keep.size()));
    for (std::size_t k = 0; k < keep.size(); ++k) o(static_cast<Eigen::Index>(k)) = v(keep[k]);
    return o;
  };
  const auto pick_real = [&](const Eigen::VectorXd& v) {
    Eigen::VectorXd o(static_cast<Eigen::Index>(keep.size()));
    for (std::size_t k = 0; k < keep.size(); ++k) o(static_cast<Eigen::Index>(k)) = v(keep[k]);
    return o;
  };
  const Eigen::VectorXd f = pick_real(a.f);
  text << a.what << ": " << a.frf.responses.size() << " response(s) × " << a.frf.references.size()
            << " reference(s), " << keep.size() << fmt::format(" lines {}…{} Hz every {} Hz\n", f(0), f(f.size() - 1), a.frf.df);
  if (b) text << "second level: " << b->what << "\n";

  nlohmann::json checks = nlohmann::json::array();
  const auto report = [&](const std::string& name, const std::string& v, const std::string& figure, nlohmann::json items) {
    text << fmt::format("{:<12} {:<5} {}\n", name, v, figure);
    checks.push_back({{"check", name}, {"verdict", v}, {"figure", figure}, {"items", std::move(items)}});
  };
  const auto pct = [](double v) { return fmt::format("{:.2f} %", 100 * v); };
  text << "\ncheck        verdict\n";

  // Reciprocity: H(b / a) against H(a / b) for two references each measured at the other's DOF.
  {
    nlohmann::json items = nlohmann::json::array();
    std::string worst = "n/a", figure = "no driving-point pair (two references, each measured at the other's DOF)";
    double worst_e = -1;
    const auto& refs = a.frf.references;
    for (std::size_t p = 0; p < refs.size(); ++p)
      for (std::size_t q = p + 1; q < refs.size(); ++q) {
        const auto hqp = frf_of(a, refs[q], refs[p]), hpq = frf_of(a, refs[p], refs[q]);
        if (!hqp || !hpq) continue;
        const id::FrfDifference d = id::compare_frfs(f, pick(*hqp), pick(*hpq));
        const std::string v = verdict(d.error, 0.10, 0.20);
        items.push_back({{"ij", {dof_text(refs[q]), dof_text(refs[p])}}, {"error", d.error}, {"frac", d.frac},
                         {"verdict", v}});
        if (std::isnan(d.error) || d.error > worst_e) {
          worst_e = std::isnan(d.error) ? std::numeric_limits<double>::infinity() : d.error;
          worst = v;
          figure = fmt::format("H({} / {}) against H({} / {}): difference {} (pass ≤ 10 %, warn ≤ 20 %), FRAC {:.4f}",
                               dof_text(refs[q]), dof_text(refs[p]), dof_text(refs[p]), dof_text(refs[q]),
                               pct(d.error), d.frac);
        }
      }
    report("reciprocity", worst, figure, items);
  }

  // Linearity: each FRF of the first set against the same FRF at the second level.
  {
    nlohmann::json items = nlohmann::json::array();
    std::string worst = "n/a", figure = "one force level only (give the other with --second)";
    if (b) {
      if (b->f.size() != a.f.size() || std::abs(b->frf.df - a.frf.df) > 1e-9 * a.frf.df)
        throw formats::InputError(fmt::format("{}: {} lines every {} Hz (expected {} every {} Hz as the first set)",
                                              vm["second"].as<std::string>(), b->f.size(), b->frf.df, a.f.size(),
                                              a.frf.df));
      double worst_e = -1;
      for (const Dof& q : a.frf.references)
        for (const Dof& r : a.frf.responses) {
          const auto h1 = frf_of(a, r, q), h2 = frf_of(*b, r, q);
          if (!h1 || !h2) continue;
          const id::FrfDifference d = id::compare_frfs(f, pick(*h1), pick(*h2));
          const std::string v = verdict(d.error, 0.10, 0.20);
          items.push_back({{"response", dof_text(r)}, {"reference", dof_text(q)}, {"error", d.error}, {"frac", d.frac},
                           {"peak_hz", {d.peak_hz_a, d.peak_hz_b}}, {"verdict", v}});
          if (std::isnan(d.error) || d.error > worst_e) {
            worst_e = std::isnan(d.error) ? std::numeric_limits<double>::infinity() : d.error;
            worst = v;
            figure = fmt::format("H({} / {}) at the two levels: difference {} (pass ≤ 10 %, warn ≤ 20 %), FRAC {:.4f}, "
                                 "peak {} Hz against {} Hz ({:+.2f} %)",
                                 dof_text(r), dof_text(q), pct(d.error), d.frac, d.peak_hz_a, d.peak_hz_b,
                                 100 * (d.peak_hz_b - d.peak_hz_a) / d.peak_hz_a);
          }
        }
      if (items.empty())
        throw formats::InputError(vm["second"].as<std::string>() +
                                  ": no FRF of the same response and reference as in the first set");
    }
    report("linearity", worst, figure, items);
  }

  // Coherence: the share of lines below the threshold, per FRF, and the bands.
  {
    nlohmann::json items = nlohmann::json::array();
    std::string worst = "n/a", figure = "no coherence (dataset 58 type 6) in the file";
    double worst_share = -1;
    for (const auto& [key, coh] : a.coherence) {
      const Eigen::VectorXd c = pick_real(coh);
      const auto bands = id::low_coherence_bands(f, c, cmin);
      Eigen::Index below = 0;
      nlohmann::json jb = nlohmann::json::array();
      for (const auto& bd : bands) {
        below += bd.lines;
        jb.push_back({{"from_hz", bd.lo_hz}, {"to_hz", bd.hi_hz}, {"min", bd.min}, {"lines", bd.lines}});
      }
      const double share = static_cast<double>(below) / static_cast<double>(c.size());
      const std::string v = verdict(share, 0.05, 0.20);
      items.push_back({{"response", dof_text(key.first)}, {"reference", dof_text(key.second)}, {"share_below", share},
                       {"bands", jb}, {"verdict", v}});
      if (share > worst_share) {
        worst_share = share;
        worst = v;
        std::string where;
        if (!bands.empty()) {
          const auto w = *std::min_element(bands.begin(), bands.end(),
                                           [](const auto& x, const auto& y) { return x.min < y.min; });
          where = fmt::format(", lowest {:.3f} in {}…{} Hz", w.min, w.lo_hz, w.hi_hz);
        }
        figure = fmt::format("{} / {}: {} of the lines below {} in {} band(s){} (pass ≤ 5 %, warn ≤ 20 %)",
                             dof_text(key.first), dof_text(key.second), pct(share), cmin, bands.size(), where);
      }
    }
    report("coherence", worst, figure, items);
  }

  // Resolution: lines across the half-power band 2ζf of each peak of the summed magnitudes.
  {
    Eigen::VectorXd sum = Eigen::VectorXd::Zero(f.size());
    for (const Dof& q : a.frf.references)
      for (const Dof& r : a.frf.responses) {
        const Eigen::VectorXd m = pick(*frf_of(a, r, q)).cwiseAbs();
        if (m.allFinite() && m.maxCoeff() > 0) sum += m / m.maxCoeff();
      }
    nlohmann::json items = nlohmann::json::array();
    std::string worst = "n/a", figure = "no isolated peak in the band";
    double worst_lines = std::numeric_limits<double>::infinity();
    for (const id::PeakResolution& p : id::peak_resolution(f, sum, identified)) {
      const std::string v = verdict(p.lines, 3.0, 1.5, true);
      items.push_back({{"hz", p.hz}, {"half_power_hz", p.half_power_hz}, {"zeta", p.zeta}, {"lines", p.lines},
                       {"zeta_from", p.from_identified ? "identified" : "half-power band of the FRFs"}, {"verdict", v}});
      if (p.lines < worst_lines) {
        worst_lines = p.lines;
        worst = v;
        figure = fmt::format("Δf = {} Hz; peak at {} Hz: half-power band 2ζf = {:.4g} Hz (ζ {:.3f} %{}), {:.2f} lines "
                             "(pass ≥ 3, warn ≥ 1.5)",
                             a.frf.df, p.hz, p.half_power_hz, 100 * p.zeta, p.from_identified ? ", identified" : "",
                             p.lines);
      }
    }
    report("resolution", worst, figure, items);
  }

  std::string overall = "n/a";
  for (const auto& c : checks)
    if (rank(c["verdict"].get<std::string>()) > rank(overall)) overall = c["verdict"].get<std::string>();
  text << "\noverall: " << overall << "\n";
  if (vm.count("json")) write_json(vm["json"].as<std::string>(), {{"checks", checks}, {"overall", overall}});
  return 0;
}

}  // namespace

int cmd_identify(const Args& args) {
  const std::string usage =
      "usage: ssid identify <modes|frf|check> ...\n"
      "  modes FILE.unv [--method armax|era|plscf] [--json OUT] [--uff OUT] [--svg OUT] [--report OUT]\n"
      "                                                               modes from the FRFs or time histories\n"
      "                                                               (UFF 58) of a modal test\n"
      "  frf FILE.unv [--estimator h1|h2|hv] [--window W] [--uff OUT]   FRFs, coherence and multiple coherence\n"
      "                                                               from time histories (Welch)\n"
      "  check FILE.unv [--second FILE2.unv] [--json OUT]             reciprocity, linearity, coherence and\n"
      "                                                               resolution against damping: verdicts\n";
  if (args.empty() || args[0] == "--help" || args[0] == "-h") {
    (args.empty() ? std::cerr : std::cout) << usage;
    return args.empty() ? 2 : 0;
  }
  Args rest(args.begin() + 1, args.end());
  if (args[0] == "modes") return identify_modes(rest);
  if (args[0] == "frf") return identify_frf(rest);
  if (args[0] == "check") return identify_check(rest);
  std::cerr << "ssid identify: unknown subcommand '" << args[0] << "'\n" << usage;
  return 2;
}

}  // namespace ssid::cli
