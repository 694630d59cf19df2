// Operator import: difference quotients checked on matrices with known
// dependence on r (linear: every scheme exact; quadratic: central exact,
// one-sided off by h·K₂), manifest round trip, and the error messages.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <unistd.h>

#include "formats/dmig.hpp"
#include "formats/op4.hpp"
#include "translators/dmig_assembly.hpp"
#include "translators/operator_import.hpp"

using namespace ssid;
namespace fs = std::filesystem;
using Sp = Eigen::SparseMatrix<double>;

namespace {

fs::path scratch() {
  fs::path p = fs::temp_directory_path() / ("ssid_import_" + std::to_string(::getpid()));
  fs::create_directories(p);
  return p;
}

Sp sym(std::initializer_list<std::initializer_list<double>> rows) {
  Eigen::MatrixXd d(static_cast<Eigen::Index>(rows.size()), static_cast<Eigen::Index>(rows.size()));
  Eigen::Index i = 0;
  for (const auto& r : rows) {
    Eigen::Index j = 0;
    for (double v : r) d(i, j++) = v;
    ++i;
  }
  return d.sparseView();
}

const Sp K0 = sym({{4, -1, 0}, {-1, 4, -1}, {0, -1, 2}});
const Sp K1 = sym({{1, -1, 0}, {-1, 1, 0}, {0, 0, 0}});
const Sp K2 = sym({{0, 0, 0}, {0, 2, -2}, {0, -2, 2}});
const Sp M0 = sym({{1, 0, 0}, {0, 1, 0}, {0, 0, 0.5}});

void op4(const fs::path& p, const Sp& A, const std::string& name = "A") {
  formats::write_op4(p.string(), {formats::Op4Matrix::from_real(name, A, formats::op4_form::Symmetric)});
}

}  // namespace

TEST_CASE("import: central differences exact for quadratic K(r), one-sided off by h K2", "[import]") {
  const fs::path d = scratch() / "quad";
  fs::create_directories(d);
  // K(r) = K0 + r K1 + r² K2, M(r) = (1 + r) M0 around r0 = 2 with h = 0.1.
  auto K = [](double r) { return Sp(K0 + r * K1 + r * r * K2); };
  auto M = [](double r) { return Sp((1 + r) * M0); };
  const double r0 = 2.0, h = 0.1;
  op4(d / "K0.op4", K(r0));
  op4(d / "M0.op4", M(r0), "MAA");
  op4(d / "Kp.op4", K(r0 + h));
  op4(d / "Mp.op4", M(r0 + h));
  op4(d / "Km.op4", K(r0 - h));
  nlohmann::json spec = {{"K", "K0.op4"},
                         {"M", {{"file", "M0.op4"}, {"matrix", "MAA"}}},
                         {"dofs", {{7, 1}, {7, 2}, {8, 1}}},
                         {"parameters",
                          {{{"label", "C"}, {"value", r0}, {"plus", {{"value", r0 + h}, {"K", "Kp.op4"}, {"M", "Mp.op4"}}},
                            {"minus", {{"value", r0 - h}, {"K", "Km.op4"}}}},
                           {{"label", "F"}, {"value", r0}, {"plus", {{"value", r0 + h}, {"K", "Kp.op4"}}}},
                           {{"label", "B"}, {"value", r0}, {"minus", {{"value", r0 - h}, {"K", "Km.op4"}}}},
                           {{"label", "G"}, {"id", 9}, {"value", r0}, {"dK", "K0.op4"}}}}};
  std::ofstream(d / "spec.json") << spec.dump();
  const auto s = translators::import_operators((d / "spec.json").string());
  REQUIRE(s.parameters.size() == 4);
  CHECK(s.dofs[2] == translators::Dof{8, 1});
  const Sp exact = Sp(K1 + 2 * r0 * K2);
  auto err = [](const Sp& a, const Sp& b) { return (a - b).norm() / b.norm(); };
  CHECK(s.parameters[0].method == "central");
  CHECK(s.parameters[0].step == Approx(h));
  CHECK(err(s.dK[0], exact) < 1e-13);
  // The minus state has no M: M(r0 - h) taken as nominal, so dM = (M(r0+h) - M0)/(2h) = M0/2.
  CHECK(err(s.dM[0], Sp(0.5 * M0)) < 1e-13);
  CHECK(s.parameters[1].method == "forward");
  CHECK(err(s.dK[1], Sp(exact + h * K2)) < 1e-13);
  CHECK(s.dM[1].norm() == 0.0);
  CHECK(s.parameters[2].method == "backward");
  CHECK(err(s.dK[2], Sp(exact - h * K2)) < 1e-13);
  CHECK(s.parameters[3].method == "given");
  CHECK(s.parameters[3].id == 9);
  CHECK(err(s.dK[3], K(r0)) == 0.0);

  // Written and read back through the manifest.
  translators::write_operator_set(s, (d / "out").string());
  const auto back = translators::read_operator_set((d / "out" / "manifest.json").string());
  CHECK(back.parameters[1].method == "forward");
  CHECK(back.parameters[1].step == Approx(h));
  CHECK(err(back.dK[0], s.dK[0]) == 0.0);
  CHECK(back.dofs == s.dofs);
}

TEST_CASE("import: bad specs are named with the parameter and key", "[import][errors]") {
  const fs::path d = scratch() / "bad";
  fs::create_directories(d);
  op4(d / "K.op4", K0);
  op4(d / "M.op4", M0);
  op4(d / "K2.op4", sym({{1, 0}, {0, 1}}));
  auto run = [&](const nlohmann::json& j) {
    std::ofstream(d / "s.json") << j.dump();
    return translators::import_operators((d / "s.json").string());
  };
  CHECK_THROWS_WITH(run({{"K", "K.op4"}}), Catch::Contains("s.json: top level") && Catch::Contains("\"M\""));
  nlohmann::json base = {{"K", "K.op4"}, {"M", "M.op4"}};
  auto with = [&](nlohmann::json p) {
    nlohmann::json j = base;
    // array(), not {p}: GCC reads {p} as a one-element array, clang as a copy of p.
    j["parameters"] = nlohmann::json::array({p});
    return j;
  };
  CHECK_THROWS_WITH(run(with({{"label", "A"}, {"value", 1.0}, {"plus", {{"value", 1.0}, {"K", "K.op4"}}}})),
                    Catch::Contains("parameter 1 (A) plus: perturbed value equals the nominal value"));
  CHECK_THROWS_WITH(run(with({{"label", "A"}, {"value", 1.0}, {"plus", {{"value", 1.1}, {"K", "K2.op4"}}}})),
                    Catch::Contains("parameter 1 (A) plus K: matrix is 2 x 2, nominal K is 3 x 3"));
  CHECK_THROWS_WITH(run(with({{"label", "A"}, {"value", 1.0}})), Catch::Contains("needs \"plus\" and/or \"minus\""));
  CHECK_THROWS_WITH(run(with({{"label", "A"}, {"value", 1.0}, {"dK", "nope.op4"}})),
                    Catch::Contains("parameter 1 (A) dK") && Catch::Contains("nope.op4"));
  CHECK_THROWS_WITH(run(with({{"label", "A"}, {"value", 1.0}, {"dK", {{"file", "K.op4"}, {"matrix", "X"}}}})),
                    Catch::Contains("no matrix named X"));
  nlohmann::json j = with({{"label", "A"}, {"value", 1.0}, {"dK", "K.op4"}});
  j["dofs"] = {{1, 1}};
  CHECK_THROWS_WITH(run(j), Catch::Contains("dofs: 1 DOFs listed, the matrices have 3"));
  j.erase("dofs");
  const auto s = run(j);
  REQUIRE(s.notes.size() == 1);
  CHECK_THAT(s.notes[0], Catch::Contains("no DOF map"));
  CHECK_THROWS_WITH(translators::read_operator_set((d / "missing.json").string()), Catch::Contains("cannot open"));
}

TEST_CASE("import: DMIG sources in a punch file, on the DMIG's own grid/component DOFs", "[import][dmig]") {
  const fs::path d = scratch() / "dmig";
  fs::create_directories(d);
  // The quadratic K(r) of the OP4 test, written as symmetric DMIGs (upper
  // triangle only, as NASTRAN punches IFO 6) on grids 7 (T1, T2) and 8 (T1); M by OP4.
  translators::DofMap map;
  for (auto dof : {translators::Dof{7, 1}, translators::Dof{7, 2}, translators::Dof{8, 1}}) map.add(dof);
  auto K = [](double r) { return Sp(K0 + r * K1 + r * r * K2); };
  const double r0 = 2.0, h = 0.1;
  std::ofstream pch(d / "k.pch");
  for (auto [name, r] : {std::pair<const char*, double>{"KAAX", r0}, {"KAAP", r0 + h}, {"KAAM", r0 - h}}) {
    translators::DmigFromMatrix o;
    o.name = name;
    o.ifo = formats::dmig_form::Symmetric;
    pch << formats::format_dmig(translators::dmig_from_matrix(K(r), map, map, o));
  }
  pch.close();
  op4(d / "M0.op4", M0);
  auto dmig = [](const char* name) { return nlohmann::json{{"dmig", "k.pch"}, {"matrix", name}}; };
  nlohmann::json param;
  param["label"] = "C";
  param["value"] = r0;
  param["plus"] = {{"value", r0 + h}, {"K", dmig("KAAP")}};
  param["minus"] = {{"value", r0 - h}, {"K", dmig("KAAM")}};
  nlohmann::json spec;
  spec["K"] = dmig("KAAX");
  spec["M"] = "M0.op4";
  spec["parameters"] = nlohmann::json::array({param});
  std::ofstream(d / "spec.json") << spec.dump();
  const auto s = translators::import_operators((d / "spec.json").string());
  REQUIRE(s.dofs.size() == 3);
  CHECK(s.dofs[0] == translators::Dof{7, 1});
  CHECK(s.dofs[1] == translators::Dof{7, 2});
  CHECK(s.dofs[2] == translators::Dof{8, 1});
  CHECK((Sp(s.K - K(r0))).norm() <= 1e-14 * K(r0).norm());
  // Central differences of the exact quadratic: K1 + 2 r0 K2, up to the
  // 16-digit DMIG fields.
  const Sp exact = Sp(K1 + 2 * r0 * K2);
  CHECK((Sp(s.dK[0] - exact)).norm() / exact.norm() < 1e-12);

  // A DMIG name that is not there, and a "dofs" list that contradicts the DMIG's.
  spec["parameters"][0]["plus"]["K"]["matrix"] = "NOPE";
  std::ofstream(d / "bad.json") << spec.dump();
  CHECK_THROWS_WITH(translators::import_operators((d / "bad.json").string()),
                    Catch::Contains("no DMIG named NOPE") && Catch::Contains("parameter 1 (C)"));
  spec["parameters"][0]["plus"]["K"]["matrix"] = "KAAP";
  spec["dofs"] = {{8, 1}, {7, 1}, {7, 2}};
  std::ofstream(d / "order.json") << spec.dump();
  CHECK_THROWS_WITH(translators::import_operators((d / "order.json").string()),
                    Catch::Contains("differs from the DMIG's own DOFs"));
}
