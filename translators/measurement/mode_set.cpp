#include "translators/measurement/mode_set.hpp"

#include <algorithm>
#include <map>
#include <set>
#include <unordered_map>
#include <variant>

namespace ssid::translators {

namespace {
std::int64_t key(const MeasuredDof& d) { return d.node * 16 + (d.direction + 8); }
}  // namespace

ModeSet modes_from_uff(const formats::uff::UffFile& file, ModeSetReport* report) {
  ModeSetReport local;
  ModeSetReport& rep = report ? *report : local;
  std::vector<const formats::uff::NodalData55*> modes;
  for (const auto* d : file.nodal_data()) {
    if (d->is_complex_mode()) ++rep.complex_modes;
    else if (!d->is_normal_mode() || d->is_complex()) ++rep.other;
    else modes.push_back(d);
  }
  ModeSet s;
  if (modes.empty()) return s;
  // DOFs present in every mode, ordered as in the first.
  std::map<std::int64_t, std::size_t> count;
  for (const auto* m : modes) {
    const int nc = std::min(m->values_per_node, 6);
    for (auto n : m->nodes)
      for (int c = 1; c <= nc; ++c) ++count[key({n, c})];
  }
  const auto* first = modes.front();
  for (auto n : first->nodes)
    for (int c = 1; c <= std::min(first->values_per_node, 6); ++c) {
      MeasuredDof d{n, c};
      if (count[key(d)] == modes.size()) s.dofs.push_back(d);
    }
  std::size_t dropped = 0;
  for (const auto& [k, c] : count) dropped += c != modes.size();
  if (dropped)
    rep.problems.push_back(std::to_string(dropped) + " DOF(s) are missing from some modes and are left out");
  std::unordered_map<std::int64_t, Eigen::Index> row;
  for (std::size_t r = 0; r < s.dofs.size(); ++r) row.emplace(key(s.dofs[r]), static_cast<Eigen::Index>(r));
  s.shapes.setZero(static_cast<Eigen::Index>(s.dofs.size()), static_cast<Eigen::Index>(modes.size()));
  for (std::size_t j = 0; j < modes.size(); ++j) {
    const auto* m = modes[j];
    const int nc = std::min(m->values_per_node, 6);
    for (std::size_t i = 0; i < m->nodes.size(); ++i)
      for (int c = 1; c <= nc; ++c) {
        auto it = row.find(key({m->nodes[i], c}));
        if (it != row.end()) s.shapes(it->second, static_cast<Eigen::Index>(j)) = m->values(static_cast<Eigen::Index>(i), c - 1);
      }
    s.frequency_hz.push_back(m->frequency_hz());
    s.numbers.push_back(static_cast<int>(m->mode_number()));
    s.damping.push_back(m->viscous_damping());
    s.modal_mass.push_back(m->modal_mass());
  }
  return s;
}

formats::uff::UffFile mode_set_to_uff(const ModeSet& set, const std::vector<formats::uff::Node>& nodes) {
  formats::uff::UffFile f;
  if (!nodes.empty()) {
    formats::uff::NodeSet ns;
    ns.dataset = 2411;
    ns.nodes = nodes;
    f.datasets.push_back(ns);
  }
  std::vector<std::int64_t> order;
  std::unordered_map<std::int64_t, Eigen::Index> node_row;
  bool rotations = false;
  for (const auto& d : set.dofs) {
    if (node_row.emplace(d.node, static_cast<Eigen::Index>(order.size())).second) order.push_back(d.node);
    rotations |= std::abs(d.direction) > 3;
  }
  const int ndv = rotations ? 6 : 3;
  for (Eigen::Index j = 0; j < set.shapes.cols(); ++j) {
    Eigen::MatrixXd v = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(order.size()), ndv);
    for (std::size_t r = 0; r < set.dofs.size(); ++r) {
      const auto& d = set.dofs[r];
      const double sign = d.direction < 0 ? -1.0 : 1.0;
      v(node_row.at(d.node), std::abs(d.direction) - 1) = sign * set.shapes(static_cast<Eigen::Index>(r), j);
    }
    const auto k = static_cast<std::size_t>(j);
    auto m = formats::uff::NodalData55::normal_mode(
        k < set.numbers.size() ? set.numbers[k] : static_cast<int>(j) + 1,
        k < set.frequency_hz.size() ? set.frequency_hz[k] : 0.0, order, v,
        k < set.modal_mass.size() ? set.modal_mass[k] : 0.0, k < set.damping.size() ? set.damping[k] : 0.0);
    f.datasets.push_back(std::move(m));
  }
  return f;
}

NodeSegments trace_segments(const formats::uff::UffFile& file) {
  std::set<std::pair<std::int64_t, std::int64_t>> out;
  for (const auto& d : file.datasets)
    if (const auto* t = std::get_if<formats::uff::TraceLine82>(&d))
      for (std::size_t k = 1; k < t->nodes.size(); ++k)
        if (t->nodes[k - 1] != 0 && t->nodes[k] != 0 && t->nodes[k - 1] != t->nodes[k])
          out.insert(std::minmax(t->nodes[k - 1], t->nodes[k]));
  return {out.begin(), out.end()};
}

NodeSegments segments_in_grids(const NodeSegments& segments, const NodeMapping& mapping) {
  std::set<std::pair<std::int64_t, std::int64_t>> out;
  for (const auto& [a, b] : segments) {
    const auto ga = mapping.grid_of(a), gb = mapping.grid_of(b);
    if (ga && gb && *ga != *gb) out.insert(std::minmax(*ga, *gb));
  }
  return {out.begin(), out.end()};
}

std::vector<TestNode> test_nodes(const formats::uff::UffFile& file) {
  std::vector<TestNode> out;
  for (const auto& n : file.nodes()) out.push_back({n.id, Eigen::Vector3d(n.xyz[0], n.xyz[1], n.xyz[2]), n.displacement_cs});
  return out;
}

std::vector<MeasuredDof> measured_dofs(const formats::uff::UffFile& file) {
  std::vector<MeasuredDof> r;
  std::set<std::int64_t> seen;
  for (const auto* f : file.functions()) {
    if (f->response_direction == 0) continue;
    MeasuredDof d{f->response_node, f->response_direction};
    if (seen.insert(key(d)).second) r.push_back(d);
  }
  return r;
}

ModeSet restrict_to(const ModeSet& set, const std::vector<MeasuredDof>& keep) {
  std::unordered_map<std::int64_t, Eigen::Index> row;
  for (std::size_t r = 0; r < set.dofs.size(); ++r) row.emplace(key(set.dofs[r]), static_cast<Eigen::Index>(r));
  ModeSet out = set;
  out.dofs.clear();
  std::vector<Eigen::Index> rows;
  for (const auto& d : keep) {
    auto it = row.find(key(d));
    if (it == row.end()) continue;
    out.dofs.push_back(d);
    rows.push_back(it->second);
  }
  out.shapes.resize(static_cast<Eigen::Index>(rows.size()), set.shapes.cols());
  for (std::size_t r = 0; r < rows.size(); ++r) out.shapes.row(static_cast<Eigen::Index>(r)) = set.shapes.row(rows[r]);
  return out;
}

std::vector<MeasuredDof> common_dofs(const ModeSet& a, const ModeSet& b) {
  std::set<std::int64_t> in_b;
  for (const auto& d : b.dofs) in_b.insert(key(d));
  std::vector<MeasuredDof> r;
  for (const auto& d : a.dofs)
    if (in_b.count(key(d))) r.push_back(d);
  return r;
}

ModeSet relabel(const ModeSet& set, const NodeMapping& mapping) {
  std::unordered_map<std::int64_t, std::int64_t> grid;
  for (const auto& m : mapping.matches) grid.emplace(m.test_node, m.grid);
  std::vector<MeasuredDof> keep;
  for (const auto& d : set.dofs)
    if (grid.count(d.node)) keep.push_back(d);
  ModeSet out = restrict_to(set, keep);
  for (auto& d : out.dofs) d.node = grid.at(d.node);
  return out;
}

}  // namespace ssid::translators
