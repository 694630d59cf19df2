/// \file fuzz_dmig.cpp
/// libFuzzer harness: DMIG matrices of a deck or punch file from bytes
/// (formats/dmig.cpp), each expanded to its complete matrix. Property: a matrix
/// written back (format_dmig, small and large field: "reals are written exactly")
/// reads back to the same header and terms.
#include "formats/deck.hpp"
#include "formats/dmig.hpp"
#include "fuzz_common.hpp"

namespace {

using namespace ssid::formats;

bool same(const Dmig& a, const Dmig& b) {
  if (a.name != b.name || a.ifo != b.ifo || a.tin != b.tin || a.tout != b.tout || a.polar != b.polar ||
      a.ncol != b.ncol || a.columns.size() != b.columns.size())
    return false;
  for (std::size_t k = 0; k < a.columns.size(); ++k) {
    const DmigColumn &x = a.columns[k], &y = b.columns[k];
    if (x.col != y.col || x.terms.size() != y.terms.size()) return false;
    for (std::size_t t = 0; t < x.terms.size(); ++t)
      if (x.terms[t].row != y.terms[t].row || x.terms[t].a != y.terms[t].a || x.terms[t].b != y.terms[t].b) return false;
  }
  return true;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  ssid::fuzz::expect_only_input_errors([&] {
    Deck deck = read_deck_text(text, "/nonexistent-ssid-fuzz/fuzz.pch");
    for (const Dmig& m : read_dmigs(deck)) {
      expand_dmig(m, &deck);
      for (FieldFormat f : {FieldFormat::Small, FieldFormat::Large}) {
        std::vector<Dmig> back;
        try {
          back = read_dmigs(read_deck_text(format_dmig(m, f), "written.pch"));
        } catch (const InputError& e) {
          ssid::fuzz::violated("DMIG " + m.name + " written does not read back: " + e.what());
        }
        if (back.size() != 1 || !same(m, back[0])) ssid::fuzz::violated("DMIG " + m.name + " written reads back different");
      }
    }
  });
  return 0;
}
