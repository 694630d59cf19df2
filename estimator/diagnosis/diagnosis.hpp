#pragma once
/// \file diagnosis.hpp
/// Model-form diagnosis (`ssid diagnose`): shows what the updated model gets
/// wrong, tests a library of model-form extensions as hypotheses, names the
/// cause and measures the gain. See docs/diagnosis.md for the method.
///
/// 1. Ordinary update of the deck's own parameters ("parameter" hypothesis)
///    and the residual evidence (evidence.hpp).
/// 2. Candidates of every extension kind (estimator/diagnosis/hypotheses). Kinds that
///    add no DOF are screened to first order at the updated parameters r*:
///    with e the weighted residual, t = S_ee^{-1/2} ∂u/∂β the weighted
///    sensitivity of the new parameter (∂λ exact, ∂φ by modal summation),
///    W the weighted sensitivity of the existing parameters (prior-scaled) and
///    H = I + WᵀW,
///      s = tᵀt − tᵀW H⁻¹ Wᵀt,  g = tᵀe,
///      ΔlogZ ≈ ½ g² / (s + 1/σ_β²) − ½ log(1 + σ_β² s),
///    the evidence gain of adding β with prior N(0, σ_β²). Kinds that add DOFs
///    are ranked by the shape misfit at their grids (or all are tried when few).
/// 3. The best `shortlist` candidates of each kind are re-estimated exactly
///    (extended deck, every parameter, the kind's prior) and scored:
///      score = log Z_Laplace(paired data) + Σ_unpaired log p_miss − log N_kind,
///    where an unpaired test mode costs the likelihood of a complete miss
///    (frequency off by `miss_frequency_pct`, shape orthogonal: ‖z − u‖² = 2)
///    and N_kind is the number of distinct locations searched (look-elsewhere).
/// 4. The decision is calibrated (calibration.hpp): the noise the data imply is
///    estimated from the ordinary update's residuals (or taken as given), the
///    estimates of step 3 use it, and the first-order screening is replayed on
///    data simulated from the ordinary update's model (parametric bootstrap) to
///    give each screened candidate its false-alarm probability. An extension
///    is the cause only when (a) its false-alarm probability is at most
///    `calibration.false_alarm` (kinds without screening: the ordinary update's
///    residuals are not consistent with the noise), (b) it predicts held-out
///    modes better (leave-one-mode-out, linearised), (c) its score beats the
///    ordinary update by `decision_margin` nats and (d) it makes neither the
///    frequency nor the shape fit of the modes both pair worse, pairs no fewer
///    modes and predicts held-back modes no worse. Otherwise "parameter" when
///    the update beats the nominal model by the margin, else "none". After a
///    screened cause, the search is repeated with the cause's model as the null
///    (a second effect) and both are named when the second passes too.
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "estimator/diagnosis/calibration.hpp"
#include "estimator/diagnosis/evidence.hpp"
#include "estimator/reporting/progress.hpp"
#include "estimator/diagnosis/hypotheses/model_extension.hpp"
#include "estimator/study/deck_study.hpp"

namespace ssid::estimator::diagnosis {

/// One tested configuration: deck text (`name`: the deck's path or name, for
/// INCLUDEs and messages) and its measured modes, labelled by test node (grid
/// ids, or nodes at `nodes`' positions when the study maps by position); a
/// mode set without DOFs is frequencies only.
struct ConfigurationInput {
  std::string name;
  std::string deck_text;
  translators::ModeSet measured;
  std::vector<translators::TestNode> nodes = {};
  std::string measured_name = {};  ///< the measured file (messages)
  std::string configuration = {};  ///< the study's configuration name (its fixed pairs)
};

struct DiagnosisOptions {
  /// The estimation problem's settings — noise, priors, pairs, pairing, modes —
  /// as `ssid estimate` takes them from its study file (deck_study.hpp): every
  /// hypothesis is built by the same builder, so the "parameter" hypothesis is
  /// what `ssid estimate` computes. Its `configurations` are not used here
  /// (the configurations are diagnose()'s argument).
  Study study;
  /// Reports of every estimate's cycles (each solve, each step halving).
  Progress update_progress;
  estimator::diagnosis::hypotheses::ExtensionOptions extension;
  std::vector<std::string> kinds;  ///< extension kinds to try; empty: all
  int shortlist = 3;               ///< candidates per kind re-estimated exactly
  int exhaustive_limit = 100;      ///< kinds without screening: try all when this few (and the model is small)
  double decision_margin = 3.0;    ///< nats
  double miss_frequency_pct = 10.0;
  int hold_back = 0;               ///< highest test modes of the first configuration held back for prediction
  CalibrationOptions calibration;  ///< noise given or estimated; bootstrap replicates; the false-alarm target
  /// Reports of the phases, counted where they are lists (candidates listed per
  /// kind, screened, re-estimated; the ordinary update's cycles). Throwing
  /// Interrupted from it stops the diagnosis with what it has (Diagnosis::partial_reason).
  Progress progress;
};

struct Fit {
  double freq_rms_pct = 0, mean_mac = 0;
  int paired = 0, measured = 0;
};

struct Hypothesis {
  std::string kind;  ///< "none", "parameter", or an extension kind
  estimator::diagnosis::hypotheses::Location location;
  std::string description;
  std::vector<std::string> names;  ///< every parameter (deck DESVARs, then the new ones)
  std::vector<estimator::diagnosis::hypotheses::NewParameter> added;
  Eigen::VectorXd estimate, posterior_std, prior_mean;
  Eigen::MatrixXd posterior_cov;  ///< Eq. (8), every parameter
  double log_evidence = 0;   ///< Laplace, paired data only
  double miss_penalty = 0;   ///< Σ log p_miss over unpaired test modes (≤ 0)
  double look_elsewhere = 0; ///< log N_kind
  double score = 0;          ///< log_evidence + miss_penalty − look_elsewhere
  double screening = 0;      ///< first-order evidence gain G of calibration.hpp [nats] (kinds with screening)
  /// Probability that a search like this one finds a first-order gain of at
  /// least `screening` in data without any model-form error (bootstrap); NaN
  /// for kinds without screening.
  double false_alarm = std::numeric_limits<double>::quiet_NaN();
  int exceed = -1;           ///< bootstrap replicates whose best gain reached `screening`
  HeldOutGain held_out;      ///< leave-one-mode-out gain over the ordinary update (screened kinds)
  bool held_out_known = false;
  int screening_column = -1; ///< the candidate's column in the screening (−1: not screened)
  std::vector<UpdatePair> pairs;  ///< the final cycle's pairs
  std::string verdict;       ///< why it is the cause, or the first reason it is not
  Fit before, after;
  double prediction_rms_pct = -1;  ///< held-back modes (−1: none)
  int predicted = 0;
  bool converged = false;
  std::vector<std::string> notes;
  std::string deck_text;     ///< the (extended) deck
};

/// The noise the data imply (docs/diagnosis.md, "Noise").
struct NoiseReport {
  bool estimated = true;                          ///< false: the assumed σ is taken as given
  double assumed_frequency_pct = 0, assumed_shape_pct = 0;  ///< σ assumed (options, study file)
  double frequency_pct = 0, shape_pct = 0;        ///< σ the estimates use: implied (estimated) or assumed
  NoiseScale scale;                               ///< ŝ, χ², ν of the ordinary update at the assumed σ
  /// Where the assumed σ come from (EstimationProblem::measurement_std). Where
  /// they are the identification's, per mode, the estimated noise scales them
  /// (σ_i → ŝ_g σ_i) and the percentages above are the study's, for modes without.
  std::string std_from;
  bool identified = false;  ///< some test mode's σ is the identification's
  /// σ the data imply with the (first) screened cause in the model (linearised
  /// at its estimate); NaN when no screened cause was named.
  double frequency_pct_cause = std::numeric_limits<double>::quiet_NaN();
  double shape_pct_cause = std::numeric_limits<double>::quiet_NaN();
};

/// Is anything left to explain after the ordinary update (docs/diagnosis.md)?
struct ResidualTest {
  double chi2_p[kRowGroups] = {1.0, 1.0};  ///< P(χ²(ν_g) ≥ χ²_g) against the assumed σ (frequencies, shapes)
  int unpaired = 0;                        ///< test modes without an analysis partner
  int candidates = 0;                      ///< screened candidates
  double statistic = std::numeric_limits<double>::quiet_NaN();  ///< their largest first-order gain [nats]
  double p = std::numeric_limits<double>::quiet_NaN();          ///< its false-alarm probability
  double p_upper = std::numeric_limits<double>::quiet_NaN();    ///< 95 % upper bound on the true tail probability
  int exceed = 0, replicates = 0;
  bool consistent = false;  ///< nothing left to explain: the answer is "parameter" or "none"
  std::string text;         ///< the verdict in a sentence, with the figures
};

/// The search for a second effect with the cause's model as the null.
struct SecondEffect {
  bool tested = false;
  std::string kind;
  estimator::diagnosis::hypotheses::Location location;
  double gain = 0, false_alarm = 1;
  HeldOutGain held_out;
  bool named = false;
  std::string text;  ///< what was found, or why no second effect is named
};

struct Diagnosis {
  NoiseReport noise;               ///< the noise the data imply
  ResidualTest residual;           ///< anything left to explain after the ordinary update?
  SecondEffect second;             ///< after a screened cause: a second one
  Evidence evidence;               ///< after the ordinary update
  Hypothesis nominal;              ///< "none": the deck as given
  std::vector<Hypothesis> ranking; ///< "parameter" and every re-estimated extension, best score first
  int cause = -1;                  ///< index into ranking; −1: "none"
  std::string cause_kind;          ///< "none", "parameter" or the extension kind
  double margin = 0;               ///< score of the cause − that of the runner-up class
  std::string summary;
  std::map<std::string, int> searched;  ///< candidates per kind
  std::vector<std::string> notes;
  /// The chosen deck with DESVARs and designed fields at the estimate.
  std::string updated_deck;
  /// Empty when every phase ran; otherwise why the diagnosis is partial
  /// (interrupted: which phase, how far): the ranking then holds the hypotheses
  /// tested so far, and the cause is chosen among them.
  std::string partial_reason;
  bool interrupted = false;
  bool partial() const { return !partial_reason.empty(); }
};

/// Reads the study's "diagnosis" section (Study::diagnosis) into `options`:
/// kinds, shortlist, decision_margin, hold_back, mass_prior_fraction,
/// stiffness_prior_fraction, miss_frequency_pct. Unknown keys and wrong types
/// throw formats::InputError naming the study file and the key path.
void read_diagnosis_section(const Study& study, DiagnosisOptions& options);

/// Runs the phases of the file comment. Bad input (decks, test data) throws
/// formats::InputError; a failed ordinary update formats::NumericalError; a
/// candidate that fails either way is left out with a note. Interrupted thrown
/// by `options.progress` (or by `options.update_progress`) returns the
/// diagnosis so far, marked partial, once the ordinary update has a cycle;
/// before that it passes to the caller.
Diagnosis diagnose(const std::vector<ConfigurationInput>& configurations, const DiagnosisOptions& options);

/// The deck text with every DESVAR at `x` and every field a DVPREL1/DVMREL1
/// designs set from it (so SOL 103 of the text gives the estimated model).
std::string deck_at(const std::string& deck_text, const std::string& name, const Eigen::VectorXd& x);

}  // namespace ssid::estimator::diagnosis
