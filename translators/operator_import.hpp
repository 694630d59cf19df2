#pragma once
/// \file operator_import.hpp
/// Operators from another FE code: K and M exported as OP4 at the nominal
/// parameters and at perturbed values of each parameter (or ∂K/∂r, ∂M/∂r
/// exported directly), turned into the operator set `ssid assemble` writes.
///
/// For parameter r_j with nominal value x₀, states K₀ = K(x₀), K₊ = K(x₊),
/// K₋ = K(x₋) (M alike), the derivative is the difference quotient of the
/// states given:
///   central  ∂K/∂r ≈ (K₊ − K₋)/(x₊ − x₋)   error O(h²)  (both states)
///   forward  ∂K/∂r ≈ (K₊ − K₀)/(x₊ − x₀)   error O(h)   (only the + state)
///   backward ∂K/∂r ≈ (K₀ − K₋)/(x₀ − x₋)   error O(h)   (only the − state)
/// and exact for K linear in r (areas, E, ρ, spring rates, masses). The step
/// h (x₊ − x₀, x₀ − x₋ or (x₊ − x₋)/2) and the scheme go into the manifest.
///
/// The spec (JSON; paths relative to the spec's folder):
///   { "dofs": "manifest.json" | [[grid, component], ...],       (optional)
///     "K": OP4, "M": OP4,                                        (nominal)
///     "parameters": [
///       { "label": "STRUTA", "id": 1, "value": x0, "lower": .., "upper": ..,
///         "plus":  {"value": x+, "K": OP4, "M": OP4},            (K or M omitted:
///         "minus": {"value": x-, "K": OP4, "M": OP4} },           unchanged by r)
///       { "label": "KSUSP", "value": x0, "dK": OP4, "dM": OP4 } ] }   ("given")
/// where OP4 is a file name (its only, or first, matrix),
/// {"file": name, "matrix": "KAA"} to pick a matrix by name, or
/// {"dmig": deck-or-punch, "matrix": "KAAX"} for a DMIG matrix. DMIG sources are
/// assembled on the DOFs of the nominal K's DMIG, in increasing (grid, component)
/// order, which also become the DOF map when "dofs" is left out.
#include <string>

#include "translators/operator_set.hpp"

namespace ssid::translators {

/// Reads the spec and every file it names. Throws std::runtime_error naming the
/// spec, the parameter and the key or file that is wrong (missing, not a square
/// real matrix of the nominal size, equal perturbed and nominal values).
OperatorSet import_operators(const std::string& spec_path);

}  // namespace ssid::translators
