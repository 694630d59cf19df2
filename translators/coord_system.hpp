#pragma once
/// \file coord_system.hpp
/// NASTRAN coordinate systems (CORD2R, CORD2C, CORD2S) resolved to the basic
/// frame: positions of points given in a system (GRID CP), the displacement
/// frame at a point (GRID CD) and the 6x6 DOF transformation.
///
/// Definition (MSC/NX QRG, CORD2R/C/S): three points A, B, C are given in the
/// reference system RID (in RID's own coordinates, so (R, θ, Z) when RID is
/// cylindrical). A is the origin, B lies on the local Z axis, C lies in the
/// local X–Z plane:
///   e_z = (B − A)/|B − A|,  e_x = unit part of (C − A) normal to e_z,  e_y = e_z × e_x.
/// Coordinates of a point P in the system:
///   rectangular  (X, Y, Z)
///   cylindrical  (R, θ, Z):  X = R cos θ, Y = R sin θ          (θ in degrees)
///   spherical    (R, θ, φ):  X = R sin θ cos φ, Y = R sin θ sin φ, Z = R cos θ
///                           (θ from the Z axis, φ from X towards Y; degrees)
/// Displacement directions at P: rectangular (e_x, e_y, e_z); cylindrical
/// (u_r, u_θ, u_z); spherical (u_r, u_θ, u_φ), unit vectors in the directions
/// of increasing coordinate. The QRG leaves them undefined on the polar axis
/// (R = 0 cylindrical, sin θ = 0 spherical); there we use the limit along
/// θ = 0 (cylindrical) or φ = 0 (spherical), i.e. the frame the system's own
/// X axis gives, so that a grid on the axis still gets a proper rotation.
#include <Eigen/Core>
#include <map>
#include <string>
#include <vector>

namespace ssid::translators {

enum class CoordType { Rectangular, Cylindrical, Spherical };

/// A resolved coordinate system: origin and axes in the basic frame.
struct CoordSystem {
  long cid = 0;
  CoordType type = CoordType::Rectangular;
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();     ///< basic coordinates of A
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();   ///< columns: local X, Y, Z in basic

  /// Basic position of a point given by its coordinates in this system
  /// (X,Y,Z / R,θ,Z / R,θ,φ with angles in degrees).
  Eigen::Vector3d to_basic(const Eigen::Vector3d& coords) const;
  /// Coordinates in this system of a basic position (angles in degrees;
  /// θ in (−180, 180] cylindrical, θ in [0,180] and φ in (−180,180] spherical).
  Eigen::Vector3d from_basic(const Eigen::Vector3d& x_basic) const;
  /// Displacement frame at a basic position: columns are the unit vectors of
  /// the point's displacement components 1, 2, 3 in basic, so
  /// u_basic = frame * u_local (the same matrix rotates rotations).
  Eigen::Matrix3d displacement_frame(const Eigen::Vector3d& x_basic) const;
};

/// A CORD2R/C/S definition as read from the deck (plain values, no card struct).
/// CORD1R/C/S (three grids) map onto it with rid = 0 and a, b, c the grids'
/// basic positions — which the caller resolves first, since those grids may
/// themselves be located in (other) coordinate systems.
struct CoordDefinition {
  long cid = 0;
  long rid = 0;
  CoordType type = CoordType::Rectangular;
  Eigen::Vector3d a, b, c;     ///< points in RID's coordinates
  std::string source;          ///< e.g. "CORD2C 5 (model.bdf:12)" for messages
};

/// Builds the system of one definition once its reference system is known.
/// Throws std::invalid_argument (naming `def.source`) when A, B, C are
/// coincident or collinear.
CoordSystem make_coord_system(const CoordDefinition& def, const CoordSystem& reference);

/// All systems of a model, with the basic system (CID 0) always present.
class CoordSystems {
public:
  CoordSystems();
  /// Resolves nested definitions in dependency order. Throws
  /// std::invalid_argument for a duplicate CID, a CID of 0, an undefined RID or
  /// a cycle of references (each message names the definitions involved).
  explicit CoordSystems(const std::vector<CoordDefinition>& defs);

  /// Throws std::out_of_range ("coordinate system 7 is not defined") if absent.
  const CoordSystem& get(long cid) const;
  bool contains(long cid) const { return m_systems.count(cid) != 0; }

  /// Basic position of a grid whose coordinates are given in system `cp`.
  Eigen::Vector3d position_to_basic(long cp, const Eigen::Vector3d& coords) const {
    return get(cp).to_basic(coords);
  }
  /// Displacement frame of a grid (CD) located at the basic position x.
  Eigen::Matrix3d displacement_frame(long cd, const Eigen::Vector3d& x_basic) const {
    return get(cd).displacement_frame(x_basic);
  }

private:
  std::map<long, CoordSystem> m_systems;
};

/// 6x6 DOF transformation blockdiag(T, T): translations and rotations of a
/// grid rotate with the same 3x3 frame. u_basic(6) = dof_transform(T) * u_local(6).
Eigen::Matrix<double, 6, 6> dof_transform(const Eigen::Matrix3d& T);

}  // namespace ssid::translators
