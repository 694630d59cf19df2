/// \file local_modes.cpp
/// local_modes: a strut modelled as a rod has no bending modes of its own, but
/// the real tube does; when its first bending frequency falls near a global
/// mode the two mix and the test shows a mode the model lacks (the seed
/// report's local strut modes). The change refines one rod (CROD or CONROD of
/// length L between GA and GB) into a beam whose local modes exist:
///
///  - three new inner grids G1, G2, G3 at the quarters of the strut, their
///    displacement frame a new CORD2R with x along the strut, their rotation
///    about the strut (no stiffness) held by GRID PS 4;
///  - the rod split into four rods GA–G1, …, G3–GB of the same property (the
///    element keeps its id for the first quarter, new ids take the others):
///    the axial rate EA/L and the mass are unchanged, and the property's design
///    relations (DVPREL1 of the PROD; a CONROD's own are copied) still apply;
///  - four CBARs along the chain carrying the bending only: a new PBAR of the
///    rod's material with A = 0, I1 = I2 = β (a round tube), J = 0, so neither
///    mass nor axial stiffness is added, clamped at both ends to the strut's
///    chord: two grids EA, EB at the end grids move with them (RBE2, 123) and
///    turn across the strut as the chord does (RBAR, the rigid motion of the
///    two ends' translations). So the strut is clamped–clamped for its local
///    modes, as a tube screwed or bonded into a node is, but the bars resist no
///    rigid motion of the structure and add no stiffness between the end
///    grids: the rod model's pinned joints stay, and the refinement leaves the
///    rod model's modes as they were both with I → ∞ and with I → 0 (μ = 0).
///    (Clamped into the end grids' own rotations instead, as the form of
///    2166f1c was, the bars resisted the truss's rigid rotation by ≈ 12EI/L³
///    wherever the deck holds those rotations to ground, GRID PS 456 in the
///    MPI rod model: the suspension modes moved.) Two bars pinned at the
///    strut's ends with one middle grid (the form before) gave one local mode
///    per plane and the pinned ratios; the test of a real tube shows its
///    second bending too (2.76 × the first, clamped).
///
/// β₁ = I [m⁴], the strut's bending inertia. A rod model often carries the
/// strut's mass in the lumped masses of its end grids (the MPI truss rod model:
/// no density, no NSM); then the tube's mass must move inwards for a local
/// mode to exist, and β₂ = μ [kg] is the mass moved: a CONM2 of μ/3 at each
/// inner grid and CONM2s of −μ/2 at GA and GB (total mass and centre of gravity
/// unchanged). With lumped mass each inner grid carries m = m_s/4 + μ/3 (m_s the
/// rod's own mass) and the first bending frequency of the clamped chain is
///   f = √(c E I / (m h³)) / 2π,  h = L/4,  c = (39 − √1233)/2 ≈ 1.943
/// (exact for the four bars clamped; kChainEigenvalue). Priors:
/// μ ~ N(μ₀, μ₀²), μ₀ = ¼ of the lighter end grid's lumped mass, 0 ≤ μ ≤ that
/// mass; I ~ N(I_h, I_h²) centred on the inertia that puts the local mode at
/// 1.25 × the highest test frequency (local modes above the band), I above the
/// value that puts it at half the lowest test frequency (I = 0 would be a
/// mechanism). The start puts the local mode at an unexplained test frequency.
///
/// Candidates are every two-grid rod, once per unexplained test frequency (up to
/// `max_surge_starts`); none when every test mode has an analysis partner
/// (unless `always_offer`). Their priority is how well a local mode of that
/// strut would give the unexplained test mode's shape at the sensors. A local
/// mode at ω_u pushes the strut's ends across its axis (a force n/2 at each end,
/// n in the plane of bending), and the structure answers that force at ω_u as
///   u = Σ_j φ_j (φ_jᵀ F) / (λ_j − ω_u²),
/// summed over the updated model's mass-normalised modes; at the sensors this
/// gives one shape s_p per bending plane, and the priority is the share of the
/// unit test shape t that the two span, ‖P t‖² ∈ [0, 1] (least squares). A
/// strut whose ends do not move across its axis in any mode gives nothing (0).
/// Without test shapes (frequencies only) the priority is the coupling to the
/// analysis mode nearest in frequency: the squared motion of the strut's middle
/// (the mean of its ends) across its axis in that mode, against the mode's
/// largest component squared (0 to 1).
#include <algorithm>
#include <array>
#include <cmath>
#include <map>

#include <Eigen/Geometry>

#include "estimator/diagnosis/hypotheses/extension_util.hpp"
#include "estimator/diagnosis/hypotheses/model_extension.hpp"

namespace ssid::estimator::diagnosis::hypotheses {

namespace {

/// The refined strut is a chain of this many bars (three inner grids).
constexpr int kBars = 4;
/// The lowest eigenvalue of the chain, clamped at both ends, in units of
/// E I / (m h³) (m each inner grid's mass, h a bar's length): the three inner
/// translations after the rotations are condensed out give, for the symmetric
/// modes, x² − 39 x + 72 = 0, so x = (39 − √1233)/2 ≈ 1.94295 (the uniform
/// clamped–clamped beam: 4.730⁴/4⁴ ≈ 1.9553 in the same units); the
/// antisymmetric mode is 96/7, the second bending at 2.66 × the first frequency
/// (the uniform beam: 2.76).
const double kChainEigenvalue = (39.0 - std::sqrt(1233.0)) / 2.0;

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
  /// The mass each inner grid carries: a quarter of the rod's own (lumped rods) and a third of the moved mass.
  double inner_mass() const { return mass / kBars + moved / (kBars - 1); }
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

/// Two unit vectors across `axis` (a unit vector), orthogonal to each other:
/// the inner grids' frame (y, z) and the planes of bending.
std::pair<Eigen::Vector3d, Eigen::Vector3d> across_axis(const Eigen::Vector3d& axis) {
  Eigen::Index k = 0;
  axis.cwiseAbs().minCoeff(&k);
  const Eigen::Vector3d z = axis.cross(Eigen::Vector3d::Unit(k)).normalized();
  return {z.cross(axis), z};
}

/// I that puts the chain's first bending mode at f: ω² = c E I / (m h³), h = L/4,
/// m the inner grids' mass (file comment).
double inertia_for(const Strut& s, double f_hz) {
  const double w = 2 * M_PI * f_hz, h = s.length / kBars;
  return w * w * s.inner_mass() * h * h * h / (kChainEigenvalue * s.E);
}

class LocalModes : public ModelExtension {
 public:
  explicit LocalModes(ExtensionOptions o) : m_options(std::move(o)) {}
  std::string kind() const override { return "local_modes"; }
  std::string describe() const override {
    return "a rod refined into four quarters with a bending bar each (three inner grids, clamped to its chord), "
           "so its local bending modes exist; "
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
      if (!(s.inner_mass() > 0) || !(s.length > 0)) continue;  // no mass anywhere: no local mode
      for (std::size_t u = 0; u < freqs.size(); ++u) {
        Candidate c;
        c.kind = kind();
        c.location = detail::member_location(r.type, r.eid, r.pid, r.ga, r.gb);
        c.ids = {r.eid};
        c.start = {inertia_for(s, freqs[u])};
        if (s.moved > 0) c.start.push_back(s.moved);
        if (guided) c.priority = priority(nominal, s, u);
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
    // The inner grids' frame: x along the strut (GA to GB), so PS 4 holds their free torsion.
    const Eigen::Vector3d axis = (s.b - s.a).normalized();
    const auto z = across_axis(axis).second;
    formats::Cord2 frame;
    frame.cid = ed.new_coord_id();
    const Eigen::Vector3d zb = s.a + z, xb = s.a + axis;
    frame.a = {s.a(0), s.a(1), s.a(2)};
    frame.b = {zb(0), zb(1), zb(2)};
    frame.c = {xb(0), xb(1), xb(2)};
    ed.append(formats::write_cord2(frame));
    // The chain GA, G1, G2, G3, GB at quarters of the strut.
    std::array<std::int64_t, kBars + 1> chain{};
    chain.front() = r.ga;
    chain.back() = r.gb;
    for (int n = 1; n < kBars; ++n)
      chain[static_cast<std::size_t>(n)] =
          ed.add_grid(s.a + (static_cast<double>(n) / kBars) * (s.b - s.a), frame.cid, "4");
    // The rod becomes four rods of the same property along the chain: the element keeps its id for the first quarter.
    std::array<std::int64_t, kBars> rod_ids{};
    rod_ids[0] = r.eid;
    for (int n = 1; n < kBars; ++n) rod_ids[static_cast<std::size_t>(n)] = ed.new_element_id();
    auto split = [&](const auto& cards, auto write) {
      for (const auto& e : cards)
        if (e.eid == r.eid)
          for (std::size_t n = 0; n < kBars; ++n) {
            auto part = e;
            part.eid = rod_ids[n];
            part.g1 = chain[n];
            part.g2 = chain[n + 1];
            if (n == 0) ed.change(e.card, write(part));
            else ed.append(write(part));
          }
    };
    if (r.type == "CROD") {
      split(b.crods, formats::write_crod);
    } else {
      split(b.conrods, formats::write_conrod);
      for (const auto& d : b.dvprel1s)  // the CONROD's own design relations follow its other parts
        if (d.type == "CONROD" && d.pid == r.eid)
          for (std::size_t n = 1; n < kBars; ++n) {
            formats::Dvprel1 q = d;
            q.id = ed.new_relation_id();
            q.pid = rod_ids[n];
            ed.append(formats::write_dvprel1(q));
          }
    }
    formats::Pbar pb;
    pb.pid = ed.new_property_id();
    pb.mid = r.mid;
    pb.i1 = pb.i2 = x0;
    ed.append(formats::write_pbar(pb));
    // The bars' ends: grids EA, EB at the strut's end grids, in the inner grids'
    // frame, their translations those of GA, GB (RBE2, 123) and their rotations
    // across the strut (5, 6) those of the chord, the rigid motion of EA's and
    // EB's translations (an RBAR each way: 1234 of its own grid and 23 of the
    // other independent, 56 dependent); their twist (4) held by PS.
    const std::array<std::int64_t, 2> ends{ed.add_grid(s.a, frame.cid, "4"), ed.add_grid(s.b, frame.cid, "4")};
    for (std::size_t e = 0; e < 2; ++e) {
      formats::Rbe2 link;
      link.eid = ed.new_element_id();
      link.gn = e == 0 ? r.ga : r.gb;
      link.cm = "123";
      link.gm = {ends[e]};
      ed.append(formats::write_rbe2(link));
    }
    for (std::size_t e = 0; e < 2; ++e) {
      formats::Rbar chord;
      chord.eid = ed.new_element_id();
      chord.ga = ends[e];
      chord.gb = ends[1 - e];
      chord.cna = "1234";
      chord.cnb = "23";
      chord.cma = "56";
      ed.append(formats::write_rbar(chord));
    }
    // The bars along EA, G1, G2, G3, EB, clamped to the chord at both ends (no
    // pin flags). Orientation (I1 = I2: any vector off the axis gives the same
    // element): the frame's y axis, every bar's GA being in the frame.
    std::array<std::int64_t, kBars + 1> bar_chain = chain;
    bar_chain.front() = ends[0];
    bar_chain.back() = ends[1];
    for (std::size_t n = 0; n < kBars; ++n) {
      formats::Cbar bar;
      bar.eid = ed.new_element_id();
      bar.pid = pb.pid;
      bar.ga = bar_chain[n];
      bar.gb = bar_chain[n + 1];
      bar.x = {0.0, 1.0, 0.0};
      ed.append(formats::write_cbar(bar));
    }
    const auto dv = ed.add_desvar(p, x0);
    ed.add_dvprel1("PBAR", pb.pid, "I1", dv, 1.0);
    ed.add_dvprel1("PBAR", pb.pid, "I2", dv, 1.0);
    if (s.moved > 0) {  // the tube's mass, lumped at the ends in the deck, moved to the inner grids
      NewParameter q;
      q.label = detail::label("XU", r.eid);
      q.prior_mean = q.prior_std = s.moved;
      q.lower = 0.0;
      q.upper = s.end_mass;
      q.meaning = "mass moved from the ends of " + r.type + " " + std::to_string(r.eid) + " to its inner grids [kg]";
      if (c.start.size() > 1) q.start = std::clamp(c.start[1], q.lower, q.upper);
      const double m0 = std::isnan(q.start) ? q.prior_mean : q.start;
      const auto dm = ed.add_desvar(q, m0);
      std::vector<std::pair<std::int64_t, double>> shares{{r.ga, -0.5}, {r.gb, -0.5}};
      for (int n = 1; n < kBars; ++n) shares.emplace_back(chain[static_cast<std::size_t>(n)], 1.0 / (kBars - 1));
      for (const auto& [g, share] : shares) {
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
  /// The translations (basic) of grid `id` in each column of the g-set `shapes`, 3 × m.
  static Eigen::Matrix3Xd translations(const FeModel& model, std::int64_t id, const Eigen::MatrixXd& shapes) {
    const auto& g = model.geometry().grid(id, "local_modes");
    Eigen::Matrix3Xd u = Eigen::Matrix3Xd::Zero(3, shapes.cols());
    for (int i = 0; i < 3; ++i) {
      const auto dof = static_cast<Eigen::Index>(g.dofs[static_cast<std::size_t>(i)]);
      if (dof < shapes.rows()) u.row(i) = shapes.row(dof);
    }
    return g.frame * u;
  }

  /// The candidate's priority for unexplained test mode u (file comment).
  double priority(const FeModel& model, const Strut& s, std::size_t u) const {
    const auto& x = m_options.unexplained;
    if (x.g_shapes.cols() == 0 || u >= x.neighbour.size()) return 0.0;
    // The mean end translation across the axis, one column a mode: what the strut's middle does.
    const Eigen::Matrix3Xd w = 0.5 * (translations(model, s.rod.ga, x.g_shapes) + translations(model, s.rod.gb, x.g_shapes));
    const Eigen::Vector3d axis = (s.b - s.a).normalized();
    const Eigen::Matrix3Xd across = w - axis * (axis.transpose() * w);
    const Eigen::VectorXd& t = x.test_shapes[u];
    if (t.size() == 0 || t.size() != x.sensor_shapes.rows() || !(t.squaredNorm() > 0)) {
      // Frequencies only: how much the strut's middle moves across it in the
      // analysis mode nearest in frequency, against the mode's largest
      // component, squared (0 to 1, as the shape share is).
      const int j = x.neighbour[u];
      const double peak = j < 0 ? 0.0 : x.g_shapes.col(j).cwiseAbs().maxCoeff();
      return peak > 0 ? std::min(1.0, across.col(j).squaredNorm() / (peak * peak)) : 0.0;
    }
    if (!(across.norm() > 1e-9 * w.norm())) return 0.0;  // no motion across the strut in any mode
    const auto [n1, n2] = across_axis(axis);
    Eigen::MatrixXd A(x.sensor_shapes.rows(), 2);
    for (int p = 0; p < 2; ++p)  // φ_jᵀF for F = n/2 at each end: n · (mean end translation)
      A.col(p) = detail::response_at_sensors(x, m_options.unexplained_hz.at(u), ((p == 0 ? n1 : n2).transpose() * w).transpose());
    return detail::explained_share(A, t);
  }

  ExtensionOptions m_options;
};

}  // namespace

std::unique_ptr<ModelExtension> make_local_modes(const ExtensionOptions& options) {
  return std::make_unique<LocalModes>(options);
}

}  // namespace ssid::estimator::diagnosis::hypotheses
