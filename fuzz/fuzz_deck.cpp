/// \file fuzz_deck.cpp
/// libFuzzer harness: a NASTRAN deck from bytes (formats/deck_reader.cpp), its
/// bulk data parsed and resolved (formats/bulk_model.cpp). Property: a deck read
/// and not modified is written back byte for byte (deck.hpp: "lossless").
#include "formats/bulk_model.hpp"
#include "formats/deck.hpp"
#include "formats/deck_writer.hpp"
#include "fuzz_common.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace ssid::formats;
  const std::string text(reinterpret_cast<const char*>(data), size);
  ssid::fuzz::expect_only_input_errors([&] {
    // The name sits in a folder that does not exist, so a relative INCLUDE finds no
    // file and the harness reads nothing but its input.
    Deck deck = read_deck_text(text, "/nonexistent-ssid-fuzz/fuzz.bdf");
    if (deck.files.size() == 1 && render_file(deck, 0) != text) ssid::fuzz::violated("deck not written back byte for byte");
    BulkModel model = parse_bulk(deck);
    resolve(deck, model);
  });
  return 0;
}
