#include "estimator/updating/modal_model.hpp"

#include <algorithm>
#include <atomic>
#include <exception>
#include <stdexcept>
#include <string>
#include <system_error>
#include <thread>

#include "estimator/updating/sensitivity.hpp"

namespace ssid::estimator {

OperatorModel::OperatorModel(Assemble assemble, EigenSolve eigensolve, SparseMatrix sensors, int nmodes,
                             ShapeDerivative shape_derivative)
    : m_assemble(std::move(assemble)),
      m_eigensolve(std::move(eigensolve)),
      m_sensors(std::move(sensors)),
      m_nmodes(nmodes),
      m_shape_derivative(shape_derivative) {
  if (m_nmodes <= 0) throw std::invalid_argument("OperatorModel: the number of modes must be positive");
}

ModalSolution OperatorModel::solve(const Eigen::VectorXd& r) {
  m_ops = m_assemble(r);
  if (m_ops.dK.size() != m_ops.dM.size())
    throw std::invalid_argument("OperatorModel: as many dM as dK operators expected");
  if (static_cast<Eigen::Index>(m_ops.dK.size()) != r.size())
    throw std::invalid_argument("OperatorModel: " + std::to_string(r.size()) + " parameters but " +
                                std::to_string(m_ops.dK.size()) + " operator derivatives");
  m_parameters = static_cast<int>(r.size());
  if (m_sensors.cols() != m_ops.K.cols())
    throw std::invalid_argument("OperatorModel: sensor selection has " + std::to_string(m_sensors.cols()) +
                                " columns, the model " + std::to_string(m_ops.K.cols()) + " DOFs");
  auto [lambda, phi] = m_eigensolve(m_ops.K, m_ops.M, m_nmodes);
  m_lambda = std::move(lambda);
  m_phi = std::move(phi);
  m_nelson.clear();
  ModalSolution s;
  s.eigenvalues = m_lambda;
  s.sensor_shapes = m_sensors * m_phi;
  // At the sensors when asked and there are sensors (see set_tracking_on_sensors).
  s.tracking_shapes = m_track_on_sensors && m_sensors.rows() > 0 ? s.sensor_shapes : m_phi;
  return s;
}

std::vector<ModeSensitivity> ModalModel::sensitivities(const std::vector<int>& modes, const std::vector<bool>& shapes) {
  if (shapes.size() != modes.size()) throw std::invalid_argument("sensitivities: one shapes flag per mode expected");
  std::vector<ModeSensitivity> out;
  out.reserve(modes.size());
  for (std::size_t k = 0; k < modes.size(); ++k) out.push_back(sensitivity(modes[k], shapes[k]));
  return out;
}

ModeSensitivity OperatorModel::sensitivity(int i, bool shapes) { return sensitivity_with(i, shapes, 0); }

std::vector<ModeSensitivity> OperatorModel::sensitivities(const std::vector<int>& modes,
                                                          const std::vector<bool>& shapes) {
  if (shapes.size() != modes.size()) throw std::invalid_argument("sensitivities: one shapes flag per mode expected");
  for (int i : modes)
    if (i < 0 || i >= m_lambda.size()) throw std::out_of_range("OperatorModel: no mode " + std::to_string(i + 1));
  // Only the shape derivatives cost (a factorisation each with Nelson's method, a
  // pass over the modes with modal summation); the rest is a few sparse products.
  // So the modes with shapes are dealt round-robin (neighbouring modes cost alike),
  // the others go to the first thread; each thread has its own solver, so the
  // values do not depend on the split.
  const auto shaped = static_cast<std::size_t>(std::count(shapes.begin(), shapes.end(), true));
  const std::size_t wanted = m_threads > 0 ? static_cast<std::size_t>(m_threads)
                                           : std::min<std::size_t>(std::max(1u, std::thread::hardware_concurrency()),
                                                                   kMaxSensitivityThreads);
  const std::size_t threads = std::min(wanted, std::max<std::size_t>(1, shaped));
  if (threads <= 1) return ModalModel::sensitivities(modes, shapes);
  std::vector<ModeSensitivity> out(modes.size());
  std::vector<std::vector<std::size_t>> share(threads);
  for (std::size_t k = 0, next = 0; k < modes.size(); ++k) share[shapes[k] ? next++ % threads : 0].push_back(k);
  if (m_shape_derivative == ShapeDerivative::Nelson) {
    if (m_nelson.size() < threads) m_nelson.resize(threads);
    for (auto& solver : m_nelson)  // created here, not in the threads: the vector is not theirs to grow
      if (!solver) solver = std::make_shared<NelsonSolver>(m_ops.K, m_ops.M);
  }
  // A failure stops the work on later modes, and the error thrown is the first
  // failing mode's in `modes` order, as one by one: each thread takes its modes in
  // that order and goes on while they come before the first failure seen.
  std::atomic<std::size_t> first_failed{modes.size()};
  std::vector<std::exception_ptr> errors(modes.size());
  auto work = [&](std::size_t t) {
    for (std::size_t k : share[t]) {
      if (k > first_failed.load()) return;
      try {
        out[k] = sensitivity_with(modes[k], shapes[k], t);
      } catch (...) {
        errors[k] = std::current_exception();
        std::size_t seen = first_failed.load();
        while (k < seen && !first_failed.compare_exchange_weak(seen, k)) {
        }
        return;
      }
    }
  };
  std::vector<std::thread> pool;
  pool.reserve(threads);  // before any thread starts: a throwing growth would leave them unjoined
  std::size_t started = 1;
  try {
    for (; started < threads; ++started) pool.emplace_back(work, started);
  } catch (const std::system_error&) {
    // No more threads to be had (a process limit): the shares not started run here.
  }
  for (std::size_t t = started; t < threads; ++t) work(t);
  work(0);
  for (auto& th : pool) th.join();
  if (first_failed.load() < modes.size()) std::rethrow_exception(errors[first_failed.load()]);
  return out;
}

ModeSensitivity OperatorModel::sensitivity_with(int i, bool shapes, std::size_t solver) {
  if (i < 0 || i >= m_lambda.size()) throw std::out_of_range("OperatorModel: no mode " + std::to_string(i + 1));
  const Eigen::VectorXd phi = m_phi.col(i);
  const std::size_t p = m_ops.dK.size();
  ModeSensitivity s;
  s.d_eigenvalue.resize(static_cast<Eigen::Index>(p));
  for (std::size_t j = 0; j < p; ++j)
    s.d_eigenvalue(static_cast<Eigen::Index>(j)) = eigenvalue_derivative(m_ops.dK[j], m_ops.dM[j], m_lambda(i), phi);
  if (!shapes) return s;
  Eigen::MatrixXd dphi;
  if (m_shape_derivative == ShapeDerivative::Nelson) {
    if (m_nelson.size() <= solver) m_nelson.resize(solver + 1);
    auto& nelson = m_nelson[solver];
    if (!nelson) nelson = std::make_shared<NelsonSolver>(m_ops.K, m_ops.M);
    dphi = nelson->derivatives(m_lambda(i), phi, m_ops.dK, m_ops.dM);
  } else {
    dphi.resize(phi.size(), static_cast<Eigen::Index>(p));
    for (std::size_t j = 0; j < p; ++j)
      dphi.col(static_cast<Eigen::Index>(j)) = modal_sum_derivative(m_phi, m_lambda, i, m_ops.dK[j], m_ops.dM[j]);
  }
  s.d_sensor_shape = m_sensors * dphi;
  return s;
}

OperatorModel::Assemble taylor_operators(Operators nominal, Eigen::VectorXd r0) {
  if (static_cast<Eigen::Index>(nominal.dK.size()) != r0.size() || nominal.dM.size() != nominal.dK.size())
    throw std::invalid_argument("taylor_operators: one dK and one dM per parameter expected");
  return [nominal = std::move(nominal), r0 = std::move(r0)](const Eigen::VectorXd& r) {
    Operators ops = nominal;
    for (Eigen::Index j = 0; j < r0.size(); ++j) {
      const double d = r(j) - r0(j);
      if (d == 0.0) continue;
      ops.K += d * nominal.dK[static_cast<std::size_t>(j)];
      ops.M += d * nominal.dM[static_cast<std::size_t>(j)];
    }
    return ops;
  };
}

}  // namespace ssid::estimator
