/// \file model_load.cpp
#include "cli/model_load.hpp"

#include "translators/assembly/rigid_modes.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <iostream>
#include <limits>
#include <stdexcept>

#include "estimator/eigen/dense_eigen.hpp"
#include "formats/bulk_model.hpp"
#include "formats/parse_error.hpp"

namespace ssid::cli {

LoadedModel load_model(const std::string& path, const translators::AssemblyOptions& options) {
  LoadedModel l;
  l.path = path;
  l.deck = formats::read_deck(path);
  l.model = translators::assemble_deck(l.deck, path, options, &l.warnings);
  return l;
}

namespace {
/// Case-control output requests (DISPLACEMENT(PLOT) = ALL, STRESS = ...): their
/// names in order of appearance, with counts.
std::vector<std::pair<std::string, int>> output_requests(const formats::Deck& deck) {
  static const char* kinds[] = {"DISPLACEMENT", "DISP", "VECTOR", "PRINT", "STRESS", "STRAIN", "FORCE", "ELFORCE",
                                "SPCFORCES", "SPCF", "MPCFORCES", "OLOAD", "ESE", "EKE", "GPFORCE", "VELOCITY",
                                "ACCELERATION", "ACCE", "SET", "ECHO", "GPSTRESS", "STRFIELD", "MEFFMASS", "OUTPUT"};
  std::vector<std::pair<std::string, int>> out;
  for (const auto& st : deck.statements) {
    if (st.section != formats::Section::CaseControl) continue;
    std::string key;
    for (char c : st.text) {
      if (!std::isalpha(static_cast<unsigned char>(c))) break;
      key += c;
    }
    bool known = false;
    for (const char* k : kinds) known |= key == k;
    if (!known) continue;
    auto it = std::find_if(out.begin(), out.end(), [&](const auto& p) { return p.first == key; });
    if (it == out.end()) out.emplace_back(key, 1);
    else ++it->second;
  }
  return out;
}
}  // namespace

void print_model_notes(const LoadedModel& m) {
  for (const auto& w : m.warnings) std::cerr << "warning: " << w << "\n";
  for (const auto& n : m.model->notes()) std::cerr << "note: " << n << "\n";
  const auto requests = output_requests(m.deck);
  if (!requests.empty()) {
    std::string list;
    for (const auto& [k, n] : requests) list += (list.empty() ? "" : ", ") + k + (n > 1 ? " x" + std::to_string(n) : "");
    std::cerr << "note: case control output requests ignored (they do not change K or M): " << list << "\n";
  }
  if (!m.model->autospc().empty())
    std::cerr << "note: AUTOSPC constrained " << m.model->autospc().size()
              << " DOF(s) without stiffness (ssid assemble lists them in its manifest)\n";
}

namespace {
estimator::EigenOptions requested_modes(const translators::FeModel& model, std::optional<int> nmodes, long n,
                                        std::string& source, int default_nd) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  auto norm_of = [](const std::string& s) {
    return s == "MAX" ? estimator::ModeNormalization::Max : estimator::ModeNormalization::Mass;
  };
  if (nmodes) {
    if (*nmodes <= 0) throw formats::InputError("--nmodes: expected a positive number, got " + std::to_string(*nmodes));
    source = "--nmodes " + std::to_string(*nmodes);
    return estimator::eigrl_options(nan, nan, *nmodes);
  }
  if (const auto* e = model.eigrl()) {
    source = "EIGRL " + std::to_string(e->sid);
    return estimator::eigrl_options(e->v1.value_or(nan), e->v2.value_or(nan), static_cast<int>(e->nd.value_or(0)),
                                    norm_of(e->norm));
  }
  if (const auto* e = model.eigr()) {
    source = "EIGR " + std::to_string(e->sid);
    return estimator::eigr_options(e->f1.value_or(nan), e->f2.value_or(nan), static_cast<int>(e->ne.value_or(0)),
                                   static_cast<int>(e->nd.value_or(0)), norm_of(e->norm));
  }
  if (n <= estimator::kDenseEigenLimit) {
    source = "no EIGRL/EIGR: every mode";
    return estimator::eigrl_options(nan, nan, 0);
  }
  source = "no EIGRL/EIGR: lowest " + std::to_string(default_nd);
  return estimator::eigrl_options(nan, nan, default_nd);
}
}  // namespace

estimator::EigenOptions eigen_options(const translators::FeModel& model, std::optional<int> nmodes, long n,
                                      std::string& source, int default_nd) {
  estimator::EigenOptions o = requested_modes(model, nmodes, n, source, default_nd);
  // The rigid-body modes let the solver fall back to the multilevel method when the
  // factor of K − σM would not fit in memory (EigenMethod::Auto), or use it on
  // request; the strain fields make its coarse space linear in each aggregate.
  if (n > estimator::kDenseEigenLimit) {
    o.near_null_space = translators::a_set_rigid_body_modes(model);
    o.strain_fields = translators::a_set_strain_fields(model);
  }
  return o;
}

std::vector<translators::Dof> a_set_dofs(const translators::FeModel& model) {
  std::vector<translators::Dof> d;
  for (std::size_t g : model.reduction().a_to_g) d.push_back(model.geometry().gset().at(g));
  return d;
}

namespace {
[[noreturn]] void solve_failed(const estimator::EigenResult& r, const std::vector<translators::Dof>& dofs) {
  std::string where;
  if (r.failed_dof >= 0 && static_cast<std::size_t>(r.failed_dof) < dofs.size()) {
    const auto& d = dofs[static_cast<std::size_t>(r.failed_dof)];
    where = d.component ? " (grid " + std::to_string(d.point) + " component " + std::to_string(d.component) + ")"
                        : " (scalar point " + std::to_string(d.point) + ")";
  }
  std::string msg = r.message;
  const std::string at = "at DOF index " + std::to_string(r.failed_dof);
  const auto k = msg.find(at);
  if (!where.empty() && k != std::string::npos) msg.insert(k + at.size(), where);
  else msg += where;
  estimator::throw_solve_failure(r, "eigen-solve failed: " + msg);
}
}  // namespace

estimator::EigenResult solve_model(const translators::FeOperators& op, const estimator::EigenOptions& options,
                                   const std::vector<translators::Dof>& dofs) {
  const long n = op.K.rows();
  if (n == 0) throw formats::InputError("the analysis set is empty: every DOF is constrained");
  if (n <= estimator::kDenseEigenLimit) {
    estimator::EigenResult r = estimator::solve_modes_dense(op.K, op.M, options);
    if (r.status == estimator::EigenResult::Status::NotPositiveDefinite) {
      // The sparse factorisation names the column where it fails.
      estimator::EigenOptions o = options;
      o.nd = 1;
      o.f_low = o.f_high = std::numeric_limits<double>::quiet_NaN();
      o.shift = r.shift;
      const estimator::EigenResult s = estimator::solve_modes(op.K, op.M, o);
      if (!s.ok()) solve_failed(s, dofs);
    }
    if (!r.ok()) solve_failed(r, dofs);
    return r;
  }
  // Every mode is checked: a backward error above 1e-8 means a wrong mode (seen with
  // the single-vector path on models with massless DOFs); block Lanczos then redoes it.
  auto worst = [](const estimator::EigenResult& r) {
    return r.backward_errors.size() ? r.backward_errors.maxCoeff() : 0.0;
  };
  // Fill-reducing ordering on the grid-point graph: a grid's DOFs are eliminated
  // together (GRID and SPOINT ids share one id space, so the ids serve as groups).
  estimator::EigenOptions grouped = options;
  if (grouped.dof_groups.empty() && dofs.size() == static_cast<std::size_t>(n)) {
    grouped.dof_groups.reserve(dofs.size());
    for (const auto& d : dofs) grouped.dof_groups.push_back(d.point);
  }
  estimator::EigenResult r = estimator::solve_modes(op.K, op.M, grouped);
  // (Not after the multilevel method: it runs where a factor would not fit.)
  if (r.ok() && worst(r) > 1e-8 && options.method != estimator::EigenMethod::BlockLanczos && r.method != "Multilevel") {
    estimator::EigenOptions o = grouped;
    o.method = estimator::EigenMethod::BlockLanczos;
    estimator::EigenResult b = estimator::solve_modes(op.K, op.M, o);
    b.warnings.insert(b.warnings.begin(), r.method + " gave a mode with backward error " + std::to_string(worst(r)) +
                                              "; solved again with block Lanczos");
    r = std::move(b);
  }
  if (!r.ok()) solve_failed(r, dofs);
  if (worst(r) > 1e-8)
    throw formats::NumericalError("eigen-solve: a mode has backward error " + std::to_string(worst(r)) +
                             " (above 1e-8): the modes are not reliable");
  return r;
}

std::vector<translators::GridPosition> grid_positions(const translators::FeModel& model) {
  std::vector<translators::GridPosition> g;
  for (const auto& p : model.geometry().grids()) g.push_back({p.id, p.x, p.frame});
  return g;
}

}  // namespace ssid::cli
