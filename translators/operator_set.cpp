#include "translators/operator_set.hpp"

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "formats/parse_error.hpp"
#include "translators/assembly/fe_model.hpp"

namespace ssid::translators {

namespace fs = std::filesystem;
using nlohmann::json;

OperatorSet operators_from_model(const FeModel& model, const Eigen::VectorXd& x, bool derivatives,
                                 const std::string& source) {
  OperatorSet s;
  s.source = source;
  FeOperators op = model.operators(x, derivatives);
  s.K = std::move(op.K);
  s.M = std::move(op.M);
  s.dK = std::move(op.dK);
  s.dM = std::move(op.dM);
  const DofMap& g = model.geometry().gset();
  for (std::size_t gi : model.reduction().a_to_g) s.dofs.push_back(g.at(gi));
  for (const auto& p : model.geometry().grids()) s.grids.push_back({p.id, p.x, p.cp, p.cd});
  const auto& params = model.parameters();
  for (std::size_t j = 0; j < params.size(); ++j) {
    const auto& p = params[j];
    OperatorParameter q;
    q.id = p.id;
    q.label = p.label;
    q.value = x(static_cast<Eigen::Index>(j));
    q.lower = p.lower;
    q.upper = p.upper;
    q.designs = p.designs;
    q.method = "exact";
    s.parameters.push_back(std::move(q));
  }
  s.notes = model.notes();
  if (!model.autospc().empty()) {
    std::string list;
    for (std::size_t gi : model.autospc()) {
      const Dof& d = g.at(gi);
      list += (list.empty() ? "" : " ") + std::to_string(d.point) + ":" + std::to_string(d.component);
    }
    s.notes.push_back("AUTOSPC constrained " + std::to_string(model.autospc().size()) + " DOF(s) (grid:component): " +
                      list);
  }
  return s;
}

namespace {

std::string tag(const OperatorParameter& p, std::size_t j) {
  return std::to_string(p.id != 0 ? p.id : static_cast<std::int64_t>(j + 1));
}

void check_square(const Eigen::SparseMatrix<double>& A, std::size_t n, const std::string& what) {
  if (A.rows() != static_cast<Eigen::Index>(n) || A.cols() != static_cast<Eigen::Index>(n))
    throw std::invalid_argument(what + " is " + std::to_string(A.rows()) + " x " + std::to_string(A.cols()) +
                                ", expected " + std::to_string(n) + " x " + std::to_string(n) + " (the DOF map)");
}

}  // namespace

void write_operator_set(const OperatorSet& s, const std::string& dir, const formats::Op4WriteOptions& op4) {
  const std::size_t n = s.dofs.size();
  check_square(s.K, n, "K");
  check_square(s.M, n, "M");
  const bool deriv = !s.dK.empty();
  if (deriv && (s.dK.size() != s.parameters.size() || s.dM.size() != s.parameters.size()))
    throw std::invalid_argument("operator set: " + std::to_string(s.dK.size()) + " dK and " +
                                std::to_string(s.dM.size()) + " dM for " + std::to_string(s.parameters.size()) +
                                " parameters");
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw formats::InputError(dir + ": cannot create the folder: " + ec.message());

  json files, names;
  auto put = [&](const Eigen::SparseMatrix<double>& A, const std::string& file, const std::string& name) {
    formats::write_op4((fs::path(dir) / file).string(), {formats::Op4Matrix::from_real(name, A, formats::op4_form::Symmetric)},
                       op4);
  };
  put(s.K, "K.op4", "KAA");
  put(s.M, "M.op4", "MAA");
  files["K"] = "K.op4";
  files["M"] = "M.op4";
  names["K"] = "KAA";
  names["M"] = "MAA";
  files["dK"] = json::array();
  files["dM"] = json::array();
  names["dK"] = json::array();
  names["dM"] = json::array();
  if (deriv)
    for (std::size_t j = 0; j < s.parameters.size(); ++j) {
      const std::string t = tag(s.parameters[j], j);
      check_square(s.dK[j], n, "dK/dr for " + s.parameters[j].label);
      check_square(s.dM[j], n, "dM/dr for " + s.parameters[j].label);
      const std::string kn = ("DK" + t).substr(0, 8), mn = ("DM" + t).substr(0, 8);
      put(s.dK[j], "dK_" + t + ".op4", kn);
      put(s.dM[j], "dM_" + t + ".op4", mn);
      files["dK"].push_back("dK_" + t + ".op4");
      files["dM"].push_back("dM_" + t + ".op4");
      names["dK"].push_back(kn);
      names["dM"].push_back(mn);
    }

  json m;
  m["format"] = "ssid-operators";
  m["version"] = 1;
  m["source"] = s.source;
  m["set"] = s.set;
  m["dof"] = n;
  m["dofs"] = json::array();
  for (const auto& d : s.dofs) m["dofs"].push_back({d.point, d.component});
  m["grids"] = json::array();
  for (const auto& g : s.grids)
    m["grids"].push_back({{"id", g.id}, {"x", {g.x.x(), g.x.y(), g.x.z()}}, {"cp", g.cp}, {"cd", g.cd}});
  m["parameters"] = json::array();
  for (const auto& p : s.parameters) {
    json d = {{"method", p.method}};
    if (p.step != 0) d["step"] = p.step;
    m["parameters"].push_back({{"id", p.id},
                               {"label", p.label},
                               {"value", p.value},
                               {"lower", p.lower},
                               {"upper", p.upper},
                               {"designs", p.designs},
                               {"derivative", d}});
  }
  m["derivatives"] = deriv;
  m["files"] = files;
  m["matrices"] = names;
  m["op4"] = op4.encoding == formats::Op4Encoding::Ascii ? "ascii" : "binary";
  m["notes"] = s.notes;
  const std::string mp = (fs::path(dir) / "manifest.json").string();
  std::ofstream out(mp);
  out << m.dump(1) << "\n";
  if (!out) throw formats::InputError(mp + ": cannot write");
}

OperatorSet read_operator_set(const std::string& manifest_path) {
  std::ifstream in(manifest_path);
  if (!in) throw formats::InputError(manifest_path + ": cannot open the manifest");
  json m;
  try {
    m = json::parse(in);
  } catch (const json::exception& e) {
    throw formats::InputError(manifest_path + ": not valid JSON: " + e.what());
  }
  const fs::path base = fs::path(manifest_path).parent_path();
  auto need = [&](const json& j, const char* key) -> const json& {
    if (!j.is_object() || !j.contains(key)) throw formats::InputError(manifest_path + ": missing \"" + key + "\"");
    return j.at(key);
  };
  OperatorSet s;
  try {
    if (need(m, "format").get<std::string>() != "ssid-operators")
      throw formats::InputError(manifest_path + ": \"format\" is not \"ssid-operators\"");
    s.source = m.value("source", "");
    s.set = m.value("set", "a");
    for (const auto& d : need(m, "dofs")) s.dofs.push_back({d.at(0).get<std::int64_t>(), d.at(1).get<int>()});
    if (m.contains("grids"))
      for (const auto& g : m["grids"]) {
        OperatorGrid q;
        q.id = g.at("id").get<std::int64_t>();
        q.x = Eigen::Vector3d(g.at("x").at(0).get<double>(), g.at("x").at(1).get<double>(), g.at("x").at(2).get<double>());
        q.cp = g.value("cp", 0);
        q.cd = g.value("cd", 0);
        s.grids.push_back(q);
      }
    for (const auto& p : need(m, "parameters")) {
      OperatorParameter q;
      q.id = p.value("id", std::int64_t{0});
      q.label = p.at("label").get<std::string>();
      q.value = p.at("value").get<double>();
      q.lower = p.value("lower", -1e20);
      q.upper = p.value("upper", 1e20);
      if (p.contains("designs")) q.designs = p["designs"].get<std::vector<std::string>>();
      if (p.contains("derivative")) {
        q.method = p["derivative"].value("method", "exact");
        q.step = p["derivative"].value("step", 0.0);
      }
      s.parameters.push_back(std::move(q));
    }
    if (m.contains("notes")) s.notes = m["notes"].get<std::vector<std::string>>();
  } catch (const json::exception& e) {
    throw formats::InputError(manifest_path + ": unexpected content: " + e.what());
  }
  const std::size_t n = s.dofs.size();
  auto load = [&](const std::string& file) {
    const std::string p = (base / file).string();
    auto mats = formats::read_op4(p);
    if (mats.size() != 1 || mats[0].is_complex())
      throw formats::InputError(p + ": expected one real matrix, found " + std::to_string(mats.size()));
    if (mats[0].rows != static_cast<Eigen::Index>(n) || mats[0].cols != static_cast<Eigen::Index>(n))
      throw formats::InputError(p + ": matrix " + mats[0].name + " is " + std::to_string(mats[0].rows) + " x " +
                               std::to_string(mats[0].cols) + ", the manifest lists " + std::to_string(n) + " DOFs");
    return mats[0].real;
  };
  const json& files = need(m, "files");
  s.K = load(need(files, "K").get<std::string>());
  s.M = load(need(files, "M").get<std::string>());
  if (files.contains("dK") && !files["dK"].empty()) {
    if (files["dK"].size() != s.parameters.size() || files.value("dM", json::array()).size() != s.parameters.size())
      throw formats::InputError(manifest_path + ": \"files\" lists " + std::to_string(files["dK"].size()) + " dK and " +
                               std::to_string(files.value("dM", json::array()).size()) + " dM for " +
                               std::to_string(s.parameters.size()) + " parameters");
    for (std::size_t j = 0; j < s.parameters.size(); ++j) {
      s.dK.push_back(load(files["dK"][j].get<std::string>()));
      s.dM.push_back(load(files["dM"][j].get<std::string>()));
    }
  }
  return s;
}

}  // namespace ssid::translators
