/// \file missing_mass.cpp
/// missing_mass: an unmodelled concentrated mass at one grid (instrumentation,
/// a heavier fitting, a cable). The change is a CONM2 at the grid, no offset,
/// no inertia, its mass M = β designed by DVPREL1 (CONM2 M = β):
///   M(β) = M₀ + β·WTMASS·Σ_{c=1..3} e_c e_cᵀ at the grid,  ∂M/∂β = WTMASS·I₃ there.
#include <cmath>

#include "estimator/diagnosis/hypotheses/extension_util.hpp"
#include "estimator/diagnosis/hypotheses/model_extension.hpp"

namespace ssid::estimator::diagnosis::hypotheses {

namespace {

class MissingMass : public ModelExtension {
 public:
  explicit MissingMass(ExtensionOptions o) : m_options(std::move(o)) {}
  std::string kind() const override { return "missing_mass"; }
  std::string describe() const override {
    return "a concentrated mass (CONM2) at one grid; parameter: its mass [kg], prior N(0, (" +
           std::to_string(m_options.mass_prior_fraction) + " x total mass)^2), mass >= 0";
  }

  std::vector<Candidate> candidates(const FeModel& nominal) const override {
    std::vector<Candidate> out;
    const auto& red = nominal.reduction();
    for (const auto& g : nominal.geometry().grids()) {
      bool free = false;
      for (int c = 0; c < 3; ++c) free = free || red.g_to_a[g.dofs[static_cast<std::size_t>(c)]] >= 0;
      if (!free) continue;
      Candidate cand;
      cand.kind = kind();
      cand.location.grids = {g.id};
      cand.location.text = "grid " + std::to_string(g.id);
      cand.ids = {g.id};
      out.push_back(cand);
    }
    return out;
  }

  ExtendedDeck apply(const std::string& text, const std::string& name, const FeModel& nominal,
                     const Candidate& c) const override {
    DeckEditor ed(text, name);
    const std::int64_t grid = c.ids.at(0);
    NewParameter p;
    p.label = detail::label("XM", grid);
    p.prior_mean = 0.0;
    p.prior_std = prior_std(nominal);
    p.lower = 0.0;
    p.meaning = "added mass at grid " + std::to_string(grid) + " [kg]";
    if (!c.start.empty()) p.start = c.start[0];
    const double x0 = std::isnan(p.start) ? p.prior_mean : p.start;
    ed.comment("ssid diagnose: missing mass at grid " + std::to_string(grid));
    formats::Conm2 m;
    m.eid = ed.new_element_id();
    m.g = grid;
    m.m = x0;
    ed.append(formats::write_conm2(m));
    const auto dv = ed.add_desvar(p, x0);
    ed.add_dvprel1("CONM2", m.eid, "M", dv, 1.0);
    return {ed.text(), ed.parameters, "a mass of unknown size at grid " + std::to_string(grid)};
  }

  std::optional<ScreeningDerivative> screening(const FeModel& nominal, const Candidate& c) const override {
    const auto& g = nominal.geometry().grid(c.ids.at(0), "missing_mass");
    std::vector<Eigen::Triplet<double>> t;
    for (int k = 0; k < 3; ++k) {
      const auto i = static_cast<int>(g.dofs[static_cast<std::size_t>(k)]);
      t.emplace_back(i, i, nominal.wtmass());
    }
    ScreeningDerivative s;
    s.dM.push_back(detail::to_aset(nominal, t));
    s.dK.push_back(Eigen::SparseMatrix<double>(s.dM.back().rows(), s.dM.back().cols()));
    s.prior_std.push_back(prior_std(nominal));
    return s;
  }

 private:
  double prior_std(const FeModel& nominal) const {
    if (!(m_total > 0)) m_total = m_options.total_mass > 0 ? m_options.total_mass : total_mass(nominal);
    return m_options.mass_prior_fraction * m_total;
  }
  mutable double m_total = 0;
  ExtensionOptions m_options;
};

}  // namespace

std::unique_ptr<ModelExtension> make_missing_mass(const ExtensionOptions& options) {
  return std::make_unique<MissingMass>(options);
}

}  // namespace ssid::estimator::diagnosis::hypotheses
