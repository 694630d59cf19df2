/// \file local_modes.cpp
/// local_modes: a strut modelled as a rod has no bending modes of its own, but
/// the real tube does; when its first bending frequency falls near a global
/// mode the two mix and the test shows a mode the model lacks (the seed
/// report's local strut modes). The change refines one rod (CROD or CONROD of
/// length L between GA and GB) so that the local modes exist:
///
///  - a new grid GM at the middle of the strut;
///  - the rod split in two rods GA–GM and GM–GB of the same property (the
///    element keeps its id, a new one takes the second half): the axial rate
///    EA/L and the mass are unchanged, and the property's design relations
///    (DVPREL1 of the PROD) still apply;
///  - two CBARs GA–GM, GM–GB carrying the bending only: a new PBAR of the rod's
///    material with A = 0, I1 = I2 = β (a round tube), J = 0, pinned at the
///    strut's ends in bending (PA/PB = 56; J = 0), so they add no stiffness between the end
///    grids — the rod model's pinned joints stay — and neither mass nor axial
///    stiffness; GM's displacement frame is a new CORD2R with x along the strut
///    and its rotation about the strut (no stiffness) held by GRID PS 4.
///
/// β₁ = I [m⁴], the strut's bending inertia. A rod model often carries the
/// strut's mass in the lumped masses of its end grids (the MPI truss rod model:
/// no density, no NSM); then the tube's mass must move to the middle for a local
/// mode to exist, and β₂ = μ [kg] is the mass moved: a CONM2 of μ at GM and
/// CONM2s of −μ/2 at GA and GB (total mass and centre of gravity unchanged).
/// With lumped mass the middle grid carries m_mid = m_s/2 + μ (m_s the rod's own
/// mass) and the first bending frequency of the two-bar chain is
///   f = √(48 E I / L³ / m_mid) / 2π   (pinned–pinned; exact for the two bars).
/// With the stiff limit I → ∞ and μ = 0 the rod comes back exactly. Priors: μ ~ N(μ₀, μ₀²),
/// μ₀ = ¼ of the lighter end grid's lumped mass, 0 ≤ μ ≤ that mass; I ~ N(I_h,
/// I_h²) centred on the inertia that puts the local mode at 1.25 × the highest
/// test frequency (local modes above the band: the rod model is the limit
/// I → ∞), I above the value that puts it at half the lowest test frequency
/// (I = 0 would be a mechanism). The start puts the local mode at an
/// unexplained test frequency.
///
/// Candidates are every two-grid rod, once per unexplained test frequency (up to
/// `max_surge_starts`); none when every test mode has an analysis partner
/// (unless `always_offer`). Their priority is how strongly the strut would couple to
/// the analysis mode that resembles the unexplained test mode: the middle mass
/// times the squared motion of its middle across the strut axis in that mode.
#include <algorithm>
#include <cmath>
#include <map>

#include <Eigen/Geometry>

#include "estimator/diagnosis/hypotheses/extension_util.hpp"
#include "estimator/diagnosis/hypotheses/model_extension.hpp"

namespace ssid::estimator::diagnosis::hypotheses {

namespace {

struct Rod {
  std::string type;  ///< CROD or CONROD
  std::int64_t eid = 0, pid = 0, mid = 0, ga = 0, gb = 0;
  double area = 0, nsm = 0;
  std::size_t card = 0;
};

std::vector<Rod> rods(const formats::BulkModel& b) {
  std::vector<Rod> out;
  for (const auto& e : b.crods)
    for (const auto& p : b.prods)
      if (p.pid == e.pid) out.push_back({"CROD", e.eid, e.pid, p.mid, e.g1, e.g2, p.a, p.nsm, e.card});
  for (const auto& e : b.conrods) out.push_back({"CONROD", e.eid, 0, e.mid, e.g1, e.g2, e.a, e.nsm, e.card});
  return out;
}

/// What the start and prior need of one strut.
struct Strut {
  Rod rod;
  Eigen::Vector3d a, b;  ///< end positions (basic)
  double length = 0, mass = 0, E = 0;
  double moved = 0;      ///< μ₀ when the rod has no mass of its own (mass moved from the ends), else 0
  double end_mass = 0;   ///< lumped translational mass of the lighter end grid [kg]
  double mid_mass() const { return mass / 2 + moved; }
};

/// Lumped translational mass at each grid (g-set diagonal of M, component 1).
std::map<std::int64_t, double> grid_masses(const FeModel& model) {
  const auto ops = model.operators(model.initial_parameters(), false);
  std::map<std::int64_t, double> out;
  for (const auto& g : model.geometry().grids()) out[g.id] = ops.Mg.coeff(static_cast<Eigen::Index>(g.dofs[0]),
                                                                          static_cast<Eigen::Index>(g.dofs[0]));
  return out;
}

Strut strut_of(const FeModel& model, const Rod& r, const std::map<std::int64_t, double>& masses) {
  Strut s;
  s.rod = r;
  const auto& ga = model.geometry().grid(r.ga, "local_modes");
  const auto& gb = model.geometry().grid(r.gb, "local_modes");
  s.a = ga.x;
  s.b = gb.x;
  s.length = (gb.x - ga.x).norm();
  s.mass = (detail::density(model.bulk(), r.mid) * r.area + r.nsm) * s.length * model.wtmass();
  s.E = detail::young_modulus(model.bulk(), r.mid);
  auto mass_at = [&](std::int64_t id) { auto it = masses.find(id); return it == masses.end() ? 0.0 : it->second; };
  s.end_mass = std::min(mass_at(r.ga), mass_at(r.gb));
  if (!(s.mass > 0)) s.moved = 0.25 * s.end_mass;
  return s;
}

/// I that puts the two-bar chain's first bending mode at f.
double inertia_for(const Strut& s, double f_hz) {
  const double w = 2 * M_PI * f_hz;
  return w * w * s.mid_mass() * std::pow(s.length, 3) / (48.0 * s.E);
}

class LocalModes : public ModelExtension {
 public:
  explicit LocalModes(ExtensionOptions o) : m_options(std::move(o)) {}
  std::string kind() const override { return "local_modes"; }
  std::string describe() const override {
    return "a rod refined into two halves with a bending bar each (a middle grid), so its local bending modes exist; "
           "parameter: the strut's bending inertia I [m^4]";
  }

  std::vector<Candidate> candidates(const FeModel& nominal) const override {
    std::vector<double> freqs = detail::start_frequencies(m_options);
    std::vector<Candidate> out;
    // Local modes are a hypothesis for test modes the model lacks: without
    // any, a refined strut has nothing to explain (and its modes would have to
    // hide above the band, where the rod model is already its limit).
    if (freqs.empty() && !m_options.always_offer) return out;
    const bool guided = !freqs.empty();
    if (!guided) freqs.push_back(1.25 * std::max(m_options.highest_test_hz, m_options.lowest_test_hz));
    const auto all = rods(nominal.bulk());
    if (all.empty()) return out;
    const auto masses = grid_masses(nominal);
    for (const auto& r : all) {
      if (!(r.area > 0) || r.ga == r.gb) continue;
      const Strut s = strut_of(nominal, r, masses);
      if (!(s.mid_mass() > 0) || !(s.length > 0)) continue;  // no mass anywhere: no local mode
      for (std::size_t u = 0; u < freqs.size(); ++u) {
        Candidate c;
        c.kind = kind();
        c.location = detail::member_location(r.type, r.eid, r.pid, r.ga, r.gb);
        c.ids = {r.eid};
        c.start = {inertia_for(s, freqs[u])};
        if (s.moved > 0) c.start.push_back(s.moved);
        if (guided && u < m_options.unexplained_neighbours.size())
          c.priority = coupling(nominal, s, m_options.unexplained_neighbours[u]);
        out.push_back(c);
      }
    }
    return out;
  }

  ExtendedDeck apply(const std::string& text, const std::string& name, const FeModel& nominal,
                     const Candidate& c) const override {
    DeckEditor ed(text, name);
    const auto& b = ed.bulk();
    const Rod* found = nullptr;
    const auto all = rods(b);
    for (const auto& r : all)
      if (r.eid == c.ids.at(0)) found = &r;
    if (!found) throw std::invalid_argument("local_modes: rod " + std::to_string(c.ids.at(0)) + " not found");
    const Rod r = *found;
    const Strut s = strut_of(nominal, r, grid_masses(nominal));
    const double top = 1.25 * std::max(m_options.highest_test_hz, m_options.lowest_test_hz);

    NewParameter p;
    p.label = detail::label("XI", r.eid);
    p.prior_mean = inertia_for(s, top);
    p.prior_std = p.prior_mean;
    p.lower = inertia_for(s, 0.5 * m_options.lowest_test_hz);
    p.meaning = "bending inertia of " + r.type + " " + std::to_string(r.eid) + " [m^4]";
    if (!c.start.empty()) p.start = std::max(c.start[0], p.lower);
    const double x0 = std::isnan(p.start) ? p.prior_mean : p.start;

    ed.comment("ssid diagnose: " + r.type + " " + std::to_string(r.eid) + " refined (local bending modes)");
    // GM's frame: x along the strut (GA to GB), so PS 4 holds its free torsion.
    const Eigen::Vector3d xm = 0.5 * (s.a + s.b), axis = (s.b - s.a).normalized();
    Eigen::Index k = 0;
    axis.cwiseAbs().minCoeff(&k);
    const Eigen::Vector3d z = axis.cross(Eigen::Vector3d::Unit(k)).normalized(), y = z.cross(axis);
    formats::Cord2 frame;
    frame.cid = ed.new_coord_id();
    const Eigen::Vector3d zb = xm + z, xb = xm + axis;
    frame.a = {xm(0), xm(1), xm(2)};
    frame.b = {zb(0), zb(1), zb(2)};
    frame.c = {xb(0), xb(1), xb(2)};
    ed.append(formats::write_cord2(frame));
    formats::Grid gm;
    gm.id = ed.new_grid_id();
    gm.x = {xm(0), xm(1), xm(2)};
    gm.cd = frame.cid;
    gm.cd_blank = false;
    gm.ps = "4";
    gm.ps_blank = false;
    ed.append(formats::write_grid(gm));
    const std::int64_t second = ed.new_element_id();
    // The element becomes its first half (GA–GM) in place; a copy is the second (GM–GB).
    auto split = [&](const auto& cards, auto write) {
      for (const auto& e : cards)
        if (e.eid == r.eid) {
          auto half = e;
          half.g2 = gm.id;
          ed.change(e.card, write(half));
          half.eid = second;
          half.g1 = gm.id;
          half.g2 = e.g2;
          ed.append(write(half));
        }
    };
    if (r.type == "CROD") {
      split(b.crods, formats::write_crod);
    } else {
      split(b.conrods, formats::write_conrod);
      for (const auto& d : b.dvprel1s)  // the CONROD's own design relations follow its second half
        if (d.type == "CONROD" && d.pid == r.eid) {
          formats::Dvprel1 q = d;
          q.id = ed.new_relation_id();
          q.pid = second;
          ed.append(formats::write_dvprel1(q));
        }
    }
    formats::Pbar pb;
    pb.pid = ed.new_property_id();
    pb.mid = r.mid;
    pb.i1 = pb.i2 = x0;
    ed.append(formats::write_pbar(pb));
    // Orientation (I1 = I2: any vector off the axis gives the same element): the
    // frame's y axis, given in each bar's GA displacement system.
    const auto& ga = nominal.geometry().grid(r.ga, "local_modes");
    const Eigen::Vector3d y_in_ga = ga.frame.transpose() * y;
    const std::array<std::array<double, 3>, 2> orient{{{y_in_ga(0), y_in_ga(1), y_in_ga(2)}, {0.0, 1.0, 0.0}}};
    const std::array<std::pair<std::int64_t, std::int64_t>, 2> ends{{{r.ga, gm.id}, {gm.id, r.gb}}};
    for (std::size_t n = 0; n < 2; ++n) {
      formats::Cbar bar;
      bar.eid = ed.new_element_id();
      bar.pid = pb.pid;
      bar.ga = ends[n].first;
      bar.gb = ends[n].second;
      bar.x = orient[n];
      (n == 0 ? bar.pa : bar.pb) = "56";  // pinned in bending at the strut's end (J = 0: torsion carries nothing)
      ed.append(formats::write_cbar(bar));
    }
    const auto dv = ed.add_desvar(p, x0);
    ed.add_dvprel1("PBAR", pb.pid, "I1", dv, 1.0);
    ed.add_dvprel1("PBAR", pb.pid, "I2", dv, 1.0);
    if (s.moved > 0) {  // the tube's mass, lumped at the ends in the deck, moved to the middle
      NewParameter q;
      q.label = detail::label("XU", r.eid);
      q.prior_mean = q.prior_std = s.moved;
      q.lower = 0.0;
      q.upper = s.end_mass;
      q.meaning = "mass moved from the ends of " + r.type + " " + std::to_string(r.eid) + " to its middle [kg]";
      if (c.start.size() > 1) q.start = std::clamp(c.start[1], q.lower, q.upper);
      const double m0 = std::isnan(q.start) ? q.prior_mean : q.start;
      const auto dm = ed.add_desvar(q, m0);
      for (auto [g, share] : {std::pair{gm.id, 1.0}, std::pair{r.ga, -0.5}, std::pair{r.gb, -0.5}}) {
        formats::Conm2 m;
        m.eid = ed.new_element_id();
        m.g = g;
        m.m = share * m0;
        ed.append(formats::write_conm2(m));
        ed.add_dvprel1("CONM2", m.eid, "M", dm, share, 0.0, -1e20);
      }
    }
    return {ed.text(), ed.parameters, "the bending of " + c.location.text + " modelled (local strut modes)"};
  }

 private:
  /// m_mid ‖w⊥‖² (m_mid the mass the middle grid would carry), w the mean translation of the strut's ends (basic) in the
  /// g-set shape `phi`, ⊥ across the strut axis.
  static double coupling(const FeModel& model, const Strut& s, const Eigen::VectorXd& phi) {
    auto translation = [&](std::int64_t id) {
      const auto& g = model.geometry().grid(id, "local_modes");
      Eigen::Vector3d u;
      for (int i = 0; i < 3; ++i) {
        const auto dof = static_cast<Eigen::Index>(g.dofs[static_cast<std::size_t>(i)]);
        u(i) = dof < phi.size() ? phi(dof) : 0.0;
      }
      return Eigen::Vector3d(g.frame * u);
    };
    const Eigen::Vector3d w = 0.5 * (translation(s.rod.ga) + translation(s.rod.gb));
    const Eigen::Vector3d e = (s.b - s.a).normalized();
    return s.mid_mass() * (w - e * e.dot(w)).squaredNorm();
  }

  ExtensionOptions m_options;
};

}  // namespace

std::unique_ptr<ModelExtension> make_local_modes(const ExtensionOptions& options) {
  return std::make_unique<LocalModes>(options);
}

}  // namespace ssid::estimator::diagnosis::hypotheses
