#pragma once
/// \file calibration.hpp
/// The statistics that make the diagnosis's decision calibrated
/// (docs/diagnosis.md, "Noise", "Anything left to explain?", "A calibrated
/// decision", "Two effects"). Everything here works on the ordinary update
/// linearised at its estimate r*, in units of the assumed noise:
///
///   e = S_ee^{-1/2}(z − u(r*))   (m rows: a frequency row and n_s shape rows per pair),
///   W = S_ee^{-1/2} T D          (prior-scaled sensitivities, D = diag prior σ),
///   θ* = D⁻¹(r* − r₀),
///
/// and on the candidates' prior-scaled weighted sensitivities
/// u_k = σ_βk S_ee^{-1/2} ∂u/∂β_k (the first-order screening's columns).
///
/// **Noise.** Each group g (frequencies, shapes) has its own scale s_g on the
/// assumed σ. With C = diag(1/s_g²) per row, the linear fit
/// (I + WᵀCW) δ = WᵀCe − θ* has residual e(C) = e − Wδ and, per group,
///   ŝ_g² = ‖e_g(C)‖² / ν_g,   ν_g = m_g − tr(P_gg),   P = W (I + WᵀCW)⁻¹ WᵀC,
/// iterated to its fixed point (ν_g: the effective degrees of freedom left to
/// the group). A group with ν_g < `min_dof` takes the pooled scale of all rows.
///
/// **Candidate statistic.** With u = u_k, the Schur complement
/// s = uᵀCu − uᵀCW H⁻¹ WᵀCu (H = I + WᵀCW), g = uᵀC e(C) and β̂ = g/(s + 1),
/// the residual with the candidate is e₁ = e(C) − ũ β̂, ũ = u − W H⁻¹ WᵀCu, and
///   G_k = −Σ_g (ν_g/2) log(‖e₁,g‖² / ‖e_g(C)‖²) − ½ log(1 + s),
/// the first-order evidence gain with each group's noise scale integrated out
/// under a Jeffreys prior (profile form: the residual sum of squares of each
/// group enters to the power −ν_g/2), so a wrongly assumed σ cancels.
///
/// **Bootstrap.** Replicates of the data from the ordinary update's model with
/// the estimated noise: ε ~ N(0, diag(ŝ_g²)), the replicate's residual after
/// the linearised update e_b = Rε + W H₀⁻¹θ* (R = I − W H₀⁻¹ Wᵀ, H₀ = I + WᵀW:
/// the fit the update makes), then the whole screening replayed on e_b — noise
/// re-estimated, every candidate's G_k — and the best T_b = max_k G_k kept.
/// A candidate with statistic G is a false alarm with probability
///   p = (1 + #{b: T_b ≥ G}) / (B + 1),
/// a valid p-value for any B (P(p ≤ α) ≤ α when the replicates and the data
/// are exchangeable under the null), whose smallest value is 1/(B + 1).
#include <Eigen/Dense>
#include <cstdint>
#include <string>
#include <vector>

namespace ssid::estimator::diagnosis {

/// Row groups of the weighted residual.
enum RowGroup : int { kFrequencyRows = 0, kShapeRows = 1 };
constexpr int kRowGroups = 2;

/// The ordinary update linearised at its estimate (see the file comment).
struct LinearUpdate {
  Eigen::VectorXd e;        ///< weighted residual, assumed-σ units (m)
  Eigen::MatrixXd W;        ///< weighted prior-scaled sensitivities (m × p)
  Eigen::VectorXd theta;    ///< D⁻¹(r* − r₀) (p)
  std::vector<int> group;   ///< per row: kFrequencyRows or kShapeRows
  std::vector<int> block;   ///< per row: the paired mode it belongs to, 0 … n_blocks − 1
  int blocks() const;
};

/// Noise scales on the assumed σ, per group.
struct NoiseScale {
  double scale[kRowGroups] = {1.0, 1.0};  ///< ŝ_g = implied σ / assumed σ
  double chi2[kRowGroups] = {0.0, 0.0};   ///< ‖e_g‖² of the ordinary update (assumed σ)
  double dof[kRowGroups] = {0.0, 0.0};    ///< ν_g (at the estimated scales)
  int rows[kRowGroups] = {0, 0};          ///< m_g
  bool pooled = false;                    ///< a group had too few degrees of freedom: one scale for all
  bool estimated = true;                  ///< false: the assumed σ is taken as given (scales 1)
};

/// ŝ_g of the file comment for residual `e` (rows of `lu`). `estimate` false
/// gives scales 1 with χ² and ν still filled in. Throws formats::InputError
/// when the fit leaves no degree of freedom to estimate the noise from.
NoiseScale estimate_noise(const LinearUpdate& lu, const Eigen::Ref<const Eigen::VectorXd>& e, bool estimate = true,
                          int min_dof = 3);

/// χ² goodness of fit of one group against the assumed σ: P(χ²(ν) ≥ χ²).
double chi2_upper_tail(double chi2, double dof);

/// The χ²(ν) value exceeded with probability p: chi2_upper_tail(x, ν) = p.
double chi2_quantile_upper(double p, double dof);

/// Options of the calibrated decision.
struct CalibrationOptions {
  bool estimate_noise = true;   ///< false: the assumed σ is the noise (study "noise": "given")
  int replicates = 199;         ///< bootstrap replicates of the first-order screening
  double false_alarm = 0.01;    ///< the largest false-alarm probability of a named cause
  std::uint64_t seed = 20261127;
  int min_dof = 3;              ///< fewer degrees of freedom in a group: pooled scale
};

/// Smallest p a bootstrap of B replicates can show, 1/(B + 1).
inline double smallest_p(int replicates) { return 1.0 / (replicates + 1.0); }

/// The one-sided 95 % upper bound (Clopper–Pearson) on the true tail
/// probability when `exceed` of `replicates` replicates reached the statistic.
double tail_upper_bound(int exceed, int replicates, double confidence = 0.95);

/// Held-out (leave-one-mode-out) prediction error of the linearised model with
/// and without a candidate, in units of the estimated noise: for each paired
/// mode i, the fit without its rows predicts them, r_i = e_i − X_i δ_{−i};
/// CV_g = Σ_i r_{i,g}ᵀ C r_{i,g}. gain_g = CV_g(null) − CV_g(candidate) (> 0: better).
struct HeldOutGain {
  double gain[kRowGroups] = {0.0, 0.0};
  double null_cv[kRowGroups] = {0.0, 0.0};
  double total() const { return gain[0] + gain[1]; }
};

/// First-order screening of a fixed set of candidate columns against a
/// linearised null, and its parametric bootstrap.
class Screening {
 public:
  /// `null`: the linearised ordinary update; `candidates`: the columns u_k (m × K).
  Screening(LinearUpdate null, Eigen::MatrixXd candidates, CalibrationOptions options);

  const LinearUpdate& null_model() const { return m_null; }
  int candidate_count() const { return static_cast<int>(m_U.cols()); }
  const NoiseScale& noise() const { return m_noise; }

  /// G_k of every candidate for the observed residual (the noise estimated from it).
  const Eigen::VectorXd& gains() const { return m_gains; }
  /// G_k for residual `e` (noise re-estimated from `e`).
  Eigen::VectorXd gains_for(const Eigen::Ref<const Eigen::VectorXd>& e) const;

  /// Runs the bootstrap (B = options.replicates); the sorted maxima T_b.
  const std::vector<double>& bootstrap();
  const std::vector<double>& maxima() const { return m_maxima; }
  /// #{b: T_b ≥ G} and the p of the file comment (bootstrap() first).
  int exceedances(double G) const;
  double false_alarm(double G) const;

  /// Leave-one-mode-out gain of candidate k over the null (observed data).
  HeldOutGain held_out(int k) const;


 private:
  struct Fit {
    Eigen::VectorXd e;   ///< e(C)
    Eigen::LDLT<Eigen::MatrixXd> H;
    Eigen::VectorXd We[kRowGroups];  ///< W_gᵀ e_g(C)
    double c[kRowGroups];
    double rss[kRowGroups];
    double dof[kRowGroups];
  };
  /// The linear fit of residual `e` (prior offset `theta`) at the scales of `ns`.
  Fit fit(const Eigen::Ref<const Eigen::VectorXd>& e, const Eigen::Ref<const Eigen::VectorXd>& theta,
          const NoiseScale& ns) const;
  /// G_k from a fit and Ute (K × 2: U_gᵀ e_g(C)).
  Eigen::VectorXd gains_from(const Fit& f, const Eigen::Ref<const Eigen::MatrixXd>& Ute) const;
  Eigen::MatrixXd group_products(const Eigen::Ref<const Eigen::VectorXd>& e) const;

  LinearUpdate m_null;
  Eigen::MatrixXd m_U;
  CalibrationOptions m_opt;
  Eigen::MatrixXd m_mask;         ///< m × 2: 1 where the row is in the group
  Eigen::MatrixXd m_A;            ///< K × 2: ‖u_k,g‖²
  Eigen::MatrixXd m_B[kRowGroups];  ///< p × K: W_gᵀ u_k,g
  Eigen::MatrixXd m_WW[kRowGroups]; ///< p × p: W_gᵀ W_g
  NoiseScale m_noise;
  Eigen::VectorXd m_gains;
  std::vector<double> m_maxima;
};

}  // namespace ssid::estimator::diagnosis
