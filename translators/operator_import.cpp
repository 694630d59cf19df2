#include "translators/operator_import.hpp"

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <map>
#include <optional>
#include <stdexcept>

#include "formats/dmig.hpp"
#include "formats/parse_error.hpp"
#include "translators/dmig_assembly.hpp"

namespace ssid::translators {

namespace fs = std::filesystem;
using nlohmann::json;
using SparseMatrix = Eigen::SparseMatrix<double>;

namespace {

struct Reader {
  std::string spec;
  fs::path base;
  [[noreturn]] void fail(const std::string& where, const std::string& what) const {
    throw formats::InputError(spec + ": " + where + ": " + what);
  }
  /// The DOF map of DMIG sources: the nominal K's DMIG DOFs, in increasing
  /// (point, component) order; every later DMIG is assembled on it.
  mutable std::optional<DofMap> dmig_map;
  /// DMIG files read so far: a punch file usually holds every state's matrices.
  mutable std::map<std::string, std::vector<formats::Dmig>> dmig_files;

  /// {"dmig": deck or .pch, "matrix": NAME}: a DMIG matrix (forms 1, 6 or 2 on
  /// the same DOFs), assembled on dmig_map.
  SparseMatrix dmig_matrix(const json& ref, const std::string& where) const {
    if (!ref.contains("matrix") || !ref["matrix"].is_string())
      fail(where, "{\"dmig\": ...} needs \"matrix\": the DMIG name");
    const std::string path = (base / ref["dmig"].get<std::string>()).string();
    const std::string name = ref["matrix"].get<std::string>();
    auto it = dmig_files.find(path);
    if (it == dmig_files.end()) {
      try {
        it = dmig_files.emplace(path, formats::read_dmig_file(path)).first;
      } catch (const formats::InputError& e) {  // the file's own error, placed in the spec
        fail(where, e.what());
      }
    }
    const std::vector<formats::Dmig>& all = it->second;
    const formats::Dmig* pick = nullptr;
    for (const auto& m : all)
      if (m.name == name) pick = &m;
    if (!pick) fail(where, path + ": no DMIG named " + name);
    try {
      if (!dmig_map) dmig_map = dmig_dofs(*pick).rows;
      return assemble_dmig_real(*pick, *dmig_map, *dmig_map);
    } catch (const formats::InputError& e) {  // the file's own error, placed in the spec
      fail(where, path + ": DMIG " + name + ": " + e.what() +
                      (dmig_map ? " (DMIG sources share the DOFs of the nominal K)" : ""));
    }
  }

  SparseMatrix matrix(const json& ref, const std::string& where) const {
    if (ref.is_object() && ref.contains("dmig") && ref["dmig"].is_string()) return dmig_matrix(ref, where);
    std::string file, name;
    if (ref.is_string()) file = ref.get<std::string>();
    else if (ref.is_object() && ref.contains("file") && ref["file"].is_string()) {
      file = ref["file"].get<std::string>();
      if (ref.contains("matrix")) name = ref["matrix"].get<std::string>();
    } else {
      fail(where, "expected an OP4 file name, {\"file\": ..., \"matrix\": ...} or {\"dmig\": ..., \"matrix\": ...}");
    }
    const std::string path = (base / file).string();
    std::vector<formats::Op4Matrix> mats;
    try {
      mats = formats::read_op4(path);
    } catch (const formats::InputError& e) {  // the file's own error, placed in the spec
      fail(where, e.what());
    }
    const formats::Op4Matrix* pick = nullptr;
    for (const auto& m : mats)
      if (name.empty() || m.name == name) {
        pick = &m;
        break;
      }
    if (!pick) fail(where, path + (name.empty() ? ": no matrix in the file" : ": no matrix named " + name));
    if (pick->is_complex()) fail(where, path + ": matrix " + pick->name + " is complex, expected real");
    if (pick->rows != pick->cols)
      fail(where, path + ": matrix " + pick->name + " is " + std::to_string(pick->rows) + " x " +
                      std::to_string(pick->cols) + ", expected square");
    return pick->real;
  }
  double number(const json& j, const char* key, const std::string& where) const {
    if (!j.contains(key) || !j[key].is_number()) fail(where, std::string("\"") + key + "\": expected a number");
    return j[key].get<double>();
  }
};

}  // namespace

OperatorSet import_operators(const std::string& spec_path) {
  std::ifstream in(spec_path);
  if (!in) throw formats::InputError(spec_path + ": cannot open the import spec");
  json spec;
  try {
    spec = json::parse(in);
  } catch (const json::exception& e) {
    throw formats::InputError(spec_path + ": not valid JSON: " + e.what());
  }
  Reader r;
  r.spec = spec_path;
  r.base = fs::path(spec_path).parent_path();
  if (!spec.is_object()) r.fail("top level", "expected an object");
  OperatorSet s;
  s.source = spec_path;
  if (!spec.contains("K") || !spec.contains("M")) r.fail("top level", "\"K\" and \"M\" (nominal OP4 files) are required");
  s.K = r.matrix(spec["K"], "K");
  s.M = r.matrix(spec["M"], "M");
  const Eigen::Index n = s.K.rows();
  auto check = [&](const SparseMatrix& A, const std::string& where) {
    if (A.rows() != n || A.cols() != n)
      r.fail(where, "matrix is " + std::to_string(A.rows()) + " x " + std::to_string(A.cols()) + ", nominal K is " +
                        std::to_string(n) + " x " + std::to_string(n));
  };
  check(s.M, "M");

  // DOF map.
  if (spec.contains("dofs")) {
    const json& d = spec["dofs"];
    if (d.is_string()) {
      const OperatorSet from = read_operator_set((r.base / d.get<std::string>()).string());
      s.dofs = from.dofs;
      s.grids = from.grids;
    } else if (d.is_array()) {
      for (const auto& e : d) {
        if (!e.is_array() || e.size() != 2) r.fail("dofs", "expected [grid, component] pairs");
        s.dofs.push_back({e[0].get<std::int64_t>(), e[1].get<int>()});
      }
    } else {
      r.fail("dofs", "expected a manifest file name or a list of [grid, component]");
    }
    if (static_cast<Eigen::Index>(s.dofs.size()) != n)
      r.fail("dofs", std::to_string(s.dofs.size()) + " DOFs listed, the matrices have " + std::to_string(n));
    if (r.dmig_map && !(s.dofs == r.dmig_map->dofs()))
      r.fail("dofs", "differs from the DMIG's own DOFs (in increasing grid, component order); leave \"dofs\" out");
  } else if (r.dmig_map) {
    s.dofs = r.dmig_map->dofs();  // the DMIG's own grid/component keys
  } else {
    for (Eigen::Index i = 0; i < n; ++i) s.dofs.push_back({static_cast<std::int64_t>(i + 1), 0});
    s.notes.push_back("no DOF map in the spec: DOF i is listed as point i, component 0");
  }

  if (!spec.contains("parameters") || !spec["parameters"].is_array())
    r.fail("top level", "\"parameters\": expected a list");
  std::size_t j = 0;
  for (const auto& p : spec["parameters"]) {
    ++j;
    const std::string where0 = "parameter " + std::to_string(j);
    if (!p.is_object() || !p.contains("label") || !p["label"].is_string()) r.fail(where0, "\"label\": expected a name");
    OperatorParameter q;
    q.label = p["label"].get<std::string>();
    const std::string where = where0 + " (" + q.label + ")";
    q.id = p.value("id", std::int64_t{0});
    q.value = r.number(p, "value", where);
    q.lower = p.value("lower", -1e20);
    q.upper = p.value("upper", 1e20);
    SparseMatrix dK, dM;
    const bool given = p.contains("dK") || p.contains("dM");
    const bool plus = p.contains("plus"), minus = p.contains("minus");
    if (given && (plus || minus)) r.fail(where, "give derivatives (dK, dM) or perturbed states (plus, minus), not both");
    if (given) {
      q.method = "given";
      dK = p.contains("dK") ? r.matrix(p["dK"], where + " dK") : SparseMatrix(n, n);
      dM = p.contains("dM") ? r.matrix(p["dM"], where + " dM") : SparseMatrix(n, n);
    } else {
      if (!plus && !minus) r.fail(where, "needs \"plus\" and/or \"minus\" perturbed states, or \"dK\"/\"dM\"");
      struct State {
        double x;
        SparseMatrix K, M;
      };
      auto state = [&](const char* key) {
        const json& st = p[key];
        const std::string w = where + " " + key;
        if (!st.is_object()) r.fail(w, "expected {\"value\": ..., \"K\": ..., \"M\": ...}");
        State out{r.number(st, "value", w), st.contains("K") ? r.matrix(st["K"], w + " K") : s.K,
                  st.contains("M") ? r.matrix(st["M"], w + " M") : s.M};
        if (!st.contains("K") && !st.contains("M")) r.fail(w, "neither \"K\" nor \"M\" given");
        check(out.K, w + " K");
        check(out.M, w + " M");
        if (out.x == q.value) r.fail(w, "perturbed value equals the nominal value " + std::to_string(q.value));
        return out;
      };
      if (plus && minus) {
        const State a = state("plus"), b = state("minus");
        const double dx = a.x - b.x;
        dK = (a.K - b.K) / dx;
        dM = (a.M - b.M) / dx;
        q.method = "central";
        q.step = dx / 2;
      } else if (plus) {
        const State a = state("plus");
        const double dx = a.x - q.value;
        dK = (a.K - s.K) / dx;
        dM = (a.M - s.M) / dx;
        q.method = "forward";
        q.step = dx;
      } else {
        const State b = state("minus");
        const double dx = q.value - b.x;
        dK = (s.K - b.K) / dx;
        dM = (s.M - b.M) / dx;
        q.method = "backward";
        q.step = dx;
      }
    }
    check(dK, where + " dK");
    check(dM, where + " dM");
    dK.prune(0.0);
    dM.prune(0.0);
    s.dK.push_back(std::move(dK));
    s.dM.push_back(std::move(dM));
    s.parameters.push_back(std::move(q));
  }
  return s;
}

}  // namespace ssid::translators
