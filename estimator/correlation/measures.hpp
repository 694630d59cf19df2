#pragma once
/// \file measures.hpp
/// Test–analysis correlation: MAC (squared and the seed's non-squared form),
/// auto-MAC, modal scale factor, mass reduction to the test DOFs (Guyan and
/// SEREP), cross-orthogonality, MEMS with its error mode, and mode pairing with
/// the table layout of the reconciliation paper's Tables 4–6.
///
/// Shapes are columns of matrices whose rows are the same DOFs in the same order
/// (the test DOFs); test shapes carry arbitrary scale and sign.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <optional>
#include <string>
#include <vector>

namespace ssid::estimator {

/// Which MAC. Squared is the usual modal assurance criterion
///   MAC(a, e) = (aᵀe)² / ((aᵀa)(eᵀe));
/// NonSquared is the seed report's MAC_ns (reconciliation paper Eq. 1)
///   MAC_ns(a, e) = |aᵀe| / (‖a‖ ‖e‖),
/// taken in absolute value because a test shape's sign is arbitrary. Both lie in
/// [0, 1], are 1 for parallel shapes and invariant to the scale of either shape;
/// MAC = MAC_ns².
enum class MacForm { Squared, NonSquared };

/// MAC of two shapes; 0 when either is the zero vector.
double mac(const Eigen::Ref<const Eigen::VectorXd>& a, const Eigen::Ref<const Eigen::VectorXd>& e,
           MacForm form = MacForm::Squared);
/// MAC of every column of A (rows) against every column of E (columns).
Eigen::MatrixXd mac_matrix(const Eigen::Ref<const Eigen::MatrixXd>& A, const Eigen::Ref<const Eigen::MatrixXd>& E,
                           MacForm form = MacForm::Squared);
/// Auto-MAC: MAC of a set against itself (ones on the diagonal; large
/// off-diagonal terms mean the sensor set cannot tell those modes apart).
Eigen::MatrixXd auto_mac(const Eigen::Ref<const Eigen::MatrixXd>& A, MacForm form = MacForm::Squared);

/// Modal scale factor: the α minimising ‖reference − α·other‖,
///   α = otherᵀ reference / otherᵀ other;
/// multiplying a test shape by MSF(analysis, test) puts it on the analysis scale
/// (and sign). 0 when `other` is zero.
double modal_scale_factor(const Eigen::Ref<const Eigen::VectorXd>& reference,
                          const Eigen::Ref<const Eigen::VectorXd>& other);

// --------------------------------------------------------------------------
// Reduction of the analysis model to the test DOFs (the a-set).

/// Outcome of a reduction: a numerical status, never an exception.
enum class ReductionStatus {
  Ok,
  SingularOmittedStiffness,  ///< Guyan: K_oo not positive definite (the a-set does not restrain the omitted DOFs)
  RankDeficientModes,        ///< SEREP: the modes are not independent at the a-set (fewer sensors than modes, or aliasing)
  BadInput                   ///< an a-set index out of range or repeated, or size mismatch
};

/// A model reduced to the a-set: u ≈ T u_a, M_r = Tᵀ M T, K_r = Tᵀ K T.
struct ReducedModel {
  ReductionStatus status = ReductionStatus::Ok;
  std::string message;  ///< what went wrong, when status != Ok
  Eigen::MatrixXd T;    ///< n x a
  Eigen::MatrixXd M;    ///< a x a
  Eigen::MatrixXd K;    ///< a x a
};

/// Guyan (static) condensation. With o the omitted DOFs,
///   T = [I; −K_oo⁻¹ K_oa]  (rows in the original DOF order),
/// exact for static loads at the a-set, and for the modes when the omitted DOFs
/// carry no mass (M_oo = 0, M_oa = 0).
ReducedModel guyan_reduce(const Eigen::SparseMatrix<double>& K, const Eigen::SparseMatrix<double>& M,
                          const std::vector<Eigen::Index>& a_set);

/// IRS (Improved Reduced System, O'Callahan 1989): Guyan's transformation T_G
/// corrected for the inertia of the omitted DOFs to first order,
///   T_IRS = T_G + S M T_G M_G⁻¹ K_G,   S = [0 0; 0 K_oo⁻¹]  (o rows only),
/// with M_G = T_Gᵀ M T_G, K_G = T_Gᵀ K T_G. Closer than Guyan to the low modes
/// when the omitted DOFs carry mass; equal to Guyan when they carry none.
/// Statuses as guyan_reduce, plus SingularOmittedStiffness when M_G is singular.
ReducedModel irs_reduce(const Eigen::SparseMatrix<double>& K, const Eigen::SparseMatrix<double>& M,
                        const std::vector<Eigen::Index>& a_set);

/// SEREP (System Equivalent Reduction Expansion Process). With Φ the n x m
/// analysis modes and Φ_a their a-set rows (a ≥ m, rank m),
///   T = Φ Φ_a⁺,  Φ_a⁺ = (Φ_aᵀ Φ_a)⁻¹ Φ_aᵀ;
/// the reduced model reproduces the m modes exactly: Φ_aᵀ M_r Φ_a = Φᵀ M Φ and
/// Φ_aᵀ K_r Φ_a = Φᵀ K Φ.
ReducedModel serep_reduce(const Eigen::SparseMatrix<double>& K, const Eigen::SparseMatrix<double>& M,
                          const Eigen::Ref<const Eigen::MatrixXd>& Phi, const std::vector<Eigen::Index>& a_set);

/// Cross-orthogonality X = Φ_aᵀ M_r Φ_e (seed report: φ_fᵀ M_r φ_r). With
/// `normalize`, each mode is first scaled to unit generalised mass under M_r,
///   X_ij = φ_aiᵀ M_r φ_ej / sqrt((φ_aiᵀ M_r φ_ai)(φ_ejᵀ M_r φ_ej)),
/// so arbitrary test scaling drops out (sign remains). Ideal: identity for the
/// paired modes; the seed accepts diagonals > 0.9 and small cross terms.
Eigen::MatrixXd cross_orthogonality(const Eigen::Ref<const Eigen::MatrixXd>& Phi_a,
                                    const Eigen::Ref<const Eigen::MatrixXd>& M_r,
                                    const Eigen::Ref<const Eigen::MatrixXd>& Phi_e, bool normalize = true);

// --------------------------------------------------------------------------
// MEMS: Minimum Error Mode Superposition (reconciliation paper Eqs. 2–3).

/// How the comparison set is scaled before the fit (the paper's alternatives:
/// FE modes are mass-normalised already; test modes need a consistent scale).
enum class ComparisonScaling { AsGiven, UnitNorm, UnitMass };

/// Result of fitting a reference mode φ by the comparison modes ψ_1..ψ_N.
struct MemsResult {
  Eigen::VectorXd alpha;       ///< least-squares coefficients α_i
  double error_squared = 0;    ///< e² = ‖φ − Σ α_i ψ_i‖² / ‖φ‖²  (Eq. 2)
  Eigen::VectorXd error_mode;  ///< ê = φ − Σ α_i ψ_i              (Eq. 3)
  double mac_superposition = 0;  ///< MAC between φ and Σ α_i ψ_i (form as asked)
  Eigen::MatrixXd comparison;  ///< the comparison set after scaling (the α refer to it)
};

/// Fits `reference` by the columns of `comparison` in the least-squares sense
/// (rank-revealing QR: dependent comparison modes get α = 0 for the redundant
/// ones). UnitMass needs `M_r` (a x a).
MemsResult mems(const Eigen::Ref<const Eigen::VectorXd>& reference, const Eigen::Ref<const Eigen::MatrixXd>& comparison,
                ComparisonScaling scaling = ComparisonScaling::AsGiven, const Eigen::MatrixXd* M_r = nullptr,
                MacForm form = MacForm::Squared);

// --------------------------------------------------------------------------
// Mode pairing.

struct PairingOptions {
  MacForm form = MacForm::Squared;
  /// A mutual-best pair is accepted when its MAC (in `form`) is at least this.
  double min_mac = 0.9;
  /// ... and |frequency error| (%) at most this.
  double max_frequency_error_pct = 10.0;
};

/// A mutual-best pair: analysis mode `fe` has its largest MAC with test mode
/// `test` and vice versa (0-based column indices).
struct ModePair {
  int fe = 0, test = 0;
  double mac = 0;
  double error_pct = 0;  ///< 100 (f_fe − f_test) / f_test
  double msf = 0;        ///< modal scale factor taking the test shape onto the analysis shape
  bool accepted = false;
};

/// One row of the pairing table (reconciliation paper, Tables 4–6): both modes
/// for a mutual-best pair; otherwise one side, with the other column naming the
/// mode it matched best ("-9-": that mode preferred a partner with higher MAC).
struct PairingRow {
  std::optional<int> fe, test;  ///< 0-based; empty on the side with no partner
  int fe_best = -1, test_best = -1;  ///< best partner of the present mode when unpaired
  std::optional<double> max_fe_mac;    ///< largest MAC of the FE mode over the test modes
  std::optional<double> max_test_mac;  ///< largest MAC of the test mode over the FE modes
  std::optional<double> error_pct;
  bool accepted = false;
};

struct Pairing {
  Eigen::MatrixXd mac;            ///< FE modes x test modes, in options.form
  std::vector<ModePair> pairs;    ///< mutual-best pairs, accepted or not, by FE mode
  std::vector<int> unpaired_fe;   ///< FE modes without an accepted pair
  std::vector<int> unpaired_test; ///< test modes without an accepted pair
  std::vector<PairingRow> table;  ///< rows in frequency order as in Tables 4–6
};

/// Pairs from a given MAC matrix (FE x test) and the frequencies (Hz).
/// MSFs are left 0 (no shapes).
Pairing pair_modes(const std::vector<double>& fe_hz, const std::vector<double>& test_hz,
                   const Eigen::Ref<const Eigen::MatrixXd>& mac, const PairingOptions& options = {});
/// Pairs from shapes at common DOFs (rows): computes the MAC in options.form and the MSF per pair.
Pairing pair_modes(const std::vector<double>& fe_hz, const Eigen::Ref<const Eigen::MatrixXd>& fe_shapes,
                   const std::vector<double>& test_hz, const Eigen::Ref<const Eigen::MatrixXd>& test_shapes,
                   const PairingOptions& options = {});

/// The pairing table as text in the layout of the paper's Tables 4–6:
/// "FEM Frequency/#  Test Frequency/#  Maximum FEM MAC  Maximum Test MAC  Frequency Error(%)",
/// accepted pairs marked "(*)", mode numbers 1-based; `fe_numbers`/`test_numbers`
/// relabel the modes (empty: column index + 1).
std::string format_pairing_table(const Pairing& p, const std::vector<double>& fe_hz,
                                 const std::vector<double>& test_hz, const std::vector<int>& fe_numbers = {},
                                 const std::vector<int>& test_numbers = {}, const std::string& test_label = "Test");

}  // namespace ssid::estimator
