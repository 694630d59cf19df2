/// \file cmd_identify.cpp
/// `ssid identify modes FILE.unv --method armax|era`: modes from the records of a universal
/// file (dataset 58) as a table, JSON and UFF 55. FRFs (function type 4) go to ERA (Markov
/// parameters by inverse FFT, ERA over model orders, the stabilisation diagram's physical
/// modes); time histories (function type 1, the forces told by their ordinate type) go to
/// the multistage ARMAX with its subset order rule, or to ERA through H1 FRFs (Welch).
/// docs/identification.md describes the methods and the rule for force records. pLSCF is
/// not here yet (issue 22).
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <iostream>
#include <limits>
#include <map>
#include <utility>

#include "cli/cli_util.hpp"
#include "estimator/identification/armax_order.hpp"
#include "estimator/identification/era.hpp"
#include "estimator/identification/frf.hpp"
#include "estimator/identification/modal_indicators.hpp"
#include "estimator/identification/stabilisation.hpp"
#include "formats/parse_error.hpp"
#include "formats/uff.hpp"

namespace ssid::cli {

namespace {

namespace uff = formats::uff;
namespace id = estimator::identification;
using Dof = std::pair<std::int64_t, int>;  // node, direction (±1 … ±6)

/// The FRFs of a file as lines of no × ni matrices, with their DOFs.
struct FrfSet {
  std::vector<Dof> responses, references;
  std::vector<Eigen::MatrixXcd> lines;
  double df = 0;
};

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
TimeSet read_time_histories(const uff::UffFile& file, const std::vector<const uff::Function58*>& records) {
  constexpr int kExcitationForce = 13;
  const bool typed = std::any_of(records.begin(), records.end(), [](const uff::Function58* f) {
    return f->axes[1].specific_data_type == kExcitationForce;
  });
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
    const bool force = typed ? f->axes[1].specific_data_type == kExcitationForce
                             : f->response_node == f->reference_node && f->response_direction == f->reference_direction;
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
  if (in.empty())
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
};

Identified era_modes(const FrfSet& s, int max_order, const id::StabilisationOptions& so) {
  // The impulse response over one period; its first half carries the least wrap-around.
  const auto Y = id::markov_from_frf(s.lines, s.df);
  const double dt = 1.0 / (static_cast<double>(Y.size()) * s.df);
  const std::vector<Eigen::MatrixXd> head(Y.begin(), Y.begin() + static_cast<std::ptrdiff_t>(Y.size() / 2));
  id::EraOptions eo;
  eo.dt = dt;
  std::vector<Eigen::Index> orders;
  for (int n = 2; n <= max_order; n += 2) orders.push_back(n);
  const id::StabilisationResult st = id::stabilise(id::order_poles(id::era_orders(head, eo, orders)), so);
  Identified r;
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
  return r;
}

/// The multistage ARMAX at orders (s, m) on all responses, then on each alone at
/// (p·s, p·m): the modes found in every run (armax_model_order), within [hz_min, hz_max].
Identified armax_modes(const TimeSet& t, int ar_order, int arx_order, const id::StabilisationOptions& so,
                       std::vector<std::string>& warnings) {
  id::ArmaxOptions all;
  all.ar_order = ar_order;
  all.arx_order = arx_order;
  const auto runs = id::single_output_runs(static_cast<int>(t.responses.size()), all);
  const id::ArmaxOrderResult res = id::armax_model_order(t.y, t.x, t.dt, runs, {});
  for (std::size_t k = 0; k < res.models.size(); ++k)
    if (!res.models[k].converged)
      warnings.push_back(fmt::format("ARMAX run {} did not converge in {} passes (its best pass is used)", k + 1,
                                     res.models[k].iterations));
  Identified r;
  r.columns_header = "  runs";
  for (const auto& p : res.rejected) ++r.rejected[p.reason];
  for (const id::RecurringMode& md : res.modes) {
    if (md.hz_mean < so.hz_min || md.hz_mean > so.hz_max) {
      ++r.rejected["outside --min-hz/--max-hz"];
      continue;
    }
    r.modes.push_back({md.hz_mean, md.zeta_mean, md.hz_std, md.zeta_std, id::rotate_to_real(md.shape.normalized()),
                       fmt::format(" {:5d}", res.models.size()), {{"runs", res.models.size()}}});
  }
  return r;
}

int identify_modes(const Args& args) {
  po::options_description desc("ssid identify modes options");
  desc.add_options()("file", po::value<std::string>()->required(),
                     "universal file with FRFs (dataset 58, type 4) or time histories (type 1)")(
      "method", po::value<std::string>()->default_value("era"), "identification method: armax (time histories) or era")(
      "json", po::value<std::string>(), "write the modes as JSON to this file ('-' for stdout)")(
      "uff", po::value<std::string>(), "write the modes as real normal modes, UFF dataset 55")(
      "max-order", po::value<int>()->default_value(40), "era: largest model order (state dimension), even")(
      "segment", po::value<int>()->default_value(1024), "era on time histories: Welch segment, samples")(
      "ar-order", po::value<int>(), "armax: AR order s with all p responses (default ⌈12/p⌉)")(
      "arx-order", po::value<int>(), "armax: prior ARX order m with all p responses (default ⌈90/p⌉)")(
      "min-hz", po::value<double>()->default_value(0.0, "0"), "keep modes from this frequency, Hz")(
      "max-hz", po::value<double>(), "keep modes up to this frequency, Hz (default: all)");
  po::positional_options_description pos;
  pos.add("file", 1);
  po::variables_map vm;
  int rc = 0;
  if (!parse_options(args,
                     "ssid identify modes FILE.unv [--method armax|era] [--json OUT] [--uff OUT] [--max-order N] "
                     "[--segment N] [--ar-order S] [--arx-order M] [--min-hz F] [--max-hz F]",
                     desc, pos, vm, rc))
    return rc;
  const std::string method = vm["method"].as<std::string>();
  if (method != "era" && method != "armax") {
    print_error("--method: expected armax or era, got \"" + method + "\" (plscf is not available yet)");
    return 2;
  }
  const int max_order = vm["max-order"].as<int>();
  if (max_order < 2 || max_order % 2) {
    print_error(fmt::format("--max-order: expected an even number ≥ 2, got {}", max_order));
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
  id::StabilisationOptions so;
  so.hz_min = vm["min-hz"].as<double>();
  if (vm.count("max-hz")) so.hz_max = vm["max-hz"].as<double>();

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
  if (time_records.empty()) {
    const FrfSet s = read_frfs(file, frf_records);
    std::cout << fmt::format("{} FRF(s): {} response(s) × {} reference(s), {} lines every {} Hz; ERA orders 2…{}\n",
                             s.responses.size() * s.references.size(), s.responses.size(), s.references.size(),
                             s.lines.size(), s.df, max_order);
    r = era_modes(s, max_order, so);
    responses = s.responses;
  } else {
    const TimeSet t = read_time_histories(file, time_records);
    responses = t.responses;
    const auto p = static_cast<int>(t.responses.size());
    std::cout << fmt::format("{} time histories: {} response(s), {} force(s), {} samples every {} s; ",
                             time_records.size(), p, t.forces.size(), t.y.rows(), t.dt);
    if (method == "era") {
      const FrfSet s = h1_frfs(file, t, segment);
      std::cout << fmt::format("H1 by Welch ({} samples, Hann, half overlap): {} lines every {} Hz; ERA orders 2…{}\n",
                               segment, s.lines.size(), s.df, max_order);
      r = era_modes(s, max_order, so);
    } else {
      if (p < 2)
        throw formats::InputError(file.path + ": --method armax needs at least two response records (the order rule "
                                              "compares the identification from all of them with each one's)");
      const int s = vm.count("ar-order") ? vm["ar-order"].as<int>() : (12 + p - 1) / p;
      const int m = vm.count("arx-order") ? vm["arx-order"].as<int>() : (90 + p - 1) / p;
      std::cout << fmt::format("ARMAX orders s = {}, m = {} on all responses, then {}, {} on each\n", s, m, p * s,
                               p * m);
      try {
        r = armax_modes(t, s, m, so, warnings);
      } catch (const formats::InputError& e) {
        // The estimator names the records by column; the file is what the user can act on.
        throw formats::InputError(file.path + ": " + e.what());
      }
    }
  }

  std::cout << "mode   frequency (Hz)      ± (Hz)   damping (%)     ± (%)" << r.columns_header << "\n";
  std::vector<std::int64_t> nodes;
  for (const auto& d : responses)
    if (std::find(nodes.begin(), nodes.end(), d.first) == nodes.end()) nodes.push_back(d.first);
  nlohmann::json modes = nlohmann::json::array();
  uff::UffFile out;
  bool rotations_dropped = false;
  for (std::size_t m = 0; m < r.modes.size(); ++m) {
    const Identified::Mode& md = r.modes[m];
    std::cout << fmt::format("{:4d} {:16.6f} {:11.3e} {:13.4f} {:9.3e}{}\n", m + 1, md.hz, md.hz_std, 100 * md.zeta,
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
    modes.push_back(j);
    out.datasets.emplace_back(uff::NodalData55::normal_mode(static_cast<std::int64_t>(m + 1), md.hz, nodes, values,
                                                            0.0, md.zeta));
  }
  if (r.modes.empty())
    std::cout << (method == "era" ? "(no mode stable across the orders)\n" : "(no mode found in every run)\n");
  std::cerr << "note: poles not kept:";
  for (const auto& [reason, count] : r.rejected) std::cerr << " " << reason << " " << count << ";";
  std::cerr << "\n";
  for (const auto& w : warnings) std::cerr << "warning: " << w << "\n";
  if (rotations_dropped) std::cerr << "warning: rotational responses are in the JSON only (UFF 55 gets X, Y, Z)\n";

  if (vm.count("json")) {
    nlohmann::json j;
    j["modes"] = modes;
    j["method"] = method;
    j["rejected"] = r.rejected;
    write_json(vm["json"].as<std::string>(), j);
  }
  if (vm.count("uff")) {
    out.path = vm["uff"].as<std::string>();
    uff::write_uff(out, out.path);
  }
  return 0;
}

}  // namespace

int cmd_identify(const Args& args) {
  const std::string usage =
      "usage: ssid identify <modes> ...\n"
      "  modes FILE.unv [--method armax|era] [--json OUT] [--uff OUT]   modes from the FRFs or time histories\n"
      "                                                               (UFF 58) of a modal test\n";
  if (args.empty() || args[0] == "--help" || args[0] == "-h") {
    (args.empty() ? std::cerr : std::cout) << usage;
    return args.empty() ? 2 : 0;
  }
  Args rest(args.begin() + 1, args.end());
  if (args[0] == "modes") return identify_modes(rest);
  std::cerr << "ssid identify: unknown subcommand '" << args[0] << "'\n" << usage;
  return 2;
}

}  // namespace ssid::cli
