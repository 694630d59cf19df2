/// \file cmd_identify.cpp
/// `ssid identify modes FILE.unv --method era`: modes from the FRFs (dataset 58, function
/// type 4) of a universal file — Markov parameters by inverse FFT, ERA over model orders,
/// the stabilisation diagram's physical modes — as a table, JSON and UFF 55.
/// docs/identification.md describes the methods. Time histories, ARMAX and pLSCF are not
/// here yet (issue 22).
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <iostream>
#include <map>
#include <utility>

#include "cli/cli_util.hpp"
#include "estimator/identification/era.hpp"
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

FrfSet read_frfs(const uff::UffFile& file) {
  std::vector<const uff::Function58*> frfs;
  for (const auto* f : file.functions())
    if (f->function_type == 4) frfs.push_back(f);
  if (frfs.empty())
    throw formats::InputError(file.path + ": no frequency response functions (dataset 58, function type 4)");
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

int identify_modes(const Args& args) {
  po::options_description desc("ssid identify modes options");
  desc.add_options()("file", po::value<std::string>()->required(), "universal file with FRFs (dataset 58, type 4)")(
      "method", po::value<std::string>()->default_value("era"), "identification method: era")(
      "json", po::value<std::string>(), "write the modes as JSON to this file ('-' for stdout)")(
      "uff", po::value<std::string>(), "write the modes as real normal modes, UFF dataset 55")(
      "max-order", po::value<int>()->default_value(40), "largest model order (state dimension), even")(
      "min-hz", po::value<double>()->default_value(0.0, "0"), "keep modes from this frequency, Hz")(
      "max-hz", po::value<double>(), "keep modes up to this frequency, Hz (default: all)");
  po::positional_options_description pos;
  pos.add("file", 1);
  po::variables_map vm;
  int rc = 0;
  if (!parse_options(args,
                     "ssid identify modes FILE.unv [--method era] [--json OUT] [--uff OUT] [--max-order N] "
                     "[--min-hz F] [--max-hz F]",
                     desc, pos, vm, rc))
    return rc;
  const std::string method = vm["method"].as<std::string>();
  if (method != "era") {
    print_error("--method: expected era, got \"" + method + "\" (armax and plscf are not available yet)");
    return 2;
  }
  const int max_order = vm["max-order"].as<int>();
  if (max_order < 2 || max_order % 2) {
    print_error(fmt::format("--max-order: expected an even number ≥ 2, got {}", max_order));
    return 2;
  }

  const uff::UffFile file = uff::read_uff(vm["file"].as<std::string>());
  const FrfSet s = read_frfs(file);
  // The impulse response over one period; its first half carries the least wrap-around.
  const auto Y = id::markov_from_frf(s.lines, s.df);
  const double dt = 1.0 / (static_cast<double>(Y.size()) * s.df);
  const std::vector<Eigen::MatrixXd> head(Y.begin(), Y.begin() + static_cast<std::ptrdiff_t>(Y.size() / 2));
  id::EraOptions eo;
  eo.dt = dt;
  std::vector<Eigen::Index> orders;
  for (int n = 2; n <= max_order; n += 2) orders.push_back(n);
  const auto results = id::era_orders(head, eo, orders);
  id::StabilisationOptions so;
  so.hz_min = vm["min-hz"].as<double>();
  if (vm.count("max-hz")) so.hz_max = vm["max-hz"].as<double>();
  const id::StabilisationResult st = id::stabilise(id::order_poles(results), so);

  std::map<std::string, int> rejected;
  for (const auto& d : st.diagram)
    if (d.reason != id::RejectReason::None) ++rejected[id::reject_reason_text(d.reason)];

  nlohmann::json modes = nlohmann::json::array();
  std::cout << fmt::format("{} FRF(s): {} response(s) × {} reference(s), {} lines every {} Hz; ERA orders 2…{}\n",
                           s.responses.size() * s.references.size(), s.responses.size(), s.references.size(),
                           s.lines.size(), s.df, max_order);
  std::cout << "mode   frequency (Hz)      ± (Hz)   damping (%)     ± (%)     MPC  orders\n";
  std::vector<std::int64_t> nodes;
  for (const auto& r : s.responses)
    if (std::find(nodes.begin(), nodes.end(), r.first) == nodes.end()) nodes.push_back(r.first);
  uff::UffFile out;
  bool rotations_dropped = false;
  for (std::size_t m = 0; m < st.modes.size(); ++m) {
    const id::ClusteredMode& md = st.modes[m];
    std::cout << fmt::format("{:4d} {:16.6f} {:11.3e} {:13.4f} {:9.3e} {:7.4f} {:7d}\n", m + 1, md.hz, md.hz_std,
                             100 * md.zeta, 100 * md.zeta_std, md.mpc, md.poles);
    const Eigen::VectorXcd phi = id::rotate_to_real(md.shape);
    nlohmann::json shape = nlohmann::json::array();
    Eigen::MatrixXd values = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(nodes.size()), 3);
    for (std::size_t o = 0; o < s.responses.size(); ++o) {
      const auto [node, dir] = s.responses[o];
      const double sign = dir < 0 ? -1.0 : 1.0;
      const std::complex<double> v = sign * phi(static_cast<Eigen::Index>(o));
      shape.push_back({node, std::abs(dir), v.real(), v.imag()});
      if (std::abs(dir) >= 1 && std::abs(dir) <= 3) {
        const auto row = std::find(nodes.begin(), nodes.end(), node) - nodes.begin();
        values(row, std::abs(dir) - 1) = v.real();
      } else {
        rotations_dropped = true;
      }
    }
    modes.push_back({{"hz", md.hz},
                     {"zeta", md.zeta},
                     {"hz_std", md.hz_std},
                     {"zeta_std", md.zeta_std},
                     {"mpc", md.mpc},
                     {"orders", md.poles},
                     {"shape", shape}});
    out.datasets.emplace_back(uff::NodalData55::normal_mode(static_cast<std::int64_t>(m + 1), md.hz, nodes, values,
                                                            0.0, md.zeta));
  }
  if (st.modes.empty()) std::cout << "(no mode stable across the orders)\n";
  std::cerr << "note: poles not kept:";
  for (const auto& [reason, count] : rejected) std::cerr << " " << reason << " " << count << ";";
  std::cerr << "\n";
  if (rotations_dropped) std::cerr << "warning: rotational responses are in the JSON only (UFF 55 gets X, Y, Z)\n";

  if (vm.count("json")) {
    nlohmann::json j;
    j["modes"] = modes;
    j["method"] = method;
    j["rejected"] = rejected;
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
      "  modes FILE.unv [--method era] [--json OUT] [--uff OUT]   modes from the FRFs (UFF 58) of a modal test\n";
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
