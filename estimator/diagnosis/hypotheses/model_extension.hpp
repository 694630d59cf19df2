#pragma once
/// \file model_extension.hpp
/// The open library of model-form extensions that `ssid diagnose` tests as
/// hypotheses. An extension is one kind of change to a deck that an analyst
/// would consider when updating the existing parameters cannot explain a test:
/// a local stiffness change, a missing mass, suspension springs with mass, a
/// flexible joint, … Each kind is one class implementing ModelExtension:
///
///  - `kind()`: the name reported ("missing_mass", …);
///  - `candidates(nominal)`: every location where the change could be made
///    (grids, elements, properties), each a Candidate;
///  - `apply(editor, candidate)`: adds the change to a deck through a
///    DeckEditor — new cards (GRID, CONM2, CONROD, CELAS, …), changed cards, and
///    for each new unknown a DESVAR (with DVPREL1 into the new cards) and its
///    prior (NewParameter). The deck stays a valid NASTRAN deck: the
///    extended, updated model is written as a deck;
///  - `screening(nominal, candidate)` (optional): ∂K/∂β and ∂M/∂β of the new
///    parameters β on the nominal model's a-set at β = initial, when the change
///    adds no DOF. The diagnosis uses them for a cheap first-order score of every
///    candidate before re-estimating the best few exactly.
///
/// A new kind is one more class and one line in standard_extensions().
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <cstdint>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "formats/bulk_model.hpp"
#include "formats/deck.hpp"
#include "translators/assembly/fe_model.hpp"

namespace ssid::estimator::diagnosis::hypotheses {

// The kinds work on assembled models; these names read as they did in translators/.
using translators::FeModel;
using translators::GridPoint;
using translators::SparseMatrix;

/// Where a change is made.
struct Location {
  std::vector<std::int64_t> grids, elements, properties;
  std::string text;  ///< readable, e.g. "grid 17" or "CROD 23 (grids 5-9)"
};

struct Candidate {
  std::string kind;
  Location location;
  /// Kind-specific data (e.g. the element id, the spring elements of a group).
  std::vector<std::int64_t> ids;
  /// Start values of the new parameters (empty: their prior means); a kind may
  /// offer several candidates that differ only in start (e.g. a surge mode
  /// placed at each unexplained test frequency).
  std::vector<double> start;
  /// Kinds without screening may rank their candidates (higher first, e.g. by
  /// how strongly the change would couple to an unexplained test mode); NaN:
  /// the diagnosis ranks them by the shape misfit at their grids.
  double priority = std::numeric_limits<double>::quiet_NaN();
};

/// A new unknown: its DESVAR label and prior (mean, σ), units stated.
struct NewParameter {
  std::string label;
  double prior_mean = 0, prior_std = 0;
  double start = std::numeric_limits<double>::quiet_NaN();  ///< NaN: the prior mean
  double lower = -1e20, upper = 1e20;
  std::string meaning;  ///< e.g. "added mass at grid 17 [kg]"
};

/// Edits a deck: changed cards (main file only), appended cards (placed before
/// ENDDATA), fresh ids in every name space. Holds the typed model of the deck
/// as read, for lookups.
class DeckEditor {
 public:
  DeckEditor(const std::string& text, const std::string& name);
  const formats::Deck& deck() const { return *m_deck; }
  const formats::BulkModel& bulk() const { return m_bulk; }

  std::int64_t new_grid_id() { return m_next_grid++; }
  std::int64_t new_element_id() { return m_next_element++; }
  std::int64_t new_property_id() { return m_next_property++; }
  std::int64_t new_desvar_id() { return m_next_desvar++; }
  std::int64_t new_relation_id() { return m_next_relation++; }
  std::int64_t new_coord_id() { return m_next_coord++; }
  std::int64_t new_material_id() { return m_next_material++; }

  /// Appends a card from values (values[0] is the name).
  void append(const std::vector<formats::FieldValue>& values);
  void comment(const std::string& text);
  /// Replaces the values of an existing card (by card index in the deck).
  void change(std::size_t card, std::vector<formats::FieldValue> values);
  /// Adds a GRID at `x` (basic), displacement frame `cd` (0: basic, written
  /// blank), permanent constraints `ps`, and returns its id.
  std::int64_t add_grid(const Eigen::Vector3d& x, std::int64_t cd, const std::string& ps);
  /// Adds a DESVAR and returns its id.
  std::int64_t add_desvar(const NewParameter& p, double xinit);
  /// Adds a DVPREL1: TYPE id PNAME = c0 + coef · DESVAR dvid.
  void add_dvprel1(const std::string& type, std::int64_t id, const std::string& pname, std::int64_t dvid,
                   double coef, double c0 = 0.0, std::optional<double> pmin = std::nullopt);
  /// The deck text with every change and appended card.
  std::string text() const;

  std::vector<NewParameter> parameters;  ///< the new unknowns, in DESVAR order

 private:
  std::unique_ptr<formats::Deck> m_deck;
  formats::BulkModel m_bulk;
  std::string m_appended;
  std::int64_t m_next_grid = 1, m_next_element = 1, m_next_property = 1, m_next_desvar = 1, m_next_relation = 1,
               m_next_coord = 1, m_next_material = 1;
};

/// The result of applying a candidate.
struct ExtendedDeck {
  std::string text;                     ///< the extended deck
  std::vector<NewParameter> parameters; ///< its new DESVARs
  std::string description;              ///< one sentence
};

/// ∂K/∂β, ∂M/∂β on the nominal a-set, one per new parameter.
struct ScreeningDerivative {
  std::vector<Eigen::SparseMatrix<double>> dK, dM;
  std::vector<double> prior_std;  ///< σ of each new parameter (as apply() would give it)
};

/// What the diagnosis knows of the test modes the ordinary update leaves
/// without an analysis partner, at the updated parameters (first configuration).
struct UnexplainedModes {
  Eigen::VectorXd eigenvalues;  ///< λ_j = ω_j² of the analysis modes [(rad/s)²]
  Eigen::MatrixXd g_shapes;     ///< their g-set shapes, mass-normalised, one column a mode
  Eigen::MatrixXd sensor_shapes;  ///< the same modes at the sensors (rows: the test's sensors)
  /// Per unexplained test frequency (ExtensionOptions::unexplained_hz order):
  /// the test mode's shape at the sensors (empty: not measured), and the
  /// analysis mode most like it at the sensors (−1: none).
  std::vector<Eigen::VectorXd> test_shapes;
  std::vector<int> neighbour;
};

/// Settings shared by the kinds (priors), SI units as the deck's.
struct ExtensionOptions {
  double mass_prior_fraction = 0.01;   ///< σ of a missing mass: this fraction of the model's total mass
  double stiffness_prior_fraction = 0.5; ///< σ of a local stiffness change: this fraction of the member's
  int max_surge_starts = 3;            ///< surge candidates start at up to this many unexplained test frequencies
  std::vector<double> unexplained_hz;  ///< test frequencies without an analysis partner (from the evidence)
  double lowest_test_hz = 1.0;         ///< scales the spring-mass prior
  double highest_test_hz = 0;          ///< centres the strut-inertia prior of local_modes (0: lowest_test_hz)
  /// The updated model's modes and the unexplained test modes' shapes: kinds
  /// that add local DOFs rank their places by the shape their new mode would
  /// give at the sensors (local_modes.cpp).
  UnexplainedModes unexplained;
  /// Kinds meant for unexplained test modes (local_modes) offer candidates even
  /// when there are none (tests of the kind itself).
  bool always_offer = false;
  double total_mass = 0;               ///< kg; 0: computed from the nominal model when needed
  /// Where the hypotheses start the deck's own parameters (the ordinary
  /// update's estimate, by DESVAR label in upper case); empty: the deck's values.
  /// support_dynamics places its start surges with the spring rates at these
  /// (detail::bulk_at_update); the other kinds start from the deck's values
  /// (local_modes' inertia from the deck's strut area, local_stiffness's
  /// section scales from the model at its initial parameters).
  std::map<std::string, double> updated;
};

class ModelExtension {
 public:
  virtual ~ModelExtension() = default;
  virtual std::string kind() const = 0;
  /// What the kind does and how it is parameterised (for reports and docs).
  virtual std::string describe() const = 0;
  virtual std::vector<Candidate> candidates(const FeModel& nominal) const = 0;
  virtual ExtendedDeck apply(const std::string& deck_text, const std::string& name, const FeModel& nominal,
                             const Candidate& candidate) const = 0;
  /// First-order screening data, or nothing when the change adds DOFs.
  virtual std::optional<ScreeningDerivative> screening(const FeModel& nominal, const Candidate& candidate) const {
    return std::nullopt;
  }
};

/// missing_mass: a CONM2 (point mass, no inertia) at one grid; β = its mass [kg],
/// prior N(0, (f·m_total)²), β ≥ 0.
std::unique_ptr<ModelExtension> make_missing_mass(const ExtensionOptions& options);
/// local_stiffness: a CONROD in parallel with one two-grid element (CROD,
/// CONROD, CBAR, CBEAM), same material; β = its area ΔA [m²] (a negative ΔA
/// softens: a loosened joint), prior N(0, (f·A)²), ΔA ≥ −0.95 A.
std::unique_ptr<ModelExtension> make_local_stiffness(const ExtensionOptions& options);
/// support_dynamics: a grounded scalar spring (a suspension spring) given its
/// own mass — the chain grid – 5k – β – 7k/2 – 49β/36 – 35k/18 – ground on two new
/// grids moving along the spring's component (CONM2s), with a scalar mass
/// 0.316β at the grid (CMASS2): a continuous spring's static rate, first two
/// surges and pulls, and low-frequency inertia; β = the first inner mass [kg].
/// One candidate per grounded spring and one per group of grounded springs
/// sharing a property (one β each).
std::unique_ptr<ModelExtension> make_support_dynamics(const ExtensionOptions& options);
/// joint_flexibility: the rigid RBE2 joining a ball to its strut ends keeps the
/// translations only; rotational CELAS1 springs (components 4, 5, 6) join each
/// strut end to the ball centre; β = the rotational rate [N·m/rad], one per
/// ball, or one for every ball at once.
std::unique_ptr<ModelExtension> make_joint_flexibility(const ExtensionOptions& options);

/// local_modes: one rod (CROD, CONROD) refined — split at a new middle grid,
/// with two bending-only CBARs (PBAR A = 0, I1 = I2 = β, J = 2β) alongside —
/// so the strut's local bending modes exist; β = its bending inertia [m⁴],
/// started so the local mode sits at an unexplained test frequency.
std::unique_ptr<ModelExtension> make_local_modes(const ExtensionOptions& options);

/// Every kind above.
std::vector<std::unique_ptr<ModelExtension>> standard_extensions(const ExtensionOptions& options);

/// Total mass of a model (trace of M over the translational DOFs / 3), kg.
double total_mass(const FeModel& model);

}  // namespace ssid::estimator::diagnosis::hypotheses
