#include "translators/measurement/sensor_mapping.hpp"

#include <cstdio>
#include <limits>
#include <map>
#include <stdexcept>
#include <unordered_map>
#include <unordered_set>

#include "formats/parse_error.hpp"

#include "formats/parse_error.hpp"

namespace ssid::translators {

std::optional<std::int64_t> NodeMapping::grid_of(std::int64_t test_node) const {
  for (const auto& m : matches)
    if (m.test_node == test_node) return m.grid;
  return std::nullopt;
}

namespace {
std::string fmt_distance(double d) {
  char b[32];
  std::snprintf(b, sizeof b, "%.6g", d);
  return b;
}
}  // namespace

NodeMapping map_test_nodes(const std::vector<TestNode>& nodes, const std::vector<GridPosition>& grids,
                           const NodeMapOptions& o) {
  if (o.by != MapBy::Id && !(o.tolerance > 0))
    throw formats::InputError("mapping test nodes by position needs a tolerance > 0 (model length units)");
  std::unordered_map<std::int64_t, std::size_t> by_id;
  for (std::size_t g = 0; g < grids.size(); ++g) by_id.emplace(grids[g].id, g);

  NodeMapping m;
  for (const auto& n : nodes) {
    if (n.displacement_cs != 0)
      m.problems.push_back("test node " + std::to_string(n.id) + " gives its directions in displacement system " +
                           std::to_string(n.displacement_cs) + ", which ssid does not apply: taken as global");
    if (o.by != MapBy::Position) {
      auto it = by_id.find(n.id);
      if (it != by_id.end()) {
        m.matches.push_back({n.id, n.id, (grids[it->second].position - n.position).norm(), false});
        continue;
      }
      if (o.by == MapBy::Id) {
        m.unmapped.push_back(n.id);
        m.why_unmapped[n.id] = "no grid with this id";
        m.problems.push_back("test node " + std::to_string(n.id) + ": " + m.why_unmapped[n.id]);
        continue;
      }
    }
    // Nearest grid (brute force: sensor counts are small next to the cost of a solve).
    double best = std::numeric_limits<double>::infinity();
    std::size_t best_g = grids.size();
    for (std::size_t g = 0; g < grids.size(); ++g) {
      const double d = (grids[g].position - n.position).squaredNorm();
      if (d < best) {
        best = d;
        best_g = g;
      }
    }
    best = std::sqrt(best);
    if (best_g < grids.size() && best <= o.tolerance) {
      m.matches.push_back({n.id, grids[best_g].id, best, true});
    } else {
      m.unmapped.push_back(n.id);
      m.why_unmapped[n.id] = best_g < grids.size() ? "nearest grid " + std::to_string(grids[best_g].id) + " at " +
                                                         fmt_distance(best) + " is beyond the tolerance " +
                                                         fmt_distance(o.tolerance)
                                                   : std::string("no grids");
      m.problems.push_back("test node " + std::to_string(n.id) + ": " + m.why_unmapped[n.id]);
    }
  }
  // Two test nodes on one grid is legal (redundant sensors) but usually a mistake.
  std::map<std::int64_t, std::vector<std::int64_t>> on_grid;
  for (const auto& x : m.matches) on_grid[x.grid].push_back(x.test_node);
  for (const auto& [g, tn] : on_grid)
    if (tn.size() > 1) {
      std::string s = "grid " + std::to_string(g) + " receives test nodes";
      for (auto t : tn) s += " " + std::to_string(t);
      m.problems.push_back(s);
    }
  return m;
}

void require_mapped(const std::vector<MeasuredDof>& measured, const NodeMapping& mapping, const std::string& test,
                    const std::string& model) {
  std::unordered_set<std::int64_t> mapped, seen;
  for (const auto& x : mapping.matches) mapped.insert(x.test_node);
  // Per node, in the order measured: "test node 5: no grid with this id".
  std::vector<std::string> lines;
  std::string single;  // the same for one node, naming the model
  for (const auto& md : measured) {
    if (mapped.count(md.node) || !seen.insert(md.node).second) continue;
    const std::string node = "test node " + std::to_string(md.node) + ": ";
    const auto why = mapping.why_unmapped.find(md.node);
    if (why != mapping.why_unmapped.end()) {
      lines.push_back(node + why->second);
      single = lines.back() + " in " + model;
    } else {
      lines.push_back(node + "not a node of the test geometry (dataset 15 or 2411)");
      single = lines.back() + ", so no grid of " + model;
    }
  }
  if (lines.empty()) return;
  const std::string lead = test.empty() ? "" : test + ": ";
  if (lines.size() == 1) throw formats::InputError(lead + single);
  constexpr std::size_t kShown = 10;
  std::string msg = lead + std::to_string(lines.size()) + " measured test nodes map to no grid of " + model + ":";
  for (std::size_t k = 0; k < lines.size() && k < kShown; ++k) msg += "\n  " + lines[k];
  if (lines.size() > kShown) msg += "\n  ... and " + std::to_string(lines.size() - kShown) + " more";
  throw formats::InputError(msg);
}

Observation observe(const std::vector<MeasuredDof>& measured, const NodeMapping& mapping,
                    const std::vector<GridPosition>& grids) {
  std::unordered_map<std::int64_t, std::size_t> by_id;
  for (std::size_t g = 0; g < grids.size(); ++g) by_id.emplace(grids[g].id, g);
  std::unordered_map<std::int64_t, std::int64_t> grid_of;
  for (const auto& x : mapping.matches) grid_of.emplace(x.test_node, x.grid);

  Observation obs;
  for (const auto& md : measured) {
    if (md.direction == 0 || md.direction < -6 || md.direction > 6)
      throw formats::InputError("test node " + std::to_string(md.node) + ": direction " +
                                  std::to_string(md.direction) + " is not one of ±1..±6");
    auto it = grid_of.find(md.node);
    if (it == grid_of.end() || !by_id.count(it->second)) {
      obs.unmapped.push_back(md);
      continue;
    }
    const GridPosition& g = grids[by_id.at(it->second)];
    const int axis = (std::abs(md.direction) - 1) % 3;     // 0..2
    const int offset = std::abs(md.direction) > 3 ? 3 : 0;  // rotations are components 4..6
    const double sign = md.direction < 0 ? -1.0 : 1.0;
    ObservationRow row;
    row.measured = md;
    for (int c = 0; c < 3; ++c) {
      const double coef = sign * g.frame(axis, c);
      if (std::abs(coef) > 1e-15) row.terms.push_back({Dof{g.id, c + 1 + offset}, coef});
    }
    obs.rows.push_back(std::move(row));
  }
  return obs;
}

Eigen::SparseMatrix<double> observation_matrix(const Observation& obs, const DofMap& dofs) {
  std::vector<Eigen::Triplet<double>> t;
  for (std::size_t r = 0; r < obs.rows.size(); ++r)
    for (const auto& [dof, coef] : obs.rows[r].terms)
      if (auto k = dofs.find(dof)) t.emplace_back(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(*k), coef);
  Eigen::SparseMatrix<double> C(static_cast<Eigen::Index>(obs.rows.size()), static_cast<Eigen::Index>(dofs.size()));
  C.setFromTriplets(t.begin(), t.end());
  return C;
}

}  // namespace ssid::translators
