#pragma once
/// \file elements.hpp
/// The element library in one include: sections (PBARL/PBEAML), rod, bar and
/// beam, CONM2, scalar springs and masses, CBUSH, rigid-body checks. All
/// routines take plain values in the basic frame (see element_types.hpp) and
/// return matrices in the grids' displacement frames; derivative routines
/// return ∂K/∂p, ∂M/∂p exactly. See docs/elements.md.
#include "translators/elements/bar.hpp"
#include "translators/elements/element_types.hpp"
#include "translators/elements/point.hpp"
#include "translators/elements/rigid_body.hpp"
#include "translators/elements/rod.hpp"
#include "translators/elements/section.hpp"
