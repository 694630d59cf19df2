/// \file bench_estimate.cpp
/// One estimation cycle on a deck — eigen-solve, pairing, sensitivities
/// (exact ∂λ, Nelson ∂φ), the Bayesian step of Eq. (7) — with the time of each
/// part. The "measured" modes are the deck's own modes at perturbed DESVAR
/// values (every parameter +3 %), sampled at the first grids (the balls of the
/// MPI truss decks) in X, Y, Z and written as a universal file, so the cycle
/// sees realistic pairs and residuals.
///
/// usage: bench_estimate DECK [--modes N] [--sensors S] [--repeat R] [--modal-sum]
///   DECK       e.g. samples/mpi_beam.bdf (≈10k DOF)
///   --modes    measured = analysis modes (default 35)
///   --sensors  grids 1..S measured (default 80)
///   --repeat   cycles timed (default 3; the first also does the symbolic analysis)
///   --modal-sum  the seed's modal-summation shape derivatives instead of Nelson's
///   --method   Krylov iteration of the eigen-solver (default auto)
#include <chrono>
#include <ctime>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <unistd.h>

#include "estimator/study/deck_study.hpp"
#include "estimator/eigen/eigen_solver.hpp"
#include "estimator/updating/updating.hpp"
#include "formats/bulk_model.hpp"
#include "formats/uff.hpp"
#include "translators/assembly/fe_model.hpp"
#include "translators/measurement/mode_set.hpp"

namespace {

using namespace ssid;

double now_s() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

struct Times {
  double assemble = 0, eigen = 0, sensitivity = 0, total = 0;
};

/// Times the model's phases for the benchmark.
class TimedModel : public estimator::ModalModel {
 public:
  TimedModel(std::shared_ptr<estimator::ModalModel> m, Times& t) : m_model(std::move(m)), m_t(t) {}
  int parameter_count() const override { return m_model->parameter_count(); }
  estimator::ModalSolution solve(const Eigen::VectorXd& r) override { return m_model->solve(r); }
  estimator::ModeSensitivity sensitivity(int i, bool shapes) override {
    const double t0 = now_s();
    auto s = m_model->sensitivity(i, shapes);
    m_t.sensitivity += now_s() - t0;
    return s;
  }
  std::vector<estimator::ModeSensitivity> sensitivities(const std::vector<int>& modes,
                                                        const std::vector<bool>& shapes) override {
    const double t0 = now_s();
    auto s = m_model->sensitivities(modes, shapes);
    m_t.sensitivity += now_s() - t0;
    return s;
  }

 private:
  std::shared_ptr<estimator::ModalModel> m_model;
  Times& m_t;
};

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: bench_estimate DECK [--modes N] [--sensors S] [--repeat R] [--modal-sum] [--method auto|spectra|block]\n");
    return 2;
  }
  const std::string deck_path = argv[1];
  int modes = 35, sensors = 80, repeat = 3;
  bool modal_sum = false;
  std::string method = "auto";
  for (int i = 2; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--modes") && i + 1 < argc) modes = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--sensors") && i + 1 < argc) sensors = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--repeat") && i + 1 < argc) repeat = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--modal-sum")) modal_sum = true;
    else if (!std::strcmp(argv[i], "--method") && i + 1 < argc) method = argv[++i];
  }
  try {
    // Truth: every DESVAR +3 %; its modes at the sensors as a universal file.
    formats::Deck deck = formats::read_deck(deck_path);
    formats::BulkModel bulk = formats::parse_bulk(deck);
    formats::resolve(deck, bulk);
    const translators::FeModel fe(deck, std::move(bulk));
    const Eigen::VectorXd truth = 1.03 * fe.initial_parameters();
    const auto ops = fe.operators(truth, false);
    estimator::EigenOptions eo;
    eo.nd = modes;
    const auto res = estimator::solve_modes(ops.K, ops.M, eo);
    if (!res.ok()) throw std::runtime_error("truth eigen-solve: " + res.message);
    std::printf("truth solve (%s): %.3f s total, factor %.3f s (%d analyses), Lanczos %.3f s, %ld solves, %d runs\n",
                res.method.c_str(), res.total_seconds, res.factor_seconds, res.analyses, res.lanczos_seconds, res.solves,
                res.lanczos_runs);
    if (method == "compare") {
      // The two Krylov iterations on the same pencil: eigenvalues and residuals.
      for (auto m : {estimator::EigenMethod::Spectra, estimator::EigenMethod::BlockLanczos}) {
        estimator::EigenOptions o = eo;
        o.method = m;
        const auto q = estimator::solve_modes(ops.K, ops.M, o);
        std::printf("%-12s %.3f s (factor %.3f s, nnz(L)/n %.1f, flops/n %.3g), status %d, max backward error %.2e, f1..f%d:",
                    q.method.c_str(), q.total_seconds, q.factor_seconds, q.factor_nnz / static_cast<double>(ops.K.rows()),
                    q.factor_flops / static_cast<double>(ops.K.rows()), static_cast<int>(q.status),
                    q.backward_errors.size() ? q.backward_errors.maxCoeff() : -1.0, q.size());
        for (int i = 0; i < q.size(); ++i) std::printf(" %.6g", std::sqrt(std::max(q.eigenvalues(i), 0.0)) / (2 * M_PI));
        std::printf("\n");
      }
      return 0;
    }
    const Eigen::MatrixXd g = fe.expand(res.modes);
    translators::ModeSet set;
    std::vector<formats::uff::Node> nodes;
    const auto& grids = fe.geometry().grids();
    for (int k = 0; k < sensors && k < static_cast<int>(grids.size()); ++k) {
      formats::uff::Node n;
      n.id = grids[static_cast<std::size_t>(k)].id;
      nodes.push_back(n);
      for (int c = 1; c <= 3; ++c) set.dofs.push_back({n.id, c});
    }
    set.shapes.resize(static_cast<Eigen::Index>(set.dofs.size()), res.size());
    for (int m = 0; m < res.size(); ++m) {
      for (std::size_t k = 0; k < nodes.size(); ++k) {
        const auto& gp = grids[k];
        Eigen::Vector3d u;
        for (int c = 0; c < 3; ++c) u(c) = g(static_cast<Eigen::Index>(gp.dofs[static_cast<std::size_t>(c)]), m);
        set.shapes.block<3, 1>(static_cast<Eigen::Index>(3 * k), m) = gp.frame * u;
      }
      set.frequency_hz.push_back(std::sqrt(std::max(res.eigenvalues(m), 0.0)) / (2 * M_PI));
      set.numbers.push_back(m + 1);
      set.damping.push_back(0);
      set.modal_mass.push_back(0);
    }
    const std::string unv =
        (std::filesystem::temp_directory_path() / ("bench_estimate_" + std::to_string(::getpid()) + ".unv")).string();
    formats::uff::write_uff(translators::mode_set_to_uff(set, nodes), unv, formats::uff::Precision::Extended);

    nlohmann::json sj = {{"analysis_modes", modes}, {"convergence", {{"max_iterations", 0}}}};
    if (modal_sum) sj["sensitivity"] = "modal-sum";
    const estimator::Study study = estimator::parse_study(sj, "bench");
    const double tp = now_s();
    estimator::EstimationProblem problem = estimator::prepare_problem(study, deck_path, unv);
    const double prepare = now_s() - tp;
    std::filesystem::remove(unv);
    auto& pc = problem.configurations[0];

    Times t;
    auto timed_assemble = [&t, a = pc.assemble](const Eigen::VectorXd& r) {
      const double t0 = now_s();
      auto o = a(r);
      t.assemble += now_s() - t0;
      return o;
    };
    auto solver = std::make_shared<estimator::EigenSolver>();
    if (method == "spectra") solver->options().method = estimator::EigenMethod::Spectra;
    if (method == "block") solver->options().method = estimator::EigenMethod::BlockLanczos;
    auto timed_eigen = [&t, solver](const estimator::SparseMatrix& K, const estimator::SparseMatrix& M, int n) {
      const double t0 = now_s();
      solver->options().nd = n;
      auto r = solver->solve(K, M);
      t.eigen += now_s() - t0;
      if (!r.ok()) throw std::runtime_error("eigen-solve: " + r.message);
      return std::make_pair(Eigen::VectorXd(r.eigenvalues), Eigen::MatrixXd(r.modes));
    };
    auto inner = std::make_shared<estimator::OperatorModel>(
        timed_assemble, timed_eigen, pc.sensors, pc.analysis_modes,
        modal_sum ? estimator::ShapeDerivative::ModalSum : estimator::ShapeDerivative::Nelson);
    TimedModel model(inner, t);
    std::printf("deck %s: %zu analysis DOFs, %lld parameters, %zu sensor DOFs, %zu measured modes, %d analysis modes\n",
                deck_path.c_str(), pc.dofs.size(), static_cast<long long>(problem.prior.mean.size()),
                pc.sensor_labels.size(), pc.test.size(), pc.analysis_modes);
    std::printf("prepare (read deck + UFF, assemble model, map sensors): %.3f s\n", prepare);
    std::printf("%-6s %10s %10s %10s %12s %12s %12s %8s %8s\n", "cycle", "total s", "cpu s", "assemble", "eigen-solve",
                "sensitivity", "pair+step", "pairs", "rms %");
    for (int k = 0; k < repeat; ++k) {
      t = Times{};
      const double t0 = now_s();
      const std::clock_t c0 = std::clock();
      const auto r = estimator::update(model, pc.test, problem.prior, problem.options);
      t.total = now_s() - t0;
      const double cpu = static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC;
      const auto& c = r.history.back();
      std::printf("%-6d %10.3f %10.3f %10.3f %12.3f %12.3f %12.3f %8zu %8.3f\n", k + 1, t.total, cpu, t.assemble, t.eigen,
                  t.sensitivity, t.total - t.assemble - t.eigen - t.sensitivity, c.pairs.size(), c.freq_rms_pct);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_estimate: %s\n", e.what());
    return 1;
  }
  return 0;
}
