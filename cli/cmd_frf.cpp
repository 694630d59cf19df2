/// \file cmd_frf.cpp
/// `ssid frf DECK --drive G,C --response G,C ...`: FRFs synthesized from the deck's
/// mass-normalised modes by modal superposition (the seed report's Eq. 2), with modal
/// damping given or taken from identified modes; UFF 58 and JSON out, and with
/// --measured the overlay of analysis and measured FRFs (the seed's Figures 4–7) as SVG
/// with the FRAC of each pair. docs/frf.md describes it.
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
#include <optional>
#include <sstream>

#include "cli/cli_util.hpp"
#include "cli/exit_codes.hpp"
#include "cli/model_load.hpp"
#include "cli/report/frf_chart.hpp"
#include "cli/report/svg.hpp"
#include "estimator/identification/frf_synthesis.hpp"
#include "estimator/reporting/number_text.hpp"
#include "formats/parse_error.hpp"
#include "formats/uff.hpp"

namespace ssid::cli {

namespace {

namespace uff = formats::uff;
namespace id = estimator::identification;
using cd = std::complex<double>;
using formats::InputError;

/// "G,C" pairs from option values: each value holds one or more pairs, "3,1" or "3,1,4,2".
std::vector<translators::Dof> parse_dofs(const std::vector<std::string>& values, const std::string& option) {
  std::vector<translators::Dof> out;
  for (const std::string& v : values) {
    std::vector<std::string> fields;
    std::stringstream ss(v);
    for (std::string f; std::getline(ss, f, ',');) fields.push_back(f);
    if (fields.empty() || fields.size() % 2)
      throw InputError(fmt::format("{} \"{}\": expected GRID,COMPONENT pairs (e.g. 12,3 or 12,3,14,1)", option, v));
    for (std::size_t k = 0; k < fields.size(); k += 2) {
      std::size_t used_g = 0, used_c = 0;
      long long g = 0;
      int c = 0;
      try {
        g = std::stoll(fields[k], &used_g);
        c = std::stoi(fields[k + 1], &used_c);
      } catch (const std::exception&) {
        used_g = 0;
      }
      if (used_g == 0 || used_g != fields[k].size() || used_c != fields[k + 1].size() || g < 1 || c < 1 || c > 6)
        throw InputError(fmt::format("{} \"{}\": \"{},{}\" is not a grid id ≥ 1 and a component 1–6", option, v,
                                     fields[k], fields[k + 1]));
      out.push_back({g, c});
    }
  }
  return out;
}

/// Modal damping of each FE mode: from the identified modes of `path` (the nearest in
/// frequency within `tol` relative, each identified mode used once, closest pairs first),
/// the rest `fallback` (NaN: the mean of the identified ζ). `source` says which per mode.
Eigen::VectorXd damping_from_identified(const std::string& path, const Eigen::VectorXd& fe_hz, double tol,
                                        double fallback, std::vector<std::string>& source) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open the identified modes (--modes-from)");
  nlohmann::json j;
  try {
    in >> j;
  } catch (const nlohmann::json::exception& e) {
    throw InputError(fmt::format("{}: not JSON ({})", path, e.what()));
  }
  if (!j.contains("modes") || !j["modes"].is_array() || j["modes"].empty())
    throw InputError(path + ": no \"modes\" array (expected the JSON of ssid identify modes)");
  std::vector<std::pair<double, double>> test;  // hz, zeta
  for (std::size_t k = 0; k < j["modes"].size(); ++k) {
    const auto& m = j["modes"][k];
    if (!m.contains("hz") || !m.contains("zeta") || !m["hz"].is_number() || !m["zeta"].is_number())
      throw InputError(fmt::format("{}: modes[{}] has no numeric \"hz\" and \"zeta\"", path, k));
    const double hz = m["hz"], z = m["zeta"];
    if (!(hz > 0) || !(z >= 0))
      throw InputError(fmt::format("{}: modes[{}]: {} Hz, ζ = {} (expected > 0 Hz and ζ ≥ 0)", path, k, hz, z));
    test.emplace_back(hz, z);
  }
  std::vector<double> test_hz;
  double mean = 0;
  for (const auto& t : test) test_hz.push_back(t.first), mean += t.second;
  mean /= static_cast<double>(test.size());
  const double rest = std::isnan(fallback) ? mean : fallback;
  Eigen::VectorXd zeta = Eigen::VectorXd::Constant(fe_hz.size(), rest);
  source.assign(static_cast<std::size_t>(fe_hz.size()),
                std::isnan(fallback) ? "mean of the identified" : "--damping (no identified mode near)");
  const auto partner = id::damping_partners(fe_hz, test_hz, tol);
  for (std::size_t r = 0; r < partner.size(); ++r)
    if (const auto t = partner[r]) {
      zeta(static_cast<Eigen::Index>(r)) = test[*t].second;
      source[r] = fmt::format("identified mode {} at {} Hz", *t + 1, estimator::significant(test[*t].first, 6));
    }
  return zeta;
}

/// The measured FRF from `drive` to `response` in `file` (dataset 58, function type 4),
/// turned to + directions; nullptr when there is none.
const uff::Function58* find_measured(const uff::UffFile& file, const translators::Dof& drive,
                                     const translators::Dof& response) {
  for (const auto* f : file.functions())
    if (f->function_type == 4 && f->reference_node == drive.point && std::abs(f->reference_direction) == drive.component &&
        f->response_node == response.point && std::abs(f->response_direction) == response.component)
      return f;
  return nullptr;
}

}  // namespace

int cmd_frf(const Args& args) {
  po::options_description desc("ssid frf options");
  desc.add_options()("deck", po::value<std::string>()->required(), "NASTRAN input file (SOL 103 bulk data)")(
      "drive", po::value<std::string>()->required(), "the force's DOF: GRID,COMPONENT (component 1–6)")(
      "response", po::value<std::vector<std::string>>()->multitoken()->required(),
      "response DOFs: GRID,COMPONENT pairs, e.g. --response 12,3 14,1 (or 12,3,14,1)")(
      "damping", po::value<double>(),
      "modal damping ratio ζ of every mode (0.01 = 1 %); with --modes-from, of the modes no identified mode is near")(
      "modes-from", po::value<std::string>(),
      "the JSON of ssid identify modes: each FE mode takes ζ of the identified mode nearest in frequency")(
      "pair-tol", po::value<double>()->default_value(10.0, "10"),
      "--modes-from: largest frequency difference of a FE mode and its identified mode, %")(
      "band", po::value<std::string>(), "frequency band F1:F2, Hz (default: 0 to 1.2 × the highest mode; with "
                                        "--measured, the measured lines)")(
      "lines", po::value<int>()->default_value(1001), "number of frequency lines over the band (without --measured)")(
      "quantity", po::value<std::string>(),
      "displacement (receptance), velocity (mobility) or acceleration (accelerance); default: the measured FRFs' "
      "ordinate type with --measured, else displacement")(
      "nmodes", po::value<int>(), "the lowest N modes (default: the deck's EIGRL/EIGR; every mode of a small model)")(
      "measured", po::value<std::string>(), "universal file with measured FRFs (dataset 58, type 4) to overlay")(
      "uff", po::value<std::string>(), "write the synthesized FRFs as UFF 58 (function type 4)")(
      "json", po::value<std::string>(), "write the FRFs (and the measured ones) as JSON ('-' for stdout)")(
      "svg", po::value<std::string>(), "write the overlay of magnitude and phase, analysis against measured, as SVG");
  po::positional_options_description pos;
  pos.add("deck", 1);
  po::variables_map vm;
  int rc = 0;
  if (!parse_options(args,
                     "ssid frf DECK --drive G,C --response G,C ... [--damping Z | --modes-from IDENTIFIED.json] "
                     "[--band F1:F2] [--lines N] [--quantity displacement|velocity|acceleration] [--nmodes N] "
                     "[--measured FILE.unv] [--uff OUT.unv] [--json OUT] [--svg OUT.svg]",
                     desc, pos, vm, rc))
    return rc;
  TextOut text_out(vm);
  std::ostream& text = text_out.stream();
  if (!vm.count("damping") && !vm.count("modes-from")) {
    print_error("give the modal damping: --damping Z (a ratio, 0.01 = 1 %) or --modes-from IDENTIFIED.json");
    return kExitBadInput;
  }
  const double damping = vm.count("damping") ? vm["damping"].as<double>() : std::numeric_limits<double>::quiet_NaN();
  if (vm.count("damping") && !(damping >= 0 && damping < 1)) {
    print_error(fmt::format("--damping: expected a ratio 0 ≤ ζ < 1 (0.01 = 1 %), got {}", damping));
    return kExitBadInput;
  }
  const double pair_tol = vm["pair-tol"].as<double>();
  if (!(pair_tol > 0)) {
    print_error(fmt::format("--pair-tol: expected a percentage > 0, got {}", pair_tol));
    return kExitBadInput;
  }
  const int nlines = vm["lines"].as<int>();
  if (nlines < 2) {
    print_error(fmt::format("--lines: expected at least 2, got {}", nlines));
    return kExitBadInput;
  }
  if (vm.count("measured") && !vm["lines"].defaulted()) {
    print_error("--lines: with --measured the lines are the measured FRFs' (narrow them with --band)");
    return kExitBadInput;
  }
  std::optional<id::FrfQuantity> quantity;
  if (vm.count("quantity")) {
    const std::string q = vm["quantity"].as<std::string>();
    if (q == "displacement") quantity = id::FrfQuantity::Displacement;
    else if (q == "velocity") quantity = id::FrfQuantity::Velocity;
    else if (q == "acceleration") quantity = id::FrfQuantity::Acceleration;
    else {
      print_error("--quantity: expected displacement, velocity or acceleration, got \"" + q + "\"");
      return kExitBadInput;
    }
  }
  std::optional<std::pair<double, double>> band;
  if (vm.count("band")) {
    const std::string b = vm["band"].as<std::string>();
    const auto colon = b.find(':');
    double lo = 0, hi = 0;
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
      return kExitBadInput;
    }
    band = std::make_pair(lo, hi);
  }
  const std::vector<translators::Dof> drives = parse_dofs({vm["drive"].as<std::string>()}, "--drive");
  if (drives.size() != 1) {
    print_error("--drive: expected one GRID,COMPONENT pair, got \"" + vm["drive"].as<std::string>() + "\"");
    return kExitBadInput;
  }
  const translators::Dof drive = drives.front();
  const std::vector<translators::Dof> responses = parse_dofs(vm["response"].as<std::vector<std::string>>(), "--response");

  // The measured FRFs first: a bad file is reported before the eigen-solve.
  std::optional<uff::UffFile> measured;
  std::vector<const uff::Function58*> meas(responses.size(), nullptr);
  if (vm.count("measured")) {
    measured = uff::read_uff(vm["measured"].as<std::string>());
    std::size_t found = 0;
    for (std::size_t o = 0; o < responses.size(); ++o) {
      meas[o] = find_measured(*measured, drive, responses[o]);
      if (meas[o]) ++found;
      else
        std::cerr << fmt::format("note: {} has no FRF of response {},{} to the drive {},{} (dataset 58, type 4): "
                                 "analysis only for it\n",
                                 measured->path, responses[o].point, responses[o].component, drive.point, drive.component);
    }
    if (found == 0)
      throw InputError(fmt::format("{}: no FRF (dataset 58, function type 4) from the drive {},{} to any response",
                                   measured->path, drive.point, drive.component));
    const uff::Function58* first = nullptr;
    for (const auto* f : meas)
      if (f && !first) first = f;
    const auto lines0 = first->abscissa();
    for (const auto* f : meas)
      if (f && f->abscissa() != lines0)
        throw InputError(fmt::format("{}: dataset 58: {} lines from {} Hz (expected the lines of {})", f->where.str(),
                                     f->y.size(), f->abscissa().empty() ? 0.0 : f->abscissa().front(),
                                     first->where.str()));
    // The measured FRFs' quantity, from the ordinate numerator's data type.
    const int code = first->axes[1].specific_data_type;
    const std::optional<id::FrfQuantity> mq = id::quantity_of_data_type(code);
    if (quantity && mq && *quantity != *mq)
      throw InputError(fmt::format("{}: the measured FRFs are of {} (ordinate type {}), --quantity asks for {}",
                                   first->where.str(), id::quantity_name(*mq), code, id::quantity_name(*quantity)));
    if (!quantity && mq) quantity = mq;
    if (!quantity)
      std::cerr << fmt::format("note: {}: the measured ordinate's data type is {} (not 8, 11 or 12): synthesizing "
                               "receptance; give --quantity if the FRFs are mobility or accelerance\n",
                               first->where.str(), code);
  }
  const id::FrfQuantity q = quantity.value_or(id::FrfQuantity::Displacement);

  LoadedModel lm = load_model(vm["deck"].as<std::string>());
  print_model_notes(lm);
  const translators::FeModel& model = *lm.model;
  const auto& gset = model.geometry().gset();
  const auto locate = [&](const translators::Dof& d, const std::string& what) {
    const auto i = gset.find(d);
    if (!i)
      throw InputError(fmt::format("{}: {} {},{}: the model has no such DOF (grid {} {})", lm.path, what, d.point,
                                   d.component, d.point,
                                   std::any_of(gset.dofs().begin(), gset.dofs().end(),
                                               [&](const translators::Dof& g) { return g.point == d.point; })
                                       ? "has no component " + std::to_string(d.component)
                                       : "is not in the deck"));
    return static_cast<Eigen::Index>(*i);
  };
  const Eigen::Index drive_row = locate(drive, "--drive");
  std::vector<Eigen::Index> rows;
  for (const auto& r : responses) rows.push_back(locate(r, "--response"));

  const translators::FeOperators op = model.operators(model.initial_parameters(), false);
  std::string source;
  std::optional<int> nmodes;
  if (vm.count("nmodes")) nmodes = vm["nmodes"].as<int>();
  estimator::EigenOptions eo = eigen_options(model, nmodes, op.K.rows(), source);
  eo.norm = estimator::ModeNormalization::Mass;  // Eq. 2 needs φᵀMφ = 1, whatever the deck's NORM
  const estimator::EigenResult er = solve_model(op, eo, a_set_dofs(model));
  for (const auto& w : er.warnings) std::cerr << "warning: " << w << "\n";
  if (er.size() == 0) throw InputError(lm.path + ": no modes to superpose (" + source + ")");
  const Eigen::MatrixXd g = model.expand(er.modes);

  id::ModalFrfModel mm;
  mm.eigenvalue = er.eigenvalues;
  mm.drive = g.row(drive_row).transpose();
  mm.response.resize(static_cast<Eigen::Index>(rows.size()), er.size());
  for (std::size_t o = 0; o < rows.size(); ++o) mm.response.row(static_cast<Eigen::Index>(o)) = g.row(rows[o]);
  if (mm.drive.cwiseAbs().maxCoeff() == 0)
    throw InputError(fmt::format("{}: --drive {},{} does not move in any mode (constrained): no force enters there",
                                 lm.path, drive.point, drive.component));
  Eigen::VectorXd fe_hz(er.size());
  for (int r = 0; r < er.size(); ++r) fe_hz(r) = er.cycles(r);
  std::vector<std::string> zeta_source;
  if (vm.count("modes-from"))
    mm.zeta = damping_from_identified(vm["modes-from"].as<std::string>(), fe_hz, pair_tol / 100, damping, zeta_source);
  else {
    mm.zeta = Eigen::VectorXd::Constant(er.size(), damping);
    zeta_source.assign(static_cast<std::size_t>(er.size()), "--damping");
  }

  // Frequency lines.
  std::vector<double> f;
  if (measured) {
    const uff::Function58* first = nullptr;
    for (const auto* m : meas)
      if (m && !first) first = m;
    for (double x : first->abscissa())
      if (!band || (x >= band->first && x <= band->second)) f.push_back(x);
    if (f.empty())
      throw InputError(fmt::format("{}: no measured line in --band {}:{} Hz", first->where.str(), band->first,
                                   band->second));
  } else {
    const bool rigid = (er.eigenvalues.array() <= 1e-8 * er.eigenvalues.cwiseAbs().maxCoeff()).any();
    const double hi = band ? band->second : 1.2 * fe_hz.maxCoeff();
    if (!(hi > 0)) throw InputError(lm.path + ": every mode is at 0 Hz: give --band F1:F2");
    const double step0 = hi / (nlines - 1);
    // A rigid-body mode makes 0 Hz infinite: the default band then starts one step above.
    const double lo = band ? band->first : (rigid ? step0 : 0.0);
    for (int k = 0; k < nlines; ++k) f.push_back(lo + (hi - lo) * k / (nlines - 1));
  }
  const Eigen::Map<const Eigen::VectorXd> fv(f.data(), static_cast<Eigen::Index>(f.size()));
  const Eigen::MatrixXcd H = id::synthesize_frf(fv, mm, q);

  // stdout: the modes and the FRFs' peaks.
  text << fmt::format("{}: {} mode(s) ({}), mass-normalised; {} FRF(s) of {} per force from drive {},{}, {} "
                           "line(s) {}…{} Hz\n",
                           lm.path, er.size(), source, responses.size(), id::quantity_name(q), drive.point, drive.component,
                           f.size(), estimator::significant(f.front(), 6), estimator::significant(f.back(), 6));
  text << "mode   frequency (Hz)   damping (%)  damping from\n";
  for (int r = 0; r < er.size(); ++r)
    text << fmt::format("{:4d} {:16.6f} {:13.4f}  {}\n", r + 1, fe_hz(r), 100 * mm.zeta(r),
                             zeta_source[static_cast<std::size_t>(r)]);
  const std::string unit = id::quantity_unit(q);
  text << fmt::format("\nresponse    peak |H| ({})   at (Hz){}\n", unit, measured ? "   measured peak   at (Hz)     FRAC" : "");

  nlohmann::json j;
  j["deck"] = lm.path;
  j["drive"] = {drive.point, drive.component};
  j["quantity"] = id::quantity_name(q);
  j["unit"] = unit + " (the deck's units)";
  j["frequency_hz"] = f;
  j["modes"] = nlohmann::json::array();
  for (int r = 0; r < er.size(); ++r)
    j["modes"].push_back({{"mode", r + 1}, {"hz", fe_hz(r)}, {"zeta", mm.zeta(r)},
                          {"damping_from", zeta_source[static_cast<std::size_t>(r)]}});
  j["responses"] = nlohmann::json::array();

  uff::UffFile out;
  std::string svg_body;
  double svg_height = 0;
  for (std::size_t o = 0; o < responses.size(); ++o) {
    const auto oi = static_cast<Eigen::Index>(o);
    Eigen::Index peak = 0;
    H.col(oi).cwiseAbs().maxCoeff(&peak);
    std::string line = fmt::format("{:>8} {:18.6e} {:10.4f}", fmt::format("{},{}", responses[o].point, responses[o].component),
                                   std::abs(H(peak, oi)), f[static_cast<std::size_t>(peak)]);
    nlohmann::json jr{{"grid", responses[o].point}, {"component", responses[o].component}};
    std::vector<double> re, im;
    for (Eigen::Index k = 0; k < H.rows(); ++k) re.push_back(H(k, oi).real()), im.push_back(H(k, oi).imag());
    jr["re"] = re;
    jr["im"] = im;
    std::vector<report::FrfCurve> curves{{"analysis", "#1f5fa8", "analysis (Eq. 2)", f, {}, ""}};
    for (Eigen::Index k = 0; k < H.rows(); ++k) curves[0].h.push_back(H(k, oi));
    if (const uff::Function58* m = meas[o]) {
      const double sign = (m->response_direction < 0 ? -1.0 : 1.0) * (m->reference_direction < 0 ? -1.0 : 1.0);
      const auto x = m->abscissa();
      Eigen::VectorXcd hm(static_cast<Eigen::Index>(f.size()));
      std::size_t n = 0;
      for (std::size_t k = 0; k < x.size(); ++k)
        if (!band || (x[k] >= band->first && x[k] <= band->second)) hm(static_cast<Eigen::Index>(n++)) = sign * m->y[k];
      Eigen::Index mp = 0;
      hm.cwiseAbs().maxCoeff(&mp);
      const double frac = id::frf_assurance(H.col(oi), hm);
      line += fmt::format(" {:17.6e} {:9.4f} {:8.5f}", std::abs(hm(mp)), f[static_cast<std::size_t>(mp)], frac);
      std::vector<double> mre, mim;
      for (Eigen::Index k = 0; k < hm.size(); ++k) mre.push_back(hm(k).real()), mim.push_back(hm(k).imag());
      jr["measured"] = {{"re", mre}, {"im", mim}, {"frac", frac}, {"at", m->where.str()}};
      curves.push_back({"measured", "#c0392b", "measured (" + m->where.str() + ")", f, {}, ""});
      for (Eigen::Index k = 0; k < hm.size(); ++k) curves.back().h.push_back(hm(k));
    }
    text << line << "\n";
    j["responses"].push_back(jr);
    if (vm.count("svg"))
      svg_body += report::frf_overlay_charts(curves,
                                 fmt::format("response {},{} / drive {},{}", responses[o].point, responses[o].component,
                                             drive.point, drive.component),
                                 unit, fmt::format("frf-{}-{}", responses[o].point, responses[o].component), svg_height);

    uff::Function58 fn;
    fn.id_lines = {"ssid frf: modal superposition (Eq. 2) of " + lm.path,
                   fmt::format("{} modes, {} per force", er.size(), id::quantity_name(q)), "NONE", "NONE", "NONE"};
    fn.function_type = 4;
    fn.function_id = static_cast<std::int64_t>(o + 1);
    fn.response_node = responses[o].point;
    fn.response_direction = responses[o].component;
    fn.reference_node = drive.point;
    fn.reference_direction = drive.component;
    fn.ordinate_type = 6;
    // Even lines (ours, or measured ones that are) as min + increment; others with their abscissa.
    const double df = f.size() > 1 ? f[1] - f[0] : 0;
    bool uniform = df > 0;
    for (std::size_t k = 1; k < f.size(); ++k) uniform = uniform && std::abs(f[k] - f[k - 1] - df) <= 1e-9 * df;
    fn.even = uniform;
    fn.abscissa_min = f.front();
    fn.abscissa_increment = fn.even ? df : 0.0;
    fn.axes[0].specific_data_type = 18;  // frequency
    fn.axes[0].label = "Frequency";
    fn.axes[0].units = "Hz";
    fn.axes[1].specific_data_type = id::quantity_data_type(q);
    fn.axes[1].length_exponent = 1;
    fn.axes[1].label = id::quantity_name(q);
    fn.axes[2].specific_data_type = 13;  // excitation force
    fn.axes[2].force_exponent = 1;
    fn.axes[2].label = "force";
    fn.x = f;
    for (Eigen::Index k = 0; k < H.rows(); ++k) fn.y.push_back(H(k, oi));
    out.datasets.emplace_back(fn);
  }

  if (vm.count("json")) write_json(vm["json"].as<std::string>(), j);
  if (vm.count("uff")) {
    out.path = vm["uff"].as<std::string>();
    uff::write_uff(out, out.path, uff::Precision::Standard);
    std::cerr << "wrote " << out.path << ": " << responses.size() << " FRF(s), dataset 58\n";
  }
  if (vm.count("svg")) {
    const std::string path = vm["svg"].as<std::string>();
    std::ofstream s(path);
    if (!s) throw InputError(path + ": cannot write the SVG");
    s << fmt::format("<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"720\" height=\"{0}\" viewBox=\"0 0 720 {0}\" "
                     "font-family=\"sans-serif\">\n<style>text{{font-size:11px;fill:#222}} .label{{font-size:12px}} "
                     ".grid{{stroke:#e4e4e4}} .frame{{fill:none;stroke:#666}}</style>\n<rect width=\"100%\" "
                     "height=\"100%\" fill=\"#fff\"/>\n{1}</svg>\n",
                     report::px(svg_height + 10), svg_body);
    if (!s) throw InputError(path + ": cannot write the SVG");
    std::cerr << "wrote " << path << ": magnitude and phase of " << responses.size() << " FRF(s)\n";
  }
  if (er.sturm_mismatch) {
    print_error("frf: the Sturm count disagrees with the modes found in the band: modes may be missing from the sum");
    return kExitUntrusted;
  }
  return kExitSuccess;
}

}  // namespace ssid::cli
