#include "translators/assembly/element_blocks.hpp"

#include <cmath>
#include <stdexcept>

#include "translators/elements/bar.hpp"
#include "translators/elements/point.hpp"
#include "translators/elements/rod.hpp"
#include "translators/elements/section.hpp"

namespace ssid::translators {

namespace el = elements;
using formats::BulkModel;

namespace {

Eigen::Vector3d vec(const std::array<double, 3>& a) { return {a[0], a[1], a[2]}; }

int pin_flags(const std::string& s) { return s.empty() ? 0 : std::stoi(s); }

template <class V>
void index_by_pid(const V& v, std::unordered_map<std::int64_t, std::size_t>& out) {
  for (std::size_t i = 0; i < v.size(); ++i) out[v[i].pid] = i;
}

std::vector<std::size_t> concat(const std::array<std::size_t, 6>& a, const std::array<std::size_t, 6>& b) {
  std::vector<std::size_t> d(a.begin(), a.end());
  d.insert(d.end(), b.begin(), b.end());
  return d;
}

el::Material material(const formats::Mat1& m) { return {m.e, m.g, m.nu, m.rho}; }

/// The material rates along `delta`, MAT1's derivation rule applied.
el::Material material_rate(const formats::Mat1& m, const ValueDelta& d) {
  const auto r = mat1_rates(m, d.get(ValueOwner::Material, m.mid, "E"), d.get(ValueOwner::Material, m.mid, "G"),
                            d.get(ValueOwner::Material, m.mid, "NU"));
  return {r[0], r[1], r[2], d.get(ValueOwner::Material, m.mid, "RHO")};
}

/// Section of a PBARL/PBEAML from its dimensions; with `ddims`, its rate.
el::BarSection dims_section(const std::string& type, const std::vector<double>& dims, double nsm,
                            const std::string& who, const std::vector<double>* ddims = nullptr, double dnsm = 0) {
  el::SectionShape shape;
  try {
    shape = el::parse_section_shape(type);
  } catch (const std::exception&) {
    throw ModelError(who + ": section type " + type + " is not supported (" + el::supported_section_types() + " are)");
  }
  el::BarSection s;
  try {
    if (!ddims) {
      const auto p = el::section_properties(shape, dims);
      s.a = p.a; s.i1 = p.i1; s.i2 = p.i2; s.i12 = p.i12; s.j = p.j; s.k1 = p.k1; s.k2 = p.k2;
      s.nsm = nsm;
      return s;
    }
    const Eigen::Matrix<double, el::kSectionValues, Eigen::Dynamic> J = el::section_jacobian(shape, dims);
    Eigen::VectorXd dd(static_cast<Eigen::Index>(ddims->size()));
    for (std::size_t i = 0; i < ddims->size(); ++i) dd(static_cast<Eigen::Index>(i)) = (*ddims)[i];
    const Eigen::Matrix<double, el::kSectionValues, 1> r = J * dd;
    s.a = r(0); s.i1 = r(1); s.i2 = r(2); s.i12 = r(3); s.j = r(4); s.k1 = r(5); s.k2 = r(6);
    s.nsm = dnsm;
    return s;
  } catch (const std::invalid_argument& e) {
    throw ModelError(who + ": " + e.what());
  }
}

}  // namespace

namespace {

/// NASTRAN keeps property ids apart by the types an element chooses among
/// (formats::id_family: PROD 1 beside PBEAM 1 is no duplicate), but the property values
/// of the assembly are keyed by id alone (property_values.hpp, DVPREL1 relations), so
/// two assembled property types sharing an id are refused here rather than confused.
void refuse_shared_property_ids(const formats::Deck& deck, const BulkModel& m) {
  std::unordered_map<std::int64_t, std::size_t> first;  // pid -> card
  auto claim = [&](std::int64_t pid, std::size_t card) {
    auto [it, fresh] = first.emplace(pid, card);
    if (fresh || deck.cards[it->second].name == deck.cards[card].name) return;  // PELAS 1 holding two entries
    const std::size_t a = std::min(it->second, card), b = std::max(it->second, card);
    throw ModelError(deck.location(deck.cards[b]),
                     deck.cards[b].name + " " + std::to_string(pid) + " shares its id with " + deck.cards[a].name + " " +
                         std::to_string(pid) + " at " +
                         deck.location(deck.cards[a]).str() +
                         ": NASTRAN keeps the two apart (an element looks its property up among its own types), "
                         "ssid's assembly keys properties by id alone; give one of them another id");
  };
  auto all = [&](const auto& v) {
    for (const auto& p : v) claim(p.pid, p.card);
  };
  all(m.prods);
  all(m.pbars);
  all(m.pbarls);
  all(m.pbeams);
  all(m.pbeamls);
  all(m.pelases);
  all(m.pmasses);
  all(m.pbushes);
}

}  // namespace

ElementSet::ElementSet(const formats::Deck& deck, const BulkModel& m, const ModelGeometry& geometry,
                       ElementSettings settings)
    : m_geometry(geometry), m_settings(settings) {
  refuse_shared_property_ids(deck, m);
  index_by_pid(m.prods, m_prod);
  index_by_pid(m.pbars, m_pbar);
  index_by_pid(m.pbarls, m_pbarl);
  index_by_pid(m.pbeams, m_pbeam);
  index_by_pid(m.pbeamls, m_pbeaml);
  index_by_pid(m.pelases, m_pelas);
  index_by_pid(m.pmasses, m_pmass);
  index_by_pid(m.pbushes, m_pbush);
  for (std::size_t i = 0; i < m.mat1s.size(); ++i) m_mat1[m.mat1s[i].mid] = i;

  auto need_mat = [&](std::int64_t mid, const std::string& who, const std::string& via) {
    if (!m_mat1.count(mid))
      throw ModelError(who + ": MAT1 " + std::to_string(mid) + (via.empty() ? "" : " (of " + via + ")") +
                       " does not exist (only MAT1 materials are assembled)");
  };
  auto need_prop = [&](std::int64_t pid, const std::string& who, std::initializer_list<const char*> types) {
    const std::string t = property_type(m, pid);
    for (const char* ok : types)
      if (t == ok) return t;
    std::string expected;
    for (const char* ok : types) expected += (expected.empty() ? "" : " or ") + std::string(ok);
    if (t.empty()) throw ModelError(who + ": property " + std::to_string(pid) + " does not exist (" + expected + " expected)");
    throw ModelError(who + ": property " + std::to_string(pid) + " is a " + t + ", expected " + expected);
  };
  auto grid_dofs = [&](std::int64_t a, std::int64_t b, const std::string& who) {
    return concat(geometry.grid(a, who).dofs, geometry.grid(b, who).dofs);
  };
  auto add = [&](ElementKind kind, std::size_t index, std::int64_t eid, std::int64_t pid, std::int64_t mid,
                 std::size_t card, std::vector<std::size_t> dofs) {
    ElementRef r{kind, index, eid, pid, mid, deck.cards.at(card).name, card_label(deck, card), std::move(dofs)};
    m_elements.push_back(std::move(r));
  };

  for (std::size_t i = 0; i < m.crods.size(); ++i) {
    const auto& c = m.crods[i];
    const auto who = card_label(deck, c.card);
    need_prop(c.pid, who, {"PROD"});
    const auto mid = m.prods[m_prod.at(c.pid)].mid;
    need_mat(mid, who, "PROD " + std::to_string(c.pid));
    add(ElementKind::Crod, i, c.eid, c.pid, mid, c.card, grid_dofs(c.g1, c.g2, who));
  }
  for (std::size_t i = 0; i < m.conrods.size(); ++i) {
    const auto& c = m.conrods[i];
    const auto who = card_label(deck, c.card);
    need_mat(c.mid, who, "");
    add(ElementKind::Conrod, i, c.eid, 0, c.mid, c.card, grid_dofs(c.g1, c.g2, who));
  }
  auto check_offt = [&](const std::string& offt, const std::string& who) {
    for (std::size_t k = 0; k < 3; ++k)
      if (k < offt.size() && offt[k] != 'G' && offt[k] != 'B')
        throw ModelError(who + ": OFFT " + offt + ": only G and B are assembled (element-system offsets are not)");
  };
  for (std::size_t i = 0; i < m.cbars.size(); ++i) {
    const auto& c = m.cbars[i];
    const auto who = card_label(deck, c.card);
    const auto t = need_prop(c.pid, who, {"PBAR", "PBARL"});
    const auto mid = t == "PBAR" ? m.pbars[m_pbar.at(c.pid)].mid : m.pbarls[m_pbarl.at(c.pid)].mid;
    need_mat(mid, who, t + " " + std::to_string(c.pid));
    check_offt(c.offt, who);
    if (c.g0 > 0) geometry.grid(c.g0, who);
    add(ElementKind::Cbar, i, c.eid, c.pid, mid, c.card, grid_dofs(c.ga, c.gb, who));
  }
  for (std::size_t i = 0; i < m.cbeams.size(); ++i) {
    const auto& c = m.cbeams[i];
    const auto who = card_label(deck, c.card);
    const auto t = need_prop(c.pid, who, {"PBEAM", "PBEAML"});
    std::int64_t mid = 0;
    if (t == "PBEAM") {
      const auto& p = m.pbeams[m_pbeam.at(c.pid)];
      mid = p.mid;
      for (const auto& s : p.stations)
        if (s.a != p.a || s.i1 != p.i1 || s.i2 != p.i2 || s.i12 != p.i12 || s.j != p.j || s.nsm != p.nsm)
          throw ModelError(who + ": PBEAM " + std::to_string(c.pid) +
                           " is tapered (its stations differ); only constant sections are assembled");
      // CBEAM extras that change K or M and that ssid's beam does not model: refused by name.
      const std::pair<const char*, bool> extras[] = {
          {"warping coefficient CW", p.cwa != 0.0 || p.cwb != 0.0},
          {"non-structural mass inertia NSI", p.nsia != 0.0 || p.nsib != 0.0},
          {"non-structural mass offset M1/M2", p.m1a != 0.0 || p.m2a != 0.0 || p.m1b != 0.0 || p.m2b != 0.0},
          {"neutral axis offset N1/N2", p.n1a != 0.0 || p.n2a != 0.0 || p.n1b != 0.0 || p.n2b != 0.0},
          {"shear relief S1/S2", p.s1 != 0.0 || p.s2 != 0.0}};
      for (const auto& e : extras)
        if (e.second)
          throw ModelError(who + ": PBEAM " + std::to_string(c.pid) + " " + e.first +
                           " is not assembled (ssid's CBEAM: constant section, shear centre on the neutral axis)");
    } else {
      const auto& p = m.pbeamls[m_pbeaml.at(c.pid)];
      mid = p.mid;
      for (const auto& s : p.stations)
        if (s.dims != p.dims() || s.nsm != p.nsm())
          throw ModelError(who + ": PBEAML " + std::to_string(c.pid) +
                           " is tapered (its stations differ); only constant sections are assembled");
      try {
        const auto shape = el::parse_section_shape(p.type);
        if (!el::shear_centre_at_centroid(shape, p.dims()))
          throw ModelError(who + ": PBEAML " + std::to_string(c.pid) + " TYPE " + p.type +
                           ": the shear centre is off the centroid for these dimensions; NASTRAN's CBEAM offsets "
                           "the neutral axis from it (coupling bending and torsion), which ssid's CBEAM does not "
                           "model (a CBAR with PBARL, which NASTRAN also assembles about one axis, is)");
      } catch (const std::invalid_argument&) {
        // Unknown TYPE: dims_section names it when the element is evaluated.
      }
    }
    need_mat(mid, who, t + " " + std::to_string(c.pid));
    check_offt(c.offt, who);
    if (c.bit && *c.bit != 0.0) throw ModelError(who + ": built-in twist (BIT) is not assembled");
    if (c.sa != 0 || c.sb != 0) throw ModelError(who + ": warping scalar points SA/SB are not assembled");
    if (c.g0 > 0) geometry.grid(c.g0, who);
    add(ElementKind::Cbeam, i, c.eid, c.pid, mid, c.card, grid_dofs(c.ga, c.gb, who));
  }
  for (std::size_t i = 0; i < m.conm2s.size(); ++i) {
    const auto& c = m.conm2s[i];
    const auto who = card_label(deck, c.card);
    const auto& g = geometry.grid(c.g, who);
    if (c.cid > 0 && !geometry.systems().contains(static_cast<long>(c.cid)))
      throw ModelError(who + ": coordinate system " + std::to_string(c.cid) + " does not exist");
    add(ElementKind::Conm2, i, c.eid, 0, 0, c.card, std::vector<std::size_t>(g.dofs.begin(), g.dofs.end()));
  }
  auto scalar_dofs = [&](std::int64_t g1, std::int64_t c1, std::int64_t g2, std::int64_t c2, const std::string& who) {
    std::vector<std::size_t> d;
    if (g1 > 0) d.push_back(geometry.dof(g1, static_cast<int>(c1), who));
    if (g2 > 0) d.push_back(geometry.dof(g2, static_cast<int>(c2), who));
    if (d.empty()) throw ModelError(who + ": both terminals grounded");
    return d;
  };
  for (std::size_t i = 0; i < m.cmass1s.size(); ++i) {
    const auto& c = m.cmass1s[i];
    const auto who = card_label(deck, c.card);
    need_prop(c.pid, who, {"PMASS"});
    add(ElementKind::Cmass1, i, c.eid, c.pid, 0, c.card, scalar_dofs(c.g1, c.c1, c.g2, c.c2, who));
  }
  for (std::size_t i = 0; i < m.cmass2s.size(); ++i) {
    const auto& c = m.cmass2s[i];
    const auto who = card_label(deck, c.card);
    add(ElementKind::Cmass2, i, c.eid, 0, 0, c.card, scalar_dofs(c.g1, c.c1, c.g2, c.c2, who));
  }
  for (std::size_t i = 0; i < m.celas1s.size(); ++i) {
    const auto& c = m.celas1s[i];
    const auto who = card_label(deck, c.card);
    need_prop(c.pid, who, {"PELAS"});
    add(ElementKind::Celas1, i, c.eid, c.pid, 0, c.card, scalar_dofs(c.g1, c.c1, c.g2, c.c2, who));
  }
  for (std::size_t i = 0; i < m.celas2s.size(); ++i) {
    const auto& c = m.celas2s[i];
    const auto who = card_label(deck, c.card);
    add(ElementKind::Celas2, i, c.eid, 0, 0, c.card, scalar_dofs(c.g1, c.c1, c.g2, c.c2, who));
  }
  for (std::size_t i = 0; i < m.cbushes.size(); ++i) {
    const auto& c = m.cbushes[i];
    const auto who = card_label(deck, c.card);
    need_prop(c.pid, who, {"PBUSH"});
    if (c.ocid >= 0) throw ModelError(who + ": spring offsets by OCID/S1-S3 are not assembled");
    if (c.cid > 0 && !geometry.systems().contains(static_cast<long>(c.cid)))
      throw ModelError(who + ": coordinate system " + std::to_string(c.cid) + " does not exist");
    if (c.g0 > 0) geometry.grid(c.g0, who);
    const auto& ga = geometry.grid(c.ga, who);
    std::vector<std::size_t> d(ga.dofs.begin(), ga.dofs.end());
    if (c.gb > 0) {
      const auto& gb = geometry.grid(c.gb, who);
      d.insert(d.end(), gb.dofs.begin(), gb.dofs.end());
    }
    add(ElementKind::Cbush, i, c.eid, c.pid, 0, c.card, std::move(d));
  }
}

bool ElementSet::touched(const ElementRef& r, const ValueDelta& d) const {
  if (r.pid && d.touches(ValueOwner::Property, r.pid)) return true;
  if (r.mid && d.touches(ValueOwner::Material, r.mid)) return true;
  return d.touches(ValueOwner::Element, r.eid);
}

std::vector<ElementBlock> ElementSet::blocks(const BulkModel& values) const {
  std::vector<ElementBlock> out;
  out.reserve(m_elements.size());
  for (std::size_t e = 0; e < m_elements.size(); ++e) out.push_back(evaluate(e, values, nullptr));
  return out;
}

std::vector<ElementBlock> ElementSet::derivative_blocks(const BulkModel& values, const ValueDelta& delta) const {
  std::vector<ElementBlock> out;
  for (std::size_t e = 0; e < m_elements.size(); ++e)
    if (touched(m_elements[e], delta)) out.push_back(evaluate(e, values, &delta));
  return out;
}

namespace {

/// The property index of each property and material id (ElementSet's maps).
using IdIndex = std::unordered_map<std::int64_t, std::size_t>;
struct PropertyIndex {
  const IdIndex &prod, &pbar, &pbarl, &pbeam, &pbeaml, &pelas, &pmass, &pbush, &mat1;
};

/// What one element's block is computed from: its card, the model's values,
/// the direction of the derivative (null: the matrices themselves), the geometry.
struct BlockInputs {
  const ElementRef& r;
  const BulkModel& v;
  const ValueDelta* d;
  const ModelGeometry& geo;
  const ElementSettings& settings;
  const PropertyIndex& at;
  /// The rate of a designed value of the element's property / of the element itself (0 without a delta).
  double P(const char* name) const { return d ? d->get(ValueOwner::Property, r.pid, name) : 0.0; }
  double E(const char* name) const { return d ? d->get(ValueOwner::Element, r.eid, name) : 0.0; }
  el::GridPair pair(std::int64_t ga, std::int64_t gb) const {
    const auto& a = geo.grid(ga, r.label);
    const auto& bb = geo.grid(gb, r.label);
    return el::GridPair{a.x, bb.x, a.frame, bb.frame};
  }
};

void set_both(ElementBlock& b, const el::ElementMatrices& em) {
  b.k = em.k;
  b.m = em.m;
}

/// CROD (PROD) and CONROD: axial and torsional rod.
void rod_block(const BlockInputs& in, ElementBlock& b) {
  el::GridPair g;
  el::RodSection s, ds;
  if (in.r.kind == ElementKind::Crod) {
    const auto& c = in.v.crods[in.r.index];
    const auto& p = in.v.prods[in.at.prod.at(in.r.pid)];
    g = in.pair(c.g1, c.g2);
    s = {p.a, p.j, p.nsm};
    ds = {in.P("A"), in.P("J"), in.P("NSM")};
  } else {
    const auto& c = in.v.conrods[in.r.index];
    g = in.pair(c.g1, c.g2);
    s = {c.a, c.j, c.nsm};
    ds = {in.E("A"), in.E("J"), in.E("NSM")};
  }
  const auto& mat = in.v.mat1s[in.at.mat1.at(in.r.mid)];
  if (!in.d) set_both(b, el::rod_matrices(g, s, material(mat), in.settings.mass));
  else set_both(b, el::rod_directional_derivative(g, s, material(mat), in.settings.mass, ds, material_rate(mat, *in.d)));
}

/// CBAR and CBEAM with a PBAR/PBEAM or a PBARL/PBEAML section: orientation
/// (G0 or X, OFFT), offsets, pin flags.
void bar_or_beam_block(const BlockInputs& in, ElementBlock& b) {
  const bool bar = in.r.kind == ElementKind::Cbar;
  std::int64_t ga, gb, g0;
  std::array<double, 3> x, wa, wb;
  std::string offt, pa, pb;
  if (bar) {
    const auto& c = in.v.cbars[in.r.index];
    ga = c.ga; gb = c.gb; g0 = c.g0; x = c.x; wa = c.wa; wb = c.wb; offt = c.offt; pa = c.pa; pb = c.pb;
  } else {
    const auto& c = in.v.cbeams[in.r.index];
    ga = c.ga; gb = c.gb; g0 = c.g0; x = c.x; wa = c.wa; wb = c.wb; offt = c.offt; pa = c.pa; pb = c.pb;
  }
  if (offt.size() < 3) offt.append(3 - offt.size(), 'G');
  el::BarGeometry g;
  g.grids = in.pair(ga, gb);
  // Orientation: from GA to G0 in basic, or X in GA's displacement system (OFFT 'G') or basic ('B').
  g.v = g0 > 0 ? Eigen::Vector3d(in.geo.grid(g0, in.r.label).x - g.grids.xa)
               : Eigen::Vector3d(offt[0] == 'B' ? vec(x) : Eigen::Vector3d(g.grids.ta * vec(x)));
  g.wa = offt[1] == 'B' ? vec(wa) : Eigen::Vector3d(g.grids.ta * vec(wa));
  g.wb = offt[2] == 'B' ? vec(wb) : Eigen::Vector3d(g.grids.tb * vec(wb));
  g.pa = pin_flags(pa);
  g.pb = pin_flags(pb);
  el::BarSection s, ds;
  if (in.at.pbar.count(in.r.pid) && bar) {
    const auto& p = in.v.pbars[in.at.pbar.at(in.r.pid)];
    s = {p.a, p.i1, p.i2, p.i12, p.j, p.nsm, p.k1, p.k2};
    ds = {in.P("A"), in.P("I1"), in.P("I2"), in.P("I12"), in.P("J"), in.P("NSM"), in.P("K1"), in.P("K2")};
  } else if (in.at.pbeam.count(in.r.pid) && !bar) {
    const auto& p = in.v.pbeams[in.at.pbeam.at(in.r.pid)];
    s = {p.a, p.i1, p.i2, p.i12, p.j, p.nsm, p.k1, p.k2};
    ds = {in.P("A"), in.P("I1"), in.P("I2"), in.P("I12"), in.P("J"), in.P("NSM"), in.P("K1"), in.P("K2")};
  } else {
    const std::vector<double>* dims;
    std::string type;
    double nsm;
    if (bar) {
      const auto& p = in.v.pbarls[in.at.pbarl.at(in.r.pid)];
      dims = &p.dims; type = p.type; nsm = p.nsm;
    } else {
      const auto& p = in.v.pbeamls[in.at.pbeaml.at(in.r.pid)];
      dims = &p.dims(); type = p.type; nsm = p.nsm();
    }
    s = dims_section(type, *dims, nsm, in.r.label);
    if (in.d) {
      std::vector<double> dd(dims->size());
      for (std::size_t i = 0; i < dd.size(); ++i) dd[i] = in.P(("DIM" + std::to_string(i + 1)).c_str());
      ds = dims_section(type, *dims, nsm, in.r.label, &dd, in.P("NSM"));
    }
  }
  const auto& mat = in.v.mat1s[in.at.mat1.at(in.r.mid)];
  if (bar) {
    if (!in.d) set_both(b, el::bar_matrices(g, s, material(mat), in.settings.mass, in.settings.barmass));
    else set_both(b, el::bar_directional_derivative(g, s, material(mat), in.settings.mass, ds, material_rate(mat, *in.d),
                                              in.settings.barmass));
  } else {
    if (!in.d) set_both(b, el::beam_matrices(g, s, material(mat), in.settings.mass));
    else set_both(b, el::beam_directional_derivative(g, s, material(mat), in.settings.mass, ds, material_rate(mat, *in.d)));
  }
}

/// CONM2: mass and inertia at an offset (the offset derivative by a central
/// difference, exact for the quadratic mass matrix).
void conm2_block(const BlockInputs& in, ElementBlock& b) {
  const auto& c = in.v.conm2s[in.r.index];
  const auto& grid = in.geo.grid(c.g, in.r.label);
  auto make = [&](const formats::Conm2& cc) {
    el::Conm2 m;
    m.mass = cc.m;
    m.i11 = cc.i11; m.i21 = cc.i21; m.i22 = cc.i22; m.i31 = cc.i31; m.i32 = cc.i32; m.i33 = cc.i33;
    m.t = grid.frame;
    if (cc.cid < 0) {
      m.offset = vec(cc.x) - grid.x;  // CID = −1: X is the CG's basic position
    } else {
      const Eigen::Matrix3d f = in.geo.systems().displacement_frame(static_cast<long>(cc.cid), grid.x);
      m.offset = f * vec(cc.x);
      m.inertia_frame = f;
    }
    return m;
  };
  const el::Conm2 m0 = make(c);
  b.k = Eigen::MatrixXd::Zero(6, 6);
  if (!in.d) {
    b.m = el::conm2_matrix(m0);
    return;
  }
  b.m = in.E("M") * el::conm2_derivative(m0, el::Conm2Param::Mass) + in.E("I11") * el::conm2_derivative(m0, el::Conm2Param::I11) +
        in.E("I21") * el::conm2_derivative(m0, el::Conm2Param::I21) + in.E("I22") * el::conm2_derivative(m0, el::Conm2Param::I22) +
        in.E("I31") * el::conm2_derivative(m0, el::Conm2Param::I31) + in.E("I32") * el::conm2_derivative(m0, el::Conm2Param::I32) +
        in.E("I33") * el::conm2_derivative(m0, el::Conm2Param::I33);
  // The mass matrix is quadratic in the offset: the central difference is exact.
  for (int k = 0; k < 3; ++k) {
    const double rate = in.E(k == 0 ? "X1" : k == 1 ? "X2" : "X3");
    if (rate == 0.0) continue;
    const double h = 1e-3 * (std::abs(c.x[static_cast<std::size_t>(k)]) + 1.0);
    formats::Conm2 up = c, dn = c;
    up.x[static_cast<std::size_t>(k)] += h;
    dn.x[static_cast<std::size_t>(k)] -= h;
    b.m += rate * (el::conm2_matrix(make(up)) - el::conm2_matrix(make(dn))) / (2.0 * h);
  }
}

/// CMASS1/2, CELAS1/2: scalar mass or spring, grounded or between two DOFs.
void scalar_block(const BlockInputs& in, ElementBlock& b) {
  const bool grounded = in.r.dofs.size() == 1;
  double value = 0;
  if (in.r.kind == ElementKind::Cmass1) value = in.d ? in.P("M") : in.v.pmasses[in.at.pmass.at(in.r.pid)].m;
  if (in.r.kind == ElementKind::Cmass2) value = in.d ? in.E("M") : in.v.cmass2s[in.r.index].m;
  // A DVPREL1 names the PELAS stiffness "K" or, as NASTRAN does, "K1": both are rates of k.
  if (in.r.kind == ElementKind::Celas1) value = in.d ? in.P("K") + in.P("K1") : in.v.pelases[in.at.pelas.at(in.r.pid)].k;
  if (in.r.kind == ElementKind::Celas2) value = in.d ? in.E("K") : in.v.celas2s[in.r.index].k;
  const Eigen::MatrixXd s = el::scalar_element_matrix(value, grounded);
  const Eigen::MatrixXd z = Eigen::MatrixXd::Zero(s.rows(), s.cols());
  const bool mass = in.r.kind == ElementKind::Cmass1 || in.r.kind == ElementKind::Cmass2;
  b.k = mass ? z : s;
  b.m = mass ? s : z;
}

/// CBUSH (PBUSH K1-K6): element axes from CID, G0/X, or the basic system.
void bush_block(const BlockInputs& in, ElementBlock& b) {
  const auto& c = in.v.cbushes[in.r.index];
  const auto& p = in.v.pbushes[in.at.pbush.at(in.r.pid)];
  el::BushGeometry g;
  const auto& ga = in.geo.grid(c.ga, in.r.label);
  g.grids.xa = ga.x;
  g.grids.ta = ga.frame;
  g.grounded = c.gb <= 0;
  if (!g.grounded) {
    const auto& gb = in.geo.grid(c.gb, in.r.label);
    g.grids.xb = gb.x;
    g.grids.tb = gb.frame;
  } else {
    g.grids.xb = ga.x;
    g.grids.tb = ga.frame;
  }
  g.s = c.s;
  if (c.cid >= 0) {
    // CID overrides the orientation; a curvilinear system is evaluated at GA.
    g.axes = in.geo.systems().displacement_frame(static_cast<long>(c.cid), ga.x).transpose();
  } else if (!c.orientation_blank) {
    const Eigen::Vector3d v0 = c.g0 > 0 ? Eigen::Vector3d(in.geo.grid(c.g0, in.r.label).x - ga.x)
                                        : Eigen::Vector3d(ga.frame * vec(c.x));
    g.axes = el::bush_axes_from_vector(g.grids.xa, g.grids.xb, v0);
  } else {
    g.axes = Eigen::Matrix3d::Identity();  // no CID, no orientation: the basic system
  }
  if (!in.d) {
    Eigen::Matrix<double, 6, 1> k;
    for (int i = 0; i < 6; ++i) k(i) = p.k[static_cast<std::size_t>(i)];
    b.k = el::bush_stiffness(g, k);
  } else {
    b.k = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(in.r.dofs.size()), static_cast<Eigen::Index>(in.r.dofs.size()));
    for (int i = 1; i <= 6; ++i)
      if (const double rate = in.P(("K" + std::to_string(i)).c_str()); rate != 0.0) b.k += rate * el::bush_derivative(g, i);
  }
  b.m = Eigen::MatrixXd::Zero(b.k.rows(), b.k.cols());
}

}  // namespace

ElementBlock ElementSet::evaluate(std::size_t e, const BulkModel& v, const ValueDelta* d) const {
  const ElementRef& r = m_elements[e];
  ElementBlock b;
  b.element = e;
  b.dofs = r.dofs;
  const PropertyIndex at{m_prod, m_pbar, m_pbarl, m_pbeam, m_pbeaml, m_pelas, m_pmass, m_pbush, m_mat1};
  const BlockInputs in{r, v, d, m_geometry, m_settings, at};
  try {
    switch (r.kind) {
      case ElementKind::Crod:
      case ElementKind::Conrod:
        rod_block(in, b);
        break;
      case ElementKind::Cbar:
      case ElementKind::Cbeam:
        bar_or_beam_block(in, b);
        break;
      case ElementKind::Conm2:
        conm2_block(in, b);
        break;
      case ElementKind::Cmass1:
      case ElementKind::Cmass2:
      case ElementKind::Celas1:
      case ElementKind::Celas2:
        scalar_block(in, b);
        break;
      case ElementKind::Cbush:
        bush_block(in, b);
        break;
    }
  } catch (const ModelError&) {
    throw;
  } catch (const std::exception& ex) {
    throw ModelError(r.label + ": " + ex.what());
  }
  return b;
}

}  // namespace ssid::translators
