#include "formats/bulk_model.hpp"

#include "formats/bulk_catalogue.hpp"
#include "formats/nastran_number.hpp"

#include <algorithm>
#include <array>
#include <map>
#include <cmath>
#include <unordered_set>
#include <functional>
#include <unordered_map>

namespace ssid::formats {

namespace {

using ParseFn = void (*)(const FieldReader&, std::size_t card, BulkModel&);

template <typename T, T (*Parse)(const FieldReader&), std::vector<T> BulkModel::*Member>
void add(const FieldReader& r, std::size_t card, BulkModel& m) {
  T v = Parse(r);
  v.card = card;
  (m.*Member).push_back(std::move(v));
}

/// Cards holding several entries (PELAS, PMASS).
template <typename T, std::vector<T> (*Parse)(const FieldReader&), std::vector<T> BulkModel::*Member>
void add_many(const FieldReader& r, std::size_t card, BulkModel& m) {
  for (T& v : Parse(r)) {
    v.card = card;
    (m.*Member).push_back(std::move(v));
  }
}

/// Cards counted as supported but parsed elsewhere (DMIG: formats/dmig.*).
void skip(const FieldReader&, std::size_t, BulkModel&) {}

const std::unordered_map<std::string, ParseFn>& parsers() {
  static const std::unordered_map<std::string, ParseFn> table = {
      {"GRID", add<Grid, parse_grid, &BulkModel::grids>},
      {"CROD", add<Crod, parse_crod, &BulkModel::crods>},
      {"CONROD", add<Conrod, parse_conrod, &BulkModel::conrods>},
      {"PROD", add<Prod, parse_prod, &BulkModel::prods>},
      {"CBAR", add<Cbar, parse_cbar, &BulkModel::cbars>},
      {"BAROR", add<Baror, parse_baror, &BulkModel::barors>},
      {"PBAR", add<Pbar, parse_pbar, &BulkModel::pbars>},
      {"PBARL", add<Pbarl, parse_pbarl, &BulkModel::pbarls>},
      {"CBEAM", add<Cbeam, parse_cbeam, &BulkModel::cbeams>},
      {"BEAMOR", add<Beamor, parse_beamor, &BulkModel::beamors>},
      {"PBEAM", add<Pbeam, parse_pbeam, &BulkModel::pbeams>},
      {"PBEAML", add<Pbeaml, parse_pbeaml, &BulkModel::pbeamls>},
      {"MAT1", add<Mat1, parse_mat1, &BulkModel::mat1s>},
      {"GRDSET", add<Grdset, parse_grdset, &BulkModel::grdsets>},
      {"CORD2R", add<Cord2, parse_cord2, &BulkModel::cord2s>},
      {"CORD2C", add<Cord2, parse_cord2, &BulkModel::cord2s>},
      {"CORD2S", add<Cord2, parse_cord2, &BulkModel::cord2s>},
      {"SPOINT", add<Spoint, parse_spoint, &BulkModel::spoints>},
      {"CONM2", add<Conm2, parse_conm2, &BulkModel::conm2s>},
      {"CMASS1", add<Cmass1, parse_cmass1, &BulkModel::cmass1s>},
      {"CMASS2", add<Cmass2, parse_cmass2, &BulkModel::cmass2s>},
      {"CMASS3", add<Cmass1, parse_cmass3, &BulkModel::cmass1s>},
      {"CMASS4", add<Cmass2, parse_cmass4, &BulkModel::cmass2s>},
      {"PMASS", add_many<Pmass, parse_pmass, &BulkModel::pmasses>},
      {"CELAS1", add<Celas1, parse_celas1, &BulkModel::celas1s>},
      {"CELAS2", add<Celas2, parse_celas2, &BulkModel::celas2s>},
      {"CELAS3", add<Celas1, parse_celas3, &BulkModel::celas1s>},
      {"CELAS4", add<Celas2, parse_celas4, &BulkModel::celas2s>},
      {"PELAS", add_many<Pelas, parse_pelas, &BulkModel::pelases>},
      {"CBUSH", add<Cbush, parse_cbush, &BulkModel::cbushes>},
      {"PBUSH", add<Pbush, parse_pbush, &BulkModel::pbushes>},
      {"RBAR", add<Rbar, parse_rbar, &BulkModel::rbars>},
      {"RBE2", add<Rbe2, parse_rbe2, &BulkModel::rbe2s>},
      {"RBE3", add<Rbe3, parse_rbe3, &BulkModel::rbe3s>},
      {"SPC", add<Spc, parse_spc, &BulkModel::spcs>},
      {"SPC1", add<Spc1, parse_spc1, &BulkModel::spc1s>},
      {"SPCADD", add<Spcadd, parse_spcadd, &BulkModel::spcadds>},
      {"MPC", add<Mpc, parse_mpc, &BulkModel::mpcs>},
      {"EIGRL", add<Eigrl, parse_eigrl, &BulkModel::eigrls>},
      {"EIGR", add<Eigr, parse_eigr, &BulkModel::eigrs>},
      {"PARAM", add<Param, parse_param, &BulkModel::params>},
      {"DESVAR", add<Desvar, parse_desvar, &BulkModel::desvars>},
      {"DVPREL1", add<Dvprel1, parse_dvprel1, &BulkModel::dvprel1s>},
      {"DVMREL1", add<Dvmrel1, parse_dvmrel1, &BulkModel::dvmrel1s>},
      {"DMIG", skip},
  };
  return table;
}

Problem error_at(const Deck& deck, const Card& card, std::size_t field, const std::string& msg) {
  return {Problem::Severity::Error, deck.location(card, field), msg};
}
Problem warning_at(const Deck& deck, const Card& card, std::size_t field, const std::string& msg) {
  return {Problem::Severity::Warning, deck.location(card, field), msg};
}

/// "CBAR 10": the card's name and first field, as written.
std::string label(const Deck& deck, std::size_t card) {
  const Card& c = deck.cards[card];
  std::string_view id = c.field(1);
  return id.empty() ? c.name : c.name + " " + std::string(id);
}

/// Only one BAROR/BEAMOR (GRDSET) is allowed; returns the first, reports the others.
template <typename T>
const T* single(const Deck& deck, const std::vector<T>& v, const char* name, std::vector<Problem>& problems) {
  for (std::size_t k = 1; k < v.size(); ++k)
    problems.push_back(error_at(deck, deck.cards[v[k].card], 0,
                                std::string("more than one ") + name + " (first at " +
                                    deck.location(deck.cards[v[0].card]).str() + ")"));
  return v.empty() ? nullptr : &v[0];
}

void apply_defaults(const Deck& deck, BulkModel& m) {
  if (const Grdset* grdset = single(deck, m.grdsets, "GRDSET", m.problems))
    for (Grid& g : m.grids) apply_grdset(g, *grdset);
  const Baror* baror = single(deck, m.barors, "BAROR", m.problems);
  for (Cbar& c : m.cbars)
    if (!apply_baror(c, baror))
      m.problems.push_back(error_at(deck, deck.cards[c.card], 5,
                                    label(deck, c.card) + ": orientation (fields 6-8) blank and no BAROR gives one"));
  const Beamor* beamor = single(deck, m.beamors, "BEAMOR", m.problems);
  for (Cbeam& c : m.cbeams)
    if (!apply_beamor(c, beamor))
      m.problems.push_back(error_at(deck, deck.cards[c.card], 5,
                                    label(deck, c.card) + ": orientation (fields 6-8) blank and no BEAMOR gives one"));
}

}  // namespace

bool is_supported_card(const std::string& name) { return parsers().count(name) > 0; }

std::vector<std::string> supported_card_names() {
  std::vector<std::string> names;
  for (const auto& [name, fn] : parsers()) names.push_back(name);
  std::sort(names.begin(), names.end());
  return names;
}

namespace {
/// "unknown card name CRDO — did you mean CROD?" (NASTRAN: USER FATAL MESSAGE 307).
/// The text is made once per name (`made`): a garbage file can hold a million cards.
Problem unknown_card(const Deck& deck, const Card& c, std::unordered_map<std::string, std::string>& made) {
  auto [it, fresh] = made.try_emplace(c.name);
  if (fresh) {
    it->second = "unknown card name " + c.name;
    if (auto near = nearest_bulk_entry_name(c.name)) it->second += " — did you mean " + *near + "?";
    else it->second += " (not a NASTRAN bulk data entry)";
  }
  return error_at(deck, c, 0, it->second);
}
}  // namespace

BulkModel parse_bulk(const Deck& deck) {
  BulkModel m;
  const auto& table = parsers();
  // Decks come in runs of one card type: remember the last lookup.
  const std::string* last_name = nullptr;
  ParseFn fn = nullptr;
  bool known = false;  ///< the name is a bulk data entry (typed or kept verbatim)
  std::unordered_map<std::string, std::string> unknown_messages;
  std::size_t* counter = nullptr;
  for (std::size_t i = 0; i < deck.cards.size(); ++i) {
    const Card& c = deck.cards[i];
    if (!last_name || *last_name != c.name) {
      auto it = table.find(c.name);
      fn = it == table.end() ? nullptr : it->second;
      counter = fn ? &m.supported[c.name] : &m.unsupported[c.name];
      known = fn || is_bulk_entry_name(c.name);
      last_name = &c.name;
    }
    ++*counter;
    if (!fn) {
      if (!known) m.problems.push_back(unknown_card(deck, c, unknown_messages));
      continue;
    }
    try {
      fn(FieldReader(deck, c), i, m);
    } catch (const ParseError& e) {
      m.problems.push_back({Problem::Severity::Error, e.where(), e.detail()});
    }
  }
  apply_defaults(deck, m);
  return m;
}

namespace {

template <typename T>
void write_all(const std::vector<T>& v, std::vector<FieldValue> (*write)(const T&),
               std::map<std::size_t, std::vector<FieldValue>>& out) {
  for (const T& x : v) {
    std::vector<FieldValue> values = write(x);
    auto [it, fresh] = out.emplace(x.card, values);
    // A card holding several entries (PELAS, PMASS): append this entry's fields.
    if (!fresh) it->second.insert(it->second.end(), values.begin() + 1, values.end());
  }
}

}  // namespace

std::map<std::size_t, std::vector<FieldValue>> write_bulk(const BulkModel& m) {
  std::map<std::size_t, std::vector<FieldValue>> out;
  write_all(m.grids, write_grid, out);
  write_all(m.crods, write_crod, out);
  write_all(m.conrods, write_conrod, out);
  write_all(m.prods, write_prod, out);
  write_all(m.cbars, write_cbar, out);
  write_all(m.barors, write_baror, out);
  write_all(m.pbars, write_pbar, out);
  write_all(m.pbarls, write_pbarl, out);
  write_all(m.cbeams, write_cbeam, out);
  write_all(m.beamors, write_beamor, out);
  write_all(m.pbeams, write_pbeam, out);
  write_all(m.pbeamls, write_pbeaml, out);
  write_all(m.mat1s, write_mat1, out);
  write_all(m.spoints, write_spoint, out);
  write_all(m.grdsets, write_grdset, out);
  write_all(m.cord2s, write_cord2, out);
  write_all(m.conm2s, write_conm2, out);
  write_all(m.cmass1s, write_cmass1, out);
  write_all(m.cmass2s, write_cmass2, out);
  write_all(m.pmasses, write_pmass, out);
  write_all(m.celas1s, write_celas1, out);
  write_all(m.celas2s, write_celas2, out);
  write_all(m.pelases, write_pelas, out);
  write_all(m.cbushes, write_cbush, out);
  write_all(m.pbushes, write_pbush, out);
  write_all(m.rbars, write_rbar, out);
  write_all(m.rbe2s, write_rbe2, out);
  write_all(m.rbe3s, write_rbe3, out);
  write_all(m.spcs, write_spc, out);
  write_all(m.spc1s, write_spc1, out);
  write_all(m.spcadds, write_spcadd, out);
  write_all(m.mpcs, write_mpc, out);
  write_all(m.eigrls, write_eigrl, out);
  write_all(m.eigrs, write_eigr, out);
  write_all(m.params, write_param, out);
  write_all(m.desvars, write_desvar, out);
  write_all(m.dvprel1s, write_dvprel1, out);
  write_all(m.dvmrel1s, write_dvmrel1, out);
  return out;
}

namespace {

/// One id space (grids, elements, properties, ...): every definition, by id.
class IdSpace {
public:
  struct Def {
    std::size_t card;  ///< index in Deck::cards
    const std::string* type;  ///< card name
  };

  IdSpace(const Deck& deck, std::vector<Problem>& problems, std::string noun)
      : m_deck(deck), m_problems(problems), m_noun(std::move(noun)) {}

  /// Adds `id` defined by card `card` (field `field`); a second definition is a problem.
  void define(std::int64_t id, std::size_t card, std::size_t field = 1) {
    const Card& c = m_deck.cards[card];
    auto [it, fresh] = m_defs.emplace(id, Def{card, &c.name});
    if (fresh) return;
    // Card types are defined in turn, not in deck order: the earlier card is the first definition.
    std::size_t later = card;
    if (card < it->second.card) {
      later = it->second.card;
      it->second = Def{card, &c.name};
    }
    const Card& first = m_deck.cards[it->second.card];
    const Card& dup = m_deck.cards[later];
    m_problems.push_back(error_at(m_deck, dup, field,
                                  "duplicate " + m_noun + " " + std::to_string(id) + " (" + dup.name +
                                      "; first defined by " + first.name + " at " + m_deck.location(first).str() +
                                      ")"));
  }

  const Def* find(std::int64_t id) const {
    auto it = m_defs.find(id);
    return it == m_defs.end() ? nullptr : &it->second;
  }

  /// Checks that `id` exists and, when `types` is not empty, is one of them.
  /// Messages: "PROD 3 required by CROD 10 does not exist";
  /// "CROD 10 refers to PID 3, which is a PBAR, expected PROD".
  void need(std::int64_t id, std::initializer_list<const char*> types, std::size_t by, std::size_t field,
            const char* field_name) const {
    need_of(id, types, by, field, field_name);
  }
  /// The same with the expected card type known only at run time (DVPREL1 TYPE).
  void need(std::int64_t id, const std::string& type, std::size_t by, std::size_t field, const char* field_name) const {
    need_of(id, std::array<std::string, 1>{type}, by, field, field_name);
  }

  template <typename Types>
  void need_of(std::int64_t id, const Types& types, std::size_t by, std::size_t field, const char* field_name) const {
    std::string expect;
    for (const auto& t : types) expect += (expect.empty() ? "" : "/") + std::string(t);
    const Card& c = m_deck.cards[by];
    const Def* d = find(id);
    if (!d) {
      m_problems.push_back(error_at(m_deck, c, field,
                                    (expect.empty() ? m_noun : expect) + " " + std::to_string(id) + " required by " +
                                        label(m_deck, by) + " does not exist"));
      return;
    }
    if (types.size() == 0) return;
    for (const auto& t : types)
      if (*d->type == t) return;
    m_problems.push_back(error_at(m_deck, c, field,
                                  label(m_deck, by) + " refers to " + field_name + " " + std::to_string(id) +
                                      ", which is a " + *d->type + ", expected " + expect));
  }

  /// Defines the ids in field 1 of cards kept verbatim whose name is in `names`.
  void define_verbatim(const std::initializer_list<const char*>& names) {
    for (std::size_t i = 0; i < m_deck.cards.size(); ++i) {
      const Card& c = m_deck.cards[i];
      for (const char* n : names)
        if (c.name == n) {
          if (auto id = parse_integer(c.field(1))) define(*id, i);
          break;
        }
    }
  }

private:
  const Deck& m_deck;
  std::vector<Problem>& m_problems;
  std::string m_noun;
  std::unordered_map<std::int64_t, Def> m_defs;
};

}  // namespace

/// The scalar points scalar elements define by naming them (SPOINT remark 2):
/// an end with component 0 or blank that no GRID, SPOINT or EPOINT defines.
/// Typed cards: CELAS1-4, CMASS1-4 (G, C pairs; the scalar forms with C = 0);
/// cards kept verbatim: CDAMP1/2 (G, C pairs), CDAMP3/4 (scalar points S1, S2
/// in fields 4-5). Each becomes a scalar point of the model (BulkModel::implied_spoints).
void define_implied_spoints(const Deck& deck, BulkModel& m, IdSpace& grids) {
  std::map<std::int64_t, std::size_t> implied;  // id -> the first card naming it
  auto end = [&](std::int64_t g, std::int64_t c, std::size_t card) {
    if (g > 0 && c == 0 && !grids.find(g)) {
      auto [it, fresh] = implied.emplace(g, card);
      if (!fresh && card < it->second) it->second = card;
    }
  };
  auto typed = [&](const auto& elements) {
    for (const auto& e : elements) end(e.g1, e.c1, e.card), end(e.g2, e.c2, e.card);
  };
  typed(m.celas1s);
  typed(m.celas2s);
  typed(m.cmass1s);
  typed(m.cmass2s);
  auto field_id = [&](const Card& c, std::size_t i) -> std::int64_t {
    auto v = parse_integer(c.field(i));
    return v ? *v : 0;
  };
  for (std::size_t i = 0; i < deck.cards.size(); ++i) {
    const Card& c = deck.cards[i];
    if (c.name == "CDAMP1" || c.name == "CDAMP2") {
      end(field_id(c, 3), field_id(c, 4), i);
      end(field_id(c, 5), field_id(c, 6), i);
    } else if (c.name == "CDAMP3" || c.name == "CDAMP4") {
      end(field_id(c, 3), 0, i);
      end(field_id(c, 4), 0, i);
    }
  }
  m.implied_spoints.clear();
  for (const auto& [id, card] : implied) {
    m.implied_spoints.push_back(id);
    grids.define(id, card);
  }
}

void resolve(const Deck& deck, BulkModel& m) {
  std::vector<Problem>& out = m.problems;

  // --- id spaces ------------------------------------------------------------
  IdSpace grids(deck, out, "grid or scalar point");
  for (const Grid& g : m.grids) grids.define(g.id, g.card);
  // SPOINT remark: "duplicate scalar point numbers are allowed" (not a GRID's).
  for (const Spoint& s : m.spoints)
    for (std::int64_t id : s.ids) {
      const IdSpace::Def* d = grids.find(id);
      if (!d || *d->type != "SPOINT") grids.define(id, s.card);
    }
  grids.define_verbatim({"EPOINT"});
  define_implied_spoints(deck, m, grids);

  // NASTRAN keeps four element id spaces apart (the QRG's "unique with respect
  // to all other element identification numbers" is said of each family, and
  // MSC/NX decks reuse ids across them): structural elements (with springs,
  // dampers and bushings), mass elements, rigid elements, plot elements. An RBE2
  // and a CQUAD4 may both be 1; two CBARs may not.
  IdSpace elements(deck, out, "element");
  for (const auto& e : m.crods) elements.define(e.eid, e.card);
  for (const auto& e : m.conrods) elements.define(e.eid, e.card);
  for (const auto& e : m.cbars) elements.define(e.eid, e.card);
  for (const auto& e : m.cbeams) elements.define(e.eid, e.card);
  for (const auto& e : m.celas1s) elements.define(e.eid, e.card);
  for (const auto& e : m.celas2s) elements.define(e.eid, e.card);
  for (const auto& e : m.cbushes) elements.define(e.eid, e.card);
  // Element cards kept verbatim share the id space of their family.
  elements.define_verbatim({"CQUAD4", "CQUAD8", "CQUADR", "CTRIA3", "CTRIA6", "CTRIAR", "CSHEAR", "CHEXA", "CPENTA",
                            "CTETRA", "CPYRAM", "CTUBE", "CBEND", "CGAP", "CDAMP1", "CDAMP2", "CDAMP3", "CDAMP4",
                            "CVISC", "CBUSH1D", "CFAST", "CWELD"});
  IdSpace masses(deck, out, "mass element");
  for (const auto& e : m.conm2s) masses.define(e.eid, e.card);
  for (const auto& e : m.cmass1s) masses.define(e.eid, e.card);
  for (const auto& e : m.cmass2s) masses.define(e.eid, e.card);
  masses.define_verbatim({"CONM1"});
  IdSpace rigids(deck, out, "rigid element");
  for (const auto& e : m.rbars) rigids.define(e.eid, e.card);
  for (const auto& e : m.rbe2s) rigids.define(e.eid, e.card);
  for (const auto& e : m.rbe3s) rigids.define(e.eid, e.card);
  rigids.define_verbatim({"RBAR1", "RBE1", "RROD", "RSPLINE", "RSSCON", "RTRPLT"});
  IdSpace plot_elements(deck, out, "plot element");
  plot_elements.define_verbatim({"PLOTEL", "PLOTEL3", "PLOTEL4", "PLOTEL6", "PLOTEL8", "PLOTTET", "PLOTPEN",
                                 "PLOTPYR", "PLOTHEX"});

  IdSpace properties(deck, out, "property");
  for (const auto& p : m.prods) properties.define(p.pid, p.card);
  for (const auto& p : m.pbars) properties.define(p.pid, p.card);
  for (const auto& p : m.pbarls) properties.define(p.pid, p.card);
  for (const auto& p : m.pbeams) properties.define(p.pid, p.card);
  for (const auto& p : m.pbeamls) properties.define(p.pid, p.card);
  for (const auto& p : m.pmasses) properties.define(p.pid, p.card);
  for (const auto& p : m.pelases) properties.define(p.pid, p.card);
  for (const auto& p : m.pbushes) properties.define(p.pid, p.card);
  properties.define_verbatim({"PSHELL", "PCOMP", "PCOMPG", "PSOLID", "PSHEAR", "PTUBE", "PBEND", "PGAP", "PDAMP",
                              "PVISC", "PBUSH1D", "PBCOMP", "PFAST", "PWELD"});

  IdSpace materials(deck, out, "material");
  for (const auto& mt : m.mat1s) materials.define(mt.mid, mt.card);
  materials.define_verbatim({"MAT2", "MAT3", "MAT8", "MAT9", "MAT10"});

  IdSpace coords(deck, out, "coordinate system");
  for (const auto& c : m.cord2s) coords.define(c.cid, c.card);
  coords.define_verbatim({"CORD1R", "CORD1C", "CORD1S", "CORD3G", "CORD3R"});

  // --- coordinate systems: RID chains end in the basic system ----------------
  {
    std::unordered_map<std::int64_t, const Cord2*> by_cid;
    for (const auto& c : m.cord2s) by_cid.emplace(c.cid, &c);
    for (const auto& c : m.cord2s) {
      if (c.rid == 0) continue;
      coords.need(c.rid, {}, c.card, 2, "RID");
      // Follow the chain; a cycle is reported once, at its smallest CID.
      std::string path = std::to_string(c.cid);
      const Cord2* at = &c;
      for (std::size_t steps = 0; steps <= by_cid.size(); ++steps) {
        auto it = by_cid.find(at->rid);
        if (at->rid == 0 || it == by_cid.end()) break;
        at = it->second;
        path += " -> " + std::to_string(at->cid);
        if (at->cid < c.cid) break;  // reported (or not a cycle) from a smaller CID
        if (at == &c) {
          out.push_back(error_at(deck, deck.cards[c.card], 2,
                                 label(deck, c.card) + ": RID chain " + path + " is a cycle (it must end in the basic system)"));
          break;
        }
      }
    }
  }
  auto need_coord = [&](std::int64_t cid, std::size_t card, std::size_t field, const char* name) {
    if (cid > 0) coords.need(cid, {}, card, field, name);
  };
  for (const Grid& g : m.grids) {
    need_coord(g.cp, g.card, 2, "CP");
    need_coord(g.cd, g.card, 6, "CD");
  }
  for (const auto& e : m.conm2s) need_coord(e.cid, e.card, 3, "CID");
  for (const auto& e : m.cbushes) {
    need_coord(e.cid, e.card, 8, "CID");
    need_coord(e.ocid, e.card, 10, "OCID");
  }

  // --- element -> grid, element -> property, property -> material -----------
  for (const Crod& c : m.crods) {
    grids.need(c.g1, {"GRID"}, c.card, 3, "G1");
    grids.need(c.g2, {"GRID"}, c.card, 4, "G2");
    properties.need(c.pid, {"PROD"}, c.card, 2, "PID");
  }
  for (const Conrod& c : m.conrods) {
    grids.need(c.g1, {"GRID"}, c.card, 2, "G1");
    grids.need(c.g2, {"GRID"}, c.card, 3, "G2");
    materials.need(c.mid, {"MAT1"}, c.card, 4, "MID");
  }
  for (const Cbar& c : m.cbars) {
    properties.need(c.pid, {"PBAR", "PBARL"}, c.card, 2, "PID");
    grids.need(c.ga, {"GRID"}, c.card, 3, "GA");
    grids.need(c.gb, {"GRID"}, c.card, 4, "GB");
    if (c.g0 > 0) grids.need(c.g0, {"GRID"}, c.card, 5, "G0");
  }
  for (const Cbeam& c : m.cbeams) {
    properties.need(c.pid, {"PBEAM", "PBEAML", "PBCOMP"}, c.card, 2, "PID");
    grids.need(c.ga, {"GRID"}, c.card, 3, "GA");
    grids.need(c.gb, {"GRID"}, c.card, 4, "GB");
    if (c.g0 > 0) grids.need(c.g0, {"GRID"}, c.card, 5, "G0");
    // QRG CBEAM: "SA, SB: scalar or grid point identification numbers".
    if (c.sa > 0) grids.need(c.sa, {}, c.card, 17, "SA");
    if (c.sb > 0) grids.need(c.sb, {}, c.card, 18, "SB");
  }
  // Scalar elements: each end a grid (component 1-6) or a scalar point (component 0).
  auto scalar_end = [&](std::int64_t g, std::int64_t c, std::size_t card, std::size_t field, const char* gname) {
    if (g == 0) return;
    grids.need(g, {}, card, field, gname);
    const IdSpace::Def* d = grids.find(g);
    if (!d) return;
    bool is_spoint = *d->type != "GRID";
    if (is_spoint && c > 0)
      out.push_back(error_at(deck, deck.cards[card], field + 1,
                             label(deck, card) + ": " + gname + " " + std::to_string(g) + " is a scalar point (" +
                                 *d->type + "), its component must be 0 or blank, got " + std::to_string(c)));
    if (!is_spoint && c == 0)
      out.push_back(error_at(deck, deck.cards[card], field + 1,
                             label(deck, card) + ": " + gname + " " + std::to_string(g) +
                                 " is a GRID, its component must be 1-6, got blank or 0"));
  };
  // CELAS3/4, CMASS3/4: S1, S2 (fields 4, 5) connect scalar points only.
  auto scalar_point = [&](std::int64_t s, std::size_t card, std::size_t field, const char* sname) {
    if (s == 0) return;
    grids.need(s, {}, card, field, sname);
    const IdSpace::Def* d = grids.find(s);
    if (d && *d->type == "GRID")
      out.push_back(error_at(deck, deck.cards[card], field,
                             label(deck, card) + ": " + sname + " " + std::to_string(s) + " is a GRID; " +
                                 deck.cards[card].name + " connects scalar points only"));
  };
  auto scalar_ends = [&](const auto& e) {
    if (e.scalar_form) {
      scalar_point(e.g1, e.card, 3, "S1");
      scalar_point(e.g2, e.card, 4, "S2");
      return;
    }
    scalar_end(e.g1, e.c1, e.card, 3, "G1");
    scalar_end(e.g2, e.c2, e.card, 5, "G2");
  };
  for (const auto& e : m.cmass1s) {
    properties.need(e.pid, {"PMASS"}, e.card, 2, "PID");
    scalar_ends(e);
  }
  for (const auto& e : m.celas1s) {
    properties.need(e.pid, {"PELAS"}, e.card, 2, "PID");
    scalar_ends(e);
  }
  for (const auto& e : m.cmass2s) scalar_ends(e);
  for (const auto& e : m.celas2s) scalar_ends(e);
  for (const auto& e : m.conm2s) grids.need(e.g, {"GRID"}, e.card, 2, "G");
  for (const auto& e : m.cbushes) {
    properties.need(e.pid, {"PBUSH"}, e.card, 2, "PID");
    grids.need(e.ga, {"GRID"}, e.card, 3, "GA");
    if (e.gb > 0) grids.need(e.gb, {"GRID"}, e.card, 4, "GB");
    if (e.g0 > 0) grids.need(e.g0, {"GRID"}, e.card, 5, "G0");
  }

  for (const auto& p : m.prods) materials.need(p.mid, {"MAT1"}, p.card, 2, "MID");
  for (const auto& p : m.pbars) materials.need(p.mid, {"MAT1"}, p.card, 2, "MID");
  for (const auto& p : m.pbarls) {
    materials.need(p.mid, {"MAT1"}, p.card, 2, "MID");
    if (!pbarl_type_sectioned(p.type))
      out.push_back(warning_at(deck, deck.cards[p.card], 4,
                               label(deck, p.card) + ": TYPE " + p.type +
                                   " is not a section type of the PBARL/PBEAML list; kept with its values but not sectioned"));
  }
  for (const auto& p : m.pbeams) materials.need(p.mid, {"MAT1"}, p.card, 2, "MID");
  for (const auto& p : m.pbeamls) {
    materials.need(p.mid, {"MAT1"}, p.card, 2, "MID");
    if (!pbarl_type_sectioned(p.type))
      out.push_back(warning_at(deck, deck.cards[p.card], 4,
                               label(deck, p.card) + ": TYPE " + p.type +
                                   " is not a section type of the PBARL/PBEAML list; kept with its values but not sectioned"));
  }

  // --- rigid elements --------------------------------------------------------
  for (const Rbar& e : m.rbars) {
    grids.need(e.ga, {"GRID"}, e.card, 2, "GA");
    grids.need(e.gb, {"GRID"}, e.card, 3, "GB");
  }
  for (const Rbe2& e : m.rbe2s) {
    grids.need(e.gn, {"GRID"}, e.card, 2, "GN");
    for (std::int64_t g : e.gm) grids.need(g, {"GRID"}, e.card, 0, "GM");
  }
  for (const Rbe3& e : m.rbe3s) {
    grids.need(e.refgrid, {"GRID"}, e.card, 3, "REFGRID");
    for (const auto& grp : e.groups)
      for (std::int64_t g : grp.grids) grids.need(g, {"GRID"}, e.card, 0, "Gi,j");
    for (const auto& [g, c] : e.um) grids.need(g, {"GRID"}, e.card, 0, "GM");
  }

  // --- constraints ------------------------------------------------------------
  std::unordered_set<std::int64_t> spc_sets;
  // NASTRAN ignores an undefined point of an SPC set with USER WARNING MESSAGE
  // 2051 (UNDEFINED GRID POINT ... IN SPC SET ... IGNORED) and runs; so do we.
  auto missing_spc_point = [&](std::int64_t g, std::size_t card, std::size_t field) {
    out.push_back(warning_at(deck, deck.cards[card], field,
                             "grid or scalar point " + std::to_string(g) + " required by " + label(deck, card) +
                                 " does not exist; ignored (NASTRAN: USER WARNING MESSAGE 2051)"));
  };
  for (const Spc& s : m.spcs) {
    spc_sets.insert(s.sid);
    for (std::size_t k = 0; k < s.entries.size(); ++k)
      if (!grids.find(s.entries[k].g)) missing_spc_point(s.entries[k].g, s.card, 2 + 3 * k);
  }
  for (const Spc1& s : m.spc1s) {
    spc_sets.insert(s.sid);
    // A THRU range over missing grids is one mistake: name the first few, count the rest.
    std::size_t missing = 0;
    for (std::int64_t g : s.grids)
      if (!grids.find(g) && ++missing <= 5) missing_spc_point(g, s.card, 0);
    if (missing > 5)
      out.push_back(warning_at(deck, deck.cards[s.card], 0,
                               "... and " + std::to_string(missing - 5) + " more grids or scalar points required by " +
                                   label(deck, s.card) + " do not exist; ignored"));
  }
  IdSpace spcadd_ids(deck, out, "SPCADD set");
  for (const Spcadd& s : m.spcadds) {
    spcadd_ids.define(s.sid, s.card);
    // NASTRAN warns (USER WARNING MESSAGE 2053, UNDEFINED SINGLE-POINT
    // CONSTRAINT SET) and runs: the set adds no constraint.
    for (std::int64_t set : s.sets)
      if (!spc_sets.count(set))
        out.push_back(warning_at(deck, deck.cards[s.card], 0,
                                 "SPC set " + std::to_string(set) + " required by " + label(deck, s.card) +
                                     " does not exist (no SPC or SPC1 with that SID); it adds no constraint"));
  }
  for (const Mpc& mp : m.mpcs)
    for (const MpcTerm& t : mp.terms) scalar_end(t.g, t.c, mp.card, 0, "Gj");

  // --- eigenvalue methods, parameters -------------------------------------------
  IdSpace methods(deck, out, "eigenvalue method (EIGRL/EIGR SID)");
  for (const auto& e : m.eigrls) methods.define(e.sid, e.card);
  for (const auto& e : m.eigrs) methods.define(e.sid, e.card);
  {
    std::unordered_map<std::string, std::size_t> seen;
    for (const Param& p : m.params) {
      auto [it, fresh] = seen.emplace(p.name, p.card);
      if (!fresh)
        out.push_back(warning_at(deck, deck.cards[p.card], 1,
                                 "PARAM " + p.name + " given again (first at " +
                                     deck.location(deck.cards[it->second]).str() + ")"));
    }
  }

  // --- design model -------------------------------------------------------------
  IdSpace desvars(deck, out, "DESVAR");
  for (const auto& d : m.desvars) desvars.define(d.id, d.card);
  IdSpace dvprels(deck, out, "DVPREL");
  for (const auto& d : m.dvprel1s) dvprels.define(d.id, d.card);
  dvprels.define_verbatim({"DVPREL2"});
  IdSpace dvmrels(deck, out, "DVMREL");
  for (const auto& d : m.dvmrel1s) dvmrels.define(d.id, d.card);
  dvmrels.define_verbatim({"DVMREL2"});
  for (const auto& d : m.dvprel1s) {
    // Element-valued designs (CONM2 M, CELAS2 K, …): the PID field holds the element id.
    if (d.type == "CONM2" || d.type == "CMASS2")
      masses.need(d.pid, d.type, d.card, 3, "EID");
    else if (d.type == "CELAS2" || d.type == "CONROD")
      elements.need(d.pid, d.type, d.card, 3, "EID");
    else
      properties.need(d.pid, d.type, d.card, 3, "PID");
    for (const auto& [dvid, coef] : d.terms) desvars.need(dvid, {}, d.card, 9, "DVID");
  }
  for (const auto& d : m.dvmrel1s) {
    materials.need(d.mid, d.type, d.card, 3, "MID");
    for (const auto& [dvid, coef] : d.terms) desvars.need(dvid, {}, d.card, 9, "DVID");
  }

  // --- material consistency -------------------------------------------------
  for (const Mat1& mt : m.mat1s) {
    // NASTRAN warns when the three given values disagree by more than 1 %.
    if (mt.e_given && mt.g_given && mt.nu_given && mt.g > 0.0) {
      double ratio = mt.e / (2.0 * (1.0 + mt.nu) * mt.g);
      if (std::abs(1.0 - ratio) > 0.01)
        out.push_back(warning_at(deck, deck.cards[mt.card], 2,
                                 label(deck, mt.card) + ": E, G and NU are not related by E = 2(1+NU)G (E/(2(1+NU)G) = " +
                                     std::to_string(ratio) + ")"));
    }
  }
}

BulkModel resolved_bulk(const Deck& deck, const std::string& who, std::vector<std::string>* warnings) {
  BulkModel model = parse_bulk(deck);
  resolve(deck, model);
  constexpr std::size_t kShown = 20;
  std::string errors;
  std::size_t count = 0;
  const std::vector<Problem>* lists[] = {&deck.problems, &model.problems};
  for (const auto* list : lists)
    for (const auto& p : *list) {
      if (p.severity != Problem::Severity::Error) {
        if (warnings) warnings->push_back(p.str());
      } else if (++count <= kShown) {
        errors += "\n  " + p.str();
      }
    }
  if (count)
    throw InputError((who.empty() ? "" : who + ": ") + std::to_string(count) + " error(s) in the deck; nothing assembled:" +
                     errors + (count > kShown ? "\n  ... and " + std::to_string(count - kShown) + " more" : ""));
  return model;
}

}  // namespace ssid::formats
