/// \file joint_flexibility.cpp
/// joint_flexibility: the joints between a ball (or any node a rigid RBE2
/// spider stands for) and the strut ends are not rigid in rotation. The RBE2
/// keeps its translational components (the strut end still follows the ball's
/// translation and rotation through the offset), drops 4, 5, 6, and three
/// rotational springs (CELAS1, components 4, 5, 6) join each dependent grid to
/// the independent one:
///   M_r = k_θ (θ_end − θ_ball) about each axis.
/// β = k_θ [N·m/rad] of every spring of the RBE2 (one per ball), or one k_θ for
/// every RBE2 at once (the "all joints" candidate). Prior N(k̄, k̄²) with
/// k̄ = 10 · max 4EI/L of the bars meeting at the ball (nearly rigid), k_θ ≥
/// 10⁻⁴ k̄; the iteration starts at k̄/10, k̄/100 and k̄/1000 (three candidates
/// per place; the diagnosis keeps the best of each place).
#include <algorithm>
#include <cmath>
#include <map>

#include "estimator/diagnosis/hypotheses/extension_util.hpp"
#include "estimator/diagnosis/hypotheses/model_extension.hpp"

namespace ssid::estimator::diagnosis::hypotheses {

namespace {

/// 4EI/L of the stiffest CBAR touching `grid` (0 when none).
double bending_rate(const formats::BulkModel& b, const FeModel& nominal, std::int64_t grid) {
  double best = 0;
  for (const auto& e : b.cbars) {
    if (e.ga != grid && e.gb != grid) continue;
    for (const auto& p : b.pbars)
      if (p.pid == e.pid) {
        const double L = (nominal.geometry().grid(e.gb, "joint").x - nominal.geometry().grid(e.ga, "joint").x).norm();
        if (L > 0) best = std::max(best, 4.0 * detail::young_modulus(b, p.mid) * std::max(p.i1, p.i2) / L);
      }
  }
  return best;
}

/// Starts of k_θ as fractions of k̄ = 10 · 4EI/L.
constexpr double kStarts[] = {0.1, 0.01, 0.001};

class JointFlexibility : public ModelExtension {
 public:
  explicit JointFlexibility(ExtensionOptions o) : m_options(std::move(o)) {}
  std::string kind() const override { return "joint_flexibility"; }
  std::string describe() const override {
    return "rotational springs between a rigid spider's centre and its ends (RBE2 keeps translations); parameter: "
           "the rotational rate [N m/rad] per ball, or one for all";
  }

  std::vector<Candidate> candidates(const FeModel& nominal) const override {
    std::vector<Candidate> out;
    Candidate all;
    all.kind = kind();
    for (const auto& r : nominal.bulk().rbe2s) {
      if (r.cm.find_first_of("456") == std::string::npos || r.gm.empty()) continue;
      const double k = rate(nominal, r);
      if (k <= 0) continue;
      Candidate c;
      c.kind = kind();
      c.ids = {r.eid};
      c.location.grids.push_back(r.gn);
      c.location.grids.insert(c.location.grids.end(), r.gm.begin(), r.gm.end());
      c.location.elements = {r.eid};
      c.location.text = "joints at grid " + std::to_string(r.gn) + " (RBE2 " + std::to_string(r.eid) + ")";
      // Several starts a decade apart: between a nearly rigid and a nearly
      // pinned joint the modes pass through the ball's own rotation modes,
      // and an estimate started on the wrong side can pair with those.
      for (double f : kStarts) {
        c.start = {f * 10.0 * k};
        out.push_back(c);
      }
      all.ids.push_back(r.eid);
      all.location.grids.push_back(r.gn);
      all.location.elements.push_back(r.eid);
    }
    const std::size_t places = out.size() / std::size(kStarts);
    if (places > 1) {
      all.ids.insert(all.ids.begin(), 0);  // 0 marks "one parameter for all"
      all.location.text = "every joint (" + std::to_string(places) + " RBE2)";
      std::vector<std::int64_t> eids(all.ids.begin() + 1, all.ids.end());
      for (double f : kStarts) {
        all.start = {f * 10.0 * max_rate(nominal, eids)};
        out.push_back(all);
      }
    }
    return out;
  }

  ExtendedDeck apply(const std::string& text, const std::string& name, const FeModel& nominal,
                     const Candidate& c) const override {
    DeckEditor ed(text, name);
    const bool shared = !c.ids.empty() && c.ids[0] == 0;
    std::vector<std::int64_t> eids(c.ids.begin() + (shared ? 1 : 0), c.ids.end());
    std::int64_t shared_pid = 0;
    for (std::size_t n = 0; n < eids.size(); ++n) {
      const formats::Rbe2* r = nullptr;
      for (const auto& x : ed.bulk().rbe2s)
        if (x.eid == eids[n]) r = &x;
      if (!r) throw std::invalid_argument("joint_flexibility: RBE2 " + std::to_string(eids[n]) + " not found");
      formats::Rbe2 changed = *r;
      changed.cm.erase(std::remove_if(changed.cm.begin(), changed.cm.end(), [](char ch) { return ch >= '4' && ch <= '6'; }),
                       changed.cm.end());
      ed.change(r->card, formats::write_rbe2(changed));
      std::int64_t pid = shared_pid;
      if (!shared || n == 0) {
        const double kbar = 10.0 * (shared ? max_rate(nominal, eids) : rate(nominal, *r));
        NewParameter p;
        p.label = shared ? std::string("XJALL") : detail::label("XJ", r->gn);
        p.prior_mean = kbar;
        p.prior_std = kbar;
        p.lower = 1e-4 * kbar;
        p.start = c.start.empty() ? kbar / 10.0 : c.start[0];
        p.meaning = std::string("rotational rate of the joints ") + (shared ? "everywhere" : "at grid " + std::to_string(r->gn)) +
                    " [N m/rad]";
        formats::Pelas pe;
        pe.pid = ed.new_property_id();
        pe.k = p.start;
        ed.comment("ssid diagnose: flexible joints " + std::string(shared ? "everywhere" : "at grid " + std::to_string(r->gn)));
        ed.append(formats::write_pelas(pe));
        const auto dv = ed.add_desvar(p, p.start);
        ed.add_dvprel1("PELAS", pe.pid, "K", dv, 1.0);
        pid = shared_pid = pe.pid;
      }
      for (auto gm : r->gm)
        for (std::int64_t comp = 4; comp <= 6; ++comp) {
          formats::Celas1 s;
          s.eid = ed.new_element_id();
          s.pid = pid;
          s.g1 = gm;
          s.c1 = comp;
          s.g2 = r->gn;
          s.c2 = comp;
          ed.append(formats::write_celas1(s));
        }
    }
    return {ed.text(), ed.parameters, "rotationally flexible joints at " + c.location.text};
  }

 private:
  static double rate(const FeModel& nominal, const formats::Rbe2& r) {
    double k = 0;
    for (auto g : r.gm) k = std::max(k, bending_rate(nominal.bulk(), nominal, g));
    return k;
  }
  static double max_rate(const FeModel& nominal, const std::vector<std::int64_t>& eids) {
    double k = 0;
    for (const auto& r : nominal.bulk().rbe2s)
      if (std::find(eids.begin(), eids.end(), r.eid) != eids.end()) k = std::max(k, rate(nominal, r));
    return k;
  }
  ExtensionOptions m_options;
};

}  // namespace

std::unique_ptr<ModelExtension> make_joint_flexibility(const ExtensionOptions& options) {
  return std::make_unique<JointFlexibility>(options);
}

}  // namespace ssid::estimator::diagnosis::hypotheses
