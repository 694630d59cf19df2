/// \file truss_deck.cpp
#include "translators/truss/truss_deck.hpp"

#include <fmt/format.h>
#include <algorithm>
#include <map>

namespace ssid::translators::truss {

namespace {

using formats::FieldValue;
using V = std::vector<FieldValue>;
const FieldValue blank = std::monostate{};
FieldValue I(long long v) { return static_cast<std::int64_t>(v); }
FieldValue R(double v) { return v; }
FieldValue S(const std::string& v) { return v; }

std::string form_name(ModelForm f) { return f == ModelForm::Rod ? "rod" : "beam"; }

}  // namespace

formats::Deck to_deck(const TrussModel& t, const TrussCards& fe, const std::string& command, const std::string& name) {
  formats::Deck d = formats::new_deck(name);
  const bool spc = !fe.spcs.empty();
  std::string head;
  head += "$ " + fe.title + ", written by ssid (MPI-like truss generator, docs/truss.md)\n";
  head += "$ command: " + command + "\n";
  head += "$ units: SI (m, kg, N, Pa, s); no WTMASS needed\n";
  head += fmt::format("$ {} balls, {} struts, {} grids, {} DOF before constraints, mass {:.3f} kg\n", t.balls.size(),
                      t.members.size(), fe.grids.size(), fe.dof_count(), fe.total_mass());
  head += "SOL 103\nCEND\n";
  head += "TITLE = MPI TRUSS " + std::string(fe.form == ModelForm::Rod ? "ROD" : "BEAM") + " MODEL\n";
  head += "ECHO = NONE\nMETHOD = 1\n";
  if (spc) head += "SPC = 1\n";
  head += "DISPLACEMENT(PLOT) = ALL\nBEGIN BULK\n";
  d.append_text(0, head);
  d.has_bulk_marker = true;

  d.append_text(0, "$ solution parameters: AUTOSPC removes the rotations no element reaches; GRDPNT prints the weight\n");
  d.append_card(0, "PARAM", V{S("PARAM"), S("AUTOSPC"), S("YES")});
  d.append_card(0, "PARAM", V{S("PARAM"), S("GRDPNT"), I(0)});
  d.append_card(0, "EIGRL", V{S("EIGRL"), I(1), blank, R(fe.eigrl_v2), I(fe.eigrl_nd)});
  d.append_text(0, "$ aluminium; RHO = 0: all mass enters through CONM2 and NSM, decoupled from the stiffness parameters\n");
  d.append_card(0, "MAT1", V{S("MAT1"), I(fe.mat.id), R(fe.mat.E), blank, R(fe.mat.nu), R(fe.mat.rho)});

  d.append_text(0, "$ grids: balls 1-80 at the ball centres\n");
  bool strut_note = false, spring_note = false;
  for (const auto& g : fe.grids) {
    if (!strut_note && (g.kind == "ball_surface" || g.kind == "strut")) {
      d.append_text(0, "$ strut grids: 100000 + 100 * strut + k (ball surface, B-nut/end cap, end cap/tube, tube ...)\n");
      strut_note = true;
    }
    if (!spring_note && g.kind == "spring") {
      d.append_text(0, "$ suspension spring chain grids (surge model): 900000 + 100 * point + k, vertical motion only\n");
      spring_note = true;
    }
    V v{S("GRID"), I(g.id), blank, R(g.x.x()), R(g.x.y()), R(g.x.z())};
    if (!g.ps.empty()) {
      v.push_back(blank);
      v.push_back(I(std::stoll(g.ps)));
    }
    d.append_card(0, "GRID", std::move(v));
  }

  if (!fe.rods.empty()) {
    d.append_text(0, "$ struts: one CROD per strut (pinned at the ball centres); PROD A = series-equivalent axial area\n");
    for (const auto& p : fe.rod_props)
      d.append_card(0, "PROD", V{S("PROD"), I(p.id), I(fe.mat.id), R(p.A), R(p.J), blank, R(p.nsm)});
    for (const auto& r : fe.rods) d.append_card(0, "CROD", V{S("CROD"), I(r.id), I(r.pid), I(r.g1), I(r.g2)});
  }
  if (!fe.bars.empty()) {
    d.append_text(0, "$ strut sections: 1 tube, 2 end cap, 3 B-nut, 4 long B-nut (A, I1, I2, J, NSM = fitting mass / length)\n");
    for (const auto& p : fe.bar_props)
      d.append_card(0, "PBAR", V{S("PBAR"), I(p.id), I(fe.mat.id), R(p.A), R(p.I1), R(p.I2), R(p.J), R(p.nsm)});
    d.append_text(0, "$ struts: B-nut, end cap, tube elements, end cap, B-nut; CBAR 100000 + 100 * strut + k\n");
    for (const auto& b : fe.bars)
      d.append_card(0, "CBAR", V{S("CBAR"), I(b.id), I(b.pid), I(b.g1), I(b.g2), R(b.v.x()), R(b.v.y()), R(b.v.z())});
    d.append_text(0, "$ node balls are rigid from the centre out to the B-nut seats\n");
    for (const auto& r : fe.rigids) {
      V v{S("RBE2"), I(r.id), I(r.gn), I(123456)};
      for (int g : r.gm) v.push_back(I(g));
      d.append_card(0, "RBE2", std::move(v));
    }
  }

  d.append_text(0, "$ concentrated masses: 1000 + ball (ball/joint), 2000 + ball (half struts, rod form),\n"
                   "$ 3000 + ball (added mass), 4000 + strut (mid-span mass), 5000 + ... (spring mass)\n");
  for (const auto& m : fe.masses) {
    V v{S("CONM2"), I(m.id), I(m.grid), blank, R(m.m)};
    if (m.inertia != 0) {
      v.insert(v.end(), {blank, blank, blank, blank, R(m.inertia), blank, R(m.inertia), blank, blank, R(m.inertia)});
    }
    d.append_card(0, "CONM2", std::move(v));
  }

  if (!fe.springs.empty()) {
    d.append_text(0, "$ suspension: vertical coil springs (PELAS 11; chain segments PELAS 12) and cable pendulum\n"
                     "$ stiffness m g / L per point (PELAS 13-15), grounded CELAS1\n");
    for (const auto& p : fe.spring_props) d.append_card(0, "PELAS", V{S("PELAS"), I(p.id), R(p.k)});
    for (const auto& s : fe.springs) {
      V v{S("CELAS1"), I(s.id), I(s.pid), I(s.g1), I(s.c1)};
      if (s.g2 != 0) {
        v.push_back(I(s.g2));
        v.push_back(I(s.c2));
      }
      d.append_card(0, "CELAS1", std::move(v));
    }
  }
  if (spc) {
    std::map<std::string, std::vector<int>> by;
    for (const auto& s : fe.spcs) by[s.components].push_back(s.grid);
    for (const auto& [c, gs] : by) {
      V v{S("SPC1"), I(1), I(std::stoll(c))};
      for (int g : gs) v.push_back(I(g));
      d.append_card(0, "SPC1", std::move(v));
    }
  }

  d.append_text(0, "$ parameters to estimate (DESVAR) and how they enter the properties (DVPREL1)\n");
  for (const auto& dv : fe.desvars) {
    d.append_text(0, "$ " + dv.label + ": " + dv.what + "\n");
    d.append_card(0, "DESVAR", V{S("DESVAR"), I(dv.id), S(dv.label), R(dv.init), R(dv.lower), R(dv.upper)});
  }
  for (const auto& r : fe.dvprels) {
    V v{S("DVPREL1"), I(r.id), S(r.type), I(r.pid), S(r.pname), blank, blank, blank, blank, I(r.dvid), R(r.coef)};
    for (const auto& [dv, c] : r.more) {
      v.push_back(I(dv));
      v.push_back(R(c));
    }
    d.append_card(0, "DVPREL1", std::move(v));
  }
  d.append_text(0, "ENDDATA\n");
  (void)form_name;
  return d;
}

nlohmann::json summary_json(const TrussModel& t, const TrussCards& fe) {
  nlohmann::json j;
  j["model"] = form_name(fe.form);
  j["name"] = t.name;
  j["configs"] = t.configs;
  j["balls"] = t.balls.size();
  j["struts"] = t.members.size();
  std::map<std::string, std::size_t> roles, groups;
  for (const auto& m : t.members) {
    ++roles[m.role];
    ++groups[m.group];
  }
  j["struts_by_role"] = roles;
  j["struts_by_group"] = groups;
  j["long_bnut_struts"] = std::count_if(t.members.begin(), t.members.end(), [](const Member& m) { return m.long_bnut; });
  j["mass_kg"] = t.total_mass();
  j["deck_mass_kg"] = fe.total_mass();
  const Eigen::Vector3d cg = t.center_of_gravity(), ex = t.extent();
  j["cg_m"] = {cg.x(), cg.y(), cg.z()};
  j["extent_m"] = {ex.x(), ex.y(), ex.z()};
  j["grids"] = fe.grids.size();
  j["dof"] = fe.dof_count();
  std::map<std::string, std::size_t> cards;
  cards["GRID"] = fe.grids.size();
  if (!fe.rods.empty()) cards["CROD"] = fe.rods.size(), cards["PROD"] = fe.rod_props.size();
  if (!fe.bars.empty()) cards["CBAR"] = fe.bars.size(), cards["PBAR"] = fe.bar_props.size();
  if (!fe.rigids.empty()) cards["RBE2"] = fe.rigids.size();
  cards["CONM2"] = fe.masses.size();
  if (!fe.springs.empty()) cards["CELAS1"] = fe.springs.size(), cards["PELAS"] = fe.spring_props.size();
  cards["DESVAR"] = fe.desvars.size();
  cards["DVPREL1"] = fe.dvprels.size();
  j["cards"] = cards;
  std::map<std::string, std::size_t> bars_by_kind;
  std::map<int, std::string> pkind;
  for (const auto& p : fe.bar_props) pkind[p.id] = p.kind;
  for (const auto& b : fe.bars) ++bars_by_kind[pkind[b.pid]];
  if (!bars_by_kind.empty()) j["elements_by_kind"] = bars_by_kind;
  j["suspension"] = nlohmann::json::array();
  for (const auto& s : t.suspension)
    j["suspension"].push_back({{"ball", s.ball},
                               {"k_vertical_N_per_m", s.k_vertical},
                               {"k_lateral_N_per_m", s.k_lateral},
                               {"spring_mass_kg", s.spring_mass},
                               {"segments", s.segments}});
  j["parameters"] = nlohmann::json::array();
  for (const auto& dv : fe.desvars) {
    nlohmann::json p = {{"id", dv.id}, {"label", dv.label}, {"initial", dv.init}, {"lower", dv.lower},
                        {"upper", dv.upper}, {"description", dv.what}};
    std::size_t n = 0;
    for (const auto& r : fe.dvprels)
      n += r.dvid == dv.id || std::any_of(r.more.begin(), r.more.end(), [&](const auto& t) { return t.first == dv.id; });
    p["dvprel1_count"] = n;
    j["parameters"].push_back(p);
  }
  return j;
}

}  // namespace ssid::translators::truss
