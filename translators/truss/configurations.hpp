#pragma once
/// \file configurations.hpp
/// The report's test configurations of the MPI truss, and its component-level
/// assemblies. Structure configurations combine (`--config a --config b`);
/// a component configuration replaces the truss by that assembly.
#include <string>
#include <vector>

#include "translators/truss/truss_model.hpp"

namespace ssid::translators::truss {

struct ConfigInfo {
  std::string name;
  std::string description;
  bool component = false;  ///< a component-level assembly (replaces the truss)
};

/// Every configuration `ssid truss mpi --config` accepts, in a stable order.
const std::vector<ConfigInfo>& list_configs();

/// Suspension design values (see docs/truss.md).
struct SuspensionDesign {
  double k_vertical = 600.0;     ///< N/m per coil spring
  double cable_length = 1.5;     ///< m, pendulum length of each suspension cable
  double surge_hz[3] = {48.0, 48.0, 57.0};  ///< fixed-fixed surge of each spring (surge variant)
  int segments = 12;             ///< chain segments per spring
};

/// Sets massless (surge = false) or distributed-mass springs at the model's three
/// suspension points; lateral pendulum stiffness from each point's static load share.
/// Throws std::invalid_argument when the CG is not inside the suspension triangle.
void set_suspension(TrussModel& t, bool surge, const SuspensionDesign& d = {});

/// The spring mass giving fixed-fixed surge frequency f (Hz) for a chain of N
/// segments of total stiffness k: f = (N/pi) sqrt(k/m) sin(pi/2N).
double surge_spring_mass(double k, double f_hz, int segments);

/// Applies a structure configuration to the MPI truss. Throws std::invalid_argument
/// for an unknown name or a component name (use build_component).
void apply_config(TrussModel& t, const std::string& name);

/// Builds the truss for a list of configuration names: the bare MPI with each
/// structure configuration applied in order, or a single component assembly.
TrussModel build_configured(const std::vector<std::string>& names);

/// Component assembly n = 1..7 (ball, B-nut, end cap, strut chains), free-free.
TrussModel build_component(int n);

}  // namespace ssid::translators::truss
