#pragma once
/// \file modal_model.hpp
/// The model as the estimator sees it: parameters r in, modes at the measured
/// DOFs and their sensitivities out.
///
/// OperatorModel is the general implementation: an `Assemble` callback gives
/// K(r), M(r), ∂K/∂r_j, ∂M/∂r_j (exact re-assembly of our own deck, or the
/// first-order Taylor model of imported operators, `taylor_operators`), an
/// `EigenSolve` callback gives the lowest modes, and the sensitivities come from
/// sensitivity.hpp: ∂λ exact, ∂φ by Nelson's method (exact) or the seed
/// report's modal summation.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <functional>
#include <memory>
#include <utility>
#include <vector>

namespace ssid::estimator {

using SparseMatrix = Eigen::SparseMatrix<double>;

/// Modes of one solve.
struct ModalSolution {
  Eigen::VectorXd eigenvalues;      ///< λ = ω² [(rad/s)²], ascending
  Eigen::MatrixXd sensor_shapes;    ///< n_s × m: shapes at the measured DOFs
  Eigen::MatrixXd tracking_shapes;  ///< n_t × m: shapes used to follow modes from cycle to cycle
};

/// Sensitivities of one mode of the last solve.
struct ModeSensitivity {
  Eigen::VectorXd d_eigenvalue;    ///< ∂λ/∂r_j, length p
  Eigen::MatrixXd d_sensor_shape;  ///< ∂φ_s/∂r_j, n_s × p (empty when not asked for)
};

class ModalModel {
 public:
  virtual ~ModalModel() = default;
  virtual int parameter_count() const = 0;
  /// Solves at parameters r (length p).
  virtual ModalSolution solve(const Eigen::VectorXd& r) = 0;
  /// Sensitivities of mode i of the last solve; shape derivatives only when asked.
  virtual ModeSensitivity sensitivity(int i, bool shapes) = 0;
  /// The sensitivities of the modes `modes` of the last solve (shapes[k]: whether
  /// mode modes[k] needs its shape derivatives), in that order: what sensitivity()
  /// gives for each. This default calls it for each in turn; a model whose modes
  /// can be differentiated independently computes them concurrently.
  virtual std::vector<ModeSensitivity> sensitivities(const std::vector<int>& modes, const std::vector<bool>& shapes);
};

/// K, M and their derivatives with respect to each parameter.
struct Operators {
  SparseMatrix K, M;
  std::vector<SparseMatrix> dK, dM;
};

enum class ShapeDerivative { Nelson, ModalSum };

class NelsonSolver;  // sensitivity.hpp

class OperatorModel : public ModalModel {
 public:
  using Assemble = std::function<Operators(const Eigen::VectorXd& r)>;
  /// Returns (eigenvalues ascending, mass-normalised modes n × m) of the lowest `nmodes`.
  using EigenSolve =
      std::function<std::pair<Eigen::VectorXd, Eigen::MatrixXd>(const SparseMatrix& K, const SparseMatrix& M, int nmodes)>;

  /// `sensors` selects (or combines) model DOFs into measured DOFs: n_s × n.
  OperatorModel(Assemble assemble, EigenSolve eigensolve, SparseMatrix sensors, int nmodes,
                ShapeDerivative shape_derivative = ShapeDerivative::Nelson);

  int parameter_count() const override { return m_parameters; }
  ModalSolution solve(const Eigen::VectorXd& r) override;
  ModeSensitivity sensitivity(int i, bool shapes) override;
  /// On up to one thread per core (at most kMaxSensitivityThreads), each with its
  /// own Nelson solver, kept until the next solve (a mode's ∂φ needs a
  /// factorisation of K − λM of its own: 35 modes of the 8.5k-DOF beam deck took
  /// 0.17 s on one core; each thread holds one such factor). The same values as one
  /// by one, and on a failure the same exception: the first failing mode's.
  /// Not to be called concurrently on one model.
  std::vector<ModeSensitivity> sensitivities(const std::vector<int>& modes, const std::vector<bool>& shapes) override;
  static constexpr std::size_t kMaxSensitivityThreads = 8;
  /// Threads for sensitivities(); 0 (the default): one per core, at most
  /// kMaxSensitivityThreads.
  void set_sensitivity_threads(int threads) { m_threads = threads; }
  /// Follow modes from cycle to cycle by their shapes at the sensors (true)
  /// rather than at every DOF (false, the default; also when there are no
  /// sensors). Strut-local modes crowd the spectrum of beam models; a global
  /// mode mixes with them as parameters move (veering) and its full shape
  /// changes a lot, while at the sensors — which see global motion only — it
  /// stays recognisable.
  void set_tracking_on_sensors(bool on) { m_track_on_sensors = on; }

  const Operators& operators() const { return m_ops; }
  ShapeDerivative shape_derivative() const { return m_shape_derivative; }
  const Eigen::MatrixXd& modes() const { return m_phi; }

 private:
  Assemble m_assemble;
  EigenSolve m_eigensolve;
  SparseMatrix m_sensors;
  int m_nmodes;
  ShapeDerivative m_shape_derivative;
  int m_parameters = -1;
  int m_threads = 0;
  bool m_track_on_sensors = false;
  Operators m_ops;
  Eigen::VectorXd m_lambda;
  Eigen::MatrixXd m_phi;
  /// Analyses of K − λM shared by the modes of one solve, one per thread that
  /// computes sensitivities (the first for sensitivity()).
  std::vector<std::shared_ptr<NelsonSolver>> m_nelson;
  ModeSensitivity sensitivity_with(int i, bool shapes, std::size_t solver);
};

/// First-order Taylor model of imported operators about r0:
///   K(r) = K0 + Σ_j (r_j − r0_j) ∂K/∂r_j, and the same for M,
/// exact when K and M are linear in r (areas, E, ρ, spring rates, masses).
OperatorModel::Assemble taylor_operators(Operators nominal, Eigen::VectorXd r0);

}  // namespace ssid::estimator
