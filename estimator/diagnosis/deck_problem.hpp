#pragma once
/// \file deck_problem.hpp
/// Glue between a deck + measured modes and the estimator (a small stand-in for
/// the study of `ssid estimate`; meant to be switched to estimator/study/deck_study
/// once that exists). It builds, for one deck text and one measured mode set:
///  - the FE model (translators::FeModel) and its operators at any DESVAR values,
///  - the observation matrix C_a on the a-set (test DOFs = C_a φ_a),
///  - an estimator::OperatorModel (exact re-assembly each cycle, CHOLMOD
///    shift-invert eigen-solve analysed once),
///  - the measured modes with their standard deviations, and
///  - the parameter prior from the DESVARs (mean XINIT, σ = prior_rel_std·|XINIT|,
///    bounds XLB/XUB), with per-label overrides (extension parameters bring
///    their own prior).
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "estimator/updating/modal_model.hpp"
#include "estimator/reporting/progress.hpp"
#include "estimator/updating/updating.hpp"
#include "formats/deck.hpp"
#include "translators/assembly/fe_model.hpp"
#include "translators/measurement/mode_set.hpp"

namespace ssid::estimator::diagnosis {

/// Prior of one parameter, by DESVAR label.
struct PriorOverride {
  double mean = 0, std = 0;
  double start = std::numeric_limits<double>::quiet_NaN();  ///< where the iteration starts (NaN: the mean)
};

struct DeckProblemOptions {
  double frequency_std_pct = 0.5;  ///< σ of a measured frequency, % of it
  /// σ of one component of a measured shape, % of the shape's RMS component;
  /// on the unit-normalised shape this is (pct/100)/√n_s.
  double shape_std_pct = 3.0;
  double prior_rel_std = 0.3;      ///< σ of a DESVAR without override, relative to |XINIT|
  int extra_modes = 12;            ///< analysis modes solved beyond the number of test modes (×2) ...
  /// ... and, when those do not reach this factor × the highest test frequency
  /// (models with many local modes below the tested global ones), the lowest
  /// `max_modes` instead (a bound on the cost: a beam model of the MPI truss
  /// has hundreds of strut-local modes within 25 % above its tested band).
  double band_factor = 1.25;
  int max_modes = 120;
  /// Shape sensitivities by Nelson's method (exact, one factorisation of
  /// K − λM per paired mode and cycle) up to this many a-set DOFs, by the seed
  /// report's modal summation over the solved modes above (beam models: ~10 k).
  int nelson_max_dofs = 3000;
  UpdateOptions update;
  /// Reports of the estimation's cycles (each solve, each step halving).
  Progress update_progress;
};

/// The model as the update sees it: an OperatorModel whose modes are followed
/// from cycle to cycle by their shapes at the sensors rather than everywhere.
/// Strut-local modes crowd the spectrum of beam models; a global mode mixes
/// with them as parameters move (veering) and its full shape changes a lot,
/// while at the sensors — which see global motion only — it stays recognisable.
class SensorTracked : public ModalModel {
 public:
  explicit SensorTracked(OperatorModel& inner) : m_inner(inner) {}
  int parameter_count() const override { return m_inner.parameter_count(); }
  ModalSolution solve(const Eigen::VectorXd& r) override {
    ModalSolution s = m_inner.solve(r);
    s.tracking_shapes = s.sensor_shapes;
    return s;
  }
  ModeSensitivity sensitivity(int i, bool shapes) override { return m_inner.sensitivity(i, shapes); }
  std::vector<ModeSensitivity> sensitivities(const std::vector<int>& modes, const std::vector<bool>& shapes) override {
    return m_inner.sensitivities(modes, shapes);
  }

 private:
  OperatorModel& m_inner;
};

/// The measured modes as the estimator takes them (shapes in the order of `set.dofs`).
std::vector<MeasuredMode> measured_modes(const translators::ModeSet& set, const DeckProblemOptions& options);

/// One deck and its test, ready for estimation. Move-only (it owns the deck the
/// model refers to).
struct DeckProblem {
  std::string name;
  std::unique_ptr<formats::Deck> deck;
  std::unique_ptr<translators::FeModel> fe;
  std::unique_ptr<OperatorModel> model;
  std::unique_ptr<SensorTracked> tracked;      ///< `model`, followed at the sensors (what the update uses)
  std::vector<MeasuredMode> test;
  std::vector<translators::MeasuredDof> dofs;  ///< measured DOFs kept (those on model grids)
  std::vector<std::string> problems;           ///< unmapped test DOFs, …
  SparseMatrix sensors;                        ///< C_a: n_s × a
  ParameterPrior prior;
  Eigen::VectorXd start;                       ///< iteration start (prior mean unless overridden)
  int nmodes = 0;
};

/// Builds the problem from deck text (`name` locates INCLUDEs and messages) and
/// a measured mode set labelled by grid ids. Throws on decks that cannot be
/// assembled and on test DOFs that match no grid at all.
DeckProblem make_deck_problem(const std::string& deck_text, const std::string& name,
                              const translators::ModeSet& measured, const DeckProblemOptions& options,
                              const std::map<std::string, PriorOverride>& priors = {});


/// Estimates the parameters of one problem (or several configurations sharing
/// their parameters: each problem's prior must list the same parameters).
UpdateResult estimate(std::vector<DeckProblem*> problems, const DeckProblemOptions& options);

}  // namespace ssid::estimator::diagnosis
