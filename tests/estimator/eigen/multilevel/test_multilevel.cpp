// The multilevel eigen-solver: its kernels against Eigen's products, the
// aggregation preconditioner (symmetric, positive, and a strong one: conjugate
// gradients converge in a few steps), LOBPCG against a dense solve, and the whole
// method against the direct (CHOLMOD + Lanczos) solver on an irregular 3D frame
// assembled from a deck.
#include <Eigen/Dense>
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <random>
#include <sstream>
#include <utility>

#include "estimator/eigen/eigen_solver.hpp"
#include "estimator/eigen/multilevel/aggregation_amg.hpp"
#include "estimator/eigen/multilevel/block_ops.hpp"
#include "estimator/eigen/multilevel/lobpcg.hpp"
#include "formats/bulk_model.hpp"
#include "formats/deck.hpp"
#include "translators/assembly/fe_model.hpp"
#include "translators/assembly/rigid_modes.hpp"
#include "tests/estimator/eigen/eigen_test_models.hpp"

using namespace ssid;
using namespace ssid::estimator;
using multilevel::RowBlock;

namespace {

/// A free 3D frame of nx x ny x nz grids about 1 m apart, positions jittered by up
/// to ±0.15 m, every lattice edge a CBAR (two sections alternating), lumped mass
/// (massless rotations), one CONM2 of 40 kg on a corner: irregular, no symmetry.
std::string frame_deck(int nx, int ny, int nz) {
  std::ostringstream s;
  s << "SOL 103\nCEND\nBEGIN BULK\n";
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> j(-0.15, 0.15);
  auto id = [&](int i, int k, int l) { return 1 + i + nx * (k + ny * l); };
  for (int l = 0; l < nz; ++l)
    for (int k = 0; k < ny; ++k)
      for (int i = 0; i < nx; ++i)
        s << "GRID," << id(i, k, l) << ",," << i + j(rng) << "," << k + j(rng) << "," << l + j(rng) << "\n";
  int eid = 1;
  for (int l = 0; l < nz; ++l)
    for (int k = 0; k < ny; ++k)
      for (int i = 0; i < nx; ++i)
        for (int d = 0; d < 3; ++d) {
          const int i2 = i + (d == 0), k2 = k + (d == 1), l2 = l + (d == 2);
          if (i2 >= nx || k2 >= ny || l2 >= nz) continue;
          s << "CBAR," << eid << "," << 1 + eid % 2 << "," << id(i, k, l) << "," << id(i2, k2, l2)
            << (d == 0 ? ",0.,1.,0.\n" : ",1.,0.,0.\n");
          ++eid;
        }
  s << "PBAR,1,1,1.e-3,1.e-6,2.e-6,2.e-6\nPBAR,2,1,2.e-3,3.e-6,1.e-6,3.e-6\n";
  s << "MAT1,1,2.1e11,8.1e10,,7850.\n";
  s << "CONM2,900001," << id(nx - 1, ny - 1, nz - 1) << ",,40.\n";
  s << "ENDDATA\n";
  return s.str();
}

struct Frame {
  translators::FeOperators op;
  std::vector<long> groups;
  Eigen::MatrixXd rigid;   // a-set rigid-body modes
  Eigen::MatrixXd strain;  // a-set constant-strain fields
};

Frame frame(int nx, int ny, int nz) {
  const formats::Deck deck = formats::read_deck_text(frame_deck(nx, ny, nz), "frame.bdf");
  formats::BulkModel bulk = formats::parse_bulk(deck);
  formats::resolve(deck, bulk);
  REQUIRE(bulk.problems.empty());
  const translators::FeModel model(deck, std::move(bulk));
  Frame f;
  f.op = model.operators(model.initial_parameters(), false);
  const auto& a_to_g = model.reduction().a_to_g;
  REQUIRE(static_cast<long>(a_to_g.size()) == f.op.K.rows());
  for (const std::size_t g : a_to_g) f.groups.push_back(static_cast<long>(model.geometry().gset().at(g).point));
  f.rigid = translators::a_set_rigid_body_modes(model);
  f.strain = translators::a_set_strain_fields(model);
  return f;
}

Eigen::MatrixXd dense(const RowBlock& X) { return Eigen::MatrixXd(X); }

}  // namespace

TEST_CASE("multilevel block kernels agree with Eigen's products", "[multilevel]") {
  const auto [K, M] = test::random_pencil(60, 11);
  const Eigen::SparseMatrix<double, Eigen::RowMajor> R = Eigen::MatrixXd::Random(40, 60).sparseView(0.5, 1.0);
  const Eigen::SparseMatrix<double, Eigen::RowMajor> Rc = Eigen::MatrixXd::Random(60, 25).sparseView(0.5, 1.0);
  const RowBlock X = Eigen::MatrixXd::Random(60, 7), Y = Eigen::MatrixXd::Random(60, 5);
  RowBlock Z;
  multilevel::sym_times(K, X, Z);
  CHECK((dense(Z) - K * dense(X)).norm() <= 1e-13 * (K * dense(X)).norm());
  multilevel::times(R, X, Z);
  CHECK((dense(Z) - R * dense(X)).norm() <= 1e-13 * (R * dense(X)).norm());
  multilevel::transpose_times(Rc, X, Z);
  CHECK((dense(Z) - Rc.transpose() * dense(X)).norm() <= 1e-13 * (Rc.transpose() * dense(X)).norm());
  const Eigen::MatrixXd G = multilevel::gram(X, Y);
  CHECK((G - dense(X).transpose() * dense(Y)).norm() <= 1e-13 * G.norm());
  const Eigen::MatrixXd C = Eigen::MatrixXd::Random(7, 3);
  RowBlock XC;
  multilevel::times_dense_into(X, C, 0.0, XC);
  CHECK((dense(XC) - dense(X) * C).norm() <= 1e-13 * (dense(X) * C).norm());
  multilevel::times_dense_into(X, C, 1.0, XC);  // accumulates
  CHECK((dense(XC) - 2.0 * dense(X) * C).norm() <= 1e-13 * (dense(X) * C).norm());
}

TEST_CASE("multilevel kernels split over the cores agree with Eigen's products", "[multilevel][slow]") {
  // Large enough that the dense products are split by rows (one serial BLAS call
  // per thread, partial Gram matrices summed), the sparse product by columns and
  // the transposed product by rows (scattered into a copy per thread).
  const long n = std::max<long>(40000, 2 * 8192 * multilevel::worker_threads() + 7);  // split at 8192 rows a thread
  std::mt19937 rng(21);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  RowBlock X(n, 6), Y(n, 4);
  for (Eigen::Index i = 0; i < X.size(); ++i) X.data()[i] = u(rng);
  for (Eigen::Index i = 0; i < Y.size(); ++i) Y.data()[i] = u(rng);
  const Eigen::MatrixXd G = multilevel::gram(X, Y), Gd = dense(X).transpose() * dense(Y);
  CHECK((G - Gd).norm() <= 1e-12 * Gd.norm());
  const Eigen::MatrixXd Gh = multilevel::gram(X, Y, n / 2 + 7), Ghd = dense(X).topRows(n / 2 + 7).transpose() * dense(Y).topRows(n / 2 + 7);
  CHECK((Gh - Ghd).norm() <= 1e-12 * Ghd.norm());
  const Eigen::MatrixXd C = Eigen::MatrixXd::Random(6, 3);
  RowBlock XC;
  multilevel::times_dense_into(X, C, 0.0, XC);
  CHECK((dense(XC) - dense(X) * C).norm() <= 1e-13 * (dense(X) * C).norm());
  multilevel::times_dense_into(X, C, 2.0, XC);  // Y = 2 Y + X C
  CHECK((dense(XC) - 3.0 * dense(X) * C).norm() <= 1e-13 * (dense(X) * C).norm());

  // A banded symmetric matrix: the fused residual forms of the product.
  std::vector<Eigen::Triplet<double>> t;
  for (long i = 0; i < n; ++i)
    for (long j = std::max(0L, i - 3); j <= std::min(n - 1, i + 3); ++j)
      if (j <= i) {
        const double v = i == j ? 10.0 : u(rng);
        t.emplace_back(i, j, v);
        if (j != i) t.emplace_back(j, i, v);
      }
  Eigen::SparseMatrix<double> A(n, n);
  A.setFromTriplets(t.begin(), t.end());
  A.makeCompressed();
  const Eigen::MatrixXd AX = A * dense(X);
  RowBlock Z;
  multilevel::sym_residual(A, X, X, Z);  // X − A X
  CHECK((dense(Z) - (dense(X) - AX)).norm() <= 1e-13 * AX.norm());
  multilevel::sym_subtract(A, X, Z);  // X − 2 A X
  CHECK((dense(Z) - (dense(X) - 2.0 * AX)).norm() <= 1e-13 * AX.norm());
  const Eigen::SparseMatrix<double, Eigen::RowMajor> Ar = A;
  multilevel::times_add(Ar, X, Z);  // X − A X
  CHECK((dense(Z) - (dense(X) - AX)).norm() <= 1e-13 * AX.norm());
  {
    // The transposed product, scattered by rows into one copy of Z per thread, of
    // a matrix that is not symmetric (Aᵀ X and A X differ).
    Eigen::SparseMatrix<double, Eigen::RowMajor> N = Ar;
    for (long i = 0; i + 5 < n; i += 7) N.coeffRef(i, i + 5) += 3.0;
    N.makeCompressed();
    multilevel::transpose_times(N, X, Z);
    const Eigen::MatrixXd NtX = Eigen::SparseMatrix<double>(N.transpose()) * dense(X);
    CHECK((dense(Z) - NtX).norm() <= 1e-13 * NtX.norm());
    CHECK((NtX - AX).norm() > 1.0);
  }

  // The Galerkin product's lower triangle, column blocks of uneven widths (an
  // aggregate may carry fewer than six coarse DOFs), against Eigen's Pᵀ A P.
  {
    const Eigen::SparseMatrix<double> P = Eigen::MatrixXd::Random(n, 23).sparseView(0.995, 1.0);
    const Eigen::SparseMatrix<double, Eigen::RowMajor> Prow = P;
    const std::vector<long> starts = {0, 6, 12, 13, 18, 23};
    const Eigen::MatrixXd G = Eigen::MatrixXd(multilevel::galerkin_lower(A, P, Prow, starts));
    const Eigen::MatrixXd Ge = Eigen::MatrixXd(Eigen::SparseMatrix<double>(P.transpose()) * (A * P));
    const Eigen::MatrixXd Gl = Ge.triangularView<Eigen::Lower>();
    CHECK(P.nonZeros() > 1000);
    CHECK((G - Gl).norm() <= 1e-13 * Ge.norm());
    CHECK(G.triangularView<Eigen::StrictlyUpper>().toDenseMatrix().norm() == 0.0);
  }

  // Sparse times sparse, split by columns, against Eigen's.
  const Eigen::SparseMatrix<double> B = Eigen::MatrixXd::Random(n, 300).sparseView(0.9, 1.0);
  const Eigen::SparseMatrix<double> AB = multilevel::parallel_product(A, B), ABe = A * B;
  CHECK(AB.nonZeros() == ABe.nonZeros());
  CHECK((Eigen::MatrixXd(AB) - Eigen::MatrixXd(ABe)).norm() <= 1e-14 * Eigen::MatrixXd(ABe).norm());
}

namespace {

/// The sparse block kernels and the block-Jacobi pass in precision T against Eigen
/// in double, for a block of b columns.
template <class T>
void check_kernels_at_width(long b, double tol) {
  using Block = multilevel::RowBlockOf<T>;
  using Dense = Eigen::Matrix<T, Eigen::Dynamic, Eigen::Dynamic>;
  const long n = 37;
  std::mt19937 rng(static_cast<unsigned>(b));
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Eigen::Triplet<T>> t;
  for (long i = 0; i < n; ++i)
    for (long j = 0; j <= i; ++j)
      if (i == j || u(rng) > 0.6) {
        const T v = static_cast<T>(i == j ? 8.0 : u(rng));
        t.emplace_back(i, j, v);
        if (i != j) t.emplace_back(j, i, v);
      }
  Eigen::SparseMatrix<T> A(n, n);
  A.setFromTriplets(t.begin(), t.end());
  A.makeCompressed();
  Eigen::SparseMatrix<T, Eigen::RowMajor> R = Dense(Dense::Random(n, 23)).sparseView(T(0.5), T(1));
  R.makeCompressed();
  Block X(n, b), B(n, b), Xs(23, b);
  for (Eigen::Index i = 0; i < X.size(); ++i) X.data()[i] = static_cast<T>(u(rng)), B.data()[i] = static_cast<T>(u(rng));
  for (Eigen::Index i = 0; i < Xs.size(); ++i) Xs.data()[i] = static_cast<T>(u(rng));
  const Eigen::MatrixXd Ad = Eigen::MatrixXd(A.template cast<double>()), Rd = Eigen::MatrixXd(R.template cast<double>());
  const Eigen::MatrixXd Xd = Eigen::MatrixXd(X.template cast<double>()), Bd = Eigen::MatrixXd(B.template cast<double>());
  const Eigen::MatrixXd AX = Ad * Xd;
  auto err = [](const Block& Z, const Eigen::MatrixXd& ref) {
    return (Eigen::MatrixXd(Z.template cast<double>()) - ref).norm() / ref.norm();
  };
  Block Z;
  multilevel::sym_times(A, X, Z);
  CHECK(err(Z, AX) <= tol);
  multilevel::sym_residual(A, X, B, Z);
  CHECK(err(Z, Bd - AX) <= tol);
  Z = B;
  multilevel::sym_subtract(A, X, Z);
  CHECK(err(Z, Bd - AX) <= tol);
  multilevel::times(R, Xs, Z);
  const Eigen::MatrixXd RXs = Rd * Eigen::MatrixXd(Xs.template cast<double>());
  CHECK(err(Z, RXs) <= tol);
  Z = B;
  multilevel::times_add(R, Xs, Z);
  CHECK(err(Z, Bd + RXs) <= tol);
  multilevel::transpose_times(R, X, Z);
  CHECK(err(Z, Rd.transpose() * Xd) <= tol);

  // Block Jacobi over grid points of 1, 2 and 3 DOFs (scattered rows), D⁻¹ dense per block.
  const std::vector<long> start = {0, 3, 4, 6, 9, 10};
  const std::vector<long> dofs = {5, 0, 12, 7, 30, 2, 11, 19, 36, 4};
  std::vector<long> dinv_start = {0};
  for (size_t g = 0; g + 1 < start.size(); ++g) {
    const long k = start[g + 1] - start[g];
    dinv_start.push_back(dinv_start.back() + k * k);
  }
  std::vector<T> dinv(static_cast<size_t>(dinv_start.back()));
  for (auto& v : dinv) v = static_cast<T>(u(rng));
  Eigen::MatrixXd Dinv = Eigen::MatrixXd::Zero(n, n);
  for (size_t g = 0; g + 1 < start.size(); ++g) {
    const long s0 = start[g], k = start[g + 1] - s0;
    for (long i = 0; i < k; ++i)
      for (long j = 0; j < k; ++j)
        Dinv(dofs[static_cast<size_t>(s0 + i)], dofs[static_cast<size_t>(s0 + j)]) = dinv[static_cast<size_t>(dinv_start[g] + i * k + j)];
  }
  const multilevel::GridBlocks<T> blocks{&start, &dofs, &dinv_start, dinv.data()};
  Eigen::MatrixXd inside = Eigen::MatrixXd::Zero(n, b);  // rows the blocks cover
  for (const long r : dofs) inside.row(r).setOnes();
  Block d = B, Xj = X;
  multilevel::block_jacobi_pass(blocks, B, 0.5, 2.0, d, Xj, false);  // d = 0.5 d + 2 D⁻¹ B, X += d
  const Eigen::MatrixXd dref = (0.5 * Bd + 2.0 * Dinv * Bd).cwiseProduct(inside);
  const Eigen::MatrixXd dgot = Eigen::MatrixXd(d.template cast<double>()).cwiseProduct(inside);
  CHECK((dgot - dref).norm() <= tol * dref.norm());
  const Eigen::MatrixXd xgot = Eigen::MatrixXd(Xj.template cast<double>()).cwiseProduct(inside);
  CHECK((xgot - (Xd.cwiseProduct(inside) + dref)).norm() <= tol * dref.norm());
  multilevel::block_jacobi_pass(blocks, B, 0.0, 1.0, d, Xj, true);  // d = X = D⁻¹ B on the blocks' rows
  const Eigen::MatrixXd zref = (Dinv * Bd).cwiseProduct(inside);
  CHECK((Eigen::MatrixXd(d.template cast<double>()).cwiseProduct(inside) - zref).norm() <= tol * zref.norm());
  CHECK((Eigen::MatrixXd(Xj.template cast<double>()).cwiseProduct(inside) - zref).norm() <= tol * zref.norm());
}

}  // namespace

TEST_CASE("multilevel kernels agree with Eigen at every register-tile width", "[multilevel]") {
  // Widths that take each tile (four, two, one 64-byte vectors, 32 and 16 bytes,
  // single values) alone and together, in both precisions.
  for (const long b : {1L, 2L, 3L, 4L, 5L, 7L, 8L, 12L, 15L, 16L, 17L, 31L, 32L, 45L, 64L, 67L, 130L}) {
    CAPTURE(b);
    check_kernels_at_width<double>(b, 1e-14);
    check_kernels_at_width<float>(b, 1e-5);
  }
}

TEST_CASE("aggregation preconditioner: symmetric, positive definite, and conjugate gradients converge fast",
          "[multilevel][slow]") {
  const Frame f = frame(9, 8, 7);
  const double sigma = automatic_shift(f.op.K, f.op.M);
  Eigen::SparseMatrix<double> A = f.op.K - sigma * f.op.M;
  A.makeCompressed();
  const multilevel::AggregationAmg amg(A, f.groups, f.rigid);
  const long n = A.rows();
  INFO("n " << n << ", aggregates " << amg.aggregates() << ", coarse " << amg.coarse_size());
  CHECK(amg.coarse_size() < n / 4);
  CHECK(amg.coarse_size() == 6 * amg.aggregates());  // six rigid-body modes on every aggregate

  // Symmetric and positive: to round-off in double, to single precision's
  // round-off in float (a relative 6e-8 per operation; 1e-8 measured here).
  multilevel::AmgOptions in_double;
  in_double.single_precision = false;
  const multilevel::AggregationAmg amg_double(A, f.groups, f.rigid, in_double);
  const RowBlock XY = Eigen::MatrixXd::Random(n, 2);
  for (const auto* cycle : {&amg_double, &amg}) {
    RowBlock T;
    cycle->apply(XY, T);
    const double xty = XY.col(0).dot(T.col(1)), ytx = XY.col(1).dot(T.col(0));
    const double tol = cycle == &amg_double ? 1e-10 : 1e-6;
    INFO((cycle == &amg_double ? "double" : "single") << " precision: asymmetry " << std::abs(xty - ytx));
    CHECK(std::abs(xty - ytx) <= tol * std::sqrt(XY.col(0).dot(T.col(0)) * XY.col(1).dot(T.col(1))));
    CHECK(XY.col(0).dot(T.col(0)) > 0.0);
    CHECK(XY.col(1).dot(T.col(1)) > 0.0);
  }
  // The single-precision cycle is the double one to single precision: to 1e-5
  // with the coarse factor in double (6e-7 measured); with the coarse factor in
  // single precision too (the default), to single precision's round-off amplified
  // by the coarse matrix's condition number (about 10⁴: 1e-4 measured).
  multilevel::AmgOptions float_cycle_double_coarse;
  float_cycle_double_coarse.coarse_single_precision = false;
  const multilevel::AggregationAmg amg_mixed(A, f.groups, f.rigid, float_cycle_double_coarse);
  CHECK(amg_mixed.coarse_factor_single() == nullptr);
  CHECK(amg.coarse_factor_single() != nullptr);
  CHECK_FALSE(amg.coarse_factor().factorized());  // no double factor was computed
  RowBlock Td, Ts, Tm;
  amg_double.apply(XY, Td);
  amg.apply(XY, Ts);
  amg_mixed.apply(XY, Tm);
  CHECK((dense(Tm) - dense(Td)).norm() <= 1e-5 * dense(Td).norm());
  CHECK((dense(Ts) - dense(Td)).norm() <= 1e-3 * dense(Td).norm());
  // A coarse matrix that fails the single-precision test (here an impossible rcond)
  // is factorised in double instead.
  multilevel::AmgOptions demanding;
  demanding.single_min_rcond = 2.0;
  const multilevel::AggregationAmg amg_fallback(A, f.groups, f.rigid, demanding);
  CHECK(amg_fallback.coarse_factor_single() == nullptr);
  CHECK(amg_fallback.coarse_factor().factorized());
  RowBlock Tf;
  amg_fallback.apply(XY, Tf);
  CHECK((dense(Tf) - dense(Td)).norm() <= 1e-5 * dense(Td).norm());
  // A model scaled beyond single precision's range (entries of 1e35 and more: a
  // float would be infinite) runs its cycle in double: the double cycle's answer,
  // scaled, where the float cycle would have returned infinities.
  {
    CHECK(amg.single_precision());
    const Eigen::SparseMatrix<double> Abig = 1e32 * A;
    const multilevel::AggregationAmg huge(Abig, f.groups, f.rigid);
    CHECK_FALSE(huge.single_precision());
    CHECK(huge.coarse_factor_single() == nullptr);
    RowBlock Th;
    huge.apply(XY, Th);
    REQUIRE(dense(Th).allFinite());
    CHECK((1e32 * dense(Th) - dense(Td)).norm() <= 1e-8 * dense(Td).norm());
  }
  // The double-precision prolongator released (as the eigen-solver does before
  // LOBPCG): the single-precision cycle gives the same bits; P is no longer
  // there to ask for. A cycle in double keeps it.
  {
    multilevel::AggregationAmg released(A, f.groups, f.rigid);
    CHECK(released.prolongator().nonZeros() == amg.prolongator().nonZeros());
    // The split coarse solve against the column-by-column one (each column alone
    // on the single-precision factor): the same solution to rounding.
    {
      const Eigen::MatrixXd B = Eigen::MatrixXd::Random(amg.coarse_size(), 45);
      const Eigen::MatrixXd Ysplit = amg.solve_coarse(B);
      Eigen::MatrixXd Ycols(B.rows(), B.cols());
      for (Eigen::Index j = 0; j < B.cols(); ++j) Ycols.col(j) = amg.solve_coarse(B.col(j));
      CHECK((Ysplit - Ycols).norm() <= 1e-4 * Ycols.norm());
    }
    released.release_double_prolongator();
    CHECK(released.double_prolongator_released());
    RowBlock Tr;
    released.apply(XY, Tr);
    CHECK((dense(Tr) - dense(Ts)).norm() == 0.0);
    // 45 columns: the coarse solve split over the cores (2 columns are solved whole).
    const RowBlock Y45 = Eigen::MatrixXd::Random(n, 45);
    RowBlock Tw, Trw;
    amg.apply(Y45, Tw);
    released.apply(Y45, Trw);
    CHECK((dense(Trw) - dense(Tw)).norm() == 0.0);
    CHECK(released.coarse_size() == amg.coarse_size());
    CHECK_THROWS_AS(released.prolongator(), std::logic_error);
    CHECK_THROWS_AS(released.prolongator_rows(), std::logic_error);
    RowBlock Xc;
    CHECK_THROWS_AS(released.prolong(RowBlock::Ones(amg.coarse_size(), 2), Xc), std::logic_error);
    multilevel::AggregationAmg kept(A, f.groups, f.rigid, in_double);
    kept.release_double_prolongator();
    CHECK_FALSE(kept.double_prolongator_released());
    CHECK(kept.prolongator().nonZeros() == amg_double.prolongator().nonZeros());
  }

  // With the strain fields: up to twelve coarse DOFs an aggregate; the tentative
  // prolongator reproduces the fields exactly (they lie in its span); and, the
  // prolongator smoothed alike, the richer coarse space can only lower the coarse
  // model's eigenvalues (Courant–Fischer: span P₀ grows, and so does S P₀).
  {
    multilevel::AmgOptions tentative;
    tentative.prolongator_steps = 0;
    const multilevel::AggregationAmg p0(A, f.groups, f.rigid, tentative, f.strain);
    CHECK(p0.coarse_size() == 12 * p0.aggregates());  // the frame's aggregates are 3D: no field lost
    CHECK(p0.options().prolongator_steps == 0);  // as asked
    const Eigen::MatrixXd P0(p0.prolongator());
    CHECK((P0.transpose() * P0 - Eigen::MatrixXd::Identity(P0.cols(), P0.cols())).norm() < 1e-12);
    for (const Eigen::MatrixXd* fields : {&f.strain, &f.rigid})
      CHECK((*fields - P0 * (P0.transpose() * *fields)).norm() <= 1e-12 * fields->norm());
    CHECK_THROWS_AS(multilevel::AggregationAmg(A, f.groups, f.rigid, tentative, f.strain.topRows(10)),
                    std::invalid_argument);

    auto coarse_lambda = [&](const multilevel::AggregationAmg& amg_) {
      const Eigen::MatrixXd P(amg_.prolongator());
      const Eigen::MatrixXd Kc = P.transpose() * (f.op.K * P), Mc = P.transpose() * (f.op.M * P);
      return Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd>(Kc, Mc).eigenvalues();
    };
    multilevel::AmgOptions one_step;
    one_step.prolongator_steps = 1;
    const multilevel::AggregationAmg rigid_only(A, f.groups, f.rigid, one_step), with_fields(A, f.groups, f.rigid, one_step, f.strain);
    const Eigen::VectorXd lr = coarse_lambda(rigid_only), lf = coarse_lambda(with_fields);
    const double top = lr(29);
    for (int j = 6; j < 30; ++j) CHECK(lf(j) <= lr(j) + 1e-9 * top);
    // And by much, in the lowest elastic modes: the coarse space bends.
    EigenOptions lowest;
    lowest.nd = 7;
    const EigenResult direct = solve_modes(f.op.K, f.op.M, lowest);
    REQUIRE(direct.ok());
    const Eigen::VectorXd& fine = direct.eigenvalues;
    INFO("first elastic eigenvalue: model " << fine(6) << ", coarse model " << lr(6) << " (rigid-body modes), "
                                            << lf(6) << " (with the strain fields)");
    CHECK(lf(6) >= fine(6) * (1.0 - 1e-9));
    CHECK(lf(6) - fine(6) < 0.5 * (lr(6) - fine(6)));
    // The automatic smoothing: one step with the fields, two without; radius 2 for a
    // model this size either way, 3 with the fields above kLargeModelGrids grid points.
    const multilevel::AggregationAmg auto_fields(A, f.groups, f.rigid, {}, f.strain);
    CHECK(auto_fields.prolongator().nonZeros() == with_fields.prolongator().nonZeros());
    CHECK(auto_fields.options().prolongator_steps == 1);
    CHECK(auto_fields.options().aggregate_radius == 2);
    CHECK(amg.options().prolongator_steps == 2);
    CHECK(amg.options().aggregate_radius == 2);
    using multilevel::AggregationAmg;
    using multilevel::AmgOptions;
    CHECK(AggregationAmg::resolved({}, AmgOptions::kLargeModelGrids, true).aggregate_radius == 2);
    CHECK(AggregationAmg::resolved({}, AmgOptions::kLargeModelGrids + 1, true).aggregate_radius == 3);
    CHECK(AggregationAmg::resolved({}, AmgOptions::kLargeModelGrids + 1, false).aggregate_radius == 2);
    CHECK(AggregationAmg::resolved({}, AmgOptions::kLargeModelGrids + 1, false).prolongator_steps == 2);
    AmgOptions asked;
    asked.aggregate_radius = 1;
    asked.prolongator_steps = 3;
    CHECK(AggregationAmg::resolved(asked, AmgOptions::kLargeModelGrids + 1, true).aggregate_radius == 1);
    CHECK(AggregationAmg::resolved(asked, AmgOptions::kLargeModelGrids + 1, true).prolongator_steps == 3);
    // All-zero fields are no fields.
    const AggregationAmg zero_fields(A, f.groups, f.rigid, {}, Eigen::MatrixXd::Zero(n, 6));
    CHECK(zero_fields.coarse_size() == 6 * zero_fields.aggregates());
    CHECK(zero_fields.options().prolongator_steps == 2);

    // A field an aggregate cannot tell from a rigid motion (here: a translation plus
    // rounding-sized noise, as a straight chain of grids or a flat patch would
    // leave) is dropped, not kept as a normalised rough shape; a field that differs
    // from it by 1e-4 of its size is kept.
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    Eigen::VectorXd noise(n);
    for (long i = 0; i < n; ++i) noise(i) = u(rng);
    for (const auto& [scale, per_aggregate] : {std::pair{1e-9, 11L}, std::pair{1e-4, 12L}}) {
      Eigen::MatrixXd F = f.strain;
      F.col(5) = 3.0 * f.rigid.col(2) + scale * F.col(5).cwiseAbs().maxCoeff() * noise;  // |noise_i| <= 1
      const AggregationAmg noisy(A, f.groups, f.rigid, tentative, F);
      INFO("perturbation " << scale << ": coarse " << noisy.coarse_size() << ", aggregates " << noisy.aggregates());
      CHECK(noisy.coarse_size() == per_aggregate * noisy.aggregates());
    }
  }

  // Preconditioned conjugate gradients on A x = b, against plain CG.
  auto cg = [&](bool precondition) {
    const Eigen::VectorXd b = Eigen::VectorXd::Random(n);
    Eigen::VectorXd x = Eigen::VectorXd::Zero(n), r = b, z, p, Ap;
    auto prec = [&](const Eigen::VectorXd& v) {
      if (!precondition) return v;
      RowBlock in = v, out;
      amg.apply(in, out);
      return Eigen::VectorXd(out.col(0));
    };
    z = prec(r);
    p = z;
    double rz = r.dot(z);
    for (int it = 1; it <= 2000; ++it) {
      Ap = A * p;
      const double alpha = rz / p.dot(Ap);
      x += alpha * p;
      r -= alpha * Ap;
      if (r.norm() <= 1e-8 * b.norm()) return it;
      z = prec(r);
      const double rz2 = r.dot(z);
      p = z + (rz2 / rz) * p;
      rz = rz2;
    }
    return 2001;
  };
  const int with = cg(true), without = cg(false);
  INFO("CG iterations: " << with << " preconditioned, " << without << " plain");
  CHECK(with <= 25);
  CHECK(without > 10 * with);
}

TEST_CASE("LOBPCG finds the largest eigenvalues of a pencil, against a dense solve", "[multilevel]") {
  const auto [K, M] = test::random_pencil(120, 5);
  const Eigen::MatrixXd Kd(K), Md(M);
  // Largest μ of M x = μ K x: the dense solve of K x = λ M x, μ = 1/λ.
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> ges(Kd, Md);
  const Eigen::LLT<Eigen::MatrixXd> inverse(Kd);
  const multilevel::BlockOperator exact = [&](const RowBlock& R, RowBlock& W) {
    W = inverse.solve(Eigen::MatrixXd(R));
  };
  // An inexact one: the inverse of K with its diagonal raised by half (spectrally
  // equivalent to K⁻¹, as a multigrid cycle is).
  const Eigen::MatrixXd Kp = Kd + 0.5 * Eigen::MatrixXd(Kd.diagonal().asDiagonal());
  const Eigen::LLT<Eigen::MatrixXd> rough(Kp);
  const multilevel::BlockOperator jacobi = [&](const RowBlock& R, RowBlock& W) { W = rough.solve(Eigen::MatrixXd(R)); };
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  RowBlock X0(120, 9);
  for (Eigen::Index i = 0; i < X0.size(); ++i) X0.data()[i] = u(rng);
  // The Gram blocks of X and P derived from the last step's small matrices (the
  // default bound), always derived (no bound), and always computed from the blocks.
  for (const auto* T : {&exact, &jacobi})
  for (const double bound : {10.0, std::numeric_limits<double>::infinity(), 0.0}) {
    multilevel::LobpcgOptions o;
    o.nev = 5;
    o.tol = 1e-9;
    o.maxit = 1000;
    o.derived_gram_bound = bound;
    const multilevel::LobpcgResult r = multilevel::lobpcg_largest(K, M, *T, X0, o);
    INFO((T == &exact ? "exact" : "inexact") << " preconditioner, derived Gram bound " << bound << ", iterations "
                                             << r.iterations << ", derived " << r.derived_grams);
    REQUIRE(r.converged);
    if (bound == 0.0) CHECK(r.derived_grams == 0);
    else if (r.iterations > 2) CHECK(r.derived_grams > 0);
    for (int j = 0; j < o.nev; ++j) {
      INFO("relative difference " << (1.0 / r.mu(j) - ges.eigenvalues()(j)) / ges.eigenvalues()(j) << ", residual " << r.residuals(j));
      CHECK(1.0 / r.mu(j) == Approx(ges.eigenvalues()(j)).epsilon(1e-10));
    }
    // A-orthonormal vectors.
    const Eigen::MatrixXd X = dense(r.X);
    CHECK((X.transpose() * Kd * X - Eigen::MatrixXd::Identity(9, 9)).norm() <= 1e-10);
  }
  // A lumped (diagonal) M, some DOFs massless: LOBPCG keeps M as its diagonal and
  // never forms M X (the path the models take), against the dense solve of the same
  // pencil; the coupled M above takes the stored products.
  {
    Eigen::VectorXd md = Eigen::VectorXd::Ones(120) + 0.5 * Eigen::VectorXd::Random(120);
    for (int i = 0; i < 120; i += 3) md(i) = 0.0;  // a third massless
    test::SpMat Ml(120, 120);
    Ml = md.asDiagonal();
    Ml.makeCompressed();
    // Largest μ = 1/λ of M x = μ K x with a singular M: the dense solve of M x = μ K x.
    Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> gm(Eigen::MatrixXd(Ml), Kd);
    const Eigen::VectorXd top = gm.eigenvalues().reverse().head(5);
    for (const auto* T : {&exact, &jacobi}) {
      multilevel::LobpcgOptions o;
      o.nev = 5;
      o.tol = 1e-9;
      o.maxit = 1000;
      const multilevel::LobpcgResult r = multilevel::lobpcg_largest(K, Ml, *T, X0, o);
      INFO((T == &exact ? "exact" : "inexact") << " preconditioner, lumped M, iterations " << r.iterations);
      REQUIRE(r.converged);
      for (int j = 0; j < o.nev; ++j) CHECK(r.mu(j) == Approx(top(j)).epsilon(1e-10));
      const Eigen::MatrixXd X = dense(r.X);
      CHECK((X.transpose() * Kd * X - Eigen::MatrixXd::Identity(9, 9)).norm() <= 1e-10);
      // The residuals reported are those of the vectors returned.
      for (int j = 0; j < o.nev; ++j) {
        const Eigen::VectorXd x = X.col(j);
        const double rel = (Eigen::MatrixXd(Ml) * x - r.mu(j) * (Kd * x)).norm() / (r.mu(j) * (Kd * x).norm());
        CHECK(r.residuals(j) == Approx(rel).epsilon(1e-6).margin(1e-14));
      }
    }
  }
  // With the two lowest modes deflated (given, K-normalised), the next five are found
  // and the vectors stay K-orthogonal to the deflated ones.
  multilevel::Deflation d;
  const Eigen::MatrixXd V = ges.eigenvectors().leftCols(2);  // M-normalised
  d.Z = V * ges.eigenvalues().head(2).cwiseSqrt().cwiseInverse().asDiagonal();  // Zᵀ K Z = I
  d.AZ = Kd * Eigen::MatrixXd(d.Z);
  multilevel::LobpcgOptions o;
  o.nev = 5;
  o.tol = 1e-9;
  o.maxit = 1000;
  const multilevel::LobpcgResult r = multilevel::lobpcg_largest(K, M, exact, X0, o, d);
  REQUIRE(r.converged);
  for (int j = 0; j < o.nev; ++j) CHECK(1.0 / r.mu(j) == Approx(ges.eigenvalues()(j + 2)).epsilon(1e-10));
  CHECK((dense(d.Z).transpose() * Kd * dense(r.X)).norm() <= 1e-10);
}

TEST_CASE("LOBPCG on a pencil whose eigenvalues all come in triples, clusters locked together or not",
          "[multilevel]") {
  // Three uncoupled copies of one pencil: every eigenvalue exactly triple (as the
  // lattice's symmetric modes are), so the Rayleigh–Ritz step may mix the copies'
  // Ritz vectors freely.
  const auto [K1, M1] = test::random_pencil(50, 3);
  const int n = 150;
  auto triple = [&](const test::SpMat& A) {
    std::vector<Eigen::Triplet<double>> t;
    for (int c = 0; c < 3; ++c)
      for (Eigen::Index j = 0; j < A.outerSize(); ++j)
        for (test::SpMat::InnerIterator it(A, j); it; ++it)
          t.emplace_back(static_cast<int>(it.row()) + 50 * c, static_cast<int>(it.col()) + 50 * c, it.value());
    test::SpMat B(n, n);
    B.setFromTriplets(t.begin(), t.end());
    B.makeCompressed();
    return B;
  };
  const test::SpMat K = triple(K1), M = triple(M1);
  const Eigen::MatrixXd Kd(K), Md(M);
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> ges(Kd, Md);
  const Eigen::MatrixXd Kp = Kd + 0.5 * Eigen::MatrixXd(Kd.diagonal().asDiagonal());
  const Eigen::LLT<Eigen::MatrixXd> rough(Kp);
  const multilevel::BlockOperator jacobi = [&](const RowBlock& R, RowBlock& W) { W = rough.solve(Eigen::MatrixXd(R)); };
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  RowBlock X0(n, 12);
  for (Eigen::Index i = 0; i < X0.size(); ++i) X0.data()[i] = u(rng);
  for (const double gap : {1e-4, 0.0}) {
    multilevel::LobpcgOptions o;
    o.nev = 9;  // three triples
    o.tol = 1e-9;
    o.maxit = 1000;
    o.lock_cluster_gap = gap;
    const multilevel::LobpcgResult r = multilevel::lobpcg_largest(K, M, jacobi, X0, o);
    INFO("cluster gap " << gap << ", iterations " << r.iterations << ", preconditioned " << r.preconditioned);
    REQUIRE(r.converged);
    for (int j = 0; j < o.nev; ++j) CHECK(1.0 / r.mu(j) == Approx(ges.eigenvalues()(j)).epsilon(1e-10));
    const Eigen::MatrixXd X = dense(r.X);
    CHECK((X.transpose() * Kd * X - Eigen::MatrixXd::Identity(12, 12)).norm() <= 1e-10);
    // Every wanted column meets the tolerance at the end, cluster partners included.
    for (int j = 0; j < o.nev; ++j) {
      const Eigen::VectorXd x = X.col(j);
      const double rel = (Md * x - r.mu(j) * (Kd * x)).norm() / (r.mu(j) * (Kd * x).norm());
      CHECK(rel <= 1e-9 * (1 + 1e-6));
    }
  }
}

TEST_CASE("multilevel eigen-solver agrees with the direct solver on an irregular free 3D frame", "[multilevel][slow]") {
  const Frame f = frame(9, 9, 9);  // 4374 DOFs: the threaded kernels (4096 rows and more) run
  EigenOptions o;
  o.nd = 24;
  o.dof_groups = f.groups;
  const EigenResult direct = solve_modes(f.op.K, f.op.M, o);
  REQUIRE(direct.ok());
  o.method = EigenMethod::Multilevel;
  o.near_null_space = f.rigid;
  // With the rigid-body modes taken out first (the default) and kept in the
  // iteration; with the start smoothed (the default) and as interpolated.
  // And with every Gram block of LOBPCG computed from the blocks (none derived).
  // And with the strain fields in the coarse space (as the CLI sets it) or not.
  struct Variant {
    bool deflate;
    int smoothing;
    double derived_gram_bound;
    bool strain;
  };
  int iterations_with_fields = 0, iterations_rigid_only = 0;
  for (const auto& [deflate, smoothing, bound, strain] :
       {Variant{true, 10, 10.0, true}, Variant{true, 10, 10.0, false}, Variant{false, 10, 10.0, true},
        Variant{true, 0, 10.0, true}, Variant{true, 10, 0.0, true}}) {
    o.multilevel.deflate = deflate;
    o.multilevel.start_smoothing = smoothing;
    o.multilevel.derived_gram_bound = bound;
    o.strain_fields = strain ? f.strain : Eigen::MatrixXd();
    const EigenResult ml = solve_modes(f.op.K, f.op.M, o);
    INFO((deflate ? "deflated: " : "not deflated: ") << "start smoothing " << smoothing << ", derived Gram bound "
                                                     << bound << (strain ? ", strain fields" : ", rigid only") << ": "
                                                     << ml.message << "; iterations " << ml.iterations << ", coarse "
                                                     << ml.coarse_size);
    REQUIRE(ml.ok());
    if (deflate && smoothing == 10 && bound == 10.0) (strain ? iterations_with_fields : iterations_rigid_only) = ml.iterations;
    CHECK(ml.method == "Multilevel");
    CHECK(ml.deflated == (deflate ? 6 : 0));
    REQUIRE(ml.size() == 24);
    const double top = direct.eigenvalues(23);
    int rigid = 0;
    for (int j = 0; j < 24; ++j) {
      if (std::abs(direct.eigenvalues(j)) < 1e-6 * top) {
        ++rigid;
        CHECK(std::abs(ml.eigenvalues(j)) < 1e-8 * top);
      } else {
        CHECK(ml.eigenvalues(j) == Approx(direct.eigenvalues(j)).epsilon(1e-10));
        CHECK(ml.residuals(j) < 1e-5);
        // Same shape (MAC with the direct mode), the frame has no repeated frequencies.
        const double mac = std::pow(ml.modes.col(j).dot(f.op.M * direct.modes.col(j)), 2);
        CHECK(mac > 1.0 - 1e-9);
      }
    }
    CHECK(rigid == 6);
    CHECK(ml.orthogonality < 1e-10);
    CHECK(ml.backward_errors.maxCoeff() < 1e-8);
  }
  INFO("LOBPCG iterations: " << iterations_with_fields << " with the strain fields, " << iterations_rigid_only
                             << " without");
  CHECK(iterations_with_fields < iterations_rigid_only);
  // Fewer modes than rigid-body ones: all from the near-null space, no iteration.
  o.multilevel.derived_gram_bound = 10.0;
  o.multilevel.deflate = true;
  o.multilevel.start_smoothing = 10;
  o.nd = 4;
  const EigenResult rigid_only = solve_modes(f.op.K, f.op.M, o);
  REQUIRE(rigid_only.ok());
  REQUIRE(rigid_only.size() == 4);
  CHECK(rigid_only.iterations == 0);
  CHECK(rigid_only.eigenvalues.cwiseAbs().maxCoeff() < 1e-8 * direct.eigenvalues(23));
  CHECK(rigid_only.backward_errors.maxCoeff() < 1e-8);  // (relative residuals mean nothing where K phi = 0)
  CHECK(rigid_only.orthogonality < 1e-10);
}

TEST_CASE("Auto falls back to the multilevel method when the factor would not fit", "[multilevel]") {
  const Frame f = frame(6, 5, 5);
  EigenOptions o;
  o.nd = 12;
  o.dof_groups = f.groups;
  o.max_factor_bytes = 1000.0;  // any factor is too large
  const EigenResult refused = solve_modes(f.op.K, f.op.M, o);
  CHECK(refused.status == EigenResult::Status::FactorFailed);
  o.near_null_space = f.rigid;
  o.strain_fields = f.strain;  // as the CLI sets them
  const EigenResult r = solve_modes(f.op.K, f.op.M, o);
  REQUIRE(r.ok());
  CHECK(r.method == "Multilevel");
  REQUIRE(r.warnings.size() == 1);
  CHECK(r.warnings[0].find("multilevel") != std::string::npos);
  o.max_factor_bytes = 0.0;
  o.near_null_space.resize(0, 0);
  o.strain_fields.resize(0, 0);
  const EigenResult direct = solve_modes(f.op.K, f.op.M, o);
  for (int j = 6; j < 12; ++j) CHECK(r.eigenvalues(j) == Approx(direct.eigenvalues(j)).epsilon(1e-10));
}

TEST_CASE("multilevel method: clear refusals", "[multilevel]") {
  const Frame f = frame(4, 4, 3);
  EigenOptions o;
  o.nd = 6;
  o.method = EigenMethod::Multilevel;
  o.dof_groups = f.groups;
  CHECK_THROWS_WITH(solve_modes(f.op.K, f.op.M, o), Catch::Contains("near_null_space"));
  o.near_null_space = f.rigid;
  o.nd = 0;
  o.f_high = 100.0;
  CHECK_THROWS_WITH(solve_modes(f.op.K, f.op.M, o), Catch::Contains("ND"));
  o.nd = 6;
  o.f_high = std::numeric_limits<double>::quiet_NaN();
  o.f_low = 1.0;  // a lower bound too is a band request
  CHECK_THROWS_WITH(solve_modes(f.op.K, f.op.M, o), Catch::Contains("frequency band"));
  o.f_low = std::numeric_limits<double>::quiet_NaN();
  o.near_null_space = f.rigid.topRows(10);
  CHECK_THROWS_WITH(solve_modes(f.op.K, f.op.M, o), Catch::Contains("near_null_space has 10 rows"));
  o.near_null_space = f.rigid;
  o.strain_fields = f.strain.topRows(12);
  CHECK_THROWS_WITH(solve_modes(f.op.K, f.op.M, o), Catch::Contains("strain_fields has 12 rows"));
  o.strain_fields = f.strain;
  o.strain_fields(3, 2) = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_WITH(solve_modes(f.op.K, f.op.M, o), Catch::Contains("strain_fields has values that are not finite"));
  o.method = EigenMethod::Auto;  // checked whatever the method
  CHECK_THROWS_WITH(solve_modes(f.op.K, f.op.M, o), Catch::Contains("strain_fields has values that are not finite"));
  o.method = EigenMethod::Multilevel;
  o.strain_fields.resize(0, 0);
  // A model too small for its coarse space: a status, not an exception.
  const Frame tiny = frame(2, 2, 2);
  o.dof_groups = tiny.groups;
  o.near_null_space = tiny.rigid;
  o.nd = 20;  // 12 coarse DOFs (two aggregates of four grids)
  const EigenResult r = solve_modes(tiny.op.K, tiny.op.M, o);
  CHECK(r.status == EigenResult::Status::NotConverged);
  CHECK(r.message.find("too small") != std::string::npos);
  CHECK(r.size() == 0);  // no modes from a run that stopped
}

TEST_CASE("multilevel method: a DOF with neither stiffness nor mass is reported, not thrown", "[multilevel]") {
  const Frame f = frame(5, 4, 4);
  // Remove every stiffness term of one rotational DOF (it has no mass): a mechanism.
  constexpr long bad = 6 * 17 + 4;
  Eigen::SparseMatrix<double> K = f.op.K;
  K.prune([](Eigen::Index r, Eigen::Index c, double) { return r != bad && c != bad; });
  EigenOptions o;
  o.nd = 8;
  o.method = EigenMethod::Multilevel;
  o.dof_groups = f.groups;
  o.near_null_space = f.rigid;
  const EigenResult r = solve_modes(K, f.op.M, o);
  CHECK(r.status == EigenResult::Status::NotPositiveDefinite);
  CHECK(r.failed_dof == bad);
  CHECK(r.message.find("neither stiffness nor mass") != std::string::npos);
  CHECK(r.size() == 0);
}

TEST_CASE("dense block kernels (Gram products, block updates) agree with Eigen at every width", "[multilevel][slow]") {
  // Gram products take rows in chunks, Y padded to whole vectors and rows of G in
  // groups of four; updates take rows in fours and columns in tiles. Widths that
  // leave every remainder, on one thread (300 rows, several chunks) and split over
  // the cores (more than 8192 rows a thread).
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  auto random = [&](long n, long b) {
    RowBlock X(n, b);
    for (Eigen::Index i = 0; i < X.size(); ++i) X.data()[i] = u(rng);
    return X;
  };
  const long threaded = 2 * 8192 * multilevel::worker_threads() + 5;
  for (const long n : {300L, threaded}) {
    for (const long p : {1L, 3L, 4L, 5L, 9L, 45L, 130L}) {
      if (n == threaded && p > 45) continue;  // the widest on one thread only (memory grows with the cores)
      for (const long q : {1L, 2L, 7L, 8L, 13L, 45L, 67L}) {
        CAPTURE(n, p, q);
        const RowBlock X = random(n, p), Y = random(n, q);
        const Eigen::MatrixXd Gd = dense(X).transpose() * dense(Y);
        CHECK((multilevel::gram(X, Y) - Gd).norm() <= 1e-13 * Gd.norm());
        const long half = n / 2 + 3;
        const Eigen::MatrixXd Gh = dense(X).topRows(half).transpose() * dense(Y).topRows(half);
        CHECK((multilevel::gram(X, Y, half) - Gh).norm() <= 1e-13 * Gh.norm());
        // Weighted (a lumped M): Xᵀ diag(w) Y, all rows and the first `half`.
        const Eigen::VectorXd w = Eigen::VectorXd::Random(n);
        const Eigen::MatrixXd Gw = dense(X).transpose() * w.asDiagonal() * dense(Y);
        CHECK((multilevel::gram_weighted(X, w, Y) - Gw).norm() <= 1e-13 * Gw.norm());
        const Eigen::MatrixXd Gwh =
            dense(X).topRows(half).transpose() * w.head(half).asDiagonal() * dense(Y).topRows(half);
        CHECK((multilevel::gram_weighted(X, w, Y, half) - Gwh).norm() <= 1e-13 * Gwh.norm());
        const Eigen::MatrixXd C = Eigen::MatrixXd::Random(p, q);
        RowBlock Z;
        multilevel::times_dense_into(X, C, 0.0, Z);
        const Eigen::MatrixXd XC = dense(X) * C;
        CHECK((dense(Z) - XC).norm() <= 1e-13 * XC.norm());
        multilevel::times_dense_into(X, C, 2.5, Z);  // Z = 2.5 Z + X C
        CHECK((dense(Z) - 3.5 * XC).norm() <= 1e-13 * XC.norm());
      }
      // Symmetric: Xᵀ (D X) with D diagonal, the upper triangle mirrored.
      CAPTURE(n, p);
      const RowBlock X = random(n, p);
      const Eigen::VectorXd d = Eigen::VectorXd::Random(n);
      const RowBlock DX = d.asDiagonal() * dense(X);
      const Eigen::MatrixXd S = multilevel::gram_symmetric(X, DX), Sd = dense(X).transpose() * dense(DX);
      CHECK((S - Sd).norm() <= 1e-13 * Sd.norm());
      CHECK(S == S.transpose());
      const Eigen::MatrixXd Sw = multilevel::gram_weighted_symmetric(X, d);
      CHECK((Sw - Sd).norm() <= 1e-13 * Sd.norm());
      CHECK(Sw == Sw.transpose());
      const long third = n / 3 + 1;
      const Eigen::MatrixXd St = dense(X).topRows(third).transpose() * dense(DX).topRows(third);
      CHECK((multilevel::gram_weighted_symmetric(X, d, third) - St).norm() <= 1e-13 * St.norm());
    }
  }
  // Y = β Y + Σ_s B_s C_s over blocks of different widths, one of them empty, on one
  // thread and split over the cores, β = 0, 1 and 2.5.
  for (const long n : {1001L, threaded}) {
    CAPTURE(n);
    const RowBlock A = random(n, 5), B(n, 0), C3 = random(n, 45), D = random(n, 17);
    const Eigen::MatrixXd C = Eigen::MatrixXd::Random(5 + 0 + 45 + 17, 23);
    Eigen::MatrixXd stacked(n, 67);
    stacked << dense(A), dense(C3), dense(D);
    const Eigen::MatrixXd ref = stacked * C;
    RowBlock Z;
    multilevel::times_dense_sum({&A, &B, &C3, &D}, C, 0.0, Z);
    CHECK((dense(Z) - ref).norm() <= 1e-13 * ref.norm());
    multilevel::times_dense_sum({&A, &B, &C3, &D}, C, 1.0, Z);
    CHECK((dense(Z) - 2.0 * ref).norm() <= 1e-13 * ref.norm());
    multilevel::times_dense_sum({&D, &A}, C.bottomRows(22), 2.5, Z);  // Z = 2.5 Z + [D A] C's last 22 rows
    const Eigen::MatrixXd ref2 = 5.0 * ref + dense(D) * C.bottomRows(22).topRows(17) + dense(A) * C.bottomRows(5);
    CHECK((dense(Z) - ref2).norm() <= 1e-13 * ref2.norm());
  }
  // Refusals, and the empty sum.
  const long n = 1001;
  const RowBlock A = random(n, 5), B(n, 0), C3 = random(n, 45);
  const Eigen::MatrixXd C = Eigen::MatrixXd::Random(67, 23);
  RowBlock Z;
  RowBlock E = Eigen::MatrixXd::Ones(n, 23);
  multilevel::times_dense_sum({&B}, Eigen::MatrixXd(0, 23), 0.0, E);  // an empty sum: zero
  CHECK(E.isZero(0.0));
  CHECK_THROWS_WITH(multilevel::times_dense_sum({&A, &C3}, C, 0.0, Z), Catch::Contains("shapes do not agree"));
  RowBlock F = random(n, 5);
  CHECK_THROWS_WITH(multilevel::times_dense_sum({&F}, Eigen::MatrixXd::Random(5, 5), 1.0, F),
                    Catch::Contains("Y is one of the blocks"));
  CHECK_THROWS_WITH(multilevel::times_dense_sum({&A, &A, &A, &A, &A}, Eigen::MatrixXd::Random(25, 3), 0.0, Z),
                    Catch::Contains("more than four"));
  CHECK_THROWS_WITH(multilevel::gram_symmetric(A, C3), Catch::Contains("different widths"));
  CHECK_THROWS_WITH(multilevel::gram_weighted(A, Eigen::VectorXd::Ones(n - 1), A), Catch::Contains("fewer weights"));
  CHECK_NOTHROW(multilevel::gram_weighted(A, Eigen::VectorXd::Ones(n - 1), A, n - 1));
}
