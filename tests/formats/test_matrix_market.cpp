// MatrixMarket writer: golden text, symmetric lower triangle, exact values.
#include <catch2/catch.hpp>

#include "formats/matrix_market.hpp"
#include "formats/parse_error.hpp"

using namespace ssid::formats;

TEST_CASE("MatrixMarket: general real and complex, golden text, 1-based, shortest exact values", "[mtx]") {
  Eigen::MatrixXd d(2, 3);
  d << 1.0, 0.0, -2.5, 0.0, 1.0 / 3.0, 1e-300;
  Eigen::SparseMatrix<double> a = d.sparseView();
  CHECK(matrix_market_string(a, MtxSymmetry::General, "KAA from x.op4") ==
        "%%MatrixMarket matrix coordinate real general\n"
        "% KAA from x.op4\n"
        "2 3 4\n"
        "1 1 1\n"
        "2 2 0.3333333333333333\n"
        "1 3 -2.5\n"
        "2 3 1e-300\n");
  Eigen::MatrixXcd z = Eigen::MatrixXcd::Zero(2, 1);
  z(1, 0) = {0.5, -4.0};
  Eigen::SparseMatrix<std::complex<double>> zs = z.sparseView();
  CHECK(matrix_market_string(zs) ==
        "%%MatrixMarket matrix coordinate complex general\n"
        "2 1 1\n"
        "2 1 0.5 -4\n");
}

TEST_CASE("MatrixMarket: symmetric writes the lower triangle; a non-symmetric matrix is refused", "[mtx]") {
  Eigen::MatrixXd d(3, 3);
  d << 4, -1, 0, -1, 3, 2, 0, 2, 5;
  Eigen::SparseMatrix<double> a = d.sparseView();
  CHECK(is_exactly_symmetric(a));
  CHECK(matrix_market_string(a, MtxSymmetry::Symmetric) ==
        "%%MatrixMarket matrix coordinate real symmetric\n"
        "3 3 5\n"
        "1 1 4\n"
        "2 1 -1\n"
        "2 2 3\n"
        "3 2 2\n"
        "3 3 5\n");
  d(0, 2) = 1e-17;
  a = d.sparseView(0.0, 0.0);
  CHECK_FALSE(is_exactly_symmetric(a));
  CHECK_THROWS_AS(matrix_market_string(a, MtxSymmetry::Symmetric), ssid::formats::InputError);
}
