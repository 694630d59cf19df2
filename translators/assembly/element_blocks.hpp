#pragma once
/// \file element_blocks.hpp
/// Every stiffness- or mass-bearing element of a deck as a dense block on its
/// g-set DOFs: CROD, CONROD, CBAR, CBEAM, CONM2, CMASS1/2, CELAS1/2, CBUSH.
/// The same code gives the blocks at the model's values and their directional
/// derivatives along a ValueDelta (∂K/∂r, ∂M/∂r of a DVPREL1/DVMREL1
/// combination), so values and derivatives cannot disagree.
#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

#include "formats/bulk_model.hpp"
#include "translators/assembly/model_geometry.hpp"
#include "translators/assembly/property_values.hpp"
#include "translators/elements/element_types.hpp"

namespace ssid::translators {

struct ElementSettings {
  elements::MassKind mass = elements::MassKind::Lumped;  ///< PARAM COUPMASS > 0: coupled
  bool barmass = false;                                  ///< PARAM BARMASS > 0: CBAR lumped torsional inertia
};

/// One element's contribution (unscaled by WTMASS).
struct ElementBlock {
  std::size_t element = 0;          ///< index into ElementSet::elements()
  std::vector<std::size_t> dofs;    ///< g-set indices
  Eigen::MatrixXd k, m;
};

enum class ElementKind { Crod, Conrod, Cbar, Cbeam, Conm2, Cmass1, Cmass2, Celas1, Celas2, Cbush };

struct ElementRef {
  ElementKind kind;
  std::size_t index = 0;        ///< into the BulkModel vector of that kind
  std::int64_t eid = 0, pid = 0, mid = 0;
  std::string type;             ///< card name
  std::string label;            ///< "file:line: CBAR 12"
  std::vector<std::size_t> dofs;
};

class ElementSet {
 public:
  /// Collects and checks every element (grids, properties and materials exist
  /// and are of the right type). Throws ModelError naming the card.
  ElementSet(const formats::Deck& deck, const formats::BulkModel& model, const ModelGeometry& geometry,
             ElementSettings settings);

  const std::vector<ElementRef>& elements() const { return m_elements; }

  /// Blocks at the values of `values` (the model, or a copy of it with
  /// property values changed: same cards, same order).
  std::vector<ElementBlock> blocks(const formats::BulkModel& values) const;
  /// d/dt of the blocks at values + t·delta; only elements the delta touches.
  std::vector<ElementBlock> derivative_blocks(const formats::BulkModel& values, const ValueDelta& delta) const;
  /// K, M of element `element` (an index into elements()) at the values of `values`.
  ElementBlock block_of(std::size_t element, const formats::BulkModel& values) const {
    return evaluate(element, values, nullptr);
  }

 private:
  /// K, M of one element, or their derivative along `delta` when given.
  ElementBlock evaluate(std::size_t e, const formats::BulkModel& v, const ValueDelta* delta) const;
  bool touched(const ElementRef& r, const ValueDelta& delta) const;

  const ModelGeometry& m_geometry;
  ElementSettings m_settings;
  std::vector<ElementRef> m_elements;
  std::unordered_map<std::int64_t, std::size_t> m_prod, m_pbar, m_pbarl, m_pbeam, m_pbeaml, m_pelas, m_pmass, m_pbush,
      m_mat1;
};

}  // namespace ssid::translators
