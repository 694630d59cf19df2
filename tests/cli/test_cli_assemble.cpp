// ssid assemble: K, M and exact derivatives written as OP4 with a manifest,
// checked against central differences of re-assembled operators; --import
// rebuilds the same set from perturbed OP4 exports. Fixture: a clamped space
// frame with six DESVARs (PBARL DIM1, PROD A, CONM2 M, PELAS K, MAT1 E, RHO).
#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <nlohmann/json.hpp>
#include <unistd.h>

#include "cli_run.hpp"
#include "formats/bulk_model.hpp"
#include "formats/deck.hpp"
#include "translators/assembly/fe_model.hpp"
#include "translators/operator_set.hpp"

namespace fs = std::filesystem;
using namespace ssid;

namespace {

fs::path scratch() { return cli_scratch("assemble"); }

const std::string kDeck = std::string(SSID_SOURCE_DIR) + "/samples/frame.bdf";

struct Model {
  formats::Deck deck;
  std::unique_ptr<translators::FeModel> fe;
};

Model load(const std::string& path) {
  Model m{formats::read_deck(path), nullptr};
  formats::BulkModel bulk = formats::parse_bulk(m.deck);
  formats::resolve(m.deck, bulk);
  m.fe = std::make_unique<translators::FeModel>(m.deck, std::move(bulk));
  return m;
}

double rel(const Eigen::SparseMatrix<double>& a, const Eigen::SparseMatrix<double>& b) {
  const double nb = b.norm();
  return (a - b).norm() / (nb > 0 ? nb : 1.0);
}

}  // namespace

TEST_CASE("ssid assemble: OP4 operators and manifest; derivatives equal central differences", "[cli][assemble]") {
  const fs::path dir = scratch() / "ops";
  auto r = run_ssid("assemble " + kDeck + " -o " + dir.string());
  INFO(r.err);
  REQUIRE(r.code == 0);
  const auto set = translators::read_operator_set((dir / "manifest.json").string());
  const Model m = load(kDeck);
  const auto& fe = *m.fe;
  const Eigen::VectorXd x0 = fe.initial_parameters();
  const auto op = fe.operators(x0, false);
  REQUIRE(set.dofs.size() == static_cast<std::size_t>(op.K.rows()));
  CHECK(rel(set.K, op.K) == 0.0);  // binary double: exact
  CHECK(rel(set.M, op.M) == 0.0);
  // DOF map: a-set index i ↔ (grid, component) as the model's reduction gives it.
  for (std::size_t i = 0; i < set.dofs.size(); ++i) {
    const auto& d = fe.geometry().gset().at(fe.reduction().a_to_g[i]);
    CHECK((set.dofs[i] == d));
  }
  auto j = nlohmann::json::parse(cli_slurp(dir / "manifest.json"));
  CHECK(j["set"] == "a");
  CHECK(j["grids"].size() == 16);
  CHECK(j["dof"] == 72);
  REQUIRE(set.parameters.size() == 6);
  REQUIRE(set.dK.size() == 6);
  CHECK(set.parameters[0].label == "ROUT");
  CHECK(set.parameters[0].value == x0(0));
  CHECK(set.parameters[0].lower == 0.017);
  CHECK(set.parameters[0].upper == 0.03);
  for (std::size_t p = 0; p < set.parameters.size(); ++p) {
    INFO("parameter " << set.parameters[p].label);
    CHECK(set.parameters[p].method == "exact");
    const double h = 1e-4 * std::abs(x0(static_cast<Eigen::Index>(p)));
    Eigen::VectorXd xp = x0, xm = x0;
    xp(static_cast<Eigen::Index>(p)) += h;
    xm(static_cast<Eigen::Index>(p)) -= h;
    const auto a = fe.operators(xp, false), b = fe.operators(xm, false);
    const Eigen::SparseMatrix<double> fdK = (a.K - b.K) / (2 * h), fdM = (a.M - b.M) / (2 * h);
    if (fdK.norm() > 0) CHECK(rel(set.dK[p], fdK) < 1e-7);
    else CHECK(set.dK[p].norm() == 0.0);
    if (fdM.norm() > 0) CHECK(rel(set.dM[p], fdM) < 1e-7);
    else CHECK(set.dM[p].norm() == 0.0);
    CHECK(set.dK[p].norm() + set.dM[p].norm() > 0);  // every parameter changes something
  }
  // --no-derivatives and --ascii.
  const fs::path d2 = scratch() / "ascii";
  REQUIRE(run_ssid("assemble " + kDeck + " -o " + d2.string() + " --ascii --no-derivatives").code == 0);
  const auto s2 = translators::read_operator_set((d2 / "manifest.json").string());
  CHECK(s2.dK.empty());
  CHECK(rel(s2.K, op.K) < 1e-15);
  CHECK(cli_slurp(d2 / "K.op4").find("1P,3E23.16") != std::string::npos);
  // --set assembles at another value.
  const fs::path d3 = scratch() / "set";
  REQUIRE(run_ssid("assemble " + kDeck + " -o " + d3.string() + " --no-derivatives --set KSPR=900").code == 0);
  const auto s3 = translators::read_operator_set((d3 / "manifest.json").string());
  Eigen::VectorXd x3 = x0;
  x3(3) = 900;
  CHECK(s3.parameters[3].value == 900);
  CHECK(rel(s3.K, fe.operators(x3, false).K) == 0.0);
  auto bad = run_ssid("assemble " + kDeck + " -o " + d3.string() + " --set NOPE=1");
  CHECK(bad.code == 2);
  CHECK_THAT(bad.err, Catch::Contains("no DESVAR with label or id NOPE"));
}

TEST_CASE("ssid assemble --import: perturbed exports rebuild the analytic operators", "[cli][assemble][import]") {
  const fs::path dir = scratch() / "import";
  fs::create_directories(dir);
  REQUIRE(run_ssid("assemble " + kDeck + " -o " + (dir / "exact").string()).code == 0);
  const auto exact = translators::read_operator_set((dir / "exact" / "manifest.json").string());
  REQUIRE(run_ssid("assemble " + kDeck + " -o " + (dir / "nominal").string() + " --no-derivatives").code == 0);
  nlohmann::json spec;
  spec["dofs"] = "nominal/manifest.json";
  spec["K"] = "nominal/K.op4";
  spec["M"] = {{"file", "nominal/M.op4"}, {"matrix", "MAA"}};
  spec["parameters"] = nlohmann::json::array();
  const double rh = 1e-4;
  for (std::size_t p = 0; p < exact.parameters.size(); ++p) {
    const auto& q = exact.parameters[p];
    const double h = rh * std::abs(q.value);
    nlohmann::json e = {{"label", q.label}, {"id", q.id}, {"value", q.value}, {"lower", q.lower}, {"upper", q.upper}};
    if (p == 3) {  // KSPR: derivatives exported directly
      e["dK"] = "exact/dK_4.op4";
      e["dM"] = {{"file", "exact/dM_4.op4"}, {"matrix", "DM4"}};
      spec["parameters"].push_back(e);
      continue;
    }
    for (int s : {+1, -1}) {
      if (p == 0 && s < 0) continue;  // ROUT: forward difference only
      const std::string tag = q.label + (s > 0 ? "_plus" : "_minus");
      char v[64];
      std::snprintf(v, sizeof v, "%.17g", q.value + s * h);
      auto r = run_ssid("assemble " + kDeck + " -o " + (dir / tag).string() + " --no-derivatives --set " + q.label +
                        "=" + v);
      REQUIRE(r.code == 0);
      e[s > 0 ? "plus" : "minus"] = {{"value", std::stod(v)}, {"K", tag + "/K.op4"}, {"M", tag + "/M.op4"}};
    }
    spec["parameters"].push_back(e);
  }
  std::ofstream(dir / "spec.json") << spec.dump(1);
  auto r = run_ssid("assemble --import " + (dir / "spec.json").string() + " -o " + (dir / "out").string());
  INFO(r.err);
  REQUIRE(r.code == 0);
  const auto imp = translators::read_operator_set((dir / "out" / "manifest.json").string());
  REQUIRE(imp.parameters.size() == exact.parameters.size());
  CHECK(imp.dofs == exact.dofs);
  CHECK(rel(imp.K, exact.K) == 0.0);
  for (std::size_t p = 0; p < imp.parameters.size(); ++p) {
    INFO("parameter " << imp.parameters[p].label);
    if (p == 3) {
      CHECK(imp.parameters[p].method == "given");
      CHECK(rel(imp.dK[p], exact.dK[p]) == 0.0);
      CHECK(imp.dM[p].norm() == 0.0);
      continue;
    }
    CHECK(imp.parameters[p].method == (p == 0 ? "forward" : "central"));
    CHECK(imp.parameters[p].step == Approx(rh * std::abs(exact.parameters[p].value)).epsilon(1e-6));
    // Central: O(h²) ≈ 1e-8 relative; forward: O(h) ≈ 1e-4 relative for the nonlinear
    // tube radius (both exact up to rounding when K, M are linear in r).
    const double tol = p == 0 ? 1e-3 : 1e-6;
    if (exact.dK[p].norm() > 0) CHECK(rel(imp.dK[p], exact.dK[p]) < tol);
    if (exact.dM[p].norm() > 0) CHECK(rel(imp.dM[p], exact.dM[p]) < tol);
  }
  // Errors name the spec and the parameter.
  spec["parameters"][0]["plus"]["K"] = "nominal/missing.op4";
  std::ofstream(dir / "bad.json") << spec.dump(1);
  auto b = run_ssid("assemble --import " + (dir / "bad.json").string() + " -o " + (dir / "bad").string());
  CHECK(b.code == 2);
  CHECK_THAT(b.err, Catch::Contains("bad.json: parameter 1 (ROUT) plus K"));
}

TEST_CASE("samples/import/make_exports.sh runs and its import matches the exact operators", "[cli][assemble][import][slow]") {
  const fs::path work = scratch() / "script";
  const std::string cmd = "SSID_IMPORT_WORK=" + work.string() + " sh " + std::string(SSID_SOURCE_DIR) +
                          "/samples/import/make_exports.sh " + std::string(SSID_EXE) + " >" +
                          (scratch() / "script.log").string() + " 2>&1";
  REQUIRE(std::system(cmd.c_str()) == 0);
  const auto imp = translators::read_operator_set((work / "imported" / "manifest.json").string());
  const auto exact = translators::read_operator_set((work / "exact" / "manifest.json").string());
  REQUIRE(imp.parameters.size() == 6);
  for (std::size_t p = 0; p < imp.parameters.size(); ++p) {
    INFO("parameter " << imp.parameters[p].label);
    CHECK(imp.parameters[p].id == exact.parameters[p].id);
    CHECK(imp.parameters[p].method == "central");
    if (exact.dK[p].norm() > 0) CHECK(rel(imp.dK[p], exact.dK[p]) < 1e-6);
    else CHECK(imp.dK[p].norm() == 0.0);
    if (exact.dM[p].norm() > 0) CHECK(rel(imp.dM[p], exact.dM[p]) < 1e-6);
    else CHECK(imp.dM[p].norm() == 0.0);
  }
}
