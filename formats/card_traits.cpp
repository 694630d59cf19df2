/// \file card_traits.cpp
/// The card-traits table: one entry per card type. The typed entries are built
/// by `typed(...)` from the struct's vector in BulkModel, its parse_xxx and
/// write_xxx (formats/cards/), then `.defines` (its id space), `.refers` (each
/// field that names another card, as resolve checks it) and `.checks` (what
/// resolve checks beyond references). The cards kept verbatim are listed after
/// them, by what resolve and the assembly need of them: their id space, the
/// scalar points they imply, and whether SOL 103 ignores them.
///
/// The entries stand in the order resolve checks them, which is the order its
/// problems come in (tests/formats/test_resolve.cpp pins it).
#include "formats/card_traits.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_map>
#include <utility>

#include "formats/bulk_model.hpp"
#include "formats/field_reader.hpp"
#include "formats/resolve_context.hpp"

namespace ssid::formats {

using detail::ResolveContext;

const char* id_space_noun(IdSpace space) {
  switch (space) {
    case IdSpace::None: return "";
    case IdSpace::GridPoint: return "grid or scalar point";
    case IdSpace::Element: return "element";
    case IdSpace::MassElement: return "mass element";
    case IdSpace::RigidElement: return "rigid element";
    case IdSpace::PlotElement: return "plot element";
    case IdSpace::Property: return "property";
    case IdSpace::Material: return "material";
    case IdSpace::CoordinateSystem: return "coordinate system";
    case IdSpace::SpcSet: return "SPC set";
    case IdSpace::SpcaddSet: return "SPCADD set";
    case IdSpace::EigenMethod: return "eigenvalue method (EIGRL/EIGR SID)";
    case IdSpace::Desvar: return "DESVAR";
    case IdSpace::Dvprel: return "DVPREL";
    case IdSpace::Dvmrel: return "DVMREL";
  }
  return "";
}

bool is_model_space(IdSpace space) {
  return space != IdSpace::None && static_cast<std::size_t>(space) <= static_cast<std::size_t>(IdSpace::CoordinateSystem);
}

namespace {

using Writes = std::map<std::size_t, std::vector<FieldValue>>;

template <typename T>
void write_all(const std::vector<T>& v, std::vector<FieldValue> (*write)(const T&), Writes& out) {
  for (const T& x : v) {
    std::vector<FieldValue> values = write(x);
    auto [it, fresh] = out.emplace(x.card, values);
    // A card holding several entries (PELAS, PMASS): append this entry's fields.
    if (!fresh) it->second.insert(it->second.end(), values.begin() + 1, values.end());
  }
}

/// Builds the entry of a typed card (see the file comment).
template <typename T>
class Typed {
public:
  using Member = std::vector<T> BulkModel::*;
  using Write = std::vector<FieldValue> (*)(const T&);
  using CardCheck = std::function<void(const T&, const BulkModel&, ResolveContext&)>;

  /// A card read into one struct.
  Typed(std::vector<std::string> names, Member member, T (*parse)(const FieldReader&), Write write, Effect effect)
      : m_member(member) {
    init(std::move(names), write, effect);
    m_traits.parse = [member, parse](const FieldReader& r, std::size_t card, BulkModel& m) {
      T v = parse(r);
      v.card = card;
      (m.*member).push_back(std::move(v));
    };
  }
  /// A card holding several entries (PELAS, PMASS), one struct each.
  Typed(std::vector<std::string> names, Member member, std::vector<T> (*parse)(const FieldReader&), Write write,
        Effect effect)
      : m_member(member) {
    init(std::move(names), write, effect);
    m_traits.parse = [member, parse](const FieldReader& r, std::size_t card, BulkModel& m) {
      for (T& v : parse(r)) {
        v.card = card;
        (m.*member).push_back(std::move(v));
      }
    };
  }

  /// Its id (`id`) lives in `space`.
  Typed& defines(IdSpace space, std::int64_t T::*id) {
    m_traits.space = space;
    Member member = m_member;
    m_traits.each_id = [member, id](const BulkModel& m, const std::function<void(std::int64_t, std::size_t)>& f) {
      for (const T& x : m.*member) f(x.*id, x.card);
    };
    return *this;
  }
  /// Each of its ids (`ids`: SPOINT's list) lives in `space`.
  Typed& defines_each(IdSpace space, std::vector<std::int64_t> T::*ids) {
    m_traits.space = space;
    Member member = m_member;
    m_traits.each_id = [member, ids](const BulkModel& m, const std::function<void(std::int64_t, std::size_t)>& f) {
      for (const T& x : m.*member)
        for (std::int64_t id : x.*ids) f(id, x.card);
    };
    return *this;
  }
  /// Its property ids are in property family `family` (CardTraits::id_family).
  Typed& family(const char* family) {
    m_traits.id_family = family;
    return *this;
  }
  /// The same id on several cards of this kind is one thing, not a duplicate.
  Typed& repeats_allowed() {
    m_traits.repeats_allowed = true;
    return *this;
  }

  /// Field `field` (`name`) refers to an id in `space`, of one of the `expected`
  /// types (any when empty); `zero_means_none`: a blank (<= 0) refers to nothing.
  Typed& refers(std::int64_t T::*id, std::size_t field, const char* name, IdSpace space,
                std::vector<std::string> expected = {}, bool zero_means_none = false) {
    Reference ref{name, field, space, std::move(expected), zero_means_none, false};
    m_traits.references.push_back(ref);
    m_refs.push_back({ref, [id](const T& x, const std::function<void(std::int64_t)>& f) { f(x.*id); }});
    return *this;
  }
  Typed& refers_optional(std::int64_t T::*id, std::size_t field, const char* name, IdSpace space,
                         std::vector<std::string> expected = {}) {
    return refers(id, field, name, space, std::move(expected), true);
  }
  /// Every id of the list `ids` refers to `space` (RBE2 GM).
  Typed& refers_each(std::vector<std::int64_t> T::*ids, std::size_t field, const char* name, IdSpace space,
                     std::vector<std::string> expected = {}) {
    Reference ref{name, field, space, std::move(expected), false, true};
    m_traits.references.push_back(ref);
    m_refs.push_back({ref, [ids](const T& x, const std::function<void(std::int64_t)>& f) {
                        for (std::int64_t id : x.*ids) f(id);
                      }});
    return *this;
  }

  /// A second card read into the same struct by its own parser (CMASS3, the
  /// scalar-point form of CMASS1, into Cmass1): the struct's writer writes each
  /// in its form, and the entry's id space, references and checks cover both.
  Typed& reads_also(std::string name, T (*parse)(const FieldReader&)) {
    m_traits.names.push_back(name);
    Member member = m_member;
    m_traits.parse = [member, name, parse, first = m_traits.parse](const FieldReader& r, std::size_t card,
                                                                   BulkModel& m) {
      if (r.card().name != name) return first(r, card, m);
      T v = parse(r);
      v.card = card;
      (m.*member).push_back(std::move(v));
    };
    return *this;
  }

  /// A scalar element connected by G1 C1 G2 C2 (fields 4-7): each end a grid
  /// (component 1-6) or a scalar point (component 0), implied when undefined.
  /// Its scalar-point form (`scalar_form`: CELAS3/4, CMASS3/4) connects S1 S2
  /// (fields 4-5, components 0): scalar points only, implied when undefined.
  Typed& scalar_ends() {
    m_traits.scalar_connection = ScalarConnection::GridComponentPairs;
    Member member = m_member;
    m_traits.each_scalar_end = [member](const BulkModel& m,
                                        const std::function<void(std::int64_t, std::int64_t, std::size_t)>& f) {
      // The scalar-point form holds S1, S2 in g1, g2 with components 0.
      for (const T& e : m.*member) f(e.g1, e.c1, e.card), f(e.g2, e.c2, e.card);
    };
    return checks([](const T& e, const BulkModel&, ResolveContext& ctx) {
      if (e.scalar_form) {
        ctx.scalar_point(e.g1, e.card, 3, "S1");
        ctx.scalar_point(e.g2, e.card, 4, "S2");
        return;
      }
      ctx.scalar_end(e.g1, e.c1, e.card, 3, "G1");
      ctx.scalar_end(e.g2, e.c2, e.card, 5, "G2");
    });
  }

  /// Checked after the card's references, card by card.
  Typed& checks(CardCheck check) {
    m_checks.push_back(std::move(check));
    return *this;
  }
  /// Checked with the references to coordinate systems, card by card.
  Typed& checks_coordinates(CardCheck check) {
    m_coordinate_checks.push_back(std::move(check));
    return *this;
  }
  /// Checked once after every card of this type (PARAM given twice).
  Typed& checks_all(std::function<void(const BulkModel&, ResolveContext&)> check) {
    m_kind_check = std::move(check);
    return *this;
  }

  operator CardTraits() const {  // NOLINT: the table reads as a list of entries
    CardTraits t = m_traits;
    Member member = m_member;
    auto refs = m_refs;
    auto checks = m_checks;
    auto coordinate_checks = m_coordinate_checks;
    auto kind_check = m_kind_check;
    t.resolve = [=](const BulkModel& m, ResolveContext& ctx, bool coordinates) {
      for (const T& x : m.*member) {
        for (const auto& r : refs)
          if ((r.ref.space == IdSpace::CoordinateSystem) == coordinates)
            r.ids(x, [&](std::int64_t id) { ctx.need(r.ref, id, x.card); });
        for (const auto& check : coordinates ? coordinate_checks : checks) check(x, m, ctx);
      }
      if (!coordinates && kind_check) kind_check(m, ctx);
    };
    return t;
  }

private:
  void init(std::vector<std::string> names, Write write, Effect effect) {
    m_traits.names = std::move(names);
    m_traits.effect = effect;
    Member member = m_member;
    m_traits.write = [member, write](const BulkModel& m, Writes& out) { write_all(m.*member, write, out); };
  }

  struct Ref {
    Reference ref;
    std::function<void(const T&, const std::function<void(std::int64_t)>&)> ids;
  };
  Member m_member;
  CardTraits m_traits;
  std::vector<Ref> m_refs;
  std::vector<CardCheck> m_checks, m_coordinate_checks;
  std::function<void(const BulkModel&, ResolveContext&)> m_kind_check;
};

template <typename T, typename Parse>
Typed<T> typed(std::vector<std::string> names, std::vector<T> BulkModel::*member, Parse parse,
               std::vector<FieldValue> (*write)(const T&), Effect effect) {
  return Typed<T>(std::move(names), member, parse, write, effect);
}

/// A card kept verbatim: its id (field 2) in `space`, its effect.
CardTraits verbatim(const char* name, IdSpace space, Effect effect,
                    ScalarConnection connection = ScalarConnection::None) {
  CardTraits t;
  t.names = {name};
  t.space = space;
  t.effect = effect;
  t.scalar_connection = connection;
  return t;
}

/// `t` with its ids in family `family` (CardTraits::id_family).
CardTraits in_family(CardTraits t, const char* family) {
  t.id_family = family;
  return t;
}

/// A property card kept verbatim whose ids are in family `family` (CardTraits::id_family).
CardTraits verbatim_property(const char* name, const char* family, Effect effect) {
  return in_family(verbatim(name, IdSpace::Property, effect), family);
}

/// A card kept verbatim that SOL 103 ignores, and why.
CardTraits ignored(const char* name, const char* because, IdSpace space = IdSpace::None,
                   ScalarConnection connection = ScalarConnection::None) {
  CardTraits t = verbatim(name, space, Effect::IgnoredInSol103, connection);
  t.ignored_because = because;
  return t;
}

// --- the cards' own checks ----------------------------------------------------

/// CORD2R/C/S: a RID chain ends in the basic system; a cycle is reported once,
/// at its smallest CID.
void check_rid_chain(const Cord2& c, const BulkModel& m, ResolveContext& ctx) {
  if (c.rid == 0) return;
  // The system a CID names, when it is a CORD2x (m.cord2s is in deck order).
  auto cord2_of = [&](std::int64_t cid) -> const Cord2* {
    const detail::IdRegistry::Def* d = ctx.ids(IdSpace::CoordinateSystem).find(cid);
    if (!d) return nullptr;
    auto it = std::lower_bound(m.cord2s.begin(), m.cord2s.end(), d->card,
                               [](const Cord2& x, std::size_t card) { return x.card < card; });
    return it != m.cord2s.end() && it->card == d->card ? &*it : nullptr;
  };
  std::string path = std::to_string(c.cid);
  const Cord2* at = &c;
  for (std::size_t steps = 0; steps <= m.cord2s.size(); ++steps) {
    const Cord2* next = at->rid == 0 ? nullptr : cord2_of(at->rid);
    if (!next) break;
    at = next;
    path += " -> " + std::to_string(at->cid);
    if (at->cid < c.cid) break;  // reported (or not a cycle) from a smaller CID
    if (at == &c) {
      ctx.error(c.card, 2, ctx.label(c.card) + ": RID chain " + path + " is a cycle (it must end in the basic system)");
      break;
    }
  }
}

/// PBARL, PBEAML: a TYPE outside the MSC list is kept, with a warning.
template <typename T>
void check_section_type(const T& p, const BulkModel&, ResolveContext& ctx) {
  if (!pbarl_type_sectioned(p.type))
    ctx.warning(p.card, 4,
                ctx.label(p.card) + ": TYPE " + p.type +
                    " is not a section type of the PBARL/PBEAML list; kept with its values but not sectioned");
}

void check_rbe3_grids(const Rbe3& e, const BulkModel&, ResolveContext& ctx) {
  auto& grids = ctx.ids(IdSpace::GridPoint);
  for (const auto& grp : e.groups)
    for (std::int64_t g : grp.grids) grids.need(g, {"GRID"}, e.card, 0, "Gi,j");
  for (const auto& [g, c] : e.um) grids.need(g, {"GRID"}, e.card, 0, "GM");
}

/// NASTRAN ignores an undefined point of an SPC set with USER WARNING MESSAGE
/// 2051 (UNDEFINED GRID POINT ... IN SPC SET ... IGNORED) and runs; so do we.
void warn_missing_spc_point(std::int64_t g, std::size_t card, std::size_t field, ResolveContext& ctx) {
  ctx.warning(card, field,
              "grid or scalar point " + std::to_string(g) + " required by " + ctx.label(card) +
                  " does not exist; ignored (NASTRAN: USER WARNING MESSAGE 2051)");
}

void check_spc_grids(const Spc& s, const BulkModel&, ResolveContext& ctx) {
  for (std::size_t k = 0; k < s.entries.size(); ++k)
    if (!ctx.ids(IdSpace::GridPoint).find(s.entries[k].g)) warn_missing_spc_point(s.entries[k].g, s.card, 2 + 3 * k, ctx);
}

/// A THRU range over missing grids is one mistake: name the first few, count the rest.
void check_spc1_grids(const Spc1& s, const BulkModel&, ResolveContext& ctx) {
  auto& grids = ctx.ids(IdSpace::GridPoint);
  std::size_t missing = 0;
  for (std::int64_t g : s.grids)
    if (!grids.find(g) && ++missing <= 5) warn_missing_spc_point(g, s.card, 0, ctx);
  if (missing > 5)
    ctx.warning(s.card, 0,
                "... and " + std::to_string(missing - 5) + " more grids or scalar points required by " +
                    ctx.label(s.card) + " do not exist; ignored");
}

/// NASTRAN warns (USER WARNING MESSAGE 2053, UNDEFINED SINGLE-POINT CONSTRAINT
/// SET) and runs: the set adds no constraint.
void check_spcadd_sets(const Spcadd& s, const BulkModel&, ResolveContext& ctx) {
  for (std::int64_t set : s.sets)
    if (!ctx.ids(IdSpace::SpcSet).find(set))
      ctx.warning(s.card, 0,
                  "SPC set " + std::to_string(set) + " required by " + ctx.label(s.card) +
                      " does not exist (no SPC or SPC1 with that SID); it adds no constraint");
}

void check_mpc_terms(const Mpc& mp, const BulkModel&, ResolveContext& ctx) {
  for (const MpcTerm& t : mp.terms) ctx.scalar_end(t.g, t.c, mp.card, 0, "Gj");
}

void check_params_once(const BulkModel& m, ResolveContext& ctx) {
  std::unordered_map<std::string, std::size_t> seen;
  for (const Param& p : m.params) {
    auto [it, fresh] = seen.emplace(p.name, p.card);
    if (!fresh)
      ctx.warning(p.card, 1,
                  "PARAM " + p.name + " given again (first at " +
                      ctx.deck().location(ctx.deck().cards[it->second]).str() + ")");
  }
}

/// DVPREL1: PID names a card of the type in TYPE; element-valued designs
/// (CONM2 M, CELAS2 K, ...) hold the element id there. Each DVID is a DESVAR.
void check_dvprel1(const Dvprel1& d, const BulkModel&, ResolveContext& ctx) {
  if (d.type == "CONM2" || d.type == "CMASS2")
    ctx.ids(IdSpace::MassElement).need(d.pid, {d.type}, d.card, 3, "EID");
  else if (d.type == "CELAS2" || d.type == "CONROD")
    ctx.ids(IdSpace::Element).need(d.pid, {d.type}, d.card, 3, "EID");
  else
    ctx.ids(IdSpace::Property).need(d.pid, {d.type}, d.card, 3, "PID");
  for (const auto& [dvid, coef] : d.terms) ctx.ids(IdSpace::Desvar).need(dvid, {}, d.card, 9, "DVID");
}

/// DVMREL1: MID names a material of the type in TYPE; each DVID is a DESVAR.
void check_dvmrel1(const Dvmrel1& d, const BulkModel&, ResolveContext& ctx) {
  ctx.ids(IdSpace::Material).need(d.mid, {d.type}, d.card, 3, "MID");
  for (const auto& [dvid, coef] : d.terms) ctx.ids(IdSpace::Desvar).need(dvid, {}, d.card, 9, "DVID");
}

/// NASTRAN warns when the three given values disagree by more than 1 %, and when NU
/// lies outside (-1.0, 0.5] beside a given E and G (USER WARNING MESSAGE 2251; the
/// parser refuses it where NU derives a modulus).
void check_mat1_moduli(const Mat1& mt, const BulkModel&, ResolveContext& ctx) {
  if (mt.nu_given && !mat1_nu_in_range(mt.nu))
    ctx.warning(mt.card, 4,
                ctx.label(mt.card) + ": NU = " + std::to_string(mt.nu) +
                    " is outside (-1.0, 0.5]; E and G are given and used as given (NASTRAN's USER WARNING MESSAGE "
                    "2251)");
  if (mt.e_given && mt.g_given && mt.nu_given && mt.g > 0.0) {
    double ratio = mt.e / (2.0 * (1.0 + mt.nu) * mt.g);
    if (std::abs(1.0 - ratio) > 0.01)
      ctx.warning(mt.card, 2,
                  ctx.label(mt.card) + ": E, G and NU are not related by E = 2(1+NU)G (E/(2(1+NU)G) = " +
                      std::to_string(ratio) + ")");
  }
}

/// DMIG is counted as a typed card but read by formats/dmig.* (read_dmigs).
CardTraits dmig() {
  CardTraits t;
  t.names = {"DMIG"};
  t.effect = Effect::StiffnessAndMass;  // through K2GG / M2GG
  t.parse = [](const FieldReader&, std::size_t, BulkModel&) {};
  return t;
}

using S = IdSpace;
using E = Effect;
const std::vector<std::string> kGrid = {"GRID"};

std::vector<CardTraits> make_table() {
  // Why SOL 103 (and the real-modes step of NASTRAN's modal solutions) runs
  // decks holding the ignored cards below without their changing K or M.
  const char* loads = "loads, enforced motion, temperatures";
  // Extra points and transfer functions too: TF enters only the direct
  // dynamic-response matrices, selected by TFL.
  const char* dynamic = "dynamic response (frequency, transient, random)";
  const char* optimisation = "optimisation";
  // The structure's modes come first; aerodynamic boxes, splines and flutter or
  // trim requests act only in SOL 144-146.
  const char* aero = "aeroelasticity (SOL 144-146)";
  const char* other = "other solutions' data, output and bookkeeping";
  // Conductivity and heat capacity: no stiffness or mass.
  const char* heat = "heat transfer (SOL 153, 159)";
  // Read by DMAP and the aerodynamics; K2GG and M2GG select DMIG, which ssid assembles.
  const char* dmi = "direct matrix input by DMI";

  std::vector<CardTraits> t = {
      // --- geometry ----------------------------------------------------------------------------
      typed({"CORD2R", "CORD2C", "CORD2S"}, &BulkModel::cord2s, parse_cord2, write_cord2, E::StiffnessAndMass)
          .defines(S::CoordinateSystem, &Cord2::cid)
          .refers_optional(&Cord2::rid, 2, "RID", S::CoordinateSystem)
          .checks_coordinates(check_rid_chain),
      typed({"GRID"}, &BulkModel::grids, parse_grid, write_grid, E::StiffnessAndMass)
          .defines(S::GridPoint, &Grid::id)
          .refers_optional(&Grid::cp, 2, "CP", S::CoordinateSystem)
          .refers_optional(&Grid::cd, 6, "CD", S::CoordinateSystem),
      typed({"SPOINT"}, &BulkModel::spoints, parse_spoint, write_spoint, E::StiffnessAndMass)
          .defines_each(S::GridPoint, &Spoint::ids)
          .repeats_allowed(),  // SPOINT remark: "duplicate scalar point numbers are allowed" (not a GRID's)
      typed({"GRDSET"}, &BulkModel::grdsets, parse_grdset, write_grdset, E::StiffnessAndMass),
      // --- elements, in the order of their references ---------------------------------------------
      typed({"CROD"}, &BulkModel::crods, parse_crod, write_crod, E::StiffnessAndMass)
          .defines(S::Element, &Crod::eid)
          .refers(&Crod::g1, 3, "G1", S::GridPoint, kGrid)
          .refers(&Crod::g2, 4, "G2", S::GridPoint, kGrid)
          .refers(&Crod::pid, 2, "PID", S::Property, {"PROD"}),
      typed({"CONROD"}, &BulkModel::conrods, parse_conrod, write_conrod, E::StiffnessAndMass)
          .defines(S::Element, &Conrod::eid)
          .refers(&Conrod::g1, 2, "G1", S::GridPoint, kGrid)
          .refers(&Conrod::g2, 3, "G2", S::GridPoint, kGrid)
          .refers(&Conrod::mid, 4, "MID", S::Material, {"MAT1"}),
      typed({"CBAR"}, &BulkModel::cbars, parse_cbar, write_cbar, E::StiffnessAndMass)
          .defines(S::Element, &Cbar::eid)
          .refers(&Cbar::pid, 2, "PID", S::Property, {"PBAR", "PBARL"})
          .refers(&Cbar::ga, 3, "GA", S::GridPoint, kGrid)
          .refers(&Cbar::gb, 4, "GB", S::GridPoint, kGrid)
          .refers_optional(&Cbar::g0, 5, "G0", S::GridPoint, kGrid),
      typed({"BAROR"}, &BulkModel::barors, parse_baror, write_baror, E::StiffnessAndMass),
      typed({"CBEAM"}, &BulkModel::cbeams, parse_cbeam, write_cbeam, E::StiffnessAndMass)
          .defines(S::Element, &Cbeam::eid)
          .refers(&Cbeam::pid, 2, "PID", S::Property, {"PBEAM", "PBEAML", "PBCOMP"})
          .refers(&Cbeam::ga, 3, "GA", S::GridPoint, kGrid)
          .refers(&Cbeam::gb, 4, "GB", S::GridPoint, kGrid)
          .refers_optional(&Cbeam::g0, 5, "G0", S::GridPoint, kGrid)
          // QRG CBEAM: "SA, SB: scalar or grid point identification numbers".
          .refers_optional(&Cbeam::sa, 17, "SA", S::GridPoint)
          .refers_optional(&Cbeam::sb, 18, "SB", S::GridPoint),
      typed({"BEAMOR"}, &BulkModel::beamors, parse_beamor, write_beamor, E::StiffnessAndMass),
      // The scalar-point forms CMASS3, CELAS3, CMASS4, CELAS4 share the structs of
      // CMASS1, CELAS1, CMASS2, CELAS2 (scalar_form set, components 0).
      typed({"CMASS1"}, &BulkModel::cmass1s, parse_cmass1, write_cmass1, E::Mass)
          .reads_also("CMASS3", parse_cmass3)
          .defines(S::MassElement, &Cmass1::eid)
          .refers(&Cmass1::pid, 2, "PID", S::Property, {"PMASS"})
          .scalar_ends(),
      typed({"CELAS1"}, &BulkModel::celas1s, parse_celas1, write_celas1, E::Stiffness)
          .reads_also("CELAS3", parse_celas3)
          .defines(S::Element, &Celas1::eid)
          .refers(&Celas1::pid, 2, "PID", S::Property, {"PELAS"})
          .scalar_ends(),
      typed({"CMASS2"}, &BulkModel::cmass2s, parse_cmass2, write_cmass2, E::Mass)
          .reads_also("CMASS4", parse_cmass4)
          .defines(S::MassElement, &Cmass2::eid)
          .scalar_ends(),
      typed({"CELAS2"}, &BulkModel::celas2s, parse_celas2, write_celas2, E::Stiffness)
          .reads_also("CELAS4", parse_celas4)
          .defines(S::Element, &Celas2::eid)
          .scalar_ends(),
      typed({"CONM2"}, &BulkModel::conm2s, parse_conm2, write_conm2, E::Mass)
          .defines(S::MassElement, &Conm2::eid)
          .refers_optional(&Conm2::cid, 3, "CID", S::CoordinateSystem)
          .refers(&Conm2::g, 2, "G", S::GridPoint, kGrid),
      typed({"CBUSH"}, &BulkModel::cbushes, parse_cbush, write_cbush, E::Stiffness)
          .defines(S::Element, &Cbush::eid)
          .refers_optional(&Cbush::cid, 8, "CID", S::CoordinateSystem)
          .refers_optional(&Cbush::ocid, 10, "OCID", S::CoordinateSystem)
          .refers(&Cbush::pid, 2, "PID", S::Property, {"PBUSH"})
          .refers(&Cbush::ga, 3, "GA", S::GridPoint, kGrid)
          .refers_optional(&Cbush::gb, 4, "GB", S::GridPoint, kGrid)
          .refers_optional(&Cbush::g0, 5, "G0", S::GridPoint, kGrid),
      // --- properties and materials ------------------------------------------------------------------
      typed({"PROD"}, &BulkModel::prods, parse_prod, write_prod, E::StiffnessAndMass)
          .defines(S::Property, &Prod::pid)
          .refers(&Prod::mid, 2, "MID", S::Material, {"MAT1"}),
      typed({"PBAR"}, &BulkModel::pbars, parse_pbar, write_pbar, E::StiffnessAndMass)
          .defines(S::Property, &Pbar::pid)
          .family("bar")
          .refers(&Pbar::mid, 2, "MID", S::Material, {"MAT1"}),
      typed({"PBARL"}, &BulkModel::pbarls, parse_pbarl, write_pbarl, E::StiffnessAndMass)
          .defines(S::Property, &Pbarl::pid)
          .family("bar")
          .refers(&Pbarl::mid, 2, "MID", S::Material, {"MAT1"})
          .checks(check_section_type<Pbarl>),
      typed({"PBEAM"}, &BulkModel::pbeams, parse_pbeam, write_pbeam, E::StiffnessAndMass)
          .defines(S::Property, &Pbeam::pid)
          .family("beam")
          .refers(&Pbeam::mid, 2, "MID", S::Material, {"MAT1"}),
      typed({"PBEAML"}, &BulkModel::pbeamls, parse_pbeaml, write_pbeaml, E::StiffnessAndMass)
          .defines(S::Property, &Pbeaml::pid)
          .family("beam")
          .refers(&Pbeaml::mid, 2, "MID", S::Material, {"MAT1"})
          .checks(check_section_type<Pbeaml>),
      typed({"PMASS"}, &BulkModel::pmasses, parse_pmass, write_pmass, E::Mass).defines(S::Property, &Pmass::pid),
      typed({"PELAS"}, &BulkModel::pelases, parse_pelas, write_pelas, E::Stiffness).defines(S::Property, &Pelas::pid),
      typed({"PBUSH"}, &BulkModel::pbushes, parse_pbush, write_pbush, E::Stiffness).defines(S::Property, &Pbush::pid),
      // --- rigid elements and constraints ------------------------------------------------------------
      typed({"RBAR"}, &BulkModel::rbars, parse_rbar, write_rbar, E::StiffnessAndMass)
          .defines(S::RigidElement, &Rbar::eid)
          .refers(&Rbar::ga, 2, "GA", S::GridPoint, kGrid)
          .refers(&Rbar::gb, 3, "GB", S::GridPoint, kGrid),
      typed({"RBE2"}, &BulkModel::rbe2s, parse_rbe2, write_rbe2, E::StiffnessAndMass)
          .defines(S::RigidElement, &Rbe2::eid)
          .refers(&Rbe2::gn, 2, "GN", S::GridPoint, kGrid)
          .refers_each(&Rbe2::gm, 0, "GM", S::GridPoint, kGrid),
      typed({"RBE3"}, &BulkModel::rbe3s, parse_rbe3, write_rbe3, E::StiffnessAndMass)
          .defines(S::RigidElement, &Rbe3::eid)
          .refers(&Rbe3::refgrid, 3, "REFGRID", S::GridPoint, kGrid)
          .checks(check_rbe3_grids),
      typed({"SPC"}, &BulkModel::spcs, parse_spc, write_spc, E::StiffnessAndMass)
          .defines(S::SpcSet, &Spc::sid)
          .repeats_allowed()
          .checks(check_spc_grids),
      typed({"SPC1"}, &BulkModel::spc1s, parse_spc1, write_spc1, E::StiffnessAndMass)
          .defines(S::SpcSet, &Spc1::sid)
          .repeats_allowed()
          .checks(check_spc1_grids),
      typed({"SPCADD"}, &BulkModel::spcadds, parse_spcadd, write_spcadd, E::StiffnessAndMass)
          .defines(S::SpcaddSet, &Spcadd::sid)
          .checks(check_spcadd_sets),
      typed({"MPC"}, &BulkModel::mpcs, parse_mpc, write_mpc, E::StiffnessAndMass).checks(check_mpc_terms),
      // --- solution requests, parameters, design model ----------------------------------------------
      typed({"EIGRL"}, &BulkModel::eigrls, parse_eigrl, write_eigrl, E::Solution).defines(S::EigenMethod, &Eigrl::sid),
      typed({"EIGR"}, &BulkModel::eigrs, parse_eigr, write_eigr, E::Solution).defines(S::EigenMethod, &Eigr::sid),
      // WTMASS scales M, COUPMASS and BARMASS choose it, AUTOSPC reduces K and M.
      typed({"PARAM"}, &BulkModel::params, parse_param, write_param, E::StiffnessAndMass).checks_all(check_params_once),
      typed({"DESVAR"}, &BulkModel::desvars, parse_desvar, write_desvar, E::Solution).defines(S::Desvar, &Desvar::id),
      typed({"DVPREL1"}, &BulkModel::dvprel1s, parse_dvprel1, write_dvprel1, E::Solution)
          .defines(S::Dvprel, &Dvprel1::id)
          .checks(check_dvprel1),
      typed({"DVMREL1"}, &BulkModel::dvmrel1s, parse_dvmrel1, write_dvmrel1, E::Solution)
          .defines(S::Dvmrel, &Dvmrel1::id)
          .checks(check_dvmrel1),
      typed({"MAT1"}, &BulkModel::mat1s, parse_mat1, write_mat1, E::StiffnessAndMass)
          .defines(S::Material, &Mat1::mid)
          .checks(check_mat1_moduli),
      dmig(),

      // --- kept verbatim: element cards share the id space of their family ----------------------------
      verbatim("CQUAD4", S::Element, E::StiffnessAndMass),
      verbatim("CQUAD8", S::Element, E::StiffnessAndMass),
      verbatim("CQUADR", S::Element, E::StiffnessAndMass),
      verbatim("CTRIA3", S::Element, E::StiffnessAndMass),
      verbatim("CTRIA6", S::Element, E::StiffnessAndMass),
      verbatim("CTRIAR", S::Element, E::StiffnessAndMass),
      verbatim("CSHEAR", S::Element, E::StiffnessAndMass),
      verbatim("CHEXA", S::Element, E::StiffnessAndMass),
      verbatim("CPENTA", S::Element, E::StiffnessAndMass),
      verbatim("CTETRA", S::Element, E::StiffnessAndMass),
      verbatim("CPYRAM", S::Element, E::StiffnessAndMass),
      verbatim("CTUBE", S::Element, E::StiffnessAndMass),
      verbatim("CBEND", S::Element, E::StiffnessAndMass),
      verbatim("CGAP", S::Element, E::Stiffness),
      ignored("CDAMP1", other, S::Element, ScalarConnection::GridComponentPairs),
      ignored("CDAMP2", other, S::Element, ScalarConnection::GridComponentPairs),
      ignored("CDAMP3", other, S::Element, ScalarConnection::ScalarPoints),
      ignored("CDAMP4", other, S::Element, ScalarConnection::ScalarPoints),
      ignored("CDAMP5", other),
      ignored("CVISC", other, S::Element),
      verbatim("CBUSH1D", S::Element, E::Stiffness),
      verbatim("CFAST", S::Element, E::Stiffness),
      verbatim("CWELD", S::Element, E::Stiffness),
      verbatim("CONM1", S::MassElement, E::Mass),
      verbatim("RBAR1", S::RigidElement, E::StiffnessAndMass),
      verbatim("RBE1", S::RigidElement, E::StiffnessAndMass),
      verbatim("RROD", S::RigidElement, E::StiffnessAndMass),
      verbatim("RSPLINE", S::RigidElement, E::StiffnessAndMass),
      verbatim("RSSCON", S::RigidElement, E::StiffnessAndMass),
      verbatim("RTRPLT", S::RigidElement, E::StiffnessAndMass),
      ignored("PLOTEL", other, S::PlotElement),
      // MSC's plot elements for 3-, 4-, 6-, 8-noded faces and solids (display only)
      ignored("PLOTEL3", other, S::PlotElement),
      ignored("PLOTEL4", other, S::PlotElement),
      ignored("PLOTEL6", other, S::PlotElement),
      ignored("PLOTEL8", other, S::PlotElement),
      ignored("PLOTTET", other, S::PlotElement),
      ignored("PLOTPEN", other, S::PlotElement),
      ignored("PLOTPYR", other, S::PlotElement),
      ignored("PLOTHEX", other, S::PlotElement),
      // --- kept verbatim: properties, materials, coordinate systems, scalar points, design ------------
      // CQUAD4, CTRIA3, ... accept PSHELL, PCOMP and PCOMPG (QRG CQUAD4, PID).
      verbatim_property("PSHELL", "shell", E::StiffnessAndMass),
      verbatim_property("PCOMP", "shell", E::StiffnessAndMass),
      verbatim_property("PCOMPG", "shell", E::StiffnessAndMass),
      verbatim("PSOLID", S::Property, E::StiffnessAndMass),
      verbatim("PSHEAR", S::Property, E::StiffnessAndMass),
      verbatim("PTUBE", S::Property, E::StiffnessAndMass),
      verbatim("PBEND", S::Property, E::StiffnessAndMass),
      verbatim("PGAP", S::Property, E::Stiffness),
      ignored("PDAMP", other, S::Property),
      ignored("PVISC", other, S::Property),
      verbatim("PBUSH1D", S::Property, E::Stiffness),
      verbatim_property("PBCOMP", "beam", E::StiffnessAndMass),
      verbatim("PFAST", S::Property, E::Stiffness),
      verbatim("PWELD", S::Property, E::Stiffness),
      verbatim("MAT2", S::Material, E::StiffnessAndMass),
      verbatim("MAT3", S::Material, E::StiffnessAndMass),
      verbatim("MAT8", S::Material, E::StiffnessAndMass),
      verbatim("MAT9", S::Material, E::StiffnessAndMass),
      verbatim("MAT10", S::Material, E::StiffnessAndMass),
      // Thermal materials: heat-transfer decks (SOL 153, 159) give them to PROD, PBAR, ...
      // A thermal material may share its id with the structural one it completes (MSC decks
      // give MAT1 1 and MAT4 1 for one material: pyNastran's htrussx, plate_py).
      in_family(ignored("MAT4", heat, S::Material), "thermal"),
      in_family(ignored("MAT5", heat, S::Material), "thermal"),
      // CORD1x are ignored only while no grid refers to them (resolve would accept
      // the reference, the geometry refuses it).
      ignored("CORD1R", other, S::CoordinateSystem),
      ignored("CORD1C", other, S::CoordinateSystem),
      ignored("CORD1S", other, S::CoordinateSystem),
      verbatim("CORD3G", S::CoordinateSystem, E::StiffnessAndMass),
      verbatim("CORD3R", S::CoordinateSystem, E::StiffnessAndMass),
      ignored("EPOINT", dynamic, S::GridPoint),
      ignored("DVPREL2", optimisation, S::Dvprel),
      ignored("DVMREL2", optimisation, S::Dvmrel),
  };
  // --- kept verbatim, no id space: ignored in SOL 103 ------------------------------------------------
  const std::vector<std::pair<const char*, std::vector<const char*>>> groups = {
      {loads, {"FORCE", "FORCE1", "FORCE2", "MOMENT", "MOMENT1", "MOMENT2", "LOAD", "PLOAD", "PLOAD1", "PLOAD2",
               "PLOAD4", "PLOADX", "GRAV", "RFORCE", "TEMP", "TEMPD", "TEMPP1", "SPCD"}},
      {dynamic, {"DAREA", "DLOAD", "RLOAD1", "RLOAD2", "TLOAD1", "TLOAD2", "DPHASE", "DELAY", "FREQ", "FREQ1", "FREQ2",
                 "FREQ3", "FREQ4", "FREQ5", "TSTEP", "TABLED1", "TABLED2", "TABLED3", "TABLED4", "TABDMP1", "RANDPS",
                 "TABRND1", "TF", "NOLIN1", "NOLIN2", "NOLIN3", "NOLIN4"}},
      {optimisation, {"DRESP1", "DRESP2", "DCONSTR", "DOPTPRM", "DEQATN", "DTABLE", "DLINK", "DCONADD"}},
      {aero, {"AERO",    "AEROS",   "CAERO1",  "CAERO2",  "CAERO3", "CAERO4",  "CAERO5",  "PAERO1",  "PAERO2",
              "PAERO3",  "PAERO4",  "PAERO5",  "SPLINE1", "SPLINE2", "SPLINE3", "SPLINE4", "SPLINE5", "SPLINE6",
              "SPLINE7", "SET1",    "SET2",    "AEFACT",  "AELINK",  "AELIST",  "AEPARM",  "AESTAT",  "AESURF",
              "AESURFS", "AECOMP",  "AECOMPL", "AEDW",    "AEFORCE", "AEPRESS", "CSSCHD",  "DIVERG",  "FLFACT",
              "FLUTTER", "GUST",    "MKAERO1", "MKAERO2", "TRIM",    "UXVEC",   "MONPNT1", "MONPNT2", "MONPNT3",
              "MONDSP1"}},
      {other, {"ENDDATA", "EIGB", "EIGC", "SUPORT", "SUPORT1", "PDAMP5", "NLPARM", "TABLES1", "MATS1", "DTI", "USET",
               "USET1", "SEQGP"}},
      {dmi, {"DMI", "DMIJ", "DMIJI", "DMIK"}},
  };
  for (const auto& [because, names] : groups)
    for (const char* name : names) t.push_back(ignored(name, because));
  return t;
}

}  // namespace

const std::vector<CardTraits>& card_traits() {
  static const std::vector<CardTraits> table = make_table();
  return table;
}

const CardTraits* find_card_traits(const std::string& name) {
  static const std::unordered_map<std::string, const CardTraits*> by_name = [] {
    std::unordered_map<std::string, const CardTraits*> m;
    for (const CardTraits& t : card_traits())
      for (const std::string& n : t.names) m.emplace(n, &t);
    return m;
  }();
  auto it = by_name.find(name);
  return it == by_name.end() ? nullptr : it->second;
}

std::string id_family(IdSpace space, const std::string& name) {
  const CardTraits* t = find_card_traits(name);
  if (t && *t->id_family) return t->id_family;
  return space == IdSpace::Property ? name : std::string();
}

}  // namespace ssid::formats
