/// \file bench_pretest.cpp
/// Issue 23's pretest benchmark (docs/performance.md "Pretest"):
///  1. Effective independence on a large model: the benchmark lattice
///     (bench/lattice.hpp; N = 25 → 93 750 DOF) solved for its 6 rigid-body and
///     40 lowest elastic modes (the eigen-solver's Auto method), the 40 elastic
///     modes being the targets; the candidates are the first 25 000 translational
///     DOFs (nodes 0 … 8 333 in lattice order); EI deletes down to 45 DOFs, and,
///     triaxially, the 8 333 whole grids (24 999 DOFs) down to 30 triaxes. Each
///     placement's wall and CPU time, its Fisher determinant and condition number.
///     `--export DIR` writes the candidates' modes (phi.bin: c × m doubles, row
///     by row; phi.txt: "c m keep" and the rows EI kept) for the numpy peer
///     bench/pretest_ei_numpy.py, which runs the same rank-one deletion.
///  2. The genetic algorithm's cost per generation on the MPI rod model
///     (samples/mpi_rod.bdf; 12 targets above 1 Hz, 18 EI sensors, 2 exciters,
///     population 20): the GA with 0 and with 40 generations, the difference / 40.
///
/// usage: bench_pretest [N] [--candidates C] [--modes M] [--sensors S] [--triaxes T]
///                      [--export DIR] [--rod PATH] [--skip-ei] [--skip-ga]
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "bench/lattice.hpp"
#include "estimator/eigen/dense_eigen.hpp"
#include "estimator/eigen/eigen_solver.hpp"
#include "estimator/pretest/exciter_placement.hpp"
#include "estimator/pretest/sensor_placement.hpp"
#include "estimator/pretest/targets.hpp"
#include "formats/deck.hpp"
#include "translators/assembly/fe_model.hpp"

namespace {

using namespace bench;
namespace pt = ssid::estimator::pretest;
using ssid::estimator::EigenOptions;
using ssid::estimator::EigenResult;
using ssid::estimator::EigenSolver;

void print_placement(const char* what, const pt::Placement& p, std::pair<double, double> t) {
  std::printf("%s: %.2f s wall, %.2f s CPU; kept %zu DOF(s); log10 det F %.6f, condition %.6g, rank %d\n", what, t.first,
              t.second, p.selected.size(), p.fisher.log10_determinant, p.fisher.condition_number, p.fisher.rank);
}

int run_ei(int n, long candidates, int modes, int sensors, int triaxes, const std::string& export_dir) {
  const Section sec;
  double t = now_s();
  const Model m = lattice(n, sec);
  std::printf("lattice %d^3: %ld nodes, %ld DOF, build %.2f s\n", n, m.nodes, static_cast<long>(m.K.rows()), now_s() - t);
  EigenOptions o;
  o.nd = modes + 6;
  o.sturm_check = false;
  o.dof_groups.resize(static_cast<std::size_t>(m.K.rows()));
  for (std::size_t i = 0; i < o.dof_groups.size(); ++i) o.dof_groups[i] = static_cast<long>(i / 6);
  o.near_null_space = rigid_body_modes(m);
  o.strain_fields = strain_fields(m);
  EigenResult r;
  const auto ts = timed([&] { r = EigenSolver(o).solve(m.K, m.M); });
  if (!r.ok()) {
    std::printf("eigen-solve failed: %s\n", r.message.c_str());
    return 1;
  }
  const auto targets = pt::select_target_modes(r.eigenvalues, modes, 1e-3);
  std::printf("eigen-solve (%s): %d modes in %.1f s wall, %.1f s CPU; targets %.4g … %.4g Hz\n", r.method.c_str(), r.size(),
              ts.first, ts.second, r.cycles(static_cast<int>(targets.front())), r.cycles(static_cast<int>(targets.back())));
  // Candidates: translations (u, v, w) of the nodes in lattice order, the first `candidates` of them.
  std::vector<Eigen::Index> rows;
  for (long a = 0; a < m.nodes && static_cast<long>(rows.size()) < candidates; ++a)
    for (int c = 0; c < 3 && static_cast<long>(rows.size()) < candidates; ++c) rows.push_back(6 * a + c);
  Eigen::MatrixXd Phi(static_cast<Eigen::Index>(rows.size()), modes);
  for (int j = 0; j < modes; ++j)
    for (std::size_t i = 0; i < rows.size(); ++i)
      Phi(static_cast<Eigen::Index>(i), j) = r.modes(rows[i], targets[static_cast<std::size_t>(j)]);
  std::printf("candidates: %zu DOFs, %d target modes, Φ_c %.1f MiB\n", rows.size(), modes,
              static_cast<double>(Phi.size()) * 8 / 1048576.0);

  pt::Placement single;
  const auto t1 = timed([&] { single = pt::effective_independence(Phi, sensors); });
  print_placement(("EI " + std::to_string(rows.size()) + " DOFs -> " + std::to_string(sensors)).c_str(), single, t1);
  std::vector<std::vector<Eigen::Index>> groups;
  for (Eigen::Index g = 0; 3 * g + 2 < Phi.rows(); ++g) groups.push_back({3 * g, 3 * g + 1, 3 * g + 2});
  const Eigen::MatrixXd Phi3 = Phi.topRows(3 * static_cast<Eigen::Index>(groups.size()));
  pt::Placement tri;
  const auto t2 = timed([&] { tri = pt::effective_independence(Phi3, triaxes, groups); });
  print_placement(("EI triaxial " + std::to_string(groups.size()) + " grids -> " + std::to_string(triaxes)).c_str(), tri, t2);
  if (!export_dir.empty()) {
    std::ofstream b(export_dir + "/phi.bin", std::ios::binary);
    for (Eigen::Index i = 0; i < Phi.rows(); ++i)
      for (Eigen::Index j = 0; j < Phi.cols(); ++j) b.write(reinterpret_cast<const char*>(&Phi(i, j)), sizeof(double));
    std::ofstream txt(export_dir + "/phi.txt");
    txt << Phi.rows() << " " << Phi.cols() << " " << sensors << "\n";
    for (auto s : single.selected) txt << s << " ";
    txt.precision(17);
    txt << "\n" << single.fisher.log10_determinant << "\n";
    std::printf("wrote %s/phi.bin and phi.txt\n", export_dir.c_str());
  }
  std::printf("peak RSS %ld MiB\n", peak_rss_mib());
  return 0;
}

int run_ga(const std::string& rod) {
  const auto deck = ssid::formats::read_deck(rod);
  const auto model = ssid::translators::assemble_deck(deck, rod);
  const auto op = model->operators(model->initial_parameters(), false);
  EigenOptions o;
  o.nd = 36;
  const EigenResult r = ssid::estimator::solve_modes_dense(op.K, op.M, o);
  const auto targets = pt::select_target_modes(r.eigenvalues, 12, 1.0);
  std::vector<ssid::translators::Dof> dofs;
  for (std::size_t g : model->reduction().a_to_g) dofs.push_back(model->geometry().gset().at(g));
  const auto cand = pt::translational_candidates(dofs);
  const auto groups = pt::group_by_grid(cand);
  std::vector<Eigen::Index> cand_rows;
  for (const auto& c : cand) cand_rows.push_back(c.row);
  Eigen::MatrixXd Phi(static_cast<Eigen::Index>(cand_rows.size()), 12);
  for (int j = 0; j < 12; ++j)
    for (std::size_t i = 0; i < cand_rows.size(); ++i)
      Phi(static_cast<Eigen::Index>(i), j) = r.modes(cand_rows[i], targets[static_cast<std::size_t>(j)]);
  const auto ei = pt::effective_independence(Phi, 18);
  std::vector<Eigen::Index> sensors;
  for (auto s : ei.selected) sensors.push_back(cand[static_cast<std::size_t>(s)].row);
  const pt::DropoffModel dm(r.modes, r.eigenvalues, sensors, cand, groups, targets, 0.01);
  std::printf("rod model: %ld DOF, %d modes, %zu candidate grids, 18 EI sensors, 12 targets\n", static_cast<long>(op.K.rows()),
              r.size(), groups.size());
  auto run = [&](int generations) {
    pt::GeneticOptions go;
    go.population = 20;
    go.generations = generations;
    pt::ExciterPlacement xp;
    std::vector<double> wall;
    for (int rep = 0; rep < 5; ++rep) wall.push_back(timed([&] { xp = pt::place_exciters(dm, 2, go); }).first);
    std::sort(wall.begin(), wall.end());
    std::printf("GA, 2 exciters, population 20, %2d generations: best of 5 %.4f s wall, median %.4f s; %ld evaluations, "
                "objective %.6g\n",
                generations, wall.front(), wall[2], static_cast<long>(xp.ga.evaluations), xp.objective);
    return std::make_pair(wall.front(), static_cast<double>(xp.ga.evaluations));
  };
  const auto g0 = run(0), g40 = run(40);
  const double per = (g40.first - g0.first) / 40, evals = (g40.second - g0.second) / 40;
  std::printf("per generation: %.3f ms (%.0f evaluations, %.1f µs each)\n", 1e3 * per, evals, 1e6 * per / evals);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  int n = 25, modes = 40, sensors = 45, triaxes = 30;
  long candidates = 25000;
  std::string export_dir, rod = "samples/mpi_rod.bdf";
  bool skip_ei = false, skip_ga = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "%s needs a value\n", a.c_str());
        std::exit(2);
      }
      return argv[++i];
    };
    if (a == "--candidates") candidates = std::stol(next());
    else if (a == "--modes") modes = std::stoi(next());
    else if (a == "--sensors") sensors = std::stoi(next());
    else if (a == "--triaxes") triaxes = std::stoi(next());
    else if (a == "--export") export_dir = next();
    else if (a == "--rod") rod = next();
    else if (a == "--skip-ei") skip_ei = true;
    else if (a == "--skip-ga") skip_ga = true;
    else if (!a.empty() && a[0] != '-') n = std::stoi(a);
    else {
      std::fprintf(stderr, "usage: bench_pretest [N] [--candidates C] [--modes M] [--sensors S] [--triaxes T] [--export DIR] "
                           "[--rod PATH] [--skip-ei] [--skip-ga]\n");
      return 2;
    }
  }
  if (!skip_ei && run_ei(n, candidates, modes, sensors, triaxes, export_dir) != 0) return 1;
  if (!skip_ga) return run_ga(rod);
  return 0;
}
