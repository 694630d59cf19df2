// DMIG assembly on a DOF map and matrices written back as DMIG.
#include <catch2/catch.hpp>

#include "formats/deck.hpp"
#include "formats/parse_error.hpp"
#include "translators/dmig_assembly.hpp"

using namespace ssid::formats;
using namespace ssid::translators;

namespace {

const char* kSym =
    "DMIG    KSYM    0       6       2\n"
    "DMIG    KSYM    10      1               10      1       4.0\n"
    "DMIG    KSYM    10      1               10      2       -1.0\n"
    "DMIG    KSYM    10      2               10      2       3.\n"
    "DMIG    KSYM    20      0               10      1       .5\n"
    "        20              5.0             10      2       2.0\n";

}  // namespace

TEST_CASE("DMIG assembly: symmetric matrix on a caller's DOF map (any order, extra DOFs)", "[dmig]") {
  Deck d = read_deck_text(kSym, "k.bdf");
  auto v = read_dmigs(d);
  REQUIRE(v.size() == 1);
  DofMap map;
  map.add({20, 0});  // c
  map.add({99, 3});  // not in the DMIG: a zero row/column
  map.add({10, 2});  // b
  map.add({10, 1});  // a
  Eigen::MatrixXd k = assemble_dmig_dense(v[0], map, map, &d);
  Eigen::MatrixXd expect(4, 4);
  // order c, x, b, a of [[4,-1,.5],[-1,3,2],[.5,2,5]] (a, b, c)
  expect << 5, 0, 2, .5,  //
      0, 0, 0, 0,         //
      2, 0, 3, -1,        //
      .5, 0, -1, 4;
  CHECK(k == expect);

  DmigDofs own = dmig_dofs(v[0]);
  REQUIRE(own.rows.size() == 3);
  CHECK(own.rows.at(0) == Dof{10, 1});
  CHECK(own.rows.at(2) == Dof{20, 0});
  Eigen::MatrixXd k2 = assemble_dmig_dense(v[0], own.rows, own.cols);
  Eigen::MatrixXd e2(3, 3);
  e2 << 4, -1, .5, -1, 3, 2, .5, 2, 5;
  CHECK(k2 == e2);

  DofMap small;
  small.add({10, 1});
  small.add({10, 2});
  try {
    assemble_dmig_real(v[0], small, small, &d);
    FAIL("no error");
  } catch (const ssid::formats::InputError& e) {
    CHECK(std::string(e.what()) ==
          "k.bdf:5: DMIG KSYM: row DOF (20,0) (grid/point, component) is not in the row DOF map (2 DOFs)");
  }
}

TEST_CASE("DMIG assembly: complex polar rectangular; real assembly of a complex DMIG refused", "[dmig]") {
  Deck d = read_deck_text(
      "DMIG    BP      0       2       3               1\n"
      "DMIG    BP      5       3               5       3       2.0     90.0\n"
      "        6       1       1.5     180.\n",
      "b.bdf");
  auto v = read_dmigs(d);
  DmigDofs own = dmig_dofs(v[0]);
  CHECK(own.rows.size() == 2);
  CHECK(own.cols.size() == 1);
  Eigen::MatrixXcd b = assemble_dmig_dense_complex(v[0], own.rows, own.cols);
  CHECK(b(0, 0) == std::complex<double>(0.0, 2.0));
  CHECK(b(1, 0) == std::complex<double>(-1.5, 0.0));
  CHECK_THROWS_AS(assemble_dmig_real(v[0], own.rows, own.cols), ssid::formats::InputError);
}

TEST_CASE("matrix -> DMIG -> cards -> DMIG -> matrix is exact (IFO 6 upper triangle, 2 complex, 9)", "[dmig]") {
  DofMap dofs;
  for (int g = 1; g <= 3; ++g)
    for (int c = 1; c <= 2; ++c) dofs.add({g * 100, c});
  dofs.add({7, 0});
  const Eigen::Index n = static_cast<Eigen::Index>(dofs.size());
  Eigen::MatrixXd s = Eigen::MatrixXd::Zero(n, n);
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index j = 0; j <= i; ++j)
      if ((i * 7 + j * 3) % 4 != 1) s(i, j) = s(j, i) = (i + 1.0) * 0.375 - j * 0.0625 + (i == j ? 1e-7 : 0.0);  // 16 characters hold them exactly
  SparseReal ss = s.sparseView();
  Dmig m = dmig_from_matrix(ss, dofs, dofs, {"KSYM", 6, 0, 0});
  CHECK(m.tin == 2);
  for (const auto& c : m.columns)
    for (const auto& t : c.terms) CHECK(*dofs.find({t.row.point, t.row.component}) <= *dofs.find({c.col.point, c.col.component}));
  for (FieldFormat f : {FieldFormat::Small, FieldFormat::Large}) {
    Deck d = read_deck_text(format_dmig(m, f), "w.bdf");
    auto back = read_dmigs(d);
    REQUIRE(back.size() == 1);
    CHECK(assemble_dmig_dense(back[0], dofs, dofs) == s);
  }
  Eigen::MatrixXd ns = s;
  ns(0, 1) += 1.0;
  SparseReal nss = ns.sparseView();
  CHECK_THROWS_AS(dmig_from_matrix(nss, dofs, dofs, {"K", 6, 0, 0}), ssid::formats::InputError);

  // Complex rectangular on different row/column maps.
  DofMap cols;
  cols.add({1, 0});
  cols.add({2, 0});
  Eigen::MatrixXcd z = Eigen::MatrixXcd::Zero(n, 2);
  z(0, 0) = {0.3125, -2.0e22};
  z(5, 1) = {0.0, 2.5e-100};
  z(6, 1) = {-4.5, 0.0};
  SparseComplex zs = z.sparseView();
  Dmig mz = dmig_from_matrix(zs, dofs, cols, {"BZ", 2, 0, 0});
  CHECK(mz.tin == 4);
  auto bz = read_dmigs(read_deck_text(format_dmig(mz), "z.bdf"));
  CHECK(assemble_dmig_dense_complex(bz[0], dofs, cols) == z);

  // IFO 9: columns by number, a null column in the middle kept by NCOL.
  Eigen::MatrixXd r = Eigen::MatrixXd::Zero(n, 3);
  r(2, 0) = 1.5;
  r(3, 2) = -2.0;
  SparseReal rs = r.sparseView();
  Dmig m9 = dmig_from_matrix(rs, dofs, DofMap{}, {"R9", 9, 1, 0});
  CHECK(m9.ncol == 3);
  auto b9 = read_dmigs(read_deck_text(format_dmig(m9), "r.bdf"));
  DmigDofs d9 = dmig_dofs(b9[0]);
  CHECK(d9.cols.size() == 3);
  CHECK(assemble_dmig_dense(b9[0], dofs, d9.cols) == r);
}

#include "formats/bulk_model.hpp"
#include "translators/assembly/model_geometry.hpp"

TEST_CASE("DMIG assembled on a deck's g-set (GRID 6 DOFs, SPOINT 1 DOF) as NASTRAN sequences it", "[dmig]") {
  const std::string text = std::string(
                               "BEGIN BULK\n"
                               "GRID    10              0.      0.      0.\n"
                               "SPOINT  20\n"
                               "GRID    30              1.      0.      0.\n") +
                           kSym + "ENDDATA\n";
  Deck d = read_deck_text(text, "g.bdf");
  const BulkModel model = parse_bulk(d);
  const ModelGeometry geo(d, model);
  REQUIRE(geo.gset().size() == 13);  // grid 10 (6), spoint 20 (1), grid 30 (6)
  auto v = read_dmigs(d);
  SparseReal k = assemble_dmig_real(v[0], geo.gset(), geo.gset(), &d);
  CHECK(k.rows() == 13);
  CHECK(k.nonZeros() == 9);
  const auto a = geo.dof(10, 1, "t"), b = geo.dof(10, 2, "t"), c = geo.dof(20, 0, "t");
  CHECK(k.coeff(a, a) == 4.0);
  CHECK(k.coeff(a, b) == -1.0);
  CHECK(k.coeff(b, a) == -1.0);
  CHECK(k.coeff(c, a) == 0.5);
  CHECK(k.coeff(a, c) == 0.5);
  CHECK(k.coeff(c, b) == 2.0);
  CHECK(k.coeff(c, c) == 5.0);
  // And back: the g-set matrix as DMIG cards gives the same matrix.
  Dmig w = dmig_from_matrix(k, geo.gset(), geo.gset(), {"KAAX", 6, 0, 0});
  auto again = read_dmigs(read_deck_text(format_dmig(w), "w.bdf"));
  CHECK(Eigen::MatrixXd(assemble_dmig_real(again[0], geo.gset(), geo.gset())) == Eigen::MatrixXd(k));
}
