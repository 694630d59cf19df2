#include "estimator/eigen/multilevel/block_ops.hpp"

#include "estimator/eigen/multilevel/column_tiles.hpp"
#include "formats/parse_error.hpp"

#include <sys/mman.h>

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <cstdlib>
#include <stdexcept>
#include <thread>
#include <vector>

namespace ssid::estimator::multilevel {

template <class T>
void resize_block(RowBlockOf<T>& Y, long rows, long cols) {
  const Eigen::Index before = Y.size();
  Y.resize(rows, cols);  // new storage exactly when the size changes (possibly at the same address)
#ifdef MADV_HUGEPAGE
  constexpr std::uintptr_t huge = std::uintptr_t{2} << 20;
  const std::size_t bytes = sizeof(T) * static_cast<std::size_t>(Y.size());
  if (Y.size() == before || bytes < (std::size_t{64} << 20)) return;
  const auto begin = (reinterpret_cast<std::uintptr_t>(Y.data()) + huge - 1) & ~(huge - 1);
  const auto end = (reinterpret_cast<std::uintptr_t>(Y.data()) + bytes) & ~(huge - 1);
  if (end > begin) madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);  // advice: failure is harmless
#endif
}
template void resize_block<double>(RowBlockOf<double>&, long, long);
template void resize_block<float>(RowBlockOf<float>&, long, long);

long worker_threads() { return std::min<long>(std::max(1u, std::thread::hardware_concurrency()), 64); }

long parallel_parts(long n, const std::function<void(long, long, long)>& body, long serial_below) {
  const long threads = worker_threads();
  if (n < serial_below || threads == 1) {
    body(0, 0, n);
    return 1;
  }
  std::vector<std::thread> pool;
  const long chunk = (n + threads - 1) / threads;
  for (long t = 1; t < threads; ++t) {
    const long b = t * chunk, e = std::min(n, b + chunk);
    if (b < e) pool.emplace_back(body, t, b, e);
  }
  body(0, 0, std::min(n, chunk));
  for (auto& th : pool) th.join();
  return threads;
}

void parallel_for(long n, const std::function<void(long, long)>& body, long serial_below) {
  parallel_parts(n, [&body](long, long begin, long end) { body(begin, end); }, serial_below);
}

namespace {

/// How a product is written into Y.
enum class Into { Overwrite, Residual, Subtract, Add };  // Y = AX, Y = B − AX, Y −= AX, Y += AX

/// The arguments of one sparse block product (see outer_rows_times).
template <class T>
struct RowsArgs {
  const int* outer;
  const int* inner;
  const T* val;
  const T* x;
  const T* base;  // the residual's B, or null
  T* y;
  long b;
  Into into;
};

template <class T>
struct JacobiArgs;
struct DenseArgs;
struct GramArgs;

/// One instruction set's versions of the kernels below (see KernelIsa).
struct KernelTable {
  void (*rows_float)(const RowsArgs<float>&, long, long);
  void (*rows_double)(const RowsArgs<double>&, long, long);
  void (*scatter_float)(const RowsArgs<float>&, long, long, float*);
  void (*scatter_double)(const RowsArgs<double>&, long, long, double*);
  void (*jacobi_float)(const JacobiArgs<float>&, long, long);
  void (*jacobi_double)(const JacobiArgs<double>&, long, long);
  void (*dense_double)(const DenseArgs&, long, long);
  void (*gram_double)(const GramArgs&, long, long, double*, double*);
};
/// The table of the kernel instruction set in use (kernel_isa()).
const KernelTable& kernels();

// The register blocking of each instruction set's kernels: vb, the vector width in
// bytes; *_k, the vectors of sums one tile keeps in registers per row; *_r, the rows
// a dense kernel handles at once (its sums: r x k vectors, plus k vectors of the
// other operand and one broadcast value, all within the register file).
// AVX-512 (32 registers of 64 bytes): the blocking the kernels were tuned with,
// 4 x 4 = 16 sums. AVX2 (16 of 32 bytes) and SSE2 (16 of 16): 4 x 3 = 12 sums + 3
// + 1 = 16 registers; the same 4 x 4 there spilled sums to the stack on every
// product (issue 25: gram_double, 46 % of an AVX2 multilevel solve, ran from the
// stack). The sparse kernels keep one row's sums (k vectors) and stream the rest.
struct IsaGeneric {
  static constexpr int vb = 16, rows_k = 8, gram_r = 4, gram_k = 3, dense_r = 4, dense_k = 3;
};
struct IsaAvx2 {
  static constexpr int vb = 32, rows_k = 8, gram_r = 4, gram_k = 3, dense_r = 4, dense_k = 3;
};
struct IsaAvx512 {
  static constexpr int vb = 64, rows_k = 4, gram_r = 4, gram_k = 4, dense_r = 4, dense_k = 4;
};

// Rows [begin, end) of Y (per `into`) Σ over the stored entries (j, a) of outer index i
// of a X.row(j), each row in register tiles (column_tiles.hpp).
template <class Isa, class T>
[[gnu::always_inline]] inline void rows_kernel(const RowsArgs<T>& a, long begin, long end) {
  const long b = a.b;
  const T sign = (a.into == Into::Residual || a.into == Into::Subtract) ? T(-1) : T(1);
  for (long i = begin; i < end; ++i) {
    T* yi = a.y + i * b;  // Y never overlaps X or the base
    const T* init = a.into == Into::Residual ? a.base + i * b : a.into == Into::Overwrite ? nullptr : yi;
    const int p0 = a.outer[i], p1 = a.outer[i + 1];
    tiles::for_tiles<T, Isa::vb, Isa::rows_k>(b, [&](auto tag, long c) __attribute__((always_inline)) {
      tiles::TileFor<T, decltype(tag)> acc;
      if (init) acc.load(init + c);
      else acc.zero();
      for (int p = p0; p < p1; ++p) acc.fma(sign * a.val[p], a.x + static_cast<long>(a.inner[p]) * b + c);
      acc.store(yi + c);
    });
  }
}

void rows(const RowsArgs<float>& a, long begin, long end) { kernels().rows_float(a, begin, end); }
void rows(const RowsArgs<double>& a, long begin, long end) { kernels().rows_double(a, begin, end); }

// out.row(j) += a X.row(i) over the stored entries (j, a) of outer index i, rows
// [begin, end): the transpose product of a row-major A, scattered.
template <class Isa, class T>
[[gnu::always_inline]] inline void scatter_kernel(const RowsArgs<T>& a, long begin, long end, T* out) {
  const long b = a.b;
  for (long i = begin; i < end; ++i) {
    const int p0 = a.outer[i], p1 = a.outer[i + 1];
    if (p0 == p1) continue;
    tiles::for_tiles<T, Isa::vb, Isa::rows_k>(b, [&](auto tag, long c) __attribute__((always_inline)) {
      tiles::TileFor<T, decltype(tag)> xi;
      xi.load(a.x + i * b + c);
      for (int p = p0; p < p1; ++p) xi.add_scaled_to(a.val[p], out + static_cast<long>(a.inner[p]) * b + c);
    });
  }
}

void scatter(const RowsArgs<float>& a, long begin, long end, float* out) { kernels().scatter_float(a, begin, end, out); }
void scatter(const RowsArgs<double>& a, long begin, long end, double* out) {
  kernels().scatter_double(a, begin, end, out);
}

// Y (per `into`) A X, A's outer index i giving Y's row i.
template <class Sparse, class T>
void outer_rows_times(const Sparse& A, const RowBlockOf<T>& X, RowBlockOf<T>& Y, Into into = Into::Overwrite,
                      const RowBlockOf<T>* base = nullptr) {
  const long rows_ = A.outerSize(), b = X.cols();
  if (into == Into::Overwrite || into == Into::Residual) resize_block(Y, rows_, b);
  else if (Y.rows() != rows_ || Y.cols() != b) throw std::invalid_argument("sparse block product: Y's shape");
  if (into == Into::Residual && (base->rows() != rows_ || base->cols() != b))
    throw std::invalid_argument("sparse block product: the base block's shape");
  const RowsArgs<T> args{A.outerIndexPtr(), A.innerIndexPtr(), A.valuePtr(), X.data(),
                         base ? base->data() : nullptr, Y.data(), b, into};
  parallel_for(rows_, [&args](long begin, long end) { rows(args, begin, end); });
}

/// The arguments of one block-Jacobi pass (see block_jacobi_pass).
template <class T>
struct JacobiArgs {
  const long* start;
  const long* dofs;
  const long* dinv_start;
  const T* dinv;
  const T* res;
  T* d;
  T* x;
  long b;
  T alpha, beta;
  bool alpha_zero, set_x;
};

template <class Isa, class T>
[[gnu::always_inline]] inline void jacobi_kernel(const JacobiArgs<T>& a, long begin, long end) {
  const long b = a.b;
  for (long g = begin; g < end; ++g) {
    const long s = a.start[g], k = a.start[g + 1] - s;
    const long* dofs = a.dofs + s;
    const T* dinv = a.dinv + a.dinv_start[g];
    for (long i = 0; i < k; ++i) {
      T* di = a.d + dofs[i] * b;
      T* xi = a.x + dofs[i] * b;
      tiles::for_tiles<T, Isa::vb, Isa::rows_k>(b, [&](auto tag, long c) __attribute__((always_inline)) {
        tiles::TileFor<T, decltype(tag)> z;  // β (D⁻¹ res)_i, then d_i
        z.zero();
        for (long j = 0; j < k; ++j) z.fma(a.beta * dinv[i * k + j], a.res + dofs[j] * b + c);
        if (!a.alpha_zero) z.fma(a.alpha, di + c);
        z.store(di + c);
        if (a.set_x) z.store(xi + c);
        else z.add_to(xi + c);
      });
    }
  }
}

void jacobi(const JacobiArgs<float>& a, long begin, long end) { kernels().jacobi_float(a, begin, end); }
void jacobi(const JacobiArgs<double>& a, long begin, long end) { kernels().jacobi_double(a, begin, end); }

/// The arguments of a dense block product Y = β Y + Σ_s B_s C_s (see dense_kernel).
struct DenseArgs {
  static constexpr int kMaxSources = 4;
  const double* src[kMaxSources];  // the row-major blocks B_s, n rows each
  long cols[kMaxSources];
  int sources;
  const double* c;  // the C_s stacked by rows, row-major, q values a row
  double* y;        // never overlaps a source
  long q;
  double beta;
};

// Rows [i, i + R) of Y: each tile's sums over every row of the stacked C stay in
// registers, for R rows at once so that a row of C is loaded once for R rows.
template <class Isa, int R>
[[gnu::always_inline]] inline void dense_rows(const DenseArgs& a, long i) {
  const long q = a.q;
  tiles::for_tiles<double, Isa::vb, Isa::dense_k>(q, [&](auto tag, long c) __attribute__((always_inline)) {
    tiles::TileFor<double, decltype(tag)> acc[R];
    #pragma GCC unroll 8
    for (int r = 0; r < R; ++r) {
      if (a.beta == 0.0) {
        acc[r].zero();
      } else {
        acc[r].load(a.y + (i + r) * q + c);
        if (a.beta != 1.0) acc[r].scale(a.beta);
      }
    }
    const double* crow = a.c + c;
    for (int s = 0; s < a.sources; ++s) {
      const long k = a.cols[s];
      const double* x = a.src[s] + i * k;
      for (long j = 0; j < k; ++j, crow += q)
        #pragma GCC unroll 8
        for (int r = 0; r < R; ++r) acc[r].fma(x[r * k + j], crow);
    }
    #pragma GCC unroll 8
    for (int r = 0; r < R; ++r) acc[r].store(a.y + (i + r) * q + c);
  });
}

template <class Isa>
[[gnu::always_inline]] inline void dense_kernel(const DenseArgs& a, long begin, long end) {
  constexpr int R = Isa::dense_r;
  long i = begin;
  for (; i + R <= end; i += R) dense_rows<Isa, R>(a, i);
  for (; i < end; ++i) dense_rows<Isa, 1>(a, i);
}

/// The arguments of a Gram product G += Xᵀ Y over a range of rows (see gram_kernel).
struct GramArgs {
  const double* x;  // n x p, row-major
  const double* wx; // weights of X's rows (X's copy scaled row by row), or null
  const double* y;  // n x q, row-major
  long p, q;
  bool upper;  // only the tiles that reach the upper triangle (j ≥ i); p = q
};

constexpr long kLanes = 8;  // doubles in a 64-byte vector

/// The Gram kernel's row width for Y (q rounded up to whole vectors) and its chunk
/// of rows (about 24 KiB of X and Y together, within the first-level cache).
constexpr long gram_padded(long q) { return (q + kLanes - 1) / kLanes * kLanes; }
constexpr long gram_chunk(long p, long q8) { return std::clamp<long>(24576 / (8 * (p + q8)), 8, 256); }

// Rows [i0, i0 + R) of G (p x q8, row-major) += Σ over the `rows` rows k of the
// chunk x_k[i0 ..]ᵀ y_k, y the chunk copied with its rows padded to q8 (a multiple
// of the 64-byte vector): R x width sums in registers per tile of G, full vectors
// only. In upper mode the tiles start at the vector holding column i0, so about
// half of G is computed. R and the tile's vectors: the instruction set's blocking
// (Isa::gram_r x Isa::gram_k vectors of sums).
template <class Isa, int R>
[[gnu::always_inline]] inline void gram_rows(const double* x, long p, const double* y, long q8, long rows, long i0,
                                             bool upper, double* G) {
  const long c0 = upper ? i0 / kLanes * kLanes : 0;
  tiles::for_tiles<double, Isa::vb, Isa::gram_k>(q8 - c0, [&](auto tag, long c) __attribute__((always_inline)) {
    c += c0;
    tiles::TileFor<double, decltype(tag)> acc[R];
    #pragma GCC unroll 8
    for (int r = 0; r < R; ++r) acc[r].zero();
    const double* xk = x + i0;
    const double* yk = y + c;
    for (long k = 0; k < rows; ++k, xk += p, yk += q8)
      #pragma GCC unroll 8
      for (int r = 0; r < R; ++r) acc[r].fma(xk[r], yk);
    #pragma GCC unroll 8
    for (int r = 0; r < R; ++r) acc[r].add_to(G + (i0 + r) * q8 + c);
  });
}

// Copies rows [k0, k0 + rows) of a row-major block of width w into `to`, each row
// padded by zeros to w8 values, in tiles (a memcpy call per row cost a quarter of
// the Gram product's time).
// With `weights`, row k is scaled by weights[k0 + k] on the way.
template <class Isa>
[[gnu::always_inline]] inline void copy_rows_padded(const double* from, long w, long k0, long rows, long w8, double* to,
                                                    const double* weights = nullptr) {
  for (long k = 0; k < rows; ++k) {
    const double* f = from + (k0 + k) * w;
    double* t = to + k * w8;
    const double s = weights ? weights[k0 + k] : 1.0;
    tiles::for_tiles<double, Isa::vb, Isa::rows_k>(w, [&](auto tag, long c) __attribute__((always_inline)) {
      tiles::TileFor<double, decltype(tag)> v;
      v.load(f + c);
      if (weights) v.scale(s);
      v.store(t + c);
    });
    for (long c = w; c < w8; ++c) t[c] = 0.0;
  }
}

// The last p mod R rows of G: gram_rows with R' = p − i0 rows (0 ≤ R' ≤ RMax).
template <class Isa, int RMax>
[[gnu::always_inline]] inline void gram_row_rest(const double* x, long p, const double* y, long q8, long rows, long i0,
                                                 bool upper, double* G) {
  if constexpr (RMax >= 1) {
    if (p - i0 == RMax) gram_rows<Isa, RMax>(x, p, y, q8, rows, i0, upper, G);
    else gram_row_rest<Isa, RMax - 1>(x, p, y, q8, rows, i0, upper, G);
  }
}

// G (p x q8, row-major) += Σ_{k ∈ [begin, end)} x_kᵀ y_k, in chunks of rows small
// enough to stay in the first-level cache while every tile of G passes over them.
// Each chunk of X and Y is first copied, streaming, into `buf` (gram_chunk(p, q8)
// x (p + q8) values), Y's rows padded by zeros to a whole number of vectors. Why
// copy: read in place, X was walked with a stride of p values four columns at a
// time and the product streamed 4 GB/s a core where a sum streams 30; and with
// q = 45 the tail tiles (8, 4 and 1 values) cost as much as the 32 before them.
template <class Isa>
[[gnu::always_inline]] inline void gram_kernel(const GramArgs& a, long begin, long end, double* G, double* buf) {
  constexpr int R = Isa::gram_r;
  const long p = a.p, q = a.q, q8 = gram_padded(q), chunk = gram_chunk(p, q8);
  double* xbuf = buf;
  double* ybuf = buf + chunk * p;
  for (long k0 = begin; k0 < end; k0 += chunk) {
    const long rows = std::min(end, k0 + chunk) - k0;
    copy_rows_padded<Isa>(a.x, p, k0, rows, p, xbuf, a.wx);
    copy_rows_padded<Isa>(a.y, q, k0, rows, q8, ybuf);
    {  // the next chunk towards the second-level cache while this one is multiplied
      const long from = k0 + rows, next = std::min(end, from + chunk);
      for (long o = from * p; o < next * p; o += 8) __builtin_prefetch(a.x + o, 0, 2);
      for (long o = from * q; o < next * q; o += 8) __builtin_prefetch(a.y + o, 0, 2);
    }
    long i0 = 0;
    for (; i0 + R <= p; i0 += R) gram_rows<Isa, R>(xbuf, p, ybuf, q8, rows, i0, a.upper, G);
    gram_row_rest<Isa, R - 1>(xbuf, p, ybuf, q8, rows, i0, a.upper, G);
  }
}

// One copy of each kernel per instruction set, register-blocked for its register
// file (the Isa* structs above), the right one chosen at run time (kernels()).
// The default copy is built for the build's target (plain x86-64, SSE2, unless
// CMAKE_CXX_FLAGS say otherwise); with GCC on x86-64 Linux also an AVX2 (x86-64-v3)
// and an AVX-512 (x86-64-v4) copy. Every helper is always inlined into these, so it
// is compiled for each target.
#define SSID_ISA_KERNELS(ATTR, Isa, name)                                                                       \
  ATTR void rows_float_##name(const RowsArgs<float>& a, long b, long e) { rows_kernel<Isa>(a, b, e); }          \
  ATTR void rows_double_##name(const RowsArgs<double>& a, long b, long e) { rows_kernel<Isa>(a, b, e); }        \
  ATTR void scatter_float_##name(const RowsArgs<float>& a, long b, long e, float* o) {                          \
    scatter_kernel<Isa>(a, b, e, o);                                                                            \
  }                                                                                                             \
  ATTR void scatter_double_##name(const RowsArgs<double>& a, long b, long e, double* o) {                       \
    scatter_kernel<Isa>(a, b, e, o);                                                                            \
  }                                                                                                             \
  ATTR void jacobi_float_##name(const JacobiArgs<float>& a, long b, long e) { jacobi_kernel<Isa>(a, b, e); }    \
  ATTR void jacobi_double_##name(const JacobiArgs<double>& a, long b, long e) { jacobi_kernel<Isa>(a, b, e); }  \
  ATTR void dense_double_##name(const DenseArgs& a, long b, long e) { dense_kernel<Isa>(a, b, e); }             \
  ATTR void gram_double_##name(const GramArgs& a, long b, long e, double* G, double* buf) {                     \
    gram_kernel<Isa>(a, b, e, G, buf);                                                                          \
  }                                                                                                             \
  constexpr KernelTable kTable_##name{&rows_float_##name,   &rows_double_##name,  &scatter_float_##name,        \
                                      &scatter_double_##name, &jacobi_float_##name, &jacobi_double_##name,      \
                                      &dense_double_##name, &gram_double_##name};

SSID_ISA_KERNELS(, IsaGeneric, generic)
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && defined(__gnu_linux__)
#define SSID_KERNEL_ISA_X86 1
SSID_ISA_KERNELS(__attribute__((target("arch=x86-64-v3"))), IsaAvx2, avx2)
SSID_ISA_KERNELS(__attribute__((target("arch=x86-64-v4"))), IsaAvx512, avx512)
#endif
#undef SSID_ISA_KERNELS


/// The kernel version in use: set once from the CPU, or by set_kernel_isa.
std::atomic<KernelIsa>& current_isa() {
  static std::atomic<KernelIsa> isa{supported_kernel_isas().back()};
  return isa;
}

const KernelTable& kernels() {
  switch (current_isa().load(std::memory_order_relaxed)) {
#ifdef SSID_KERNEL_ISA_X86
    case KernelIsa::Avx512: return kTable_avx512;
    case KernelIsa::Avx2: return kTable_avx2;
#endif
    default: return kTable_generic;
  }
}

template <class T>
void check_symmetric(const SparseOf<T>& A, const RowBlockOf<T>& X) {
  if (!A.isCompressed() || A.rows() != A.cols() || A.cols() != X.rows())
    throw std::invalid_argument("sym_times: A must be square, compressed and match X");
}

}  // namespace

const char* kernel_isa_name(KernelIsa isa) {
  switch (isa) {
    case KernelIsa::Avx512: return "avx512";
    case KernelIsa::Avx2: return "avx2";
    case KernelIsa::Generic: break;
  }
  return "generic";
}

KernelIsa kernel_isa_named(const std::string& name) {
  for (const KernelIsa isa : {KernelIsa::Generic, KernelIsa::Avx2, KernelIsa::Avx512})
    if (name == kernel_isa_name(isa)) return isa;
  throw formats::InputError("unknown kernel instruction set \"" + name + "\" (expected generic, avx2 or avx512)");
}

bool kernel_isa_supported(KernelIsa isa) {
  switch (isa) {
    case KernelIsa::Generic: return true;
#ifdef SSID_KERNEL_ISA_X86
    // The features GCC's x86-64-v3 and -v4 levels add that these kernels' code may use.
    case KernelIsa::Avx2:
      return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") && __builtin_cpu_supports("bmi2");
    case KernelIsa::Avx512:
      return kernel_isa_supported(KernelIsa::Avx2) && __builtin_cpu_supports("avx512f") &&
             __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("avx512bw") &&
             __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512cd");
#endif
    default: return false;
  }
}

std::vector<KernelIsa> supported_kernel_isas() {
  std::vector<KernelIsa> isas;
  for (const KernelIsa isa : {KernelIsa::Generic, KernelIsa::Avx2, KernelIsa::Avx512})
    if (kernel_isa_supported(isa)) isas.push_back(isa);
  return isas;
}

KernelIsa kernel_isa() { return current_isa().load(); }

void set_kernel_isa(KernelIsa isa) {
  if (!kernel_isa_supported(isa)) {
    std::string have;
    for (const KernelIsa s : supported_kernel_isas()) have += std::string(have.empty() ? "" : ", ") + kernel_isa_name(s);
    throw formats::InputError(std::string("kernel instruction set ") + kernel_isa_name(isa) +
                              " is not supported by this CPU or build (supported: " + have + ")");
  }
  current_isa().store(isa);
}

void apply_kernel_isa_environment() {
  const char* value = std::getenv("SSID_KERNEL_ISA");
  if (value && *value) set_kernel_isa(kernel_isa_named(value));
}

template <class T>
void sym_times(const SparseOf<T>& A, const RowBlockOf<T>& X, RowBlockOf<T>& Y) {
  check_symmetric(A, X);
  outer_rows_times(A, X, Y);
}

template <class T>
void sym_residual(const SparseOf<T>& A, const RowBlockOf<T>& X, const RowBlockOf<T>& B, RowBlockOf<T>& Y) {
  check_symmetric(A, X);
  outer_rows_times(A, X, Y, Into::Residual, &B);
}

template <class T>
void sym_subtract(const SparseOf<T>& A, const RowBlockOf<T>& X, RowBlockOf<T>& Y) {
  check_symmetric(A, X);
  outer_rows_times(A, X, Y, Into::Subtract);
}

template <class T>
void times_add(const SparseRowOf<T>& A, const RowBlockOf<T>& X, RowBlockOf<T>& Y) {
  if (!A.isCompressed() || A.cols() != X.rows()) throw std::invalid_argument("times_add: A must be compressed and match X");
  outer_rows_times(A, X, Y, Into::Add);
}

template <class T>
void times(const SparseRowOf<T>& A, const RowBlockOf<T>& X, RowBlockOf<T>& Y) {
  if (!A.isCompressed() || A.cols() != X.rows()) throw std::invalid_argument("times: A must be compressed and match X");
  outer_rows_times(A, X, Y);
}

template <class T>
void transpose_times(const SparseRowOf<T>& A, const RowBlockOf<T>& X, RowBlockOf<T>& Y) {
  if (!A.isCompressed() || A.rows() != X.rows())
    throw std::invalid_argument("transpose_times: A must be compressed and match X");
  const long m = A.cols(), b = X.cols();
  Y.setZero(m, b);
  const RowsArgs<T> args{A.outerIndexPtr(), A.innerIndexPtr(), A.valuePtr(), X.data(), nullptr, Y.data(), b,
                         Into::Add};
  // Each thread scatters its rows of A into its own copy of Y (the first into Y
  // itself); the copies are added in order, so the bits do not depend on timing.
  std::vector<RowBlockOf<T>> partial(static_cast<size_t>(worker_threads()));
  const long parts = parallel_parts(A.rows(), [&](long t, long begin, long end) {
    T* out = Y.data();
    if (t > 0) {
      partial[static_cast<size_t>(t)].setZero(m, b);
      out = partial[static_cast<size_t>(t)].data();
    }
    scatter(args, begin, end, out);
  });
  if (parts == 1) return;
  T* y = Y.data();
  parallel_for(m * b, [&](long begin, long end) {
    for (long t = 1; t < parts; ++t) {
      if (partial[static_cast<size_t>(t)].size() == 0) continue;  // a part with no rows
      const T* q = partial[static_cast<size_t>(t)].data();
      for (long i = begin; i < end; ++i) y[i] += q[i];
    }
  });
}

template <class From, class To>
void convert(const RowBlockOf<From>& X, RowBlockOf<To>& Y) {
  resize_block(Y, X.rows(), X.cols());
  const long b = X.cols();
  const From* x = X.data();
  To* y = Y.data();
  parallel_for(X.rows(), [=](long begin, long end) {
    for (long i = begin * b; i < end * b; ++i) y[i] = static_cast<To>(x[i]);
  });
}

template <class T>
void block_jacobi_pass(const GridBlocks<T>& blocks, const RowBlockOf<T>& res, double alpha, double beta,
                       RowBlockOf<T>& d, RowBlockOf<T>& X, bool set_x) {
  const long n = res.rows(), b = res.cols();
  if (alpha == 0.0) resize_block(d, n, b);  // d is written before it is read
  else if (d.rows() != n || d.cols() != b) throw std::invalid_argument("block_jacobi_pass: d's shape");
  if (set_x) resize_block(X, n, b);
  else if (X.rows() != n || X.cols() != b) throw std::invalid_argument("block_jacobi_pass: X's shape");
  const JacobiArgs<T> args{blocks.start->data(), blocks.dofs->data(), blocks.dinv_start->data(), blocks.dinv,
                           res.data(), d.data(), X.data(), b, static_cast<T>(alpha), static_cast<T>(beta),
                           alpha == 0.0, set_x};
  parallel_for(static_cast<long>(blocks.start->size()) - 1, [&args](long begin, long end) { jacobi(args, begin, end); });
}

#define SSID_BLOCK_OPS(T)                                                                                \
  template void sym_times<T>(const SparseOf<T>&, const RowBlockOf<T>&, RowBlockOf<T>&);                  \
  template void sym_residual<T>(const SparseOf<T>&, const RowBlockOf<T>&, const RowBlockOf<T>&,          \
                                RowBlockOf<T>&);                                                         \
  template void sym_subtract<T>(const SparseOf<T>&, const RowBlockOf<T>&, RowBlockOf<T>&);               \
  template void times_add<T>(const SparseRowOf<T>&, const RowBlockOf<T>&, RowBlockOf<T>&);               \
  template void times<T>(const SparseRowOf<T>&, const RowBlockOf<T>&, RowBlockOf<T>&);                   \
  template void transpose_times<T>(const SparseRowOf<T>&, const RowBlockOf<T>&, RowBlockOf<T>&);                     \
  template void block_jacobi_pass<T>(const GridBlocks<T>&, const RowBlockOf<T>&, double, double, RowBlockOf<T>&, \
                                     RowBlockOf<T>&, bool);
SSID_BLOCK_OPS(double)
SSID_BLOCK_OPS(float)
#undef SSID_BLOCK_OPS
template void convert<double, float>(const RowBlockOf<double>&, RowBlockOf<float>&);
template void convert<float, double>(const RowBlockOf<float>&, RowBlockOf<double>&);

namespace {

/// Rows per thread below which a dense product runs on the calling thread alone.
constexpr long kSplitRows = 8192;

}  // namespace

SparseMatrix parallel_product(const SparseMatrix& A, const SparseMatrix& B) {
  if (A.cols() != B.rows()) throw std::invalid_argument("parallel_product: shapes do not agree");
  const long threads = worker_threads(), nc = B.cols();
  if (threads == 1 || nc < 64) return SparseMatrix(A * B);
  // One part per thread, by columns (parts left empty where a thread had none).
  std::vector<SparseMatrix> parts(static_cast<size_t>(threads));
  parallel_parts(
      nc,
      [&](long t, long begin, long end) {
        SparseMatrix& part = parts[static_cast<size_t>(t)];
        part = A * B.middleCols(begin, end - begin);
        part.makeCompressed();
      },
      0);
  long nnz = 0;
  for (const auto& part : parts) nnz += part.nonZeros();
  SparseMatrix C(A.rows(), nc);
  C.resizeNonZeros(nnz);
  long col = 0, at = 0;
  for (const auto& part : parts) {
    for (long j = 0; j < part.cols(); ++j) C.outerIndexPtr()[col + j] = static_cast<int>(at + part.outerIndexPtr()[j]);
    std::copy(part.innerIndexPtr(), part.innerIndexPtr() + part.nonZeros(), C.innerIndexPtr() + at);
    std::copy(part.valuePtr(), part.valuePtr() + part.nonZeros(), C.valuePtr() + at);
    col += part.cols();
    at += part.nonZeros();
  }
  C.outerIndexPtr()[nc] = static_cast<int>(at);
  return C;
}

SparseMatrix galerkin_lower(const SparseMatrix& B, const SparseMatrix& P, const SparseRowMatrix& Prow,
                            const std::vector<long>& starts) {
  const long n = P.rows(), nc = P.cols();
  if (B.rows() != n || B.cols() != n || Prow.rows() != n || Prow.cols() != nc || !B.isCompressed() ||
      !P.isCompressed() || !Prow.isCompressed() || starts.empty() || starts.front() != 0 || starts.back() != nc)
    throw std::invalid_argument("galerkin_lower: shapes, compression or column blocks do not agree");
  const long nblocks = static_cast<long>(starts.size()) - 1;
  struct Column {
    std::vector<int> rows;
    std::vector<double> values;
  };
  std::vector<Column> columns(static_cast<size_t>(nc));
  parallel_for(
      nblocks,
      [&](long begin, long end) {
        std::vector<long> mark(static_cast<size_t>(n), -1), cmark(static_cast<size_t>(nc), -1);
        std::vector<long> touched, ctouched;
        std::vector<double> Y, G;  // B P_block rows, Pᵀ (B P_block) rows; block width w
        for (long blk = begin; blk < end; ++blk) {
          const long c0 = starts[static_cast<size_t>(blk)], w = starts[static_cast<size_t>(blk) + 1] - c0;
          touched.clear(), Y.clear();
          for (long j = 0; j < w; ++j)
            for (SparseMatrix::InnerIterator pit(P, c0 + j); pit; ++pit)
              for (SparseMatrix::InnerIterator bit(B, pit.row()); bit; ++bit) {  // column = row of B
                long& m = mark[static_cast<size_t>(bit.row())];
                if (m < 0) {
                  m = static_cast<long>(touched.size());
                  touched.push_back(bit.row());
                  Y.resize(Y.size() + static_cast<size_t>(w), 0.0);
                }
                Y[static_cast<size_t>(m * w + j)] += bit.value() * pit.value();
              }
          ctouched.clear(), G.clear();
          for (size_t t = 0; t < touched.size(); ++t) {
            const long i = touched[t];
            const double* y = Y.data() + t * static_cast<size_t>(w);
            for (SparseRowMatrix::InnerIterator qit(Prow, i); qit; ++qit) {
              const long q = qit.col();
              if (q < c0) continue;  // the lower triangle only
              long& m = cmark[static_cast<size_t>(q)];
              if (m < 0) {
                m = static_cast<long>(ctouched.size());
                ctouched.push_back(q);
                G.resize(G.size() + static_cast<size_t>(w), 0.0);
              }
              double* g = G.data() + m * w;
              for (long j = 0; j < w; ++j) g[j] += qit.value() * y[j];
            }
            mark[static_cast<size_t>(i)] = -1;
          }
          std::vector<long> order(ctouched.size());
          for (size_t k = 0; k < order.size(); ++k) order[k] = static_cast<long>(k);
          std::sort(order.begin(), order.end(), [&](long a, long b) { return ctouched[static_cast<size_t>(a)] < ctouched[static_cast<size_t>(b)]; });
          for (long j = 0; j < w; ++j) {
            Column& col = columns[static_cast<size_t>(c0 + j)];
            for (const long k : order) {
              const long q = ctouched[static_cast<size_t>(k)];
              if (q >= c0 + j) col.rows.push_back(static_cast<int>(q)), col.values.push_back(G[static_cast<size_t>(k * w + j)]);
            }
          }
          for (const long q : ctouched) cmark[static_cast<size_t>(q)] = -1;
        }
      },
      2);
  long nnz = 0;
  for (const auto& c : columns) nnz += static_cast<long>(c.rows.size());
  SparseMatrix L(nc, nc);
  L.resizeNonZeros(nnz);
  long at = 0;
  for (long j = 0; j < nc; ++j) {
    L.outerIndexPtr()[j] = static_cast<int>(at);
    const Column& c = columns[static_cast<size_t>(j)];
    std::copy(c.rows.begin(), c.rows.end(), L.innerIndexPtr() + at);
    std::copy(c.values.begin(), c.values.end(), L.valuePtr() + at);
    at += static_cast<long>(c.rows.size());
  }
  L.outerIndexPtr()[nc] = static_cast<int>(at);
  return L;
}

namespace {

Eigen::MatrixXd gram_of(const RowBlock& X, const RowBlock& Y, long rows, bool upper, const Eigen::VectorXd* weights) {
  if (X.rows() != Y.rows()) throw std::invalid_argument("gram: blocks of different lengths");
  if (upper && X.cols() != Y.cols()) throw std::invalid_argument("gram_symmetric: blocks of different widths");
  const long m = rows < 0 ? static_cast<long>(X.rows()) : std::min<long>(rows, X.rows());
  if (weights && weights->size() < m) throw std::invalid_argument("gram: fewer weights than rows");
  const long p = X.cols(), q = Y.cols();
  Eigen::MatrixXd G = Eigen::MatrixXd::Zero(p, q);
  if (m == 0 || p == 0 || q == 0) return G;
  // Split by rows, a row-major partial G per part, the parts added in order: the
  // same bits on every run.
  const GramArgs args{X.data(), weights ? weights->data() : nullptr, Y.data(), p, q, upper};
  const long q8 = gram_padded(q);
  std::vector<std::vector<double>> partial(static_cast<size_t>(worker_threads()));
  const long parts = parallel_parts(
      m,
      [&](long t, long begin, long end) {
        std::vector<double>& g = partial[static_cast<size_t>(t)];
        g.assign(static_cast<size_t>(p * q8), 0.0);
        std::vector<double> buf(static_cast<size_t>(gram_chunk(p, q8) * (p + q8)));
        kernels().gram_double(args, begin, end, g.data(), buf.data());
      },
      kSplitRows * worker_threads());
  for (long t = 0; t < parts; ++t) {
    const std::vector<double>& g = partial[static_cast<size_t>(t)];
    if (g.empty()) continue;  // a part with no rows
    for (long i = 0; i < p; ++i)
      for (long j = upper ? i : 0; j < q; ++j) G(i, j) += g[static_cast<size_t>(i * q8 + j)];
  }
  if (upper)
    for (long j = 0; j < q; ++j)
      for (long i = j + 1; i < p; ++i) G(i, j) = G(j, i);
  return G;
}

}  // namespace

Eigen::MatrixXd gram(const RowBlock& X, const RowBlock& Y, long rows) { return gram_of(X, Y, rows, false, nullptr); }

Eigen::MatrixXd gram_symmetric(const RowBlock& X, const RowBlock& Y, long rows) {
  return gram_of(X, Y, rows, true, nullptr);
}

Eigen::MatrixXd gram_weighted(const RowBlock& X, const Eigen::VectorXd& d, const RowBlock& Y, long rows) {
  return gram_of(X, Y, rows, false, &d);
}

Eigen::MatrixXd gram_weighted_symmetric(const RowBlock& X, const Eigen::VectorXd& d, long rows) {
  return gram_of(X, X, rows, true, &d);
}

void times_dense_sum(const std::vector<const RowBlock*>& blocks, const Eigen::Ref<const Eigen::MatrixXd>& C,
                     double beta, RowBlock& Y) {
  if (blocks.empty()) throw std::invalid_argument("times_dense_sum: no blocks");
  const long n = blocks.front()->rows(), q = C.cols();
  DenseArgs args{};
  long k = 0;
  for (const RowBlock* B : blocks) {
    if (B->rows() != n) throw std::invalid_argument("times_dense_sum: blocks of different lengths");
    if (B->data() == Y.data() && B->size() > 0) throw std::invalid_argument("times_dense_sum: Y is one of the blocks");
    k += B->cols();
    if (B->cols() == 0) continue;
    if (args.sources == DenseArgs::kMaxSources) throw std::invalid_argument("times_dense_sum: more than four blocks");
    args.src[args.sources] = B->data();
    args.cols[args.sources] = B->cols();
    ++args.sources;
  }
  if (k != C.rows()) throw std::invalid_argument("times_dense_sum: shapes do not agree");
  if (beta == 0.0) resize_block(Y, n, q);
  else if (Y.rows() != n || Y.cols() != q) throw std::invalid_argument("times_dense_sum: Y's shape");
  if (Y.size() == 0) return;
  if (args.sources == 0) {  // an empty sum
    if (beta == 0.0) Y.setZero();
    else Y *= beta;
    return;
  }
  const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> Cr = C;
  args.c = Cr.data();
  args.y = Y.data();
  args.q = q;
  args.beta = beta;
  parallel_for(n, [&args](long begin, long end) { kernels().dense_double(args, begin, end); });
}

void times_dense_into(const RowBlock& X, const Eigen::Ref<const Eigen::MatrixXd>& C, double beta, RowBlock& Y) {
  if (X.cols() != C.rows()) throw std::invalid_argument("times_dense_into: shapes do not agree");
  times_dense_sum({&X}, C, beta, Y);
}

}  // namespace ssid::estimator::multilevel
