// The problem file reads back identically, bit for bit, and refuses damaged files
// with the file and the item named.
#include <Eigen/Dense>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>

#include "formats/problem_file.hpp"

using namespace ssid::formats;

namespace {

Eigen::SparseMatrix<double> random_sparse(int n, int m, double density, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j)
      if (std::abs(u(rng)) < density) t.emplace_back(i, j, u(rng) * std::pow(10.0, 30 * u(rng)));
  Eigen::SparseMatrix<double> s(n, m);
  s.setFromTriplets(t.begin(), t.end());
  s.makeCompressed();
  return s;
}

ProblemFile sample(std::mt19937& rng) {
  ProblemFile pf;
  pf.title = "chain \"quoted\" ünïcode";
  pf.parameters = {{"AREA", 1, 1.0e-4, 2.0e-5, 0.0, 1.0}, {"E", 2, 7.0e10, 7.0e9, -1e20, 1e20}};
  pf.prior_correlation = Eigen::MatrixXd::Identity(2, 2);
  pf.prior_correlation(0, 1) = pf.prior_correlation(1, 0) = 0.25;
  pf.options.max_iterations = 7;
  pf.options.shape_derivative = "modal-sum";
  for (int k = 0; k < 2; ++k) {
    ProblemConfiguration c;
    c.name = k ? "tip mass" : "bare";
    c.deck = "mpi.bdf";
    c.modes = 12;
    const int n = 9;
    for (int i = 0; i < n; ++i) c.dofs.emplace_back(100 + i / 3, 1 + i % 3);
    c.sensor_labels = {"1:1", "2:3", "5:2"};
    c.sensors = random_sparse(3, n, 0.3, rng);
    c.K = random_sparse(n, n, 0.4, rng);
    c.M = random_sparse(n, n, 0.2, rng);
    c.dK = {random_sparse(n, n, 0.1, rng), Eigen::SparseMatrix<double>(n, n)};
    c.dM = {Eigen::SparseMatrix<double>(n, n), random_sparse(n, n, 0.1, rng)};
    for (auto* m : {&c.dK[1], &c.dM[0]}) m->makeCompressed();
    ProblemMode a;
    a.id = 1;
    a.frequency_hz = 7.75;
    a.frequency_std_hz = 0.01;
    a.shape = Eigen::Vector3d(0.1, -1.0 / 3.0, M_PI);
    a.shape_std = 0.02;
    ProblemMode b;
    b.id = 2;
    b.frequency_hz = 11.65;
    b.use_shape = false;
    c.measured = {a, b};
    pf.configurations.push_back(c);
  }
  return pf;
}

bool same(const Eigen::SparseMatrix<double>& a, const Eigen::SparseMatrix<double>& b) {
  if (a.rows() != b.rows() || a.cols() != b.cols() || a.nonZeros() != b.nonZeros()) return false;
  for (Eigen::Index k = 0; k <= a.outerSize(); ++k)
    if (a.outerIndexPtr()[k] != b.outerIndexPtr()[k]) return false;
  for (Eigen::Index k = 0; k < a.nonZeros(); ++k)
    if (a.innerIndexPtr()[k] != b.innerIndexPtr()[k] || a.valuePtr()[k] != b.valuePtr()[k]) return false;
  return true;
}

std::string temp(const char* name) { return (std::filesystem::temp_directory_path() / name).string(); }

}  // namespace

TEST_CASE("problem file reads back identically", "[formats][problem]") {
  std::mt19937 rng(7);
  const ProblemFile pf = sample(rng);
  const std::string path = temp("ssid_problem_roundtrip.ssid");
  write_problem(path, pf);
  const ProblemFile back = read_problem(path);
  CHECK(back.title == pf.title);
  REQUIRE(back.parameters.size() == 2);
  CHECK(back.parameters[1].name == "E");
  CHECK(back.parameters[0].initial == pf.parameters[0].initial);
  CHECK(back.parameters[0].prior_std == pf.parameters[0].prior_std);
  CHECK(back.prior_correlation == pf.prior_correlation);
  CHECK(back.options.max_iterations == 7);
  CHECK(back.options.shape_derivative == "modal-sum");
  REQUIRE(back.configurations.size() == 2);
  for (std::size_t k = 0; k < 2; ++k) {
    const auto &a = pf.configurations[k], &b = back.configurations[k];
    CHECK(b.name == a.name);
    CHECK(b.dofs == a.dofs);
    CHECK(b.sensor_labels == a.sensor_labels);
    CHECK(same(a.K, b.K));
    CHECK(same(a.M, b.M));
    CHECK(same(a.sensors, b.sensors));
    for (std::size_t j = 0; j < 2; ++j) {
      CHECK(same(a.dK[j], b.dK[j]));
      CHECK(same(a.dM[j], b.dM[j]));
    }
    REQUIRE(b.measured.size() == 2);
    CHECK(b.measured[0].shape == a.measured[0].shape);  // bit for bit
    CHECK(b.measured[1].shape.size() == 0);
    CHECK_FALSE(b.measured[1].use_shape);
  }
  // Writing what was read gives the same bytes.
  const std::string again = temp("ssid_problem_again.ssid");
  write_problem(again, back);
  std::ifstream f1(path, std::ios::binary), f2(again, std::ios::binary);
  const std::string s1((std::istreambuf_iterator<char>(f1)), {}), s2((std::istreambuf_iterator<char>(f2)), {});
  CHECK(s1 == s2);
  std::filesystem::remove(path);
  std::filesystem::remove(again);
}

TEST_CASE("damaged problem files are refused with the item named", "[formats][problem]") {
  std::mt19937 rng(3);
  const ProblemFile pf = sample(rng);
  const std::string path = temp("ssid_problem_bad.ssid");
  write_problem(path, pf);
  std::ifstream in(path, std::ios::binary);
  const std::string good((std::istreambuf_iterator<char>(in)), {});
  auto write = [&](const std::string& bytes) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out << bytes;
  };
  SECTION("truncated") {
    write(good.substr(0, good.size() - 10));
    CHECK_THROWS_WITH(read_problem(path), Catch::Contains("truncated") && Catch::Contains("tip mass' mode 1 shape"));
  }
  SECTION("not a problem file") {
    write("BEGIN BULK\n");
    CHECK_THROWS_WITH(read_problem(path), Catch::Contains("not an ssid problem file"));
  }
  SECTION("newer version") {
    std::string b = good;
    b[9] = '9';
    write(b);
    CHECK_THROWS_WITH(read_problem(path), Catch::Contains("version 9"));
  }
  SECTION("sizes that disagree are refused on write") {
    ProblemFile bad = pf;
    bad.configurations[0].dK.pop_back();
    CHECK_THROWS_WITH(write_problem(path, bad), Catch::Contains("one dK and one dM per parameter"));
    bad = pf;
    bad.configurations[1].measured[0].shape = Eigen::Vector2d(1, 2);
    CHECK_THROWS_WITH(write_problem(path, bad), Catch::Contains("mode 1 has 2 shape components for 3 sensors"));
  }
  std::filesystem::remove(path);
}
