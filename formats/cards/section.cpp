#include "formats/cards/section.hpp"

#include <map>

#include "formats/cards/card_values.hpp"

namespace ssid::formats {

int pbarl_dim_count(const std::string& type) {
  static const std::map<std::string, int> n = {
      {"ROD", 1},   {"TUBE", 2}, {"TUBE2", 2}, {"BAR", 2},   {"BOX", 4},  {"BOX1", 6},  {"I", 6},
      {"I1", 4},    {"CHAN", 4}, {"CHAN1", 4}, {"CHAN2", 4}, {"T", 4},    {"T1", 4},    {"T2", 4},
      {"L", 4},     {"H", 4},    {"Z", 4},     {"CROSS", 4}, {"HEXA", 3}, {"HAT", 4},   {"HAT1", 5},
      {"DBOX", 10},
  };
  auto it = n.find(type);
  return it == n.end() ? 0 : it->second;
}

bool pbarl_type_sectioned(const std::string& type) { return pbarl_dim_count(type) > 0; }

namespace {

std::string dim_name(const char* prefix, int k, const char* suffix) {
  return std::string(prefix) + std::to_string(k + 1) + suffix;
}

void read_dims(const FieldReader& r, std::size_t at, int n, const std::string& suffix, std::vector<double>& dims,
               const std::vector<double>* dflt) {
  dims.resize(n);
  for (int k = 0; k < n; ++k) {
    std::string name = dim_name("DIM", k, suffix.c_str());
    if (dflt && r.blank(at + k)) {
      dims[k] = (*dflt)[k];
      continue;
    }
    dims[k] = r.real(at + k, name.c_str());
    if (dims[k] <= 0.0) r.fail(at + k, name.c_str(), "real > 0.0");
  }
}

}  // namespace

Pbarl parse_pbarl(const FieldReader& r) {
  Pbarl p;
  p.pid = r.id(1, "PID");
  p.mid = r.id(2, "MID");
  p.group_blank = r.blank(3);
  p.group = r.text_or(3, "GROUP", "MSCBML0");
  p.type = r.text(4, "TYPE");
  for (std::size_t i = 5; i < 9; ++i)
    if (!r.blank(i)) r.fail(i, "(blank)", "blank");
  int n = pbarl_dim_count(p.type);
  p.known_type = n > 0;
  if (!p.known_type) {
    for (std::size_t i = 9; i < r.size(); ++i) p.dims.push_back(r.real_or(i, "DIM", 0.0));
    return p;
  }
  read_dims(r, 9, n, "", p.dims, nullptr);
  p.nsm = r.real_or(9 + n, "NSM", 0.0);
  r.at_most(10 + n);
  return p;
}

std::vector<FieldValue> write_pbarl(const Pbarl& p) {
  std::vector<FieldValue> v = {std::string("PBARL"), p.pid, p.mid,
                               p.group_blank && p.group == "MSCBML0" ? FieldValue() : FieldValue(p.group), p.type};
  put(v, 8, FieldValue());
  for (double d : p.dims) v.emplace_back(d);
  if (p.known_type) v.push_back(or_default(p.nsm, 0.0));
  trim_blanks(v);
  return v;
}

Pbeaml parse_pbeaml(const FieldReader& r) {
  Pbeaml p;
  p.pid = r.id(1, "PID");
  p.mid = r.id(2, "MID");
  p.group_blank = r.blank(3);
  p.group = r.text_or(3, "GROUP", "MSCBML0");
  p.type = r.text(4, "TYPE");
  for (std::size_t i = 5; i < 9; ++i)
    if (!r.blank(i)) r.fail(i, "(blank)", "blank");
  int n = pbarl_dim_count(p.type);
  p.known_type = n > 0;
  PbeamlStation a;
  a.xxb = 0.0;
  if (!p.known_type) {
    for (std::size_t i = 9; i < r.size(); ++i) a.dims.push_back(r.real_or(i, "DIM", 0.0));
    p.stations.push_back(a);
    return p;
  }
  read_dims(r, 9, n, "(A)", a.dims, nullptr);
  a.nsm = r.real_or(9 + n, "NSM(A)", 0.0);
  p.stations.push_back(a);
  for (std::size_t i = 10 + n; i < r.size(); i += n + 3) {
    PbeamlStation s;
    s.so = r.choice(i, "SO", {"YES", "YESA", "NO"}, "YES");
    s.xxb = r.real_or(i + 1, "X/XB", 1.0);
    if (s.xxb < 0.0 || s.xxb > 1.0) r.fail(i + 1, "X/XB", "real in [0.0, 1.0]");
    read_dims(r, i + 2, n, "", s.dims, &p.stations.front().dims);
    s.nsm = r.real_or(i + 2 + n, "NSM", 0.0);
    p.stations.push_back(s);
  }
  return p;
}

std::vector<FieldValue> write_pbeaml(const Pbeaml& p) {
  std::vector<FieldValue> v = {std::string("PBEAML"), p.pid, p.mid,
                               p.group_blank && p.group == "MSCBML0" ? FieldValue() : FieldValue(p.group), p.type};
  put(v, 8, FieldValue());
  for (std::size_t s = 0; s < p.stations.size(); ++s) {
    const PbeamlStation& st = p.stations[s];
    if (s > 0) {
      v.push_back(or_default(st.so, "YES"));
      v.push_back(or_default(st.xxb, 1.0));
    }
    for (double d : st.dims) v.emplace_back(d);
    if (p.known_type) v.push_back(or_default(st.nsm, 0.0));
  }
  trim_blanks(v);
  return v;
}

}  // namespace ssid::formats
