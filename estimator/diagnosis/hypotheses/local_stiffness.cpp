/// \file local_stiffness.cpp
/// local_stiffness: one member (or the joint in it) stiffer or softer than
/// modelled — a loosened B-nut, a long fitting. The change is a CONROD in
/// parallel with the element, between its two grids, of the element's material,
/// its area ΔA = β designed by DVPREL1 (CONROD A = β). A negative ΔA softens.
/// With e the unit vector from GA to GB, L the length and E the modulus:
///   ∂K/∂β = (E/L) [e eᵀ, −e eᵀ; −e eᵀ, e eᵀ] on the translations of GA, GB
/// (rotated into each grid's displacement frame).
#include <cmath>

#include "estimator/diagnosis/hypotheses/extension_util.hpp"
#include "estimator/diagnosis/hypotheses/model_extension.hpp"

namespace ssid::estimator::diagnosis::hypotheses {

namespace {

struct Member {
  std::string type;
  std::int64_t eid = 0, pid = 0, mid = 0, ga = 0, gb = 0;
  double area = 0;
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
    if (const auto* p = pbar(e.pid)) out.push_back({"CBAR", e.eid, e.pid, p->mid, e.ga, e.gb, p->a});
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
           std::to_string(m_options.stiffness_prior_fraction) + " x the element's area)^2), dA >= -0.95 A";
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
};

}  // namespace

std::unique_ptr<ModelExtension> make_local_stiffness(const ExtensionOptions& options) {
  return std::make_unique<LocalStiffness>(options);
}

}  // namespace ssid::estimator::diagnosis::hypotheses
