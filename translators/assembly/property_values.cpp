#include "translators/assembly/property_values.hpp"

#include <stdexcept>

namespace ssid::translators {

namespace {

using formats::BulkModel;

template <class V>
auto* find_pid(V& v, std::int64_t pid) {
  for (auto& p : v)
    if (p.pid == pid) return &p;
  return static_cast<typename V::value_type*>(nullptr);
}
template <class V>
auto* find_eid(V& v, std::int64_t eid) {
  for (auto& p : v)
    if (p.eid == eid) return &p;
  return static_cast<typename V::value_type*>(nullptr);
}

/// DIMi -> i-1, or -1.
int dim_index(const std::string& name) {
  if (name.size() < 4 || name.compare(0, 3, "DIM") != 0) return -1;
  for (std::size_t k = 3; k < name.size(); ++k)
    if (name[k] < '0' || name[k] > '9') return -1;
  return std::stoi(name.substr(3)) - 1;
}

[[noreturn]] void no_field(const std::string& type, std::int64_t id, const std::string& name) {
  throw std::invalid_argument(type + " " + std::to_string(id) + " has no designable field " + name);
}

/// Every double that holds the named value (several for multi-station beams).
std::vector<double*> slots(BulkModel& m, const ValueKey& k, std::string& type) {
  const std::string& n = k.name;
  if (k.owner == ValueOwner::Material) {
    type = "MAT1";
    for (auto& mat : m.mat1s)
      if (mat.mid == k.id) {
        if (n == "E") return {&mat.e};
        if (n == "G") return {&mat.g};
        if (n == "NU") return {&mat.nu};
        if (n == "RHO") return {&mat.rho};
        no_field(type, k.id, n);
      }
    throw std::invalid_argument("MAT1 " + std::to_string(k.id) + " does not exist");
  }
  if (k.owner == ValueOwner::Element) {
    if (auto* c = find_eid(m.conm2s, k.id)) {
      type = "CONM2";
      if (n == "M") return {&c->m};
      if (n == "X1") return {&c->x[0]};
      if (n == "X2") return {&c->x[1]};
      if (n == "X3") return {&c->x[2]};
      if (n == "I11") return {&c->i11};
      if (n == "I21") return {&c->i21};
      if (n == "I22") return {&c->i22};
      if (n == "I31") return {&c->i31};
      if (n == "I32") return {&c->i32};
      if (n == "I33") return {&c->i33};
      no_field(type, k.id, n);
    }
    if (auto* c = find_eid(m.celas2s, k.id)) {
      type = "CELAS2";
      if (n == "K") return {&c->k};
      no_field(type, k.id, n);
    }
    if (auto* c = find_eid(m.cmass2s, k.id)) {
      type = "CMASS2";
      if (n == "M") return {&c->m};
      no_field(type, k.id, n);
    }
    if (auto* c = find_eid(m.conrods, k.id)) {
      type = "CONROD";
      if (n == "A") return {&c->a};
      if (n == "J") return {&c->j};
      if (n == "NSM") return {&c->nsm};
      no_field(type, k.id, n);
    }
    throw std::invalid_argument("element " + std::to_string(k.id) + " is not a CONM2, CELAS2, CMASS2 or CONROD");
  }
  if (auto* p = find_pid(m.prods, k.id)) {
    type = "PROD";
    if (n == "A") return {&p->a};
    if (n == "J") return {&p->j};
    if (n == "NSM") return {&p->nsm};
    no_field(type, k.id, n);
  }
  if (auto* p = find_pid(m.pbars, k.id)) {
    type = "PBAR";
    if (n == "A") return {&p->a};
    if (n == "I1") return {&p->i1};
    if (n == "I2") return {&p->i2};
    if (n == "I12") return {&p->i12};
    if (n == "J") return {&p->j};
    if (n == "NSM") return {&p->nsm};
    if (n == "K1") return {&p->k1};
    if (n == "K2") return {&p->k2};
    no_field(type, k.id, n);
  }
  if (auto* p = find_pid(m.pbarls, k.id)) {
    type = "PBARL";
    if (n == "NSM") return {&p->nsm};
    const int i = dim_index(n);
    if (i >= 0 && i < static_cast<int>(p->dims.size())) return {&p->dims[static_cast<std::size_t>(i)]};
    no_field(type, k.id, n);
  }
  if (auto* p = find_pid(m.pbeams, k.id)) {
    type = "PBEAM";
    if (n == "A") { auto v = std::vector<double*>{&p->a}; for (auto& s : p->stations) v.push_back(&s.a); return v; }
    if (n == "I1") { auto v = std::vector<double*>{&p->i1}; for (auto& s : p->stations) v.push_back(&s.i1); return v; }
    if (n == "I2") { auto v = std::vector<double*>{&p->i2}; for (auto& s : p->stations) v.push_back(&s.i2); return v; }
    if (n == "I12") { auto v = std::vector<double*>{&p->i12}; for (auto& s : p->stations) v.push_back(&s.i12); return v; }
    if (n == "J") { auto v = std::vector<double*>{&p->j}; for (auto& s : p->stations) v.push_back(&s.j); return v; }
    if (n == "NSM") { auto v = std::vector<double*>{&p->nsm}; for (auto& s : p->stations) v.push_back(&s.nsm); return v; }
    if (n == "K1") return {&p->k1};
    if (n == "K2") return {&p->k2};
    no_field(type, k.id, n);
  }
  if (auto* p = find_pid(m.pbeamls, k.id)) {
    type = "PBEAML";
    std::vector<double*> out;
    const int i = dim_index(n);
    for (auto& s : p->stations) {
      if (n == "NSM") out.push_back(&s.nsm);
      else if (i >= 0 && i < static_cast<int>(s.dims.size())) out.push_back(&s.dims[static_cast<std::size_t>(i)]);
    }
    if (out.empty()) no_field(type, k.id, n);
    return out;
  }
  if (auto* p = find_pid(m.pelases, k.id)) {
    type = "PELAS";
    // NASTRAN's DVPREL1 names the first PELAS stiffness "K1" (the card's PID1/K1
    // pair); "K" is accepted as the field's plain name.
    if (n == "K" || n == "K1") return {&p->k};
    no_field(type, k.id, n);
  }
  if (auto* p = find_pid(m.pmasses, k.id)) {
    type = "PMASS";
    if (n == "M") return {&p->m};
    no_field(type, k.id, n);
  }
  if (auto* p = find_pid(m.pbushes, k.id)) {
    type = "PBUSH";
    for (int i = 0; i < 6; ++i)
      if (n == "K" + std::to_string(i + 1)) return {&p->k[static_cast<std::size_t>(i)]};
    no_field(type, k.id, n);
  }
  throw std::invalid_argument("property " + std::to_string(k.id) + " does not exist");
}

}  // namespace

bool ValueDelta::touches(ValueOwner owner, std::int64_t id) const {
  auto it = m_rates.lower_bound({owner, id, ""});
  return it != m_rates.end() && it->first.owner == owner && it->first.id == id;
}

std::string property_type(const formats::BulkModel& model, std::int64_t pid) {
  auto& m = const_cast<formats::BulkModel&>(model);
  if (find_pid(m.prods, pid)) return "PROD";
  if (find_pid(m.pbars, pid)) return "PBAR";
  if (find_pid(m.pbarls, pid)) return "PBARL";
  if (find_pid(m.pbeams, pid)) return "PBEAM";
  if (find_pid(m.pbeamls, pid)) return "PBEAML";
  if (find_pid(m.pelases, pid)) return "PELAS";
  if (find_pid(m.pmasses, pid)) return "PMASS";
  if (find_pid(m.pbushes, pid)) return "PBUSH";
  return "";
}

double get_value(const formats::BulkModel& model, const ValueKey& key) {
  std::string type;
  return *slots(const_cast<formats::BulkModel&>(model), key, type).front();
}

void set_value(formats::BulkModel& model, const ValueKey& key, double value) {
  std::string type;
  for (double* p : slots(model, key, type)) *p = value;
  if (key.owner != ValueOwner::Material) return;
  for (auto& mat : model.mat1s) {
    if (mat.mid != key.id) continue;
    const bool derived = (key.name == "E" && !mat.e_given) || (key.name == "G" && !mat.g_given) ||
                         (key.name == "NU" && !mat.nu_given);
    if (derived)
      throw std::invalid_argument("MAT1 " + std::to_string(key.id) + " field " + key.name +
                                  " is derived (blank on the card); give it on the MAT1 card to design it");
    const int given = int(mat.e_given) + int(mat.g_given) + int(mat.nu_given);
    if (given == 2) {
      if (!mat.g_given) mat.g = mat.e / (2.0 * (1.0 + mat.nu));
      else if (!mat.nu_given) mat.nu = mat.e / (2.0 * mat.g) - 1.0;
      else mat.e = 2.0 * (1.0 + mat.nu) * mat.g;
    }
  }
}

std::array<double, 3> mat1_rates(const formats::Mat1& m, double de, double dg, double dnu) {
  const int given = int(m.e_given) + int(m.g_given) + int(m.nu_given);
  if (given == 2) {
    if (!m.g_given) dg = de / (2.0 * (1.0 + m.nu)) - m.e * dnu / (2.0 * (1.0 + m.nu) * (1.0 + m.nu));
    else if (!m.nu_given) dnu = de / (2.0 * m.g) - m.e * dg / (2.0 * m.g * m.g);
    else de = 2.0 * (1.0 + m.nu) * dg + 2.0 * m.g * dnu;
  }
  return {de, dg, dnu};
}

}  // namespace ssid::translators
