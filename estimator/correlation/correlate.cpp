#include "estimator/correlation/correlate.hpp"

#include <stdexcept>

#include "formats/parse_error.hpp"

namespace ssid::estimator {

Correlation correlate(const translators::ModeSet& fe, const translators::ModeSet& test, const PairingOptions& options) {
  Correlation c;
  c.dofs = translators::common_dofs(test, fe);
  if (c.dofs.empty())
    throw formats::InputError("the analysis and test mode sets share no measured DOF (node and direction): "
                                "check the node numbering or map the test nodes by position");
  c.fe = translators::restrict_to(fe, c.dofs);
  c.test = translators::restrict_to(test, c.dofs);
  c.pairing = pair_modes(c.fe.frequency_hz, c.fe.shapes, c.test.frequency_hz, c.test.shapes, options);
  c.auto_mac_fe = auto_mac(c.fe.shapes, options.form);
  c.auto_mac_test = auto_mac(c.test.shapes, options.form);
  return c;
}

}  // namespace ssid::estimator
