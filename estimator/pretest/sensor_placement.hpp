#pragma once
/// \file sensor_placement.hpp
/// Pretest planning, step 2: where to put the sensors (issue 23 item 2; seed
/// report, pretest paper §2.1-2.3 and §5).
///
/// Every method works on the target modes at the candidate DOFs, Φ_c (c x m,
/// rows = candidates, columns = target modes), and returns positions in those
/// rows. A *group* is a set of candidate rows placed together (a triax: the three
/// translations of one grid); ungrouped placement is placement over singleton
/// groups.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <string>
#include <vector>

namespace ssid::estimator::pretest {

enum class PlacementMethod {
  EffectiveIndependence,  ///< Kammer's EI: iterative deletion of the least independent DOF
  KineticEnergy,          ///< largest share of one target mode's kinetic energy
  AverageKineticEnergy,   ///< largest kinetic energy averaged over the target modes
  EigenvectorProduct,     ///< largest |Π_j φ_ij| (Jarvis)
  EigenvectorSum          ///< largest Σ_j |φ_ij| / max_k |φ_kj| (the absolute-sum variant)
};

/// "ei", "ke", "ake", "evp", "evp-sum".
std::string method_name(PlacementMethod m);

/// The Fisher information F = Φ_sᵀ Φ_s of a sensor set (unit sensor noise) and
/// what the paper reports of it.
struct FisherSummary {
  double determinant = 0;        ///< det F (scale: that of the modes; mass-normalised here)
  double log10_determinant = 0;  ///< log10 det F (-inf when singular)
  double condition_number = 0;   ///< σ_max² / σ_min² of Φ_s (= cond₂ F); +inf when rank-deficient
  int rank = 0;                  ///< numerical rank of Φ_s
};
FisherSummary fisher_summary(const Eigen::Ref<const Eigen::MatrixXd>& Phi_s);

struct Placement {
  PlacementMethod method = PlacementMethod::EffectiveIndependence;
  bool grouped = false;
  std::vector<Eigen::Index> selected;  ///< candidate rows kept, ascending
  std::vector<Eigen::Index> groups_kept;  ///< groups kept (positions in the group list), ascending
  /// Score of each selected row, in the order of `selected`: EI's E_i = [Φ_s (Φ_sᵀΦ_s)⁻¹ Φ_sᵀ]_ii
  /// on the final set, or the ranking metric of the other methods.
  Eigen::VectorXd score;
  FisherSummary fisher;  ///< of the selected rows
  int protected_groups = 0;  ///< EI, grouped: groups kept only because one of their DOFs had E = 1
};

/// Effective independence (Kammer 1991) by iterative deletion. With the Fisher
/// information F = Φᵀ Φ of the rows still in place and E_i = φ_iᵀ F⁻¹ φ_i (the
/// diagonal of the projector Φ F⁻¹ Φᵀ, 0 ≤ E_i ≤ 1, Σ E_i = m), deleting row i
/// multiplies det F by (1 − E_i); each step deletes the group g with the
/// smallest Σ_{i∈g} E_i, except (grouped) a group holding a row with E_i = 1 —
/// essential to the independence of the modes — which is kept regardless
/// (pretest paper §5.2), and a group whose joint deletion would make F singular.
/// The update is rank-k (Woodbury; Sherman–Morrison for a single row), never a
/// fresh determinant: with G = Φ_g, V = F⁻¹Gᵀ, S = I − G V,
///   F⁻¹ ← F⁻¹ + V S⁻¹ Vᵀ,  E_j ← E_j + w_jᵀ S⁻¹ w_j,  w_j = Vᵀ φ_j,  det F ← det F · det S,
/// O(c m k) a step; F⁻¹ and E are recomputed from scratch each time the row count
/// halves, to keep round-off from accumulating. Invariant to the scaling of the
/// modes (E is a projector's diagonal).
/// `groups` empty: every row is its own group and `keep` counts rows; otherwise
/// `keep` counts groups. Throws formats::InputError when fewer rows than modes
/// would remain, `keep` exceeds what there is, or the modes are not independent
/// on the candidates to begin with.
Placement effective_independence(const Eigen::Ref<const Eigen::MatrixXd>& Phi_c, int keep,
                                 const std::vector<std::vector<Eigen::Index>>& groups = {});

/// Fraction of target mode j's kinetic energy at DOF i,
///   KE_ij = φ_ij (M φ_j)_i / (φ_jᵀ M φ_j),
/// for the DOFs `rows` of `Phi` (n x m, rows = the DOFs of M). With a lumped mass
/// KE_ij = m_i φ_ij² / (φ_jᵀMφ_j) ≥ 0 and Σ_i KE_ij = 1 over all DOFs. M may be
/// the FE mass or a reduced one (then Phi holds the modes on the reduced DOFs).
Eigen::MatrixXd kinetic_energy_fractions(const Eigen::Ref<const Eigen::MatrixXd>& Phi,
                                         const Eigen::SparseMatrix<double>& M, const std::vector<Eigen::Index>& rows);

/// Ranking metric of the non-iterative methods, one value per candidate row:
/// KE max_j KE_ij; AKE (1/m) Σ_j KE_ij; EVP |Π_j φ_ij|; EVP-sum Σ_j |φ_ij| / max_k |φ_kj|
/// (each mode scaled to a largest candidate value of 1, so that no mode dominates
/// by its normalisation). `ke` (c x m) is needed for KE and AKE only.
Eigen::VectorXd placement_metric(PlacementMethod method, const Eigen::Ref<const Eigen::MatrixXd>& Phi_c,
                                 const Eigen::Ref<const Eigen::MatrixXd>& ke);

/// Keeps the `keep` rows (ungrouped) or groups (grouped: by the sum of their rows'
/// metric) with the largest metric; ties go to the lower index. Throws
/// formats::InputError when `keep` exceeds what there is or is < 1.
Placement rank_placement(PlacementMethod method, const Eigen::Ref<const Eigen::MatrixXd>& Phi_c,
                         const Eigen::Ref<const Eigen::VectorXd>& metric, int keep,
                         const std::vector<std::vector<Eigen::Index>>& groups = {});

}  // namespace ssid::estimator::pretest
