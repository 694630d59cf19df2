#pragma once
/// \file column_tiles.hpp
/// Register tiles for the row-major block kernels (block_ops.cpp): a row of b
/// values is covered by tiles of fixed width (four, two or one 64-byte vectors,
/// then 32 and 16 bytes, then single values), and each tile's sum over the stored
/// entries of a sparse row is kept in vector registers until it is written once.
///
/// Why: written as `y_i[c] += a · x_j[c]` over a runtime b, the compiler loads and
/// stores y_i for every stored entry, a chain through memory; the kernels ran at
/// 4-7 GB/s on a machine that streams 28 GB/s (the 1M-DOF lattice,
/// bench_kernels). With fixed-width tiles the sums stay in registers and only x_j
/// is read per entry. GCC's generic vectors (vector_size) are lowered to whatever
/// the target has: SSE2 by default, AVX2 or AVX-512 in the kernels built for those
/// (target_clones in block_ops.cpp).
///
/// Internal to estimator/eigen/multilevel; every function here is always inlined, so it
/// is compiled once per target of the kernel that uses it.
#include <cstring>

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"  // vector arguments never cross a call: all inlined

namespace ssid::estimator::multilevel::tiles {

template <class T, int Bytes>
struct VecOf {
  typedef T type __attribute__((vector_size(Bytes)));
};
template <class T, int Bytes>
using Vec = typename VecOf<T, Bytes>::type;

/// A tile of K vectors of `Bytes` bytes: width() values of one row.
template <int Bytes, int K>
struct Tag {
  static constexpr int bytes = Bytes, k = K;
};

template <class T, int Bytes, int K>
struct Tile {
  static constexpr int lanes = Bytes / static_cast<int>(sizeof(T));
  Vec<T, Bytes> v[K];

  [[gnu::always_inline]] void zero() {
    for (int k = 0; k < K; ++k) v[k] = Vec<T, Bytes>{};
  }
  [[gnu::always_inline]] void load(const T* p) {
    for (int k = 0; k < K; ++k) std::memcpy(&v[k], p + k * lanes, Bytes);  // unaligned
  }
  [[gnu::always_inline]] void store(T* p) const {
    for (int k = 0; k < K; ++k) std::memcpy(p + k * lanes, &v[k], Bytes);
  }
  /// this += a · p[0 .. width)
  [[gnu::always_inline]] void fma(T a, const T* p) {
    for (int k = 0; k < K; ++k) {
      Vec<T, Bytes> x;
      std::memcpy(&x, p + k * lanes, Bytes);
      v[k] += a * x;
    }
  }
  /// p[0 .. width) += a · this
  [[gnu::always_inline]] void add_scaled_to(T a, T* p) const {
    for (int k = 0; k < K; ++k) {
      Vec<T, Bytes> x;
      std::memcpy(&x, p + k * lanes, Bytes);
      x += a * v[k];
      std::memcpy(p + k * lanes, &x, Bytes);
    }
  }
  /// this *= a
  [[gnu::always_inline]] void scale(T a) {
    for (int k = 0; k < K; ++k) v[k] *= a;
  }
  /// p[0 .. width) += this
  [[gnu::always_inline]] void add_to(T* p) const {
    for (int k = 0; k < K; ++k) {
      Vec<T, Bytes> x;
      std::memcpy(&x, p + k * lanes, Bytes);
      x += v[k];
      std::memcpy(p + k * lanes, &x, Bytes);
    }
  }
};

/// One value: a plain scalar (a one-lane vector went through the stack).
template <class T>
struct Tile<T, static_cast<int>(sizeof(T)), 1> {
  T v;
  [[gnu::always_inline]] void zero() { v = T(0); }
  [[gnu::always_inline]] void load(const T* p) { v = *p; }
  [[gnu::always_inline]] void store(T* p) const { *p = v; }
  [[gnu::always_inline]] void fma(T a, const T* p) { v += a * *p; }
  [[gnu::always_inline]] void add_scaled_to(T a, T* p) const { *p += a * v; }
  [[gnu::always_inline]] void scale(T a) { v *= a; }
  [[gnu::always_inline]] void add_to(T* p) const { *p += v; }
};

/// Calls f(Tag<Bytes, K>{}, c) for tiles covering the columns [0, b) of a row:
/// as many four-vector tiles as fit, then at most one each of two and one 64-byte
/// vectors, 32 and 16 bytes, and single values for the rest.
template <class T, class F>
[[gnu::always_inline]] inline void for_tiles(long b, F&& f) {
  constexpr long L = 64 / static_cast<long>(sizeof(T));
  long c = 0;
  for (; c + 4 * L <= b; c += 4 * L) f(Tag<64, 4>{}, c);
  if (c + 2 * L <= b) f(Tag<64, 2>{}, c), c += 2 * L;
  if (c + L <= b) f(Tag<64, 1>{}, c), c += L;
  if (c + L / 2 <= b) f(Tag<32, 1>{}, c), c += L / 2;
  if (c + L / 4 <= b) f(Tag<16, 1>{}, c), c += L / 4;
  for (; c < b; ++c) f(Tag<static_cast<int>(sizeof(T)), 1>{}, c);
}

/// The Tile type a Tag names, for values of type T.
template <class T, class TagT>
using TileFor = Tile<T, TagT::bytes, TagT::k>;

}  // namespace ssid::estimator::multilevel::tiles

#pragma GCC diagnostic pop
