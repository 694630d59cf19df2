/// \file fuzz_dmig.cpp
/// libFuzzer harness: DMIG matrices of a deck or punch file from bytes
/// (formats/dmig.cpp), each expanded to its complete matrix.
#include "formats/deck.hpp"
#include "formats/dmig.hpp"
#include "fuzz_common.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace ssid::formats;
  const std::string text(reinterpret_cast<const char*>(data), size);
  ssid::fuzz::expect_only_input_errors([&] {
    Deck deck = read_deck_text(text, "/nonexistent-ssid-fuzz/fuzz.pch");
    for (const Dmig& m : read_dmigs(deck)) expand_dmig(m, &deck);
  });
  return 0;
}
