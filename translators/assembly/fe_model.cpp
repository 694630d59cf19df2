#include "translators/assembly/fe_model.hpp"
#include "formats/card_traits.hpp"
#include "formats/text_util.hpp"

#include <algorithm>
#include <cctype>
#include <map>
#include <set>
#include <sstream>

namespace ssid::translators {

namespace {

using formats::BulkModel;
using formats::Deck;
using formats::detail::upper;

/// Cards kept verbatim that cannot change K or M in a real-eigenvalue analysis
/// (Effect::IgnoredInSol103 in formats/card_traits.cpp, which says why for each):
/// ignored, with a note. NASTRAN's SOL 103 runs decks that hold them.
bool ignored_in_sol103(const std::string& name) {
  const formats::CardTraits* traits = formats::find_card_traits(name);
  return traits && traits->effect == formats::Effect::IgnoredInSol103;
}

/// `NAME = n` in case control (global, or the first subcase), e.g. SPC, MPC, METHOD;
/// `where` receives the statement's place.
std::optional<std::int64_t> case_control(const Deck& deck, const std::string& name, formats::SourceLocation& where) {
  std::optional<std::int64_t> global, first_subcase;
  formats::SourceLocation global_at, first_subcase_at;
  int subcase = 0;
  for (const auto& st : deck.statements) {
    if (st.section != formats::Section::CaseControl) continue;
    const std::string t = upper(st.text);
    if (t.rfind("SUBCASE", 0) == 0) {
      ++subcase;
      continue;
    }
    const auto eq = t.find('=');
    if (eq == std::string::npos) continue;
    std::string key = t.substr(0, eq);
    key.erase(std::remove_if(key.begin(), key.end(), [](unsigned char c) { return std::isspace(c); }), key.end());
    if (const auto paren = key.find('('); paren != std::string::npos) key = key.substr(0, paren);
    if (key != name) continue;
    try {
      const std::int64_t v = std::stoll(t.substr(eq + 1));
      if (subcase == 0) {
        global = v;
        global_at = deck.location(st.file, st.line);
      } else if (subcase == 1 && !first_subcase) {
        first_subcase = v;
        first_subcase_at = deck.location(st.file, st.line);
      }
    } catch (const std::exception&) {
    }
  }
  where = global ? global_at : first_subcase_at;
  return global ? global : first_subcase;
}

/// The case-control command `AUTOSPC[(options)] [= YES|NO]` (global, or the first
/// subcase; a bare AUTOSPC is YES). NASTRAN's case-control AUTOSPC takes precedence
/// over PARAM,AUTOSPC. Any other value is bad input, named at the statement.
std::optional<bool> case_control_autospc(const Deck& deck, formats::SourceLocation& where) {
  std::optional<bool> global, first_subcase;
  formats::SourceLocation global_at, first_subcase_at;
  int subcase = 0;
  for (const auto& st : deck.statements) {
    if (st.section != formats::Section::CaseControl) continue;
    std::string t = upper(st.text);
    if (const auto dollar = t.find('$'); dollar != std::string::npos) t = t.substr(0, dollar);
    t.erase(std::remove_if(t.begin(), t.end(), [](unsigned char c) { return std::isspace(c); }), t.end());
    if (t.rfind("SUBCASE", 0) == 0) {
      ++subcase;
      continue;
    }
    if (t.rfind("AUTOSPC", 0) != 0) continue;
    std::string rest = t.substr(7);
    if (!rest.empty() && rest[0] == '(') {
      const auto close = rest.find(')');
      rest = close == std::string::npos ? "" : rest.substr(close + 1);
    }
    bool v;
    if (rest.empty() || rest == "=YES") v = true;
    else if (rest == "=NO") v = false;
    else
      throw ModelError(deck.location(st.file, st.line), "case control " + st.text + ": expected AUTOSPC = YES or NO");
    if (subcase == 0) {
      global = v;
      global_at = deck.location(st.file, st.line);
    } else if (subcase == 1 && !first_subcase) {
      first_subcase = v;
      first_subcase_at = deck.location(st.file, st.line);
    }
  }
  where = global ? global_at : first_subcase_at;
  return global ? global : first_subcase;
}

/// MDLPRM parameters that cannot change K or M of what ssid assembles: HDF5
/// output (HDF5, H5*), the PARDISO and pivoting controls of the solver (PRD*,
/// NONUPIV), element output (INTOUT), aerodynamic spline selection (MLTSPLIN),
/// shell-element formulations (QR6ROT, QRSHEAR, SHRTOQ4, IGNSHBDN, NSGRDS4: ssid
/// refuses shells anyway), and OFFDEF = LROFF (large-rotation offsets: nonlinear
/// solutions only). Any other MDLPRM parameter or value is refused by name.
bool mdlprm_no_effect(const std::string& name, const std::string& value) {
  static const std::set<std::string> names = {"HDF5",     "H5GM34",   "H5INFO",   "H5MDL",    "H5MTX",
                                              "H5NORDOF", "H5XHH",    "PRDIDPVT", "PRDITRFN", "PRDMTYPE",
                                              "PRDOOC",   "PRDWMTCH", "NONUPIV",  "INTOUT",   "MLTSPLIN",
                                              "QR6ROT",   "QRSHEAR",  "SHRTOQ4",  "IGNSHBDN", "NSGRDS4"};
  if (name == "OFFDEF") return value == "LROFF";
  return names.count(name) != 0;
}

/// True when the deck has a case control section (selections then come from it).
bool has_case_control(const Deck& deck) {
  for (const auto& st : deck.statements)
    if (st.section == formats::Section::CaseControl) return true;
  return false;
}

const formats::Param* find_param(const BulkModel& m, const std::string& name) {
  for (const auto& p : m.params)
    if (upper(p.name) == name) return &p;
  return nullptr;
}

/// Field number (FID) to name, for the cards whose layout is fixed.
std::string field_name(const std::string& type, std::int64_t fid) {
  static const std::map<std::string, std::map<std::int64_t, std::string>> names = {
      {"PROD", {{4, "A"}, {5, "J"}, {7, "NSM"}}},
      {"PBAR", {{4, "A"}, {5, "I1"}, {6, "I2"}, {7, "J"}, {8, "NSM"}, {19, "I12"}}},
      {"PELAS", {{3, "K"}}},
      {"PMASS", {{3, "M"}}},
      {"CONM2", {{5, "M"}, {6, "X1"}, {7, "X2"}, {8, "X3"}}},
      {"CELAS2", {{3, "K"}}},
      {"CMASS2", {{3, "M"}}},
  };
  auto t = names.find(type);
  if (t == names.end()) return "";
  auto f = t->second.find(fid);
  return f == t->second.end() ? "" : f->second;
}

}  // namespace

FeModel::FeModel(const Deck& deck, BulkModel model, AssemblyOptions options) : m_model(std::move(model)) {
  refuse_unassembled_cards(deck);
  const ReductionSettings reduction = read_analysis_parameters(deck, options);
  m_geometry = std::make_unique<ModelGeometry>(deck, m_model);
  m_elements = std::make_unique<ElementSet>(deck, m_model, *m_geometry, m_settings);
  const ConstraintSelection sets = select_sets(deck, options);
  const std::vector<std::size_t> spc = single_point_constraints(deck, sets);
  const std::vector<MpcEquation> mpcs = multipoint_constraints(deck, sets);
  relate_parameters(deck);
  apply_constraints(spc, mpcs, reduction);
}

/// Cards we do not assemble: harmless ones are noted, the others refused, at the first of them.
void FeModel::refuse_unassembled_cards(const Deck& deck) {
  for (const auto& st : deck.statements)
    if (st.section == formats::Section::Bulk)
      throw ModelError(deck.location(st.file, st.line),
                       st.text + ": the bulk data after it (a part superelement or another partition) is kept "
                                 "verbatim and not assembled; ssid assembles one structure: export K and M from "
                                 "NASTRAN (OP4 or DMIG) and build the operators with `ssid assemble --import SPEC.json`");
  for (const auto& c : deck.cards) {
    if (c.name != "MDLPRM") continue;
    // MDLPRM, PARAM1, VAL1, PARAM2, VAL2, ... (pairs run on into continuations).
    for (std::size_t i = 1; i < c.size(); i += 2) {
      const std::string name = upper(std::string(formats::detail::trim(c.field(i))));
      if (name.empty()) continue;
      const std::string value = upper(std::string(formats::detail::trim(c.field(i + 1))));
      if (!mdlprm_no_effect(name, value))
        throw ModelError(deck.location(c), "MDLPRM " + name + " " + value +
                                               ": ssid does not apply this model parameter and it may change K or M");
      m_notes.push_back("MDLPRM " + name + " " + value + " ignored: no effect on K or M of the assembled elements");
    }
  }
  for (const auto& [name, count] : m_model.unsupported) {
    if (name == "MDLPRM") continue;  // checked parameter by parameter above
    if (ignored_in_sol103(name)) {
      m_notes.push_back(std::to_string(count) + " " + name + " card" + (count > 1 ? "s" : "") +
                        " ignored: no effect on K or M");
      continue;
    }
    const std::string& card_name = name;  // a structured binding cannot be captured in C++17 (clang refuses)
    const auto first =
        std::find_if(deck.cards.begin(), deck.cards.end(), [&](const auto& c) { return c.name == card_name; });
    const formats::SourceLocation at = first != deck.cards.end() ? deck.location(*first) : formats::SourceLocation{};
    throw ModelError(at, name + " (" + std::to_string(count) + " card" + (count > 1 ? "s" : "") +
                             (at.file.empty() ? "" : ", first at " + at.str()) +
                             "): ssid cannot assemble this card and it may change K or M; remove it, model it with "
                             "supported cards, or export K and M from NASTRAN (OP4 or DMIG) and build the operators "
                             "with `ssid assemble --import SPEC.json`");
  }
}

/// PARAM COUPMASS, BARMASS, WTMASS, AUTOSPC, EPZERO (the options override them).
FeModel::ReductionSettings FeModel::read_analysis_parameters(const Deck& deck, const AssemblyOptions& options) {
  const BulkModel& m = m_model;
  auto param_int = [&](const char* name) -> std::optional<std::int64_t> {
    if (const auto* p = find_param(m, name)) {
      if (auto v = p->integer()) return v;
      if (auto t = p->text()) return upper(*t) == "YES" ? 1 : upper(*t) == "NO" ? 0 : -1;
    }
    return std::nullopt;
  };
  m_settings.mass = options.coupled_mass ? (*options.coupled_mass ? elements::MassKind::Coupled : elements::MassKind::Lumped)
                                         : (param_int("COUPMASS").value_or(-1) > 0 ? elements::MassKind::Coupled
                                                                                   : elements::MassKind::Lumped);
  m_settings.barmass = param_int("BARMASS").value_or(0) > 0;
  m_wtmass = options.wtmass ? *options.wtmass : 1.0;
  if (!options.wtmass)
    if (const auto* p = find_param(m, "WTMASS")) {
      if (auto v = p->real()) m_wtmass = *v;
      else throw ModelError(card_label(deck, p->card) + ": PARAM WTMASS: expected a real value");
    }
  ReductionSettings r;
  formats::SourceLocation autospc_at;
  const std::optional<bool> autospc_cc = case_control_autospc(deck, autospc_at);
  r.autospc = options.autospc ? *options.autospc
              : autospc_cc    ? *autospc_cc
                              : param_int("AUTOSPC").value_or(1) != 0;
  if (!options.autospc && autospc_cc && find_param(m, "AUTOSPC"))
    m_notes.push_back(std::string("case control AUTOSPC = ") + (*autospc_cc ? "YES" : "NO") + " (" + autospc_at.str() +
                      ") overrides PARAM AUTOSPC");
  r.epzero = options.epzero;
  if (const auto* p = find_param(m, "EPZERO"))
    if (auto v = p->real()) r.epzero = *v;
  if (m_wtmass != 1.0) m_notes.push_back("PARAM WTMASS " + std::to_string(m_wtmass) + " scales the mass matrix");
  if (m_settings.mass == elements::MassKind::Coupled) m_notes.push_back("PARAM COUPMASS: coupled mass for rods and bars");
  return r;
}

/// The SPC, MPC and METHOD sets selected by case control (or the only one in a
/// deck without case control); the METHOD's EIGRL/EIGR.
FeModel::ConstraintSelection FeModel::select_sets(const Deck& deck, const AssemblyOptions& options) {
  const BulkModel& m = m_model;
  std::map<std::string, formats::SourceLocation> selected_at;  // the case control statement of each selection
  auto select = [&](const char* what, std::optional<std::int64_t> forced, std::set<std::int64_t> available)
      -> std::optional<std::int64_t> {
    if (forced) return forced;
    if (auto cc = case_control(deck, what, selected_at[what])) return cc;
    if (!has_case_control(deck) && available.size() == 1) {
      m_notes.push_back(std::string("no case control: ") + what + " set " + std::to_string(*available.begin()) +
                        " applied, as the only one");
      return *available.begin();
    }
    if (!available.empty())
      m_notes.push_back(std::string(what) + " sets present but none selected in case control: not applied");
    return std::nullopt;
  };
  std::set<std::int64_t> spc_ids, mpc_ids, method_ids;
  for (const auto& s : m.spcs) spc_ids.insert(s.sid);
  for (const auto& s : m.spc1s) spc_ids.insert(s.sid);
  for (const auto& s : m.spcadds) spc_ids.insert(s.sid);
  for (const auto& s : m.mpcs) mpc_ids.insert(s.sid);
  for (const auto& e : m.eigrls) method_ids.insert(e.sid);
  for (const auto& e : m.eigrs) method_ids.insert(e.sid);
  ConstraintSelection sets;
  sets.spc = select("SPC", options.spc_set, spc_ids);
  sets.mpc = select("MPC", options.mpc_set, mpc_ids);
  const auto method = select("METHOD", options.method, method_ids);
  sets.spc_at = selected_at["SPC"];
  if (method) {
    for (const auto& e : m.eigrls)
      if (e.sid == *method) m_eigrl = &e;
    for (const auto& e : m.eigrs)
      if (e.sid == *method) m_eigr = &e;
    if (!m_eigrl && !m_eigr)
      throw ModelError(selected_at["METHOD"], "METHOD = " + std::to_string(*method) + ": no EIGRL or EIGR with that SID");
  }
  return sets;
}

/// Single-point constraints: GRID PS and the selected set (SPCADD expanded), as
/// g-set DOFs in increasing order.
std::vector<std::size_t> FeModel::single_point_constraints(const Deck& deck, const ConstraintSelection& sets) {
  const BulkModel& m = m_model;
  const ModelGeometry& geo = *m_geometry;
  std::set<std::size_t> spc;
  auto add_components = [&](std::int64_t point, const std::string& comps, const std::string& who) {
    if (!geo.is_scalar_point(point) && !geo.has_grid(point)) {
      // resolve warned (NASTRAN's USER WARNING MESSAGE 2051); NASTRAN ignores the point
      m_notes.push_back(who + ": grid or scalar point " + std::to_string(point) + " does not exist; ignored");
      return;
    }
    if (geo.is_scalar_point(point)) {
      spc.insert(geo.dof(point, 0, who));
      return;
    }
    for (char c : comps) spc.insert(geo.dof(point, c - '0', who));
  };
  for (const auto& g : geo.grids())
    if (!g.ps.empty()) add_components(g.id, g.ps, card_label(deck, g.card));
  if (const auto& spc_set = sets.spc) {
    std::set<std::int64_t> ids{*spc_set};
    for (const auto& a : m.spcadds)
      if (a.sid == *spc_set) ids.insert(a.sets.begin(), a.sets.end());
    bool found = false;
    for (const auto& s : m.spcs)
      if (ids.count(s.sid)) {
        found = true;
        for (const auto& e : s.entries) {
          if (e.d != 0.0)
            m_notes.push_back(card_label(deck, s.card) + ": enforced displacement " + std::to_string(e.d) +
                              " has no effect on modes; treated as a constraint");
          add_components(e.g, e.c, card_label(deck, s.card));
        }
      }
    for (const auto& s : m.spc1s)
      if (ids.count(s.sid)) {
        found = true;
        for (auto g : s.grids) add_components(g, s.c, card_label(deck, s.card));
      }
    if (!found && !std::any_of(m.spcadds.begin(), m.spcadds.end(), [&](const auto& a) { return a.sid == *spc_set; }))
      throw ModelError(sets.spc_at, "SPC = " + std::to_string(*spc_set) + ": no SPC, SPC1 or SPCADD with that SID");
  }
  return {spc.begin(), spc.end()};
}

/// Multipoint constraints: rigid elements and the selected MPC set.
std::vector<MpcEquation> FeModel::multipoint_constraints(const Deck& deck, const ConstraintSelection& sets) const {
  const BulkModel& m = m_model;
  const ModelGeometry& geo = *m_geometry;
  std::vector<MpcEquation> mpcs;
  auto rigid = [&](const GridPoint& g, const std::string& ind, const std::string& dep) {
    return RigidGrid{g.x, g.dofs, ind, dep, g.frame};
  };
  try {
    for (const auto& r : m.rbars) {
      const auto who = card_label(deck, r.card);
      const auto& a = geo.grid(r.ga, who);
      const auto& b = geo.grid(r.gb, who);
      std::string cma = r.cma, cmb = r.cmb;
      if (cma.empty() && cmb.empty()) {
        // QRG: with CMA and CMB blank, every DOF not in CNA/CNB is dependent.
        for (char c : std::string("123456")) {
          if (r.cna.find(c) == std::string::npos) cma += c;
          if (r.cnb.find(c) == std::string::npos) cmb += c;
        }
      }
      auto part = rigid_equations({rigid(a, r.cna, cma), rigid(b, r.cnb, cmb)}, who);
      mpcs.insert(mpcs.end(), part.begin(), part.end());
    }
    for (const auto& r : m.rbe2s) {
      const auto who = card_label(deck, r.card);
      std::vector<RigidGrid> grids{rigid(geo.grid(r.gn, who), "123456", "")};
      for (auto g : r.gm) grids.push_back(rigid(geo.grid(g, who), "", r.cm));
      auto part = rigid_equations(grids, who);
      mpcs.insert(mpcs.end(), part.begin(), part.end());
    }
    for (const auto& r : m.rbe3s) {
      const auto who = card_label(deck, r.card);
      if (!r.um.empty()) throw ModelError(who + ": UM (user-chosen dependent DOFs) is not supported");
      const auto& ref = geo.grid(r.refgrid, who);
      std::vector<Rbe3Group> groups;
      for (const auto& grp : r.groups) {
        Rbe3Group g;
        g.weight = grp.weight;
        g.components = grp.components;
        for (auto id : grp.grids) {
          const auto& p = geo.grid(id, who);
          g.grids.emplace_back(p.x, p.dofs);
          g.frames.push_back(p.frame);
        }
        groups.push_back(std::move(g));
      }
      auto part = rbe3_equations(ref.x, ref.dofs, r.refc, groups, who, ref.frame);
      mpcs.insert(mpcs.end(), part.begin(), part.end());
    }
    if (sets.mpc)
      for (const auto& c : m.mpcs) {
        if (c.sid != *sets.mpc) continue;
        const auto who = card_label(deck, c.card);
        const auto& t0 = c.terms.front();
        if (t0.a == 0.0) throw ModelError(who + ": the dependent term's coefficient A1 is zero");
        MpcEquation e;
        e.dependent = geo.dof(t0.g, static_cast<int>(t0.c), who);
        e.source = who;
        for (std::size_t k = 1; k < c.terms.size(); ++k)
          e.terms.emplace_back(geo.dof(c.terms[k].g, static_cast<int>(c.terms[k].c), who), -c.terms[k].a / t0.a);
        mpcs.push_back(std::move(e));
      }
  } catch (const std::invalid_argument& e) {
    throw ModelError(e.what());
  }
  return mpcs;
}

/// The DESVARs as parameters and their DVPREL1/DVMREL1 relations to the model.
void FeModel::relate_parameters(const Deck& deck) {
  const BulkModel& m = m_model;
  std::map<std::int64_t, std::size_t> desvar_index;
  for (const auto& d : m.desvars) {
    desvar_index[d.id] = m_parameters.size();
    m_parameters.push_back({d.id, d.label, d.xinit, d.xlb, d.xub, {}, {}});
  }
  auto relate = [&](ValueKey key, const std::string& type, double c0, std::optional<double> lo, double hi,
                    const std::vector<std::pair<std::int64_t, double>>& terms, const std::string& who) {
    Relation rel{std::move(key), c0, lo, hi, {}, who};
    for (const auto& [dvid, coef] : terms) {
      auto it = desvar_index.find(dvid);
      if (it == desvar_index.end()) throw ModelError(who + ": DESVAR " + std::to_string(dvid) + " does not exist");
      rel.terms.emplace_back(it->second, coef);
      std::ostringstream s;
      s << (rel.key.owner == ValueOwner::Material ? "MAT1 " : "") << rel.key.id << " " << rel.key.name << " ("
        << who.substr(who.find(": ") + 2) << ", coefficient " << coef << ")";
      m_parameters[it->second].designs.push_back(s.str());
      m_parameters[it->second].fields.push_back({type, rel.key.id, rel.key.name, coef});
    }
    try {
      (void)get_value(m_model, rel.key);
    } catch (const std::invalid_argument& e) {
      throw ModelError(who + ": " + e.what());
    }
    m_relations.push_back(std::move(rel));
  };
  for (const auto& d : m.dvprel1s) {
    const auto who = card_label(deck, d.card);
    const std::string type = upper(d.type);
    std::string name = upper(d.pname);
    if (name.empty()) {
      name = field_name(type, d.fid);
      if (name.empty())
        throw ModelError(who + ": field number " + std::to_string(d.fid) + " of " + type +
                         " is not supported; give the field name (PNAME)");
    }
    // The QRG names the first property of a PELAS/PMASS card K1 / M1 (a card holds
    // two); ssid types one property per id, whose value is K / M.
    if ((type == "PELAS" && name == "K1") || (type == "PMASS" && name == "M1")) name = name.substr(0, 1);
    const bool element = type == "CONM2" || type == "CELAS2" || type == "CMASS2" || type == "CONROD";
    if (!element) {
      const std::string actual = property_type(m, d.pid);
      if (actual != type)
        throw ModelError(who + ": TYPE " + type + " but property " + std::to_string(d.pid) +
                         (actual.empty() ? " does not exist" : " is a " + actual));
    }
    relate({element ? ValueOwner::Element : ValueOwner::Property, d.pid, name}, type, d.c0, d.pmin, d.pmax, d.terms, who);
  }
  for (const auto& d : m.dvmrel1s) {
    const auto who = card_label(deck, d.card);
    if (upper(d.type) != "MAT1") throw ModelError(who + ": only MAT1 materials are designed (TYPE " + d.type + ")");
    relate({ValueOwner::Material, d.mid, upper(d.mpname)}, "MAT1", d.c0, d.mpmin, d.mpmax, d.terms, who);
  }
}

/// Constraint sets at the nominal design; AUTOSPC from the stiffness there.
void FeModel::apply_constraints(const std::vector<std::size_t>& spc, const std::vector<MpcEquation>& mpcs,
                                const ReductionSettings& r) {
  std::vector<std::size_t> spc_list = spc;
  const ModelGeometry& geo = *m_geometry;
  const std::size_t ng = geo.gset().size();
  try {
    m_reduction = build_reduction(ng, mpcs, spc_list);
    if (r.autospc) {
      const SparseMatrix Kg = sum_blocks(m_elements->blocks(values_at(initial_parameters())), false);
      m_autospc = find_singular_dofs(Kg, m_reduction, geo.gset(), r.epzero);
      if (!m_autospc.empty()) {
        std::sort(m_autospc.begin(), m_autospc.end());
        spc_list.insert(spc_list.end(), m_autospc.begin(), m_autospc.end());
        m_reduction = build_reduction(ng, mpcs, spc_list);
      }
    }
  } catch (const std::invalid_argument& e) {
    throw ModelError(e.what());
  }
}

Eigen::VectorXd FeModel::initial_parameters() const {
  Eigen::VectorXd x(static_cast<Eigen::Index>(m_parameters.size()));
  for (std::size_t j = 0; j < m_parameters.size(); ++j) x(static_cast<Eigen::Index>(j)) = m_parameters[j].initial;
  return x;
}

BulkModel FeModel::values_at(const Eigen::VectorXd& x) const {
  if (x.size() != static_cast<Eigen::Index>(m_parameters.size()))
    throw std::invalid_argument("values_at: " + std::to_string(m_parameters.size()) + " parameters expected, got " +
                                std::to_string(x.size()));
  BulkModel v = m_model;
  for (const auto& rel : m_relations) {
    double value = rel.c0;
    for (const auto& [j, coef] : rel.terms) value += coef * x(static_cast<Eigen::Index>(j));
    if (rel.lower) value = std::max(value, *rel.lower);
    value = std::min(value, rel.upper);
    set_value(v, rel.key, value);
  }
  return v;
}

SparseMatrix FeModel::sum_blocks(const std::vector<ElementBlock>& blocks, bool mass) const {
  std::vector<Eigen::Triplet<double>> t;
  for (const auto& b : blocks) {
    const Eigen::MatrixXd& a = mass ? b.m : b.k;
    for (Eigen::Index i = 0; i < a.rows(); ++i)
      for (Eigen::Index j = 0; j < a.cols(); ++j)
        if (a(i, j) != 0.0)
          t.emplace_back(static_cast<int>(b.dofs[static_cast<std::size_t>(i)]),
                         static_cast<int>(b.dofs[static_cast<std::size_t>(j)]), a(i, j));
  }
  const auto n = static_cast<Eigen::Index>(m_geometry->gset().size());
  SparseMatrix s(n, n);
  s.setFromTriplets(t.begin(), t.end());
  if (mass && m_wtmass != 1.0) s *= m_wtmass;
  return s;
}

FeOperators FeModel::operators(const Eigen::VectorXd& x, bool derivatives) const {
  const BulkModel v = values_at(x);
  const auto blocks = m_elements->blocks(v);
  FeOperators op;
  op.Kg = sum_blocks(blocks, false);
  op.Mg = sum_blocks(blocks, true);
  op.K = reduce(op.Kg, m_reduction);
  op.M = reduce(op.Mg, m_reduction);
  if (!derivatives) return op;
  for (std::size_t j = 0; j < m_parameters.size(); ++j) {
    ValueDelta delta;
    for (const auto& rel : m_relations) {
      double value = rel.c0, rate = 0;
      for (const auto& [k, coef] : rel.terms) {
        value += coef * x(static_cast<Eigen::Index>(k));
        if (k == j) rate += coef;
      }
      // A value held at PMIN/PMAX does not move with the parameter.
      const bool clipped = (rel.lower && value < *rel.lower) || value > rel.upper;
      if (rate != 0.0 && !clipped) delta.add(rel.key, rate);
    }
    const auto d = m_elements->derivative_blocks(v, delta);
    op.dK.push_back(reduce(sum_blocks(d, false), m_reduction));
    op.dM.push_back(reduce(sum_blocks(d, true), m_reduction));
  }
  return op;
}

Eigen::MatrixXd FeModel::expand(const Eigen::MatrixXd& a_modes) const { return m_reduction.T * a_modes; }

std::unique_ptr<FeModel> assemble_deck(const Deck& deck, const std::string& who, const AssemblyOptions& options,
                                       std::vector<std::string>* warnings) {
  BulkModel bulk = formats::resolved_bulk(deck, who, warnings);
  try {
    return std::make_unique<FeModel>(deck, std::move(bulk), options);
  } catch (const ModelError& e) {
    const std::string at = e.where().file.empty() ? who : e.where().str();
    throw ModelError(e.where(), (at.empty() ? "" : at + ": ") + "cannot assemble the model: " + e.what());
  }
}

}  // namespace ssid::translators
