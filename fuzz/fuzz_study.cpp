/// \file fuzz_study.cpp
/// libFuzzer harness: a study file from bytes (estimator/study/deck_study.cpp), as
/// read_study reads it: JSON syntax first, then the study's keys and values.
/// parse_study documents std::invalid_argument for bad values (read_study turns
/// JSON syntax errors into the same); both are expected here, as is InputError
/// should the study reader move to the project's bad-input channel.
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "estimator/study/deck_study.hpp"
#include "fuzz_common.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  nlohmann::json j = nlohmann::json::parse(data, data + size, nullptr, /*allow_exceptions=*/false);
  if (j.is_discarded()) return 0;  // read_study: "not valid JSON (byte N)"
  ssid::fuzz::expect_only_input_errors([&] {
    try {
      ssid::estimator::parse_study(j, "fuzz/study.json");
    } catch (const std::invalid_argument&) {
    }
  });
  return 0;
}
