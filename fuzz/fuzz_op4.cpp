/// \file fuzz_op4.cpp
/// libFuzzer harness: OP4 matrices from bytes, ASCII or binary (formats/op4_reader.cpp).
/// Property: every matrix read has the dimensions its header gave (after the
/// documented completion of diagonal forms) and its values live in the member
/// its precision names.
#include "formats/op4.hpp"
#include "fuzz_common.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace ssid::formats;
  ssid::fuzz::expect_only_input_errors([&] {
    const auto matrices = read_op4_buffer(reinterpret_cast<const char*>(data), size, "fuzz.op4");
    for (const auto& m : matrices) {
      const auto rows = m.is_complex() ? m.complex.rows() : m.real.rows();
      const auto cols = m.is_complex() ? m.complex.cols() : m.real.cols();
      if (rows != m.rows || cols != m.cols) ssid::fuzz::violated("matrix " + m.name + ": storage size differs from rows x cols");
    }
  });
  return 0;
}
