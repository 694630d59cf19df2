#pragma once
/// \file evidence.hpp
/// What the model gets wrong after the ordinary update: the residual evidence
/// an analyst reads before forming hypotheses.
///  - test modes with no analysis partner (frequency, where they move: the grids
///    with the largest share of the shape, Σ_c ψ_{g,c}² / ‖ψ‖²);
///  - analysis modes (within the tested band) with no test partner;
///  - the pattern of frequency errors of the pairs: mean (a global scale error),
///    RMS, and the slope of error against frequency;
///  - MEMS (reconciliation paper Eqs. 2–3): each test mode fitted by all analysis
///    modes at the sensors; e² near 0 means the model can represent the shape,
///    near 1 that the shape lies outside the model's space (a missing mode
///    family); the error mode's grids;
///  - shape errors concentrated at grids: for each grid,
///    E_g = Σ_pairs Σ_{c at g} ((z − u)_c / σ_s)²  (weighted misfit of the unit shapes).
#include <string>
#include <vector>

#include "estimator/study/deck_study.hpp"
#include "estimator/reporting/number_text.hpp"

namespace ssid::estimator::diagnosis {

struct GridShare {
  std::int64_t grid = 0;
  double share = 0;  ///< fraction (0–1)
};

struct UnpairedTestMode {
  int id = 0;
  double frequency_hz = 0;
  std::vector<GridShare> moves;   ///< the grids it moves most, largest first (≤ 5)
  double mems_error = 0;          ///< e² of its MEMS fit by the analysis modes
};

struct UnpairedFeMode {
  int mode = 0;  ///< 1-based analysis mode number
  double frequency_hz = 0;
};

struct ModeEvidence {
  int test_id = 0;
  double test_hz = 0;
  int fem = 0;  ///< 1-based; 0 when unpaired
  double fem_hz = 0, error_pct = 0, mac = 0;
  double mems_error = 0;
  std::vector<GridShare> error_grids;  ///< where its error-mode shape is largest (≤ 3)
};

struct Evidence {
  std::vector<ModeEvidence> modes;          ///< every test mode
  std::vector<UnpairedTestMode> unpaired_test;
  std::vector<UnpairedFeMode> unpaired_fe;  ///< analysis modes up to 1.1× the highest test frequency
  double mean_error_pct = 0, rms_error_pct = 0, error_slope_pct_per_hz = 0;
  std::vector<GridShare> grid_misfit;       ///< E_g normalised to sum 1, largest first
  /// One-line readings ("2 test modes near 48 Hz have no partner", …).
  std::vector<std::string> findings;
};

/// Builds the evidence from one configuration solved at `r` and the pairs of
/// the update's final cycle.
Evidence gather_evidence(PreparedConfiguration& problem, const Eigen::VectorXd& r, const std::vector<UpdatePair>& pairs);

}  // namespace ssid::estimator::diagnosis
