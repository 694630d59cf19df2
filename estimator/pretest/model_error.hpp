#pragma once
/// \file model_error.hpp
/// Pretest planning, step 6: the model-error study (issue 23 item 6; pretest paper §6):
/// the placement rerun on a model whose struts' areas are perturbed, a third −20 % and a
/// third +20 %, chosen by a seed.
#include <cstdint>

#include "formats/deck.hpp"

namespace ssid::estimator::pretest {

struct AreaPerturbation {
  std::int64_t struts = 0;     ///< CROD, CONROD and CBAR elements found
  std::int64_t decreased = 0;  ///< areas × (1 − change)
  std::int64_t increased = 0;  ///< areas × (1 + change)
};

/// Perturbs the cross-section areas of the deck's struts in place. The struts (CROD,
/// CONROD, CBAR, in that order, each in deck order) are shuffled by a Fisher–Yates
/// shuffle driven by std::mt19937_64(seed) (our own mapping to indices, so a seed gives
/// the same choice on every platform); the first ⌊N/3⌋ get A × (1 − change), the next
/// ⌊N/3⌋ A × (1 + change), the rest are unchanged. A CROD or CBAR gets its own copy of
/// its PROD or PBAR (a new PID above the deck's largest, only A changed; a bar's I and J
/// are left as they are); a CONROD's A is changed on the card. The structural mass ρAL
/// follows A; the non-structural mass per length (NSM) is kept. Throws
/// formats::InputError when the deck has no strut or a strut's property is missing, and
/// for change outside (0, 1).
AreaPerturbation perturb_strut_areas(formats::Deck& deck, std::uint64_t seed, double change = 0.2);

}  // namespace ssid::estimator::pretest
