/// \file local_stiffness.cpp
/// local_stiffness: one member (or the joint in it) stiffer or softer than
/// modelled — a loosened B-nut, a long fitting, a dented or thinner tube.
///
/// A rod (CROD, CONROD) or a beam element without its own PBAR gets a CONROD in
/// parallel, between its two grids, of the element's material, its area ΔA = β
/// designed by DVPREL1 (CONROD A = β). A negative ΔA softens. With e the unit
/// vector from GA to GB, L the length and E the modulus:
///   ∂K/∂β = (E/L) [e eᵀ, −e eᵀ; −e eᵀ, e eᵀ] on the translations of GA, GB
/// (rotated into each grid's displacement frame).
///
/// A CBAR with a PBAR carries its stiffness in bending and torsion as much as in
/// tension, which an axial rod cannot change (on a frame, the softer member was
/// then explained as flexible joints). It gets a PBAR of its own instead, a copy of
/// its PBAR whose DVPREL1s are copied too (so at β = 0 it follows the deck's
/// parameters as before), with a term added to each of A, I1, I2, I12, J:
///   P(x, β) = P(x) + P₀ β   (P₀ the deck's value; β relative, prior N(0, f²), β ≥ −0.95)
/// and NSM − ρA₀β, so that the mass stays as it was. At the deck's values the
/// section scales by (1 + β), shear factors and all, so
///   ∂K/∂β = K_e, the element's own stiffness matrix; ∂M/∂β = 0 with lumped mass (the
///   rotary terms ρI of coupled mass or BARMASS move with I).
/// The written deck stays valid NASTRAN (no negative section, unlike a parallel
/// element for a softer member). A CBAR inside an INCLUDE file cannot be changed:
/// that hypothesis is not tested (the diagnosis notes why).
#include <cmath>

#include "estimator/diagnosis/hypotheses/extension_util.hpp"
#include "estimator/diagnosis/hypotheses/model_extension.hpp"
#include "translators/constraints.hpp"

namespace ssid::estimator::diagnosis::hypotheses {

namespace {

struct Member {
  std::string type;
  std::int64_t eid = 0, pid = 0, mid = 0, ga = 0, gb = 0;
  double area = 0;
  bool bar = false;  ///< a CBAR with a PBAR: the whole-section form (file comment)
};

std::vector<Member> members(const formats::BulkModel& b) {
  std::vector<Member> out;
  auto prod = [&](std::int64_t pid) -> const formats::Prod* {
    for (const auto& p : b.prods) if (p.pid == pid) return &p;
    return nullptr;
  };
  auto pbar = [&](std::int64_t pid) -> const formats::Pbar* {
    for (const auto& p : b.pbars) if (p.pid == pid) return &p;
    return nullptr;
  };
  auto pbeam = [&](std::int64_t pid) -> const formats::Pbeam* {
    for (const auto& p : b.pbeams) if (p.pid == pid) return &p;
    return nullptr;
  };
  for (const auto& e : b.crods)
    if (const auto* p = prod(e.pid)) out.push_back({"CROD", e.eid, e.pid, p->mid, e.g1, e.g2, p->a});
  for (const auto& e : b.conrods) out.push_back({"CONROD", e.eid, 0, e.mid, e.g1, e.g2, e.a});
  for (const auto& e : b.cbars)
    if (const auto* p = pbar(e.pid)) out.push_back({"CBAR", e.eid, e.pid, p->mid, e.ga, e.gb, p->a, true});
  for (const auto& e : b.cbeams)
    if (const auto* p = pbeam(e.pid)) out.push_back({"CBEAM", e.eid, e.pid, p->mid, e.ga, e.gb, p->a});
  return out;
}

class LocalStiffness : public ModelExtension {
 public:
  explicit LocalStiffness(ExtensionOptions o) : m_options(std::move(o)) {}
  std::string kind() const override { return "local_stiffness"; }
  std::string describe() const override {
    return "a rod (CONROD) in parallel with one element; parameter: its area dA [m^2] (negative: softer), prior N(0, (" +
           std::to_string(m_options.stiffness_prior_fraction) +
           " x the element's area)^2), dA >= -0.95 A; a CBAR with a PBAR: a PBAR of its own, its section x (1 + b), "
           "its mass kept, parameter b (the relative stiffness change), prior N(0, " +
           std::to_string(m_options.stiffness_prior_fraction) + "^2), b >= -0.95";
  }

  std::vector<Candidate> candidates(const FeModel& nominal) const override {
    std::vector<Candidate> out;
    for (const auto& m : members(nominal.bulk())) {
      if (!(m.area > 0) || m.ga == m.gb) continue;
      Candidate c;
      c.kind = kind();
      c.location = detail::member_location(m.type, m.eid, m.pid, m.ga, m.gb);
      c.ids = {m.eid};
      out.push_back(c);
    }
    return out;
  }

  ExtendedDeck apply(const std::string& text, const std::string& name, const FeModel& nominal,
                     const Candidate& c) const override {
    const Member m = find(nominal.bulk(), c.ids.at(0));
    if (m.bar) return apply_bar(text, name, nominal, c, m);
    DeckEditor ed(text, name);
    NewParameter p;
    p.label = detail::label("XK", m.eid);
    p.prior_mean = 0.0;
    p.prior_std = m_options.stiffness_prior_fraction * m.area;
    p.lower = -0.95 * m.area;
    p.meaning = "area of a rod in parallel with " + m.type + " " + std::to_string(m.eid) +
                " [m^2] (relative stiffness change = dA / " + fmt(m.area) + ")";
    if (!c.start.empty()) p.start = c.start[0];
    const double x0 = std::isnan(p.start) ? p.prior_mean : p.start;
    ed.comment("ssid diagnose: local stiffness change of " + m.type + " " + std::to_string(m.eid));
    formats::Conrod r;
    r.eid = ed.new_element_id();
    r.g1 = m.ga;
    r.g2 = m.gb;
    r.mid = m.mid;
    r.a = x0;
    ed.append(formats::write_conrod(r));
    const auto dv = ed.add_desvar(p, x0);
    ed.add_dvprel1("CONROD", r.eid, "A", dv, 1.0, 0.0, -1e20);
    return {ed.text(), ed.parameters, "the stiffness of " + c.location.text + " changed by an unknown amount"};
  }

  std::optional<ScreeningDerivative> screening(const FeModel& nominal, const Candidate& c) const override {
    const Member m = find(nominal.bulk(), c.ids.at(0));
    if (m.bar) return screening_bar(nominal, m);
    const auto& ga = nominal.geometry().grid(m.ga, "local_stiffness");
    const auto& gb = nominal.geometry().grid(m.gb, "local_stiffness");
    const Eigen::Vector3d d = gb.x - ga.x;
    const double L = d.norm();
    const Eigen::Vector3d e = d / L;
    const double k = detail::young_modulus(nominal.bulk(), m.mid) / L;
    // Per grid, the axial direction in its displacement frame: u_basic = F u_cd, so e·u_basic = (Fᵀe)·u_cd.
    const Eigen::Vector3d ea = ga.frame.transpose() * e, eb = gb.frame.transpose() * e;
    std::vector<Eigen::Triplet<double>> t;
    auto block = [&](const GridPoint& g1, const Eigen::Vector3d& v1, const GridPoint& g2, const Eigen::Vector3d& v2,
                     double s) {
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
          t.emplace_back(static_cast<int>(g1.dofs[static_cast<std::size_t>(i)]),
                         static_cast<int>(g2.dofs[static_cast<std::size_t>(j)]), s * k * v1(i) * v2(j));
    };
    block(ga, ea, ga, ea, 1.0);
    block(gb, eb, gb, eb, 1.0);
    block(ga, ea, gb, eb, -1.0);
    block(gb, eb, ga, ea, -1.0);
    ScreeningDerivative s;
    s.dK.push_back(detail::to_aset(nominal, t));
    s.dM.push_back(Eigen::SparseMatrix<double>(s.dK.back().rows(), s.dK.back().cols()));
    s.prior_std.push_back(m_options.stiffness_prior_fraction * m.area);
    return s;
  }

 private:
  /// The whole-section form of a CBAR with a PBAR (file comment).
  ExtendedDeck apply_bar(const std::string& text, const std::string& name, const FeModel& nominal,
                         const Candidate& c, const Member& m) const {
    DeckEditor ed(text, name);
    const formats::BulkModel& b = ed.bulk();
    const formats::Cbar* bar = nullptr;
    for (const auto& e : b.cbars)
      if (e.eid == m.eid) bar = &e;
    const formats::Pbar* card = nullptr;
    for (const auto& p : b.pbars)
      if (bar && p.pid == bar->pid) card = &p;
    if (!bar || !card)
      throw formats::InputError("local_stiffness: CBAR " + std::to_string(m.eid) + " and its PBAR are not in this "
                                "configuration's deck");
    // The rates are the section the model starts from: the card's values as its DVPREL1s
    // set them at the initial DESVARs (and ρ likewise), so that the section scales by
    // (1 + β) there and the screening's derivative (at the same values) is the deck's.
    const formats::BulkModel start = nominal.values_at(nominal.initial_parameters());
    const formats::Pbar* prop = card;
    for (const auto& p : start.pbars)
      if (p.pid == card->pid) prop = &p;
    const double rho = detail::density(start, prop->mid);
    NewParameter p;
    p.label = detail::label("XK", m.eid);
    p.prior_mean = 0.0;
    p.prior_std = m_options.stiffness_prior_fraction;
    p.lower = -0.95;
    p.meaning = "relative stiffness change of CBAR " + std::to_string(m.eid) +
                " (its section x (1 + this value), its mass kept; -0.1: 10 % softer)";
    if (!c.start.empty()) p.start = c.start[0];
    const double x0 = std::isnan(p.start) ? p.prior_mean : p.start;
    ed.comment("ssid diagnose: local stiffness change of CBAR " + std::to_string(m.eid) +
               " (a PBAR of its own, its section scaled, its mass kept)");
    // The scaled fields, with the rate of each per unit β (NSM keeps ρA + NSM).
    struct Scaled {
      const char* name;
      std::int64_t fid;
      double formats::Pbar::*field;
      double rate;
    };
    std::vector<Scaled> scaled = {{"A", 4, &formats::Pbar::a, prop->a},      {"I1", 5, &formats::Pbar::i1, prop->i1},
                                  {"I2", 6, &formats::Pbar::i2, prop->i2},   {"J", 7, &formats::Pbar::j, prop->j},
                                  {"I12", 19, &formats::Pbar::i12, prop->i12}, {"NSM", 8, &formats::Pbar::nsm, -rho * prop->a}};
    formats::Pbar own = *card;
    own.pid = ed.new_property_id();
    for (const auto& f : scaled) own.*(f.field) = (*prop).*(f.field) + f.rate * x0;  // the starting section, scaled
    ed.append(formats::write_pbar(own));
    formats::Cbar moved = *bar;
    moved.pid = own.pid;
    moved.pid_blank = false;  // a BAROR's PID would not be the new one
    ed.change(bar->card, formats::write_cbar(moved));
    const auto dv = ed.add_desvar(p, x0);
    std::vector<bool> done(scaled.size(), false);
    for (const auto& r : b.dvprel1s) {
      if (r.type != "PBAR" || r.pid != card->pid) continue;
      formats::Dvprel1 copy = r;
      copy.id = ed.new_relation_id();
      copy.pid = own.pid;
      for (std::size_t k = 0; k < scaled.size(); ++k)
        if ((r.pname == scaled[k].name || (r.pname.empty() && r.fid == scaled[k].fid)) && scaled[k].rate != 0.0) {
          copy.terms.push_back({dv, scaled[k].rate});
          copy.pmin = -1e20;
          done[k] = true;
        }
      ed.append(formats::write_dvprel1(copy));
    }
    for (std::size_t k = 0; k < scaled.size(); ++k)
      if (!done[k] && scaled[k].rate != 0.0)
        ed.add_dvprel1("PBAR", own.pid, scaled[k].name, dv, scaled[k].rate, (*prop).*(scaled[k].field), -1e20);
    return {ed.text(), ed.parameters, "the stiffness of " + c.location.text + " changed by an unknown factor"};
  }

  /// ∂K/∂β, ∂M/∂β of the whole-section form at the deck's starting values: K and M of
  /// the element are linear in a uniform scaling of its section (the shear ratio stays),
  /// so they are the element's blocks with β = 1 less those with β = 0 (with coupled
  /// mass or BARMASS the rotary terms ρI move with I: ∂M/∂β is not zero there).
  ScreeningDerivative screening_bar(const FeModel& nominal, const Member& m) const {
    if (m_values_for != &nominal) {  // the values the extended model starts from, once per model
      m_values = nominal.values_at(nominal.initial_parameters());
      m_values_for = &nominal;
    }
    const auto& els = nominal.elements().elements();
    std::size_t k = 0;
    while (k < els.size() && !(els[k].kind == translators::ElementKind::Cbar && els[k].eid == m.eid)) ++k;
    if (k == els.size()) throw std::invalid_argument("local_stiffness: CBAR " + std::to_string(m.eid) + " not assembled");
    formats::Pbar* prop = nullptr;
    for (auto& p : m_values.pbars)
      if (p.pid == els[k].pid) prop = &p;
    if (!prop) throw std::invalid_argument("local_stiffness: CBAR " + std::to_string(m.eid) + ": no PBAR");
    const double rho = detail::density(m_values, prop->mid);
    const auto at0 = nominal.elements().block_of(k, m_values);
    const formats::Pbar kept = *prop;  // β = 1 in place (only this element is evaluated), then restored
    prop->a *= 2;
    prop->i1 *= 2;
    prop->i2 *= 2;
    prop->i12 *= 2;
    prop->j *= 2;
    prop->nsm -= rho * kept.a;
    const auto at1 = nominal.elements().block_of(k, m_values);
    *prop = kept;
    translators::ElementBlock rate = at1;
    rate.k -= at0.k;
    rate.m -= at0.m;
    ScreeningDerivative s;  // summed as the model sums its blocks (WTMASS on the mass), then reduced
    s.dK.push_back(reduce(nominal.sum_blocks({rate}, false), nominal.reduction()));
    s.dM.push_back(reduce(nominal.sum_blocks({rate}, true), nominal.reduction()));
    s.prior_std.push_back(m_options.stiffness_prior_fraction);
    return s;
  }

  static Member find(const formats::BulkModel& b, std::int64_t eid) {
    for (const auto& m : members(b))
      if (m.eid == eid) return m;
    throw std::invalid_argument("local_stiffness: element " + std::to_string(eid) + " not found");
  }
  static std::string fmt(double x) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.4g", x);
    return buf;
  }
  ExtensionOptions m_options;
  /// screening_bar's values of the nominal model at its initial parameters (the
  /// screening runs on one thread, candidate after candidate).
  mutable formats::BulkModel m_values;
  mutable const FeModel* m_values_for = nullptr;
};

}  // namespace

std::unique_ptr<ModelExtension> make_local_stiffness(const ExtensionOptions& options) {
  return std::make_unique<LocalStiffness>(options);
}

}  // namespace ssid::estimator::diagnosis::hypotheses
