#pragma once
/// Byte builders for hand-made OP4 test files, written from the format description
/// (docs/op4.md), independently of the library's writer.
#include <cstdint>
#include <cstring>
#include <string>

namespace op4test {

/// Bytes of a Fortran record payload in a chosen byte order and word size.
struct Bytes {
  bool big = false;
  int word = 4;
  std::string s;

  Bytes& u(std::uint64_t v, int n) {
    for (int i = 0; i < n; ++i) {
      const int shift = big ? 8 * (n - 1 - i) : 8 * i;
      s += static_cast<char>((v >> shift) & 0xff);
    }
    return *this;
  }
  Bytes& i(std::int64_t v) { return u(static_cast<std::uint64_t>(v), word); }
  Bytes& f32(float f) {
    std::uint32_t x;
    std::memcpy(&x, &f, 4);
    return u(x, 4);
  }
  Bytes& f64(double d) {
    std::uint64_t x;
    std::memcpy(&x, &d, 8);
    return u(x, 8);
  }
  Bytes& text(const std::string& t) {
    s += t;
    return *this;
  }
};

/// A Fortran unformatted record: length marker, payload, length marker.
inline std::string record(const Bytes& payload, int marker = 4) {
  Bytes m;
  m.big = payload.big;
  m.u(payload.s.size(), marker);
  return m.s + payload.s + m.s;
}

}  // namespace op4test
