/// \file fuzz_uff.cpp
/// libFuzzer harness: a universal file from bytes (formats/uff_reader.cpp).
/// Property: what was read can be written (format_uff) and read back.
#include "formats/uff.hpp"
#include "fuzz_common.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace ssid::formats;
  const std::string text(reinterpret_cast<const char*>(data), size);
  ssid::fuzz::expect_only_input_errors([&] {
    const uff::UffFile file = uff::parse_uff(text, "fuzz.unv");
    const std::string written = uff::format_uff(file, uff::Precision::Extended);
    try {
      uff::parse_uff(written, "written.unv");
    } catch (const InputError& e) {
      ssid::fuzz::violated(std::string("the file written from what was read does not read back: ") + e.what());
    }
  });
  return 0;
}
