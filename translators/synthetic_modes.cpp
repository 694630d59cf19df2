#include "translators/synthetic_modes.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <unordered_map>
#include <unordered_set>

#include "formats/parse_error.hpp"

namespace ssid::translators {

double NormalDeviates::operator()() {
  if (m_has_spare) {
    m_has_spare = false;
    return m_spare;
  }
  constexpr double two_pi = 6.283185307179586476925286766559;
  constexpr double ulp53 = 1.0 / 9007199254740992.0;  // 2^-53
  const double u1 = (static_cast<double>(m_engine() >> 11) + 1.0) * ulp53;
  const double u2 = static_cast<double>(m_engine() >> 11) * ulp53;
  const double r = std::sqrt(-2.0 * std::log(u1));
  m_spare = r * std::sin(two_pi * u2);
  m_has_spare = true;
  return r * std::cos(two_pi * u2);
}

namespace {

std::string fmt_pct(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

}  // namespace

SyntheticTest synthetic_test(const FeModeData& fe, const DofMap& gset, const std::vector<GridPosition>& grids,
                             const SyntheticTestOptions& options) {
  const Eigen::Index nm = fe.shapes.cols();
  if (static_cast<std::size_t>(fe.shapes.rows()) != gset.size())
    throw std::invalid_argument("synthetic_test: " + std::to_string(fe.shapes.rows()) + " shape rows for a g-set of " +
                                std::to_string(gset.size()) + " DOFs");
  if (fe.frequency_hz.size() != static_cast<std::size_t>(nm))
    throw std::invalid_argument("synthetic_test: " + std::to_string(fe.frequency_hz.size()) + " frequencies for " +
                                std::to_string(nm) + " modes");
  if (!fe.generalized_mass.empty() && fe.generalized_mass.size() != static_cast<std::size_t>(nm))
    throw std::invalid_argument("synthetic_test: " + std::to_string(fe.generalized_mass.size()) +
                                " generalized masses for " + std::to_string(nm) + " modes");
  if (!(options.noise_freq_pct >= 0) || !(options.noise_shape_pct >= 0))
    throw formats::InputError("synthetic_test: noise percentages must be zero or positive");

  std::unordered_map<std::int64_t, std::size_t> by_id;
  for (std::size_t i = 0; i < grids.size(); ++i) by_id.emplace(grids[i].id, i);
  std::vector<std::int64_t> sensors = options.sensors;
  if (sensors.empty())
    for (const auto& g : grids) sensors.push_back(g.id);
  std::unordered_set<std::int64_t> seen;
  const int ncomp = options.rotations ? 6 : 3;

  SyntheticTest out;
  ModeSet& set = out.modes;
  std::vector<formats::uff::Node> nodes;
  // Observation rows: sensor DOF (grid, basic axis) = Σ_c R(axis, c) u_cd(c).
  std::vector<std::vector<std::pair<std::size_t, double>>> rows;
  for (auto id : sensors) {
    auto it = by_id.find(id);
    if (it == by_id.end()) throw formats::InputError("sensor grid " + std::to_string(id) + " is not a grid of the model");
    if (!seen.insert(id).second) continue;
    const GridPosition& g = grids[it->second];
    formats::uff::Node n;
    n.id = id;
    n.xyz = {g.position.x(), g.position.y(), g.position.z()};
    nodes.push_back(n);
    for (int a = 1; a <= ncomp; ++a) {
      const int base = a <= 3 ? 0 : 3;
      std::vector<std::pair<std::size_t, double>> terms;
      for (int c = 0; c < 3; ++c) {
        const double r = g.frame(a - 1 - base, c);
        if (r == 0.0) continue;
        auto dof = gset.find({id, base + c + 1});
        if (!dof)
          throw formats::InputError("sensor grid " + std::to_string(id) + " component " + std::to_string(base + c + 1) +
                                      " is not in the g-set");
        terms.emplace_back(*dof, r);
      }
      set.dofs.push_back({id, a});
      rows.push_back(std::move(terms));
    }
  }

  set.shapes.setZero(static_cast<Eigen::Index>(rows.size()), nm);
  for (std::size_t r = 0; r < rows.size(); ++r)
    for (const auto& [dof, c] : rows[r])
      set.shapes.row(static_cast<Eigen::Index>(r)) += c * fe.shapes.row(static_cast<Eigen::Index>(dof));

  NormalDeviates z(options.seed);
  const double pf = options.noise_freq_pct / 100.0, ps = options.noise_shape_pct / 100.0;
  for (Eigen::Index j = 0; j < nm; ++j) {
    double f = fe.frequency_hz[static_cast<std::size_t>(j)];
    f *= 1.0 + pf * z();
    const double scale = set.shapes.rows() ? set.shapes.col(j).cwiseAbs().maxCoeff() : 0.0;
    for (Eigen::Index i = 0; i < set.shapes.rows(); ++i) set.shapes(i, j) += ps * scale * z();
    set.frequency_hz.push_back(f);
    set.numbers.push_back(static_cast<int>(j) + 1);
    set.damping.push_back(0.0);
    set.modal_mass.push_back(fe.generalized_mass.empty() ? 1.0 : fe.generalized_mass[static_cast<std::size_t>(j)]);
  }

  out.file = mode_set_to_uff(set, nodes);
  const std::string noise = "noise: frequency " + fmt_pct(options.noise_freq_pct) + " %, shape " +
                            fmt_pct(options.noise_shape_pct) + " % of max, seed " + std::to_string(options.seed);
  for (auto& d : out.file.datasets)
    if (auto* m = std::get_if<formats::uff::NodalData55>(&d)) {
      m->id_lines[0] = options.description.substr(0, 80);
      m->id_lines[1] = noise.substr(0, 80);
      m->id_lines[2] = "mode " + std::to_string(m->mode_number());
    }
  return out;
}

SyntheticTest synthetic_test(const FeModeData& a_modes, const Reduction& reduction, const DofMap& gset,
                             const std::vector<GridPosition>& grids, const SyntheticTestOptions& options) {
  if (a_modes.shapes.rows() != reduction.T.cols())
    throw std::invalid_argument("synthetic_test: " + std::to_string(a_modes.shapes.rows()) +
                                " shape rows for an a-set of " + std::to_string(reduction.T.cols()) + " DOFs");
  FeModeData g = a_modes;
  g.shapes = reduction.T * a_modes.shapes;
  return synthetic_test(g, gset, grids, options);
}

std::vector<std::int64_t> parse_sensor_list(const std::string& text, const std::vector<GridPosition>& grids,
                                            const std::string& source) {
  std::string clean;
  {
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) {
      auto h = line.find('#');
      if (h != std::string::npos) line.erase(h);
      for (char& c : line)
        if (c == ',' || c == ';' || c == '\t' || c == '\r') c = ' ';
      clean += line + " ";
    }
  }
  std::vector<std::string> tokens;
  {
    std::istringstream in(clean);
    for (std::string t; in >> t;) tokens.push_back(t);
  }
  auto to_id = [&](const std::string& t) {
    std::size_t used = 0;
    long long v = 0;
    try {
      v = std::stoll(t, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != t.size() || t.empty())
      throw formats::InputError(source + ": expected a grid id, \"A:B\" or \"A THRU B\", got \"" + t + "\"");
    return static_cast<std::int64_t>(v);
  };
  auto range = [&](std::int64_t a, std::int64_t b, std::vector<std::int64_t>& out) {
    if (b < a) throw formats::InputError(source + ": range " + std::to_string(a) + " to " + std::to_string(b) + " is empty");
    for (const auto& g : grids)
      if (g.id >= a && g.id <= b) out.push_back(g.id);
  };
  std::vector<std::int64_t> ids;
  for (std::size_t i = 0; i < tokens.size(); ++i) {
    const std::string& t = tokens[i];
    auto colon = t.find(':');
    if (colon != std::string::npos) {
      range(to_id(t.substr(0, colon)), to_id(t.substr(colon + 1)), ids);
    } else if (i + 2 < tokens.size() && (tokens[i + 1] == "THRU" || tokens[i + 1] == "thru")) {
      range(to_id(t), to_id(tokens[i + 2]), ids);
      i += 2;
    } else {
      ids.push_back(to_id(t));
    }
  }
  return ids;
}

}  // namespace ssid::translators
