#pragma once
/// \file column_tiles.hpp
/// Register tiles for the row-major block kernels (block_ops.cpp): a row of b
/// values is covered by tiles of fixed width (KMax vectors of the instruction
/// set's width, one shorter tile, then half and quarter vectors, then single
/// values: for_tiles), and each tile's sum over the stored entries of a sparse row
/// is kept in vector registers until it is written once.
///
/// Why: written as `y_i[c] += a · x_j[c]` over a runtime b, the compiler loads and
/// stores y_i for every stored entry, a chain through memory; the kernels ran at
/// 4-7 GB/s on a machine that streams 28 GB/s (the 1M-DOF lattice,
/// bench_kernels). With fixed-width tiles the sums stay in registers and only x_j
/// is read per entry. GCC's generic vectors (vector_size) are lowered to whatever
/// the target has: SSE2 by default, AVX2 or AVX-512 in the kernels built for those
/// (one version per KernelIsa in block_ops.cpp, each with its own tile sizes).
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
#pragma GCC unroll 16
    for (int k = 0; k < K; ++k) v[k] = Vec<T, Bytes>{};
  }
  [[gnu::always_inline]] void load(const T* p) {
#pragma GCC unroll 16
    for (int k = 0; k < K; ++k) std::memcpy(&v[k], p + k * lanes, Bytes);  // unaligned
  }
  [[gnu::always_inline]] void store(T* p) const {
#pragma GCC unroll 16
    for (int k = 0; k < K; ++k) std::memcpy(p + k * lanes, &v[k], Bytes);
  }
  /// this += a · p[0 .. width)
  [[gnu::always_inline]] void fma(T a, const T* p) {
#pragma GCC unroll 16
    for (int k = 0; k < K; ++k) {
      Vec<T, Bytes> x;
      std::memcpy(&x, p + k * lanes, Bytes);
      v[k] += a * x;
    }
  }
  /// p[0 .. width) += a · this
  [[gnu::always_inline]] void add_scaled_to(T a, T* p) const {
#pragma GCC unroll 16
    for (int k = 0; k < K; ++k) {
      Vec<T, Bytes> x;
      std::memcpy(&x, p + k * lanes, Bytes);
      x += a * v[k];
      std::memcpy(p + k * lanes, &x, Bytes);
    }
  }
  /// this *= a
  [[gnu::always_inline]] void scale(T a) {
#pragma GCC unroll 16
    for (int k = 0; k < K; ++k) v[k] *= a;
  }
  /// p[0 .. width) += this
  [[gnu::always_inline]] void add_to(T* p) const {
#pragma GCC unroll 16
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

namespace detail {

// One tile of k (1 ≤ k ≤ K) vectors of VB bytes, k known at run time, called as
// the Tag of that width (a compile-time switch).
template <int VB, int K, class F>
[[gnu::always_inline]] inline void tile_of(long k, long c, F& f) {
  if constexpr (K >= 1) {
    if (k == K) f(Tag<VB, K>{}, c);
    else tile_of<VB, K - 1>(k, c, f);
  }
}

// At most one vector each of Bytes, Bytes/2, ... 16 bytes, while it fits in b.
template <class T, int Bytes, class F>
[[gnu::always_inline]] inline void narrower_tiles(long b, long& c, F& f) {
  if constexpr (Bytes >= 16) {
    constexpr long L = Bytes / static_cast<long>(sizeof(T));
    if (c + L <= b) f(Tag<Bytes, 1>{}, c), c += L;
    narrower_tiles<T, Bytes / 2>(b, c, f);
  }
}

}  // namespace detail

/// Calls f(Tag<Bytes, K>{}, c) for tiles covering the columns [0, b) of a row:
/// as many tiles of KMax vectors of VB bytes as fit, then one tile of fewer such
/// vectors, then at most one vector each of VB/2, VB/4, ... 16 bytes, and single
/// values for the rest. VB is the vector width of the instruction set the caller
/// is compiled for and KMax × (the kernel's rows) its register budget: a tile's
/// sums must stay in the register file (AVX-512: 32 registers of 64 bytes; AVX2:
/// 16 of 32; SSE2: 16 of 16), see KernelIsa in block_ops.hpp.
template <class T, int VB, int KMax, class F>
[[gnu::always_inline]] inline void for_tiles(long b, F&& f) {
  static_assert(VB >= 16 && (VB & (VB - 1)) == 0, "for_tiles: the vector width is 16, 32 or 64 bytes");
  static_assert(KMax >= 1, "for_tiles: at least one vector a tile");
  constexpr long L = VB / static_cast<long>(sizeof(T));
  long c = 0;
  for (; c + KMax * L <= b; c += KMax * L) f(Tag<VB, KMax>{}, c);
  if (const long k = (b - c) / L; k > 0) detail::tile_of<VB, KMax - 1>(k, c, f), c += k * L;
  detail::narrower_tiles<T, VB / 2>(b, c, f);
  for (; c < b; ++c) f(Tag<static_cast<int>(sizeof(T)), 1>{}, c);
}

/// The Tile type a Tag names, for values of type T.
template <class T, class TagT>
using TileFor = Tile<T, TagT::bytes, TagT::k>;

}  // namespace ssid::estimator::multilevel::tiles

#pragma GCC diagnostic pop
