/// \file support_dynamics.cpp
/// support_dynamics: a suspension (grounded) spring that has mass of its own,
/// so the test shows its surge modes. The spring of rate k between (grid, c)
/// and ground becomes two springs of rate 2k in series with a mass m on a new
/// grid between them (moving along c only): the static rate is still k and the
/// spring's first fixed–fixed surge frequency is
///   f = √(4k/m) / 2π   (the two-segment chain; a continuous spring: √(k/m)/2).
/// β = m [kg]. Prior N(0, σ²) with σ = 4k/(2π f_low)² (the mass that puts the
/// surge at the lowest test frequency), m ≥ 0; the start places the surge at an
/// unexplained test frequency when there is one. The design relations of the
/// spring (DVPREL1 of its PELAS or CELAS2) are carried to the new springs with
/// doubled coefficients, so the spring rate stays a parameter.
#include <cmath>
#include <map>

#include "estimator/diagnosis/hypotheses/extension_util.hpp"
#include "estimator/diagnosis/hypotheses/model_extension.hpp"

namespace ssid::estimator::diagnosis::hypotheses {

namespace {

struct Spring {
  std::string type;  ///< CELAS1 or CELAS2
  std::int64_t eid = 0, pid = 0, grid = 0;
  int component = 0;
  double k = 0;
  std::size_t card = 0;
};

std::vector<Spring> grounded_springs(const formats::BulkModel& b) {
  std::map<std::int64_t, double> pk;
  for (const auto& p : b.pelases) pk[p.pid] = p.k;
  std::vector<Spring> out;
  for (const auto& e : b.celas1s) {
    const bool g1 = e.g1 > 0 && e.g2 == 0, g2 = e.g2 > 0 && e.g1 == 0;
    if (!(g1 || g2) || !pk.count(e.pid)) continue;
    const auto c = static_cast<int>(g1 ? e.c1 : e.c2);
    if (c < 1 || c > 3) continue;
    out.push_back({"CELAS1", e.eid, e.pid, g1 ? e.g1 : e.g2, c, pk[e.pid], e.card});
  }
  for (const auto& e : b.celas2s) {
    const bool g1 = e.g1 > 0 && e.g2 == 0, g2 = e.g2 > 0 && e.g1 == 0;
    if (!(g1 || g2)) continue;
    const auto c = static_cast<int>(g1 ? e.c1 : e.c2);
    if (c < 1 || c > 3) continue;
    out.push_back({"CELAS2", e.eid, 0, g1 ? e.g1 : e.g2, c, e.k, e.card});
  }
  return out;
}

class SupportDynamics : public ModelExtension {
 public:
  explicit SupportDynamics(ExtensionOptions o) : m_options(std::move(o)) {}
  std::string kind() const override { return "support_dynamics"; }
  std::string describe() const override {
    return "a grounded (suspension) spring with its own mass: two springs of twice the rate with a mass between "
           "them (surge modes); parameter: the mass [kg] of each spring";
  }

  std::vector<Candidate> candidates(const FeModel& nominal) const override {
    const auto springs = grounded_springs(nominal.bulk());
    std::vector<std::vector<Spring>> sets;
    for (const auto& s : springs) sets.push_back({s});
    std::map<std::int64_t, std::vector<Spring>> by_pid;
    for (const auto& s : springs)
      if (s.type == "CELAS1") by_pid[s.pid].push_back(s);
    for (const auto& [pid, v] : by_pid)
      if (v.size() > 1) sets.push_back(v);
    // Start values: the surge at each unexplained test frequency, or at the lowest test frequency.
    std::vector<double> freqs = detail::start_frequencies(m_options);
    if (freqs.empty()) freqs.push_back(m_options.lowest_test_hz);
    std::vector<Candidate> out;
    for (const auto& set : sets) {
      std::vector<std::vector<double>> starts;
      for (double f : freqs) {
        std::vector<double> s;
        for (const auto& sp : set) s.push_back(mass_for(sp.k, f));
        starts.push_back(s);
      }
      if (set.size() > 1 && freqs.size() > 1) {  // spread: spring i at frequency i
        std::vector<double> s;
        for (std::size_t i = 0; i < set.size(); ++i) s.push_back(mass_for(set[i].k, freqs[i % freqs.size()]));
        starts.push_back(s);
      }
      for (const auto& st : starts) {
        Candidate c;
        c.kind = kind();
        for (const auto& sp : set) {
          c.ids.push_back(sp.eid);
          c.location.grids.push_back(sp.grid);
          c.location.elements.push_back(sp.eid);
          if (sp.pid) c.location.properties.push_back(sp.pid);
        }
        c.location.text = set.size() == 1
                              ? set[0].type + " " + std::to_string(set[0].eid) + " (grid " + std::to_string(set[0].grid) +
                                    " component " + std::to_string(set[0].component) + ")"
                              : "all " + std::to_string(set.size()) + " springs of PELAS " + std::to_string(set[0].pid);
        c.start = st;
        out.push_back(c);
      }
    }
    return out;
  }

  ExtendedDeck apply(const std::string& text, const std::string& name, const FeModel& nominal,
                     const Candidate& c) const override {
    DeckEditor ed(text, name);
    const auto& b = ed.bulk();
    const auto springs = grounded_springs(b);
    std::map<std::int64_t, std::int64_t> new_pid;  // old PELAS -> doubled PELAS
    for (std::size_t n = 0; n < c.ids.size(); ++n) {
      const Spring* sp = nullptr;
      for (const auto& s : springs)
        if (s.eid == c.ids[n]) sp = &s;
      if (!sp) throw std::invalid_argument("support_dynamics: grounded spring " + std::to_string(c.ids[n]) + " not found");
      const auto& g = nominal.geometry().grid(sp->grid, "support_dynamics");
      ed.comment("ssid diagnose: spring " + std::to_string(sp->eid) + " with mass (surge)");
      // The new grid: at the spring's grid, free only along the spring's component.
      formats::Grid ng;
      ng.id = ed.new_grid_id();
      ng.x = {g.x(0), g.x(1), g.x(2)};
      ng.cd = g.cd;
      ng.cd_blank = g.cd == 0;
      ng.cp_blank = true;
      for (int k = 1; k <= 6; ++k)
        if (k != sp->component) ng.ps += static_cast<char>('0' + k);
      ng.ps_blank = false;
      ed.append(formats::write_grid(ng));
      const auto c_ = static_cast<std::int64_t>(sp->component);
      if (sp->type == "CELAS1") {
        if (!new_pid.count(sp->pid)) {
          formats::Pelas p;
          p.pid = ed.new_property_id();
          p.k = 2.0 * sp->k;
          ed.append(formats::write_pelas(p));
          for (const auto& r : b.dvprel1s)
            if (r.type == "PELAS" && r.pid == sp->pid) {
              formats::Dvprel1 q = r;
              q.id = ed.new_relation_id();
              q.pid = p.pid;
              q.c0 *= 2.0;
              for (auto& t : q.terms) t.second *= 2.0;
              ed.append(formats::write_dvprel1(q));
            }
          new_pid[sp->pid] = p.pid;
        }
        for (const auto& e : b.celas1s)
          if (e.eid == sp->eid) {
            formats::Celas1 moved = e;
            moved.pid = new_pid[sp->pid];
            moved.pid_blank = false;
            if (e.g1 == sp->grid) { moved.g2 = ng.id; moved.c2 = c_; }
            else { moved.g1 = ng.id; moved.c1 = c_; }
            ed.change(e.card, formats::write_celas1(moved));
          }
        formats::Celas1 lower;
        lower.eid = ed.new_element_id();
        lower.pid = new_pid[sp->pid];
        lower.g1 = ng.id;
        lower.c1 = c_;
        ed.append(formats::write_celas1(lower));
      } else {
        for (const auto& e : b.celas2s)
          if (e.eid == sp->eid) {
            formats::Celas2 moved = e;
            moved.k = 2.0 * e.k;
            if (e.g1 == sp->grid) { moved.g2 = ng.id; moved.c2 = c_; }
            else { moved.g1 = ng.id; moved.c1 = c_; }
            ed.change(e.card, formats::write_celas2(moved));
          }
        formats::Celas2 lower;
        lower.eid = ed.new_element_id();
        lower.k = 2.0 * sp->k;
        lower.g1 = ng.id;
        lower.c1 = c_;
        ed.append(formats::write_celas2(lower));
        for (const auto& r : b.dvprel1s)
          if (r.type == "CELAS2" && r.pid == sp->eid)
            for (auto id : {sp->eid, lower.eid}) {
              formats::Dvprel1 q = r;
              q.id = ed.new_relation_id();
              q.pid = id;
              q.c0 *= 2.0;
              for (auto& t : q.terms) t.second *= 2.0;
              ed.append(formats::write_dvprel1(q));
            }
      }
      NewParameter p;
      p.label = detail::label("XS", sp->eid);
      p.prior_mean = 0.0;
      p.prior_std = mass_for(sp->k, m_options.lowest_test_hz);
      p.lower = 0.0;
      p.meaning = "mass of spring " + std::to_string(sp->eid) + " at grid " + std::to_string(sp->grid) + " [kg]";
      if (n < c.start.size()) p.start = c.start[n];
      const double x0 = std::isnan(p.start) ? p.prior_mean : p.start;
      formats::Conm2 m;
      m.eid = ed.new_element_id();
      m.g = ng.id;
      m.m = x0;
      ed.append(formats::write_conm2(m));
      const auto dv = ed.add_desvar(p, x0);
      ed.add_dvprel1("CONM2", m.eid, "M", dv, 1.0);
    }
    return {ed.text(), ed.parameters, "suspension springs with mass at " + c.location.text};
  }

 private:
  /// Two-segment chain: ω² = 4k/m at the surge frequency f.
  static double mass_for(double k, double f_hz) {
    const double w = 2.0 * M_PI * f_hz;
    return 4.0 * k / (w * w);
  }
  ExtensionOptions m_options;
};

}  // namespace

std::unique_ptr<ModelExtension> make_support_dynamics(const ExtensionOptions& options) {
  return std::make_unique<SupportDynamics>(options);
}

}  // namespace ssid::estimator::diagnosis::hypotheses
