#pragma once
/// \file truss_model.hpp
/// The MPI-like truss as hardware: node balls, struts (each a tube with an end
/// cap and a B-nut at both ends), added masses and suspension points. This is
/// the inventory the generator keeps for itself — counts, masses, centre of
/// gravity — independent of how a model form (rod or beam) turns it into cards.
///
/// Units are SI throughout: metre, kilogram, newton, pascal, second.
#include <Eigen/Core>
#include <string>
#include <vector>

namespace ssid::translators::truss {

/// One piece of the strut joint hardware (B-nut or end cap), modelled as a
/// uniform bar of the given length, section and mass (report's "three beams in series").
struct FittingSection {
  double length = 0;  ///< m, along the strut axis
  double area = 0;    ///< m^2, axial stiffness section
  double inertia = 0; ///< m^4, bending (same about both axes: round parts)
  double mass = 0;    ///< kg
};

/// Physical properties shared by every strut and ball (nominal values; see docs/truss.md).
struct Hardware {
  double E = 0, nu = 0;       ///< aluminium tube and fittings, Pa
  double rho = 0;             ///< kg/m^3, tube material (drawn aluminium)
  double tube_od = 0;         ///< m
  double tube_area = 0;       ///< m^2 (A_strut)
  double tube_inertia = 0;    ///< m^4, from od and area
  FittingSection bnut, endcap, long_bnut;
  double ball_radius = 0;     ///< m, rigid from centre to the B-nut seat
  double ball_mass = 0;       ///< kg
  /// Tube mass per metre (kg/m) = rho * tube_area.
  double tube_mass_per_length() const { return rho * tube_area; }
};

struct Ball {
  int id = 0;                 ///< 1-based, also the GRID id
  Eigen::Vector3d x = Eigen::Vector3d::Zero();
  std::string group;          ///< "optics_boom", "tower", "metrology_boom"
  std::string label;          ///< e.g. "O3-2" (boom letter, station, corner)
  double added_mass = 0;      ///< kg, configuration masses (tip masses)
};

struct Member {
  int id = 0;                 ///< 1-based, also the CROD id
  int a = 0, b = 0;           ///< ball ids
  std::string group;          ///< "optics_boom", "tower", "metrology_boom"
  std::string role;           ///< "longeron", "batten", "diagonal", "section_diagonal", "tower_diagonal", "extra_diagonal"
  bool long_bnut = false;     ///< the report's long B-nut assemblies
  double mid_mass = 0;        ///< kg added at mid-span (instrumentation, the 240 g configuration)
};

/// A suspension spring: a vertical coil spring on a cable from a ceiling point
/// down to a ball. Stiffness k (N/m) vertically; pendulum stiffness horizontally.
struct Suspension {
  int ball = 0;
  double k_vertical = 0;      ///< N/m
  double k_lateral = 0;       ///< N/m, pendulum m g / L per point
  double spring_mass = 0;     ///< kg; 0 = massless spring (the report's model)
  int segments = 0;           ///< chain segments when spring_mass > 0
};

struct TrussModel {
  std::string name;           ///< "mpi" or a component configuration name
  Hardware hw;
  std::vector<Ball> balls;
  std::vector<Member> members;
  std::vector<Suspension> suspension;  ///< empty: free-free
  std::vector<std::string> configs;    ///< configurations applied, in order

  const Ball& ball(int id) const { return balls.at(static_cast<std::size_t>(id - 1)); }
  double length(const Member& m) const { return (ball(m.b).x - ball(m.a).x).norm(); }
  /// Length of the tube between the two end caps.
  double tube_length(const Member& m) const;
  const FittingSection& bnut_of(const Member& m) const { return m.long_bnut ? hw.long_bnut : hw.bnut; }
  /// Mass of the whole strut: tube, two end caps, two B-nuts and its mid-span mass.
  double member_mass(const Member& m) const;
  /// Total structural mass (balls, added masses, struts); suspension springs excluded.
  double total_mass() const;
  /// Centre of gravity of total_mass(), m.
  Eigen::Vector3d center_of_gravity() const;
  /// Bounding box extent of the ball centres, m.
  Eigen::Vector3d extent() const;
  /// Members with a given role or group (empty string matches all).
  std::size_t count_members(const std::string& role, const std::string& group = "") const;
};

/// Nominal hardware (the report's final identified component values, in SI).
Hardware mpi_hardware();

/// The layout of the MPI-like truss, m. Optics boom along x, tower along z
/// standing on the optics boom's middle bay, metrology boom along y on top of
/// the tower. The tower's section (tower_width_x by tower_width_y) is also the
/// optics boom's middle bay and the metrology boom's bay at the tower, so all
/// three share balls. See docs/truss.md for why each number.
struct MpiLayout {
  double optics_length = 7.0;       ///< report: 7 m
  int optics_bays = 7;
  double optics_depth = 0.58;       ///< z
  double metrology_length = 6.3;    ///< report: 6.3 m
  int metrology_bays = 7;
  double metrology_depth = 0.58;    ///< z
  double overall_height = 5.5;      ///< report: 5.5 m, optics bottom to metrology top (before tilt)
  int tower_bays = 5;
  double tower_width_x = 0.76;      ///< the tower's section; also the optics boom width (y) ...
  double tower_width_y = 0.66;      ///< ... and the metrology boom width (x)
  int tower_station = 3;            ///< optics bay 3-4 carries the tower: three bays either side
  int metrology_tower_station = 2;  ///< metrology bay 2-3 sits on the tower: a short and a long arm
  double metrology_tilt_deg = 2.0;  ///< long arm raised: "slightly acute angle with the tower"
};

/// The bare MPI-like truss: 80 balls, 252 struts, three suspension points with
/// massless springs. See docs/truss.md for every dimension and why.
TrussModel build_mpi(const MpiLayout& layout = {});

/// Ids of the four balls at the metrology boom's far tip, the optics boom's tip,
/// and the longest strut (the report's mid-span mass location).
std::vector<int> metrology_tip_balls(const TrussModel& t);
std::vector<int> optics_tip_balls(const TrussModel& t);
int longest_member(const TrussModel& t);

}  // namespace ssid::translators::truss
