#include "estimator/linalg/dense_blas.hpp"

#include <catch2/catch.hpp>
#include <dlfcn.h>

#include <Eigen/Dense>
#include <stdexcept>

using namespace ssid::estimator;

TEST_CASE("gemm through the system BLAS matches Eigen's products, blocks and transposes", "[blas]") {
  Eigen::MatrixXd big = Eigen::MatrixXd::Random(40, 30);
  const Eigen::MatrixXd B = Eigen::MatrixXd::Random(40, 7);
  // A block with an outer stride (40) larger than its rows (25).
  const auto A = big.block(5, 3, 25, 12);
  const Eigen::MatrixXd Bt = Eigen::MatrixXd::Random(12, 9);
  Eigen::MatrixXd C = Eigen::MatrixXd::Random(25, 9);
  const Eigen::MatrixXd C0 = C;
  detail::gemm(false, false, 2.0, A, Bt, 0.5, C);
  CHECK((C - (2.0 * Eigen::MatrixXd(A) * Bt + 0.5 * C0)).norm() <= 1e-13 * C.norm());
  const Eigen::MatrixXd AtB = detail::at_b(big.leftCols(10), B);
  CHECK((AtB - big.leftCols(10).transpose() * B).norm() <= 1e-13 * AtB.norm());
  const Eigen::MatrixXd AB = detail::a_b(big.middleCols(2, 7), Bt.topRows(7));
  CHECK((AB - big.middleCols(2, 7) * Bt.topRows(7)).norm() <= 1e-13 * AB.norm());
  const Eigen::MatrixXd P = Eigen::MatrixXd::Random(5, 12), Q = Eigen::MatrixXd::Random(9, 5);
  Eigen::MatrixXd D(12, 9);
  detail::gemm(true, true, 1.0, P, Q, 0.0, D);
  CHECK((D - P.transpose() * Q.transpose()).norm() <= 1e-13 * D.norm());
  Eigen::MatrixXd wrong(3, 3);
  CHECK_THROWS_AS(detail::gemm(false, false, 1.0, A, B, 0.0, wrong), std::invalid_argument);
}

TEST_CASE("largest_eigenpairs gives the top of a symmetric spectrum with its vectors", "[blas]") {
  for (int k : {1, 7, 60}) {
    const Eigen::MatrixXd X = Eigen::MatrixXd::Random(k, k);
    Eigen::MatrixXd T = X + X.transpose();
    T(0, 0) += 3.0;
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(T);
    for (long count : {1L, static_cast<long>((k + 1) / 2), static_cast<long>(k)}) {
      Eigen::VectorXd values;
      Eigen::MatrixXd vectors;
      detail::largest_eigenpairs(T, count, values, vectors);
      REQUIRE(values.size() == count);
      REQUIRE(vectors.cols() == count);
      const double scale = es.eigenvalues().cwiseAbs().maxCoeff();
      for (long i = 0; i < count; ++i) {
        CHECK(values(i) == Approx(es.eigenvalues()(k - count + i)).margin(1e-12 * scale));
        CHECK((T * vectors.col(i) - values(i) * vectors.col(i)).norm() <= 1e-12 * scale);
      }
      CHECK((vectors.transpose() * vectors - Eigen::MatrixXd::Identity(count, count)).cwiseAbs().maxCoeff() <= 1e-12);
    }
  }
  Eigen::VectorXd v;
  Eigen::MatrixXd z;
  CHECK_THROWS_AS(detail::largest_eigenpairs(Eigen::MatrixXd::Identity(3, 3), 4, v, z), std::invalid_argument);
}

TEST_CASE("BlasThreadLimit holds OpenBLAS to one thread while it lives and restores the count", "[blas]") {
  using Get = int (*)();
  using Set = void (*)(int);
  const auto get = reinterpret_cast<Get>(dlsym(RTLD_DEFAULT, "openblas_get_num_threads"));
  const auto set = reinterpret_cast<Set>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads"));
  const Eigen::MatrixXd A = Eigen::MatrixXd::Random(300, 200), B = Eigen::MatrixXd::Random(200, 150);
  const Eigen::MatrixXd expected = A * B;
  auto product_ok = [&] {
    Eigen::MatrixXd C(300, 150);
    detail::gemm(false, false, 1.0, A, B, 0.0, C);
    return (C - expected).norm() <= 1e-12 * expected.norm();
  };
  if (!get || !set) {  // another BLAS: the limit is a no-op, products unchanged
    const detail::BlasThreadLimit limit;
    CHECK(product_ok());
    return;
  }
  const int before = get();
  set(2);  // a count the limit must change and restore, on any machine
  if (get() != 2) {  // a serial OpenBLAS (libopenblas0-serial): one thread whatever is asked
    const detail::BlasThreadLimit limit;
    CHECK(get() == 1);
    CHECK(product_ok());
    return;
  }
  {
    const detail::BlasThreadLimit limit;
    CHECK(get() == 1);
    CHECK(product_ok());
  }
  CHECK(get() == 2);
  set(1);  // already one: left alone
  {
    const detail::BlasThreadLimit limit;
    CHECK(get() == 1);
  }
  CHECK(get() == 1);
  set(before);
  CHECK(product_ok());
}
