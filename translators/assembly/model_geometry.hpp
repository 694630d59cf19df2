#pragma once
/// \file model_geometry.hpp
/// The g-set of a deck: every GRID (6 DOFs, in its displacement frame CD) and
/// every SPOINT (1 DOF), in ascending id order as NASTRAN sequences them, with
/// grid positions resolved to the basic system through CORD2R/C/S (nested).
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

#include "formats/bulk_model.hpp"
#include "translators/coord_system.hpp"
#include "translators/dof_map.hpp"

namespace ssid::translators {

struct GridPoint {
  std::int64_t id = 0;
  Eigen::Vector3d x = Eigen::Vector3d::Zero();           ///< basic position
  Eigen::Matrix3d frame = Eigen::Matrix3d::Identity();   ///< displacement frame: u_basic = frame · u_cd
  std::int64_t cp = 0, cd = 0;
  std::string ps;                                        ///< permanent SPC components
  std::array<std::size_t, 6> dofs{};                     ///< g-set indices of components 1–6
  std::size_t card = 0;
};

/// Bad model data found while assembling (a dangling reference, a degenerate
/// geometry): the message starts with "file:line: CARD id", or, for what no
/// single card says (cards of a type ssid does not assemble, a case control
/// selection), the place is given apart as where().
class ModelError : public formats::InputError {
 public:
  using formats::InputError::InputError;
  ModelError(formats::SourceLocation where, const std::string& message)
      : formats::InputError(message), m_where(std::move(where)) {}
  /// The first card or statement at fault; file empty when the message names it.
  const formats::SourceLocation& where() const { return m_where; }

 private:
  formats::SourceLocation m_where;
};

class ModelGeometry {
 public:
  ModelGeometry(const formats::Deck& deck, const formats::BulkModel& model);

  const DofMap& gset() const { return m_gset; }
  const std::vector<GridPoint>& grids() const { return m_grids; }
  const CoordSystems& systems() const { return m_systems; }

  bool has_grid(std::int64_t id) const { return m_grid_index.count(id) != 0; }
  /// The grid, or a ModelError "<who>: GRID <id> does not exist".
  const GridPoint& grid(std::int64_t id, const std::string& who) const;
  /// g-set index of (point, component): component 1–6 of a grid, 0 (or 1) of a
  /// scalar point; ModelError naming `who` otherwise.
  std::size_t dof(std::int64_t point, int component, const std::string& who) const;
  bool is_scalar_point(std::int64_t id) const { return m_spoint_dof.count(id) != 0; }

 private:
  CoordSystems m_systems;
  std::vector<GridPoint> m_grids;
  std::unordered_map<std::int64_t, std::size_t> m_grid_index;
  std::unordered_map<std::int64_t, std::size_t> m_spoint_dof;
  DofMap m_gset;
};

/// "file:line: CARD id" of a card, for messages.
std::string card_label(const formats::Deck& deck, std::size_t card);

}  // namespace ssid::translators
