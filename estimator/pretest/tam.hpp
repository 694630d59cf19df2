#pragma once
/// \file tam.hpp
/// Pretest planning, step 3: test-analysis models (TAM) on a sensor set and the
/// orthogonality check of the target modes with them (issue 23 item 3; pretest
/// paper §4-5: cross-orthogonality with an "exactly reduced" (SEREP) mass).
/// The reductions themselves are estimator/correlation/measures.hpp's guyan_reduce,
/// serep_reduce and irs_reduce.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <string>
#include <vector>

#include "estimator/correlation/measures.hpp"

namespace ssid::estimator::pretest {

enum class TamKind { Guyan, Serep, Irs };
std::string tam_name(TamKind k);  ///< "guyan", "serep", "irs"

/// The usual acceptance of a cross-orthogonality matrix (pretest paper §5,
/// its reference [16]): diagonal > 0.9; off-diagonal < 0.1 (secondary modes),
/// < 0.02 (primary modes, where the paper applies it).
struct XorAcceptance {
  double min_diagonal = 0.9;
  double max_offdiagonal = 0.1;
  double max_offdiagonal_primary = 0.02;
};

struct TamCheck {
  TamKind kind = TamKind::Guyan;
  ReductionStatus status = ReductionStatus::Ok;
  std::string message;  ///< why the reduction failed, when status != Ok
  /// X = Φ_aᵀ M_TAM Φ_a (m x m), with Φ_a the FE target modes (mass-normalised on
  /// the full model) at the sensors, not rescaled: the diagonal says how much of
  /// each mode's mass the TAM keeps (1 ideally), the off-diagonal how well the TAM
  /// mass tells the modes apart (0 ideally).
  Eigen::MatrixXd xor_matrix;
  double min_diagonal = 0, max_offdiagonal = 0;  ///< of |X|
  Eigen::VectorXd tam_hz;    ///< per target, the nearest frequency (Hz) of (K_TAM, M_TAM)
  double max_frequency_error_pct = 0;  ///< max_j 100 |f_TAM − f_FE,j| / f_FE,j, f_TAM the TAM frequency nearest f_FE,j
  bool accepted = false;          ///< diagonal and secondary off-diagonal criteria met
  bool accepted_primary = false;  ///< ... and the primary off-diagonal criterion
};

/// Reduces (K, M) (n x n) to the sensor rows `sensors` with `kind`, and checks the
/// target modes `Phi` (n x m, mass-normalised: φᵀMφ = 1, frequencies `hz`) with the TAM mass.
/// A failed reduction comes back as the status, never an exception.
TamCheck tam_check(TamKind kind, const Eigen::SparseMatrix<double>& K, const Eigen::SparseMatrix<double>& M,
                   const Eigen::Ref<const Eigen::MatrixXd>& Phi, const Eigen::Ref<const Eigen::VectorXd>& hz,
                   const std::vector<Eigen::Index>& sensors, const XorAcceptance& acceptance = {});

}  // namespace ssid::estimator::pretest
