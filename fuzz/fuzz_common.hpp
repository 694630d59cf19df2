#pragma once
/// \file fuzz_common.hpp
/// What every harness shares: the one rule of what counts as a finding.
///
/// A parser given arbitrary bytes may only fail through the project's bad-input
/// channel, formats::InputError (ParseError and ModelError derive from it): that
/// is the documented behaviour and the harness swallows it. Anything else — another
/// exception type (it would reach the CLI as exit 1, "a bug"), a crash, a sanitizer
/// report, a timeout, an allocation beyond libFuzzer's -rss_limit_mb — escapes and
/// libFuzzer records the input as a finding.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "formats/parse_error.hpp"

namespace ssid::fuzz {

/// Runs `parse`; bad-input errors are the expected outcome, everything else escapes.
template <class F>
void expect_only_input_errors(F&& parse) {
  try {
    parse();
  } catch (const formats::InputError&) {
  }
}

/// A property of the result that must hold (a round trip, an invariant) and did
/// not: reported as a finding with its reason.
[[noreturn]] inline void violated(const std::string& what) {
  std::fprintf(stderr, "ssid fuzz: property violated: %s\n", what.c_str());
  std::abort();
}

}  // namespace ssid::fuzz
