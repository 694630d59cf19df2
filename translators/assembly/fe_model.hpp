#pragma once
/// \file fe_model.hpp
/// The NASDSA analogue: from a deck to the operators the estimator needs.
///
///   g-set  every GRID (6 DOFs in its CD frame) and SPOINT, by id;
///   K_g, M_g  sum of element blocks (CROD, CONROD, CBAR, CBEAM, CONM2, CMASS1/2,
///          CELAS1/2, CBUSH), M_g scaled by PARAM WTMASS;
///   m-set  dependent DOFs of RBAR, RBE2, RBE3 and the selected MPC set,
///          eliminated exactly (u_g = T u_a);
///   s-set  GRID PS, the selected SPC set (SPC, SPC1, SPCADD) and, with PARAM
///          AUTOSPC (default YES), the DOFs without stiffness found by NASTRAN's
///          grid-point singularity check (EPZERO);
///   a-set  the rest: K_a = Tᵀ K_g T, M_a = Tᵀ M_g T.
/// Parameters are the DESVARs; DVPREL1/DVMREL1 relate them to property,
/// material and element values (value = C0 + Σ COEFᵢ·xᵢ, clipped to
/// PMIN/PMAX), so ∂K/∂xⱼ = Σ COEF · ∂K/∂(value), element by element and exact.
/// The constraint sets (and the a-set) are fixed at the nominal design so that
/// every parameter value gives operators on the same DOFs.
#include <Eigen/SparseCore>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "formats/bulk_model.hpp"
#include "translators/assembly/element_blocks.hpp"
#include "translators/assembly/model_geometry.hpp"
#include "translators/constraints.hpp"

namespace ssid::translators {

struct AssemblyOptions {
  std::optional<bool> coupled_mass;         ///< overrides PARAM COUPMASS
  std::optional<double> wtmass;             ///< overrides PARAM WTMASS
  std::optional<bool> autospc;              ///< overrides PARAM AUTOSPC
  double epzero = 1e-8;                     ///< singularity ratio (PARAM EPZERO)
  std::optional<std::int64_t> spc_set;      ///< overrides case control SPC =
  std::optional<std::int64_t> mpc_set;      ///< overrides case control MPC =
  std::optional<std::int64_t> method;       ///< overrides case control METHOD =
};

/// One field a DESVAR designs: value = C0 + Σ coefficient · x (DVPREL1/DVMREL1).
struct DesignedField {
  std::string type;   ///< the card type designed: "PROD", "CONM2", "MAT1", …
  std::int64_t id = 0;
  std::string field;  ///< upper case: "A", "M", "E", …
  double coefficient = 0;
};

/// A DESVAR and what it designs.
struct DesignParameter {
  std::int64_t id = 0;
  std::string label;
  double initial = 0, lower = -1e20, upper = 1e20;
  std::vector<std::string> designs;  ///< e.g. "PBAR 3 I1 (DVPREL1 10, coef 1)"
  std::vector<DesignedField> fields; ///< the same, as data
};

struct FeOperators {
  SparseMatrix Kg, Mg;
  SparseMatrix K, M;                    ///< a-set
  std::vector<SparseMatrix> dK, dM;     ///< a-set, one per parameter (empty when not asked)
};

class FeModel {
 public:
  /// Builds the model; throws ModelError (file:line, card, what) for anything
  /// that cannot be assembled and would change K or M.
  FeModel(const formats::Deck& deck, formats::BulkModel model, AssemblyOptions options = {});
  FeModel(const FeModel&) = delete;
  FeModel& operator=(const FeModel&) = delete;

  const formats::BulkModel& bulk() const { return m_model; }
  const ModelGeometry& geometry() const { return *m_geometry; }
  const ElementSet& elements() const { return *m_elements; }
  const Reduction& reduction() const { return m_reduction; }
  const std::vector<DesignParameter>& parameters() const { return m_parameters; }
  Eigen::VectorXd initial_parameters() const;
  /// DOFs constrained by AUTOSPC (g-set indices), as NASTRAN lists them.
  const std::vector<std::size_t>& autospc() const { return m_autospc; }
  /// What was ignored or assumed, for the user (e.g. "12 FORCE cards ignored: loads do not change K or M").
  const std::vector<std::string>& notes() const { return m_notes; }
  double wtmass() const { return m_wtmass; }
  bool coupled_mass() const { return m_settings.mass == elements::MassKind::Coupled; }
  /// The selected EIGRL or EIGR (case control METHOD, or the only one), if any.
  const formats::Eigrl* eigrl() const { return m_eigrl; }
  const formats::Eigr* eigr() const { return m_eigr; }

  /// The bulk model with the DESVAR values x applied through DVPREL1/DVMREL1.
  formats::BulkModel values_at(const Eigen::VectorXd& x) const;
  /// K, M (g and a sets) at x; with `derivatives`, ∂K/∂xⱼ, ∂M/∂xⱼ on the a-set.
  FeOperators operators(const Eigen::VectorXd& x, bool derivatives = true) const;
  /// Modes on the a-set expanded to the g-set: u_g = T u_a.
  Eigen::MatrixXd expand(const Eigen::MatrixXd& a_modes) const;
  /// The g-set sum of element blocks: their K, or their M scaled by WTMASS.
  SparseMatrix sum_blocks(const std::vector<ElementBlock>& blocks, bool mass) const;

 private:
  struct Relation {  ///< one DVPREL1/DVMREL1
    ValueKey key;
    double c0 = 0;
    std::optional<double> lower;
    double upper = 1e20;
    std::vector<std::pair<std::size_t, double>> terms;  ///< (parameter index, coefficient)
    std::string label;
  };
  /// The constructor's phases, in order.
  struct ConstraintSelection {  ///< the SPC and MPC sets case control selects, and where
    std::optional<std::int64_t> spc, mpc;
    formats::SourceLocation spc_at;
  };
  struct ReductionSettings {  ///< AUTOSPC and its singularity threshold
    bool autospc = true;
    double epzero = 1e-8;
  };
  void refuse_unassembled_cards(const formats::Deck& deck);
  ReductionSettings read_analysis_parameters(const formats::Deck& deck, const AssemblyOptions& options);
  ConstraintSelection select_sets(const formats::Deck& deck, const AssemblyOptions& options);
  std::vector<std::size_t> single_point_constraints(const formats::Deck& deck, const ConstraintSelection& sets);
  std::vector<MpcEquation> multipoint_constraints(const formats::Deck& deck, const ConstraintSelection& sets) const;
  void relate_parameters(const formats::Deck& deck);
  void apply_constraints(const std::vector<std::size_t>& spc, const std::vector<MpcEquation>& mpcs, const ReductionSettings& r);

  formats::BulkModel m_model;
  std::unique_ptr<ModelGeometry> m_geometry;
  ElementSettings m_settings;
  std::unique_ptr<ElementSet> m_elements;
  double m_wtmass = 1.0;
  Reduction m_reduction;
  std::vector<std::size_t> m_autospc;
  std::vector<DesignParameter> m_parameters;
  std::vector<Relation> m_relations;
  std::vector<std::string> m_notes;
  const formats::Eigrl* m_eigrl = nullptr;
  const formats::Eigr* m_eigr = nullptr;
};

/// The one way from a read deck to its model (modes, assemble, correlate, estimate,
/// diagnose, update-deck): formats::resolved_bulk, which refuses a deck with errors
/// (InputError, each with its file:line), then the FeModel, whose ModelError comes
/// back as "<place>: cannot assemble the model: <what>", the place being the first
/// card or statement at fault, or `who` (the deck's name) when the message itself
/// starts with the card's file:line. Warnings are appended to `warnings` when given.
std::unique_ptr<FeModel> assemble_deck(const formats::Deck& deck, const std::string& who,
                                       const AssemblyOptions& options = {},
                                       std::vector<std::string>* warnings = nullptr);

}  // namespace ssid::translators
