/// \file support_dynamics.cpp
/// support_dynamics: a suspension (grounded) spring that has mass of its own,
/// so the test shows its surge modes. The spring of rate k between (grid, c)
/// and ground becomes a chain grid –k₁– m₁ –k₂– m₂ –k₃– ground on two new grids
/// moving along c only. Why this chain: a real coil spring is a continuous
/// one, whose dynamic stiffness at the attachment, its far end held, is
///   K(ω) = k x cot x = k − Σ_n 2kω² / (ω_n² − ω²),   x = π ω/ω₁, ω_n = n ω₁:
/// the static rate k, surges at ω₁, 2ω₁, 3ω₁, …, each pulling on the structure
/// with the same 2k. The two-mass chain has the static rate, two surges and
/// their two pulls as parameters of its five values, and matching the
/// continuous spring's first two (solved apart from this code, in scipy; the
/// solution is unique) gives
///   k₁ = 5k, k₂ = 7k/2, k₃ = 35k/18,  m₁ = β, m₂ = 49β/36,  ω₁² = 5k/(2β),
/// so the chain surges at f₁ = √(5k/(2β))/2π and exactly 2f₁, and pulls as the
/// real spring does. The surges above, n ≥ 3, pull on the structure below them
/// as a mass: Σ_{n≥3} 2kω²/(n²ω₁²) = ω² (2k/ω₁²)(π²/6 − 5/4) = 0.316β ω²; a
/// scalar mass of that size at (grid, c) (CMASS2) completes the spring's
/// low-frequency inertia to the continuous one's m/3 (m = π²k/ω₁², the spring's
/// whole mass). Without it the chain was 0.08 m light at the grid, and below its
/// surge the pull it gives was off by up to 20 % of k (k x cot x vanishes at
/// half the surge, the chain alone gives 0.2k): the sweep's surging
/// suspensions then fitted the modes the model already paired worse. (The
/// forms before: 2k – m – 2k, one surge with half the pull, then 3k – m – 3k/2,
/// one surge with the right pull: a test that sees a spring's second surge, as
/// the sweep's surging suspensions below 33 Hz do, had nothing to pair it with.)
/// β = m₁ [kg]. Prior N(0, σ²) with σ = 5k/(2(2π f_low)²) (the mass that puts the
/// first surge at the lowest test frequency), β ≥ 0, with the deck's rate k: a
/// prior is fixed before the data. The start places the surge at an unexplained
/// test frequency when there is one, with the rate where the hypotheses start
/// (the ordinary update's: below the test band the suspension's rate is barely
/// informed and may have moved far, and the surge with it). A group of springs (the
/// CELAS1s of one PELAS) starts with all at each unexplained frequency, spread
/// over them in turn, and matched: each spring at the unexplained test mode
/// whose shape its surge would give best (the structure's answer to a force
/// at the spring's grid at that frequency, against the test shape). The design
/// relations of the spring (DVPREL1 of its PELAS or CELAS2) are carried to the
/// three springs with their coefficients × 5, × 7/2 and × 35/18, so the spring
/// rate stays a parameter.
#include <algorithm>
#include <array>
#include <cmath>
#include <map>

#include "estimator/diagnosis/hypotheses/extension_util.hpp"
#include "estimator/diagnosis/hypotheses/model_extension.hpp"

namespace ssid::estimator::diagnosis::hypotheses {

namespace {

/// The chain's three rates, grid side first, in units of the spring's k, and
/// its two masses in units of β (file comment).
constexpr std::array<double, 3> kRates{5.0, 3.5, 35.0 / 18.0};
constexpr std::array<double, 2> kMasses{1.0, 49.0 / 36.0};
/// The higher surges' pull as a mass at the spring's grid, in units of β:
/// (2k/ω₁²)(π²/6 − 5/4) with 2k/ω₁² = 4β/5 (file comment).
constexpr double kResidualMass = 0.8 * (M_PI * M_PI / 6.0 - 1.25);
/// ω₁² = kFirstSurge · k / β.
constexpr double kFirstSurge = 2.5;

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

/// Whether a DVPREL1 of a PELAS or CELAS2 designs its rate K (PELAS field 3, CELAS2 field 3), not GE or S.
bool designs_rate(const formats::Dvprel1& r) { return r.pname == "K" || (r.pname.empty() && r.fid == 3); }

/// Relation `r` of a spring, for the spring or property `pid` whose rate is
/// `factor` × the original's: a relation of the rate scaled (C0, the
/// coefficients and the bounds), one of GE or S as it is. Its id is r's.
formats::Dvprel1 relation_for(const formats::Dvprel1& r, std::int64_t pid, double factor) {
  formats::Dvprel1 q = r;
  q.pid = pid;
  if (designs_rate(r)) {
    q.c0 *= factor;
    for (auto& t : q.terms) t.second *= factor;
    if (q.pmin) *q.pmin *= factor;
    if (q.pmax < 1.0e20) q.pmax *= factor;
  }
  return q;
}

class SupportDynamics : public ModelExtension {
 public:
  explicit SupportDynamics(ExtensionOptions o) : m_options(std::move(o)) {}
  std::string kind() const override { return "support_dynamics"; }
  std::string describe() const override {
    return "a grounded (suspension) spring with its own mass: a chain 5k - m - 7k/2 - 49m/36 - 35k/18 to ground, "
           "the static rate and the first two surges and pulls of a continuous spring (surge modes), the higher "
           "surges' pull as a mass 0.316 m at the grid; "
           "parameter: the first inner mass [kg] of each spring";
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
    // Start values: the surge at each unexplained test frequency, or at the lowest
    // test frequency, with the spring's rate where the hypotheses start (file comment).
    std::vector<double> freqs = detail::start_frequencies(m_options);
    if (freqs.empty()) freqs.push_back(m_options.lowest_test_hz);
    std::map<std::int64_t, double> rate;
    for (const auto& s : grounded_springs(detail::bulk_at_update(nominal, m_options))) rate[s.eid] = s.k;
    auto mass_at = [&](const Spring& sp, double f) {
      const auto it = rate.find(sp.eid);
      return mass_for(it != rate.end() ? it->second : sp.k, f);
    };
    std::vector<Candidate> out;
    for (const auto& set : sets) {
      std::vector<std::vector<double>> starts;
      for (double f : freqs) {
        std::vector<double> s;
        for (const auto& sp : set) s.push_back(mass_at(sp, f));
        starts.push_back(s);
      }
      if (set.size() > 1 && freqs.size() > 1) {  // spread: spring i at frequency i
        std::vector<double> s;
        for (std::size_t i = 0; i < set.size(); ++i) s.push_back(mass_at(set[i], freqs[i % freqs.size()]));
        starts.push_back(s);
        // Matched: each spring at the unexplained test mode its surge would give the shape of best.
        std::vector<double> m;
        for (const auto& sp : set) m.push_back(mass_at(sp, freqs[best_match(nominal, sp, freqs.size())]));
        if (std::find(starts.begin(), starts.end(), m) == starts.end()) starts.push_back(m);
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
    std::map<std::pair<std::int64_t, double>, std::int64_t> new_pid;  // (old PELAS, factor) -> its new PELAS
    // A new PELAS of `factor` × the old one's rate (GE and S as they were), with
    // the old one's design relations: of K scaled alike (C0, the coefficients
    // and PMIN/PMAX), of GE or S as they are.
    auto scaled_pelas = [&](std::int64_t pid, double k, double factor) {
      auto& id = new_pid[{pid, factor}];
      if (id) return id;
      formats::Pelas p;
      for (const auto& q : b.pelases)
        if (q.pid == pid) p = q;
      p.pid = id = ed.new_property_id();
      p.k = factor * k;
      ed.append(formats::write_pelas(p));
      for (const auto& r : b.dvprel1s)
        if (r.type == "PELAS" && r.pid == pid) {
          formats::Dvprel1 q = relation_for(r, p.pid, factor);
          q.id = ed.new_relation_id();
          ed.append(formats::write_dvprel1(q));
        }
      return id;
    };
    for (std::size_t n = 0; n < c.ids.size(); ++n) {
      const Spring* sp = nullptr;
      for (const auto& s : springs)
        if (s.eid == c.ids[n]) sp = &s;
      if (!sp) throw std::invalid_argument("support_dynamics: grounded spring " + std::to_string(c.ids[n]) + " not found");
      const auto& g = nominal.geometry().grid(sp->grid, "support_dynamics");
      ed.comment("ssid diagnose: spring " + std::to_string(sp->eid) + " with mass (surge)");
      // The two new grids: at the spring's grid, free only along the spring's component.
      std::string held;
      for (int k = 1; k <= 6; ++k)
        if (k != sp->component) held += static_cast<char>('0' + k);
      const std::array<std::int64_t, 2> inner{ed.add_grid(g.x, g.cd, held), ed.add_grid(g.x, g.cd, held)};
      const auto c_ = static_cast<std::int64_t>(sp->component);
      // The chain grid –k₁– inner[0] –k₂– inner[1] –k₃– ground: the spring itself
      // becomes k₁, ending at the first inner grid; k₂ and k₃ are new.
      const std::array<std::pair<std::int64_t, std::int64_t>, 2> links{{{inner[0], inner[1]}, {inner[1], 0}}};
      if (sp->type == "CELAS1") {
        for (const auto& e : b.celas1s)
          if (e.eid == sp->eid) {
            formats::Celas1 moved = e;
            moved.pid = scaled_pelas(sp->pid, sp->k, kRates[0]);
            moved.pid_blank = false;
            if (e.g1 == sp->grid) { moved.g2 = inner[0]; moved.c2 = c_; }
            else { moved.g1 = inner[0]; moved.c1 = c_; }
            ed.change(e.card, formats::write_celas1(moved));
          }
        for (std::size_t l = 0; l < links.size(); ++l) {
          formats::Celas1 e;
          e.eid = ed.new_element_id();
          e.pid = scaled_pelas(sp->pid, sp->k, kRates[l + 1]);
          e.g1 = links[l].first;
          e.c1 = c_;
          e.g2 = links[l].second;
          e.c2 = links[l].second ? c_ : 0;
          ed.append(formats::write_celas1(e));
        }
      } else {
        std::vector<std::pair<std::int64_t, double>> designed{{sp->eid, kRates[0]}};
        for (const auto& e : b.celas2s)
          if (e.eid == sp->eid) {
            formats::Celas2 moved = e;
            moved.k = kRates[0] * e.k;
            if (e.g1 == sp->grid) { moved.g2 = inner[0]; moved.c2 = c_; }
            else { moved.g1 = inner[0]; moved.c1 = c_; }
            ed.change(e.card, formats::write_celas2(moved));
          }
        for (std::size_t l = 0; l < links.size(); ++l) {
          formats::Celas2 e;
          e.eid = ed.new_element_id();
          e.k = kRates[l + 1] * sp->k;
          e.g1 = links[l].first;
          e.c1 = c_;
          e.g2 = links[l].second;
          e.c2 = links[l].second ? c_ : 0;
          ed.append(formats::write_celas2(e));
          designed.emplace_back(e.eid, kRates[l + 1]);
        }
        // The spring's own relations design its grid-side rate (changed in place:
        // one relation a field), copies the new springs'; GE and S relations as they are.
        for (const auto& r : b.dvprel1s)
          if (r.type == "CELAS2" && r.pid == sp->eid)
            for (const auto& [id, factor] : designed) {
              formats::Dvprel1 q = relation_for(r, id, factor);
              if (id == sp->eid) {
                ed.change(r.card, formats::write_dvprel1(q));
              } else {
                q.id = ed.new_relation_id();
                ed.append(formats::write_dvprel1(q));
              }
            }
      }
      NewParameter p;
      p.label = detail::label("XS", sp->eid);
      p.prior_mean = 0.0;
      p.prior_std = mass_for(sp->k, m_options.lowest_test_hz);
      p.lower = 0.0;
      p.meaning = "mass of spring " + std::to_string(sp->eid) + " at grid " + std::to_string(sp->grid) +
                  ", its first inner mass [kg]";
      if (n < c.start.size()) p.start = c.start[n];
      const double x0 = std::isnan(p.start) ? p.prior_mean : p.start;
      const auto dv = ed.add_desvar(p, x0);
      for (std::size_t i = 0; i < inner.size(); ++i) {
        formats::Conm2 m;
        m.eid = ed.new_element_id();
        m.g = inner[i];
        m.m = kMasses[i] * x0;
        ed.append(formats::write_conm2(m));
        ed.add_dvprel1("CONM2", m.eid, "M", dv, kMasses[i]);
      }
      formats::Cmass2 r;  // the higher surges' pull, along the spring only
      r.eid = ed.new_element_id();
      r.m = kResidualMass * x0;
      r.g1 = sp->grid;
      r.c1 = c_;
      ed.append(formats::write_cmass2(r));
      ed.add_dvprel1("CMASS2", r.eid, "M", dv, kResidualMass);
    }
    return {ed.text(), ed.parameters, "suspension springs with mass at " + c.location.text};
  }

 private:
  /// Of the first `n` unexplained test modes, the one whose shape the surge of
  /// `sp` would give best: the structure's answer at its frequency to a force
  /// at the spring's grid and component (detail::response_at_sensors), against
  /// the test shape (MAC); 0 when no test shapes are known.
  std::size_t best_match(const FeModel& model, const Spring& sp, std::size_t n) const {
    const auto& x = m_options.unexplained;
    const auto& g = model.geometry().grid(sp.grid, "support_dynamics");
    const auto dof = static_cast<Eigen::Index>(g.dofs[static_cast<std::size_t>(sp.component - 1)]);
    std::size_t best = 0;
    double best_share = -1;
    for (std::size_t u = 0; u < n && u < x.test_shapes.size(); ++u) {
      const Eigen::VectorXd& t = x.test_shapes[u];
      if (x.g_shapes.cols() == 0 || dof >= x.g_shapes.rows() || t.size() != x.sensor_shapes.rows()) continue;
      const double share = detail::explained_share(
          detail::response_at_sensors(x, m_options.unexplained_hz.at(u), x.g_shapes.row(dof).transpose()), t);
      if (share > best_share) { best_share = share; best = u; }
    }
    return best;
  }

  /// The first inner mass β that puts the first surge at f: ω₁² = 5k/(2β).
  static double mass_for(double k, double f_hz) {
    const double w = 2.0 * M_PI * f_hz;
    return kFirstSurge * k / (w * w);
  }
  ExtensionOptions m_options;
};

}  // namespace

std::unique_ptr<ModelExtension> make_support_dynamics(const ExtensionOptions& options) {
  return std::make_unique<SupportDynamics>(options);
}

}  // namespace ssid::estimator::diagnosis::hypotheses
