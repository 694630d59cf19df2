#pragma once
/// \file block_ops.hpp
/// Kernels of the multilevel eigen-solver on blocks of vectors stored row by row
/// (n x b, row-major: the b values of one DOF side by side).
///
/// Why row-major: the solver's time goes into sparse-matrix times block products
/// (A X with b ≈ 50 columns at a million DOF), threaded by parallel_for. Row by row, each stored entry a_ij
/// of A is read once and updates b contiguous values of Y's row i from X's row j,
/// which vectorises; column by column A would be read b times. The dense products
/// of the Rayleigh–Ritz steps (Gram matrices, block updates) are register-tiled
/// kernels of their own, below.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace ssid::estimator::multilevel {

template <class T>
using RowBlockOf = Eigen::Matrix<T, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
template <class T>
using SparseOf = Eigen::SparseMatrix<T>;  // column-major
template <class T>
using SparseRowOf = Eigen::SparseMatrix<T, Eigen::RowMajor>;
using RowBlock = RowBlockOf<double>;
using SparseMatrix = SparseOf<double>;
using SparseRowMatrix = SparseRowOf<double>;

/// The instruction sets ssid's own kernels (the sparse block products, the
/// block-Jacobi pass, the Gram and block-update products below) have a version of
/// their own for, each register-blocked for its register file: Avx512 (x86-64-v4,
/// 32 registers of 64 bytes), Avx2 (x86-64-v3: AVX2 and FMA, 16 registers of 32
/// bytes) and Generic (the build's target; SSE2 on plain x86-64, 16 registers of 16
/// bytes). Why per instruction set: blocked for AVX-512's 32 registers, the same
/// source compiled for AVX2 kept its sums on the stack, and the multilevel solve
/// of the 94k lattice took 47.5 s instead of 5 (issue 25). The Avx2 and Avx512
/// versions exist in GCC builds for x86-64 Linux only.
enum class KernelIsa { Generic, Avx2, Avx512 };
/// "generic", "avx2", "avx512".
const char* kernel_isa_name(KernelIsa isa);
/// The KernelIsa of a name kernel_isa_name gives; throws formats::InputError
/// naming the accepted ones for any other.
KernelIsa kernel_isa_named(const std::string& name);
/// Whether this build has a version for `isa` and this CPU can run it.
bool kernel_isa_supported(KernelIsa isa);
/// Every supported KernelIsa, narrowest first.
std::vector<KernelIsa> supported_kernel_isas();
/// The version the kernels run: the widest supported one unless set_kernel_isa
/// chose another.
KernelIsa kernel_isa();
/// Makes every kernel run the version for `isa` from now on, process-wide (for
/// benchmarks and tests: comparing the versions on one machine; the CLI and the
/// benchmarks take it from the environment variable SSID_KERNEL_ISA). Throws
/// formats::InputError when !kernel_isa_supported(isa). Not to be called while
/// another thread runs a kernel.
void set_kernel_isa(KernelIsa isa);

/// set_kernel_isa(kernel_isa_named(value)) when the environment variable
/// SSID_KERNEL_ISA is set (and not empty); nothing otherwise. For main() of the
/// CLI and the benchmarks (as restart_with_huge_page_heap), once, before any
/// kernel runs. Throws formats::InputError for an unknown or unsupported value.
void apply_kernel_isa_environment();

/// Y.resize(rows, cols), and when that gave Y new storage of at least 64 MiB, asks
/// the kernel to back it with transparent huge pages (Linux madvise
/// MADV_HUGEPAGE; nothing elsewhere, nothing when the system has them off). Why:
/// on a virtual machine the first touch of a fresh 4 KiB page costs several µs;
/// the 1M-DOF solve spent 0.5-1 s on each new 360 MB block (LOBPCG's start: 3.5 s
/// for four blocks), against one fault per 2 MiB with huge pages. Not below
/// 64 MiB: advising the coarse level's blocks too (8-24 MB, allocated and freed
/// many times) made the 1M start 2.5x slower.
template <class T>
void resize_block(RowBlockOf<T>& Y, long rows, long cols);

/// Runs body(begin, end) over [0, n) split into one contiguous range per hardware
/// thread (serially below `serial_below` items). Plain threads that block when done:
/// an OpenMP runtime's spinning workers had competed with the other threads for the
/// cores (the 64k-DOF lattice solved 27 % faster with passive waiting).
void parallel_for(long n, const std::function<void(long begin, long end)>& body, long serial_below = 4096);
/// The number of parts parallel_for and parallel_parts split into (the hardware
/// threads, at most 64).
long worker_threads();
/// The same split, the body also told its part's index (0 .. parts − 1, ranges in
/// order): partial results stored by part and combined in that order give the same
/// bits on every run. Returns the number of parts (1 when serial).
long parallel_parts(long n, const std::function<void(long part, long begin, long end)>& body,
                    long serial_below = 4096);

// The sparse block products, for T = double and float.
/// Y = A X for a symmetric A in full (both triangles) column-major storage:
/// column i of A is row i. Threaded over rows.
template <class T>
void sym_times(const SparseOf<T>& A, const RowBlockOf<T>& X, RowBlockOf<T>& Y);
/// Y = B − A X (a residual; Y resized, must not be B or X) and Y −= A X: the same
/// product fused with the update, one pass over the blocks instead of two or three.
template <class T>
void sym_residual(const SparseOf<T>& A, const RowBlockOf<T>& X, const RowBlockOf<T>& B, RowBlockOf<T>& Y);
template <class T>
void sym_subtract(const SparseOf<T>& A, const RowBlockOf<T>& X, RowBlockOf<T>& Y);
/// Y = A X for a row-major sparse A (any shape). Threaded over rows.
template <class T>
void times(const SparseRowOf<T>& A, const RowBlockOf<T>& X, RowBlockOf<T>& Y);
/// Y += A X (Y of A X's shape, not X).
template <class T>
void times_add(const SparseRowOf<T>& A, const RowBlockOf<T>& X, RowBlockOf<T>& Y);
/// Y = Aᵀ X for a row-major sparse A (rows(A) = rows(X)): each row i of X is
/// scattered into the rows of Y that row i of A names, threaded over A's rows with
/// one copy of Y per thread, added in order. Why not the column-major A's rows
/// (a gather): each row of X was then read once per stored entry of its row in A,
/// from cache at best (the 1M-DOF restriction, 40 entries a row: 0.21 s at 2.5 GB/s
/// against the 0.08 s of the same product untransposed).
template <class T>
void transpose_times(const SparseRowOf<T>& A, const RowBlockOf<T>& X, RowBlockOf<T>& Y);
/// Grid-point blocks of a block-diagonal D⁻¹: the DOFs of grid point g are
/// dofs[start[g] .. start[g+1]) and their inverse block (k x k, row-major) starts at
/// dinv[dinv_start[g]].
template <class T>
struct GridBlocks {
  const std::vector<long>* start = nullptr;
  const std::vector<long>* dofs = nullptr;
  const std::vector<long>* dinv_start = nullptr;
  const T* dinv = nullptr;
};
/// One fused block-Jacobi pass, grid point by grid point: z = β D⁻¹ res, then
/// d = α d + z (d = z when α = 0; d is resized then) and X += d (X = d when set_x;
/// X is resized then). The smoother's vector updates in one pass over the blocks
/// (as separate block expressions they cost as much as the sparse products).
template <class T>
void block_jacobi_pass(const GridBlocks<T>& blocks, const RowBlockOf<T>& res, double alpha, double beta,
                       RowBlockOf<T>& d, RowBlockOf<T>& X, bool set_x);
/// Y = X in another precision, threaded.
template <class From, class To>
void convert(const RowBlockOf<From>& X, RowBlockOf<To>& Y);

/// A B for column-major sparse matrices, B's columns split over the cores (Eigen's
/// sparse product runs on one: the preconditioner's setup of the 1M-DOF lattice
/// spent 22 s in these products).
SparseMatrix parallel_product(const SparseMatrix& A, const SparseMatrix& B);

/// The lower triangle (diagonal included) of Pᵀ B P, for a symmetric B (both
/// triangles stored) and a P whose columns come in blocks [starts[k], starts[k+1])
/// (a smoothed-aggregation prolongator: the six columns of an aggregate share most
/// of their rows). Prow: P row-major. Each block's B P is gathered once as rows of
/// block width and multiplied by Pᵀ row by row, threaded over blocks: the index
/// work of a general sparse product is paid once per block rather than per column
/// (the 1M lattice's coarse matrix: 9-11 s as two general products).
SparseMatrix galerkin_lower(const SparseMatrix& B, const SparseMatrix& P, const SparseRowMatrix& Prow,
                            const std::vector<long>& starts);

/// Xᵀ Y (b_x x b_y, column-major) over the first `rows` rows (all when negative).
/// The dense kernels here are register-tiled like the sparse ones (column_tiles.hpp,
/// one version per KernelIsa) rather than BLAS calls: on these tall-skinny shapes
/// (a million rows, 45 columns) OpenBLAS packs both operands and ran slower than
/// these kernels on both instruction sets (bench_kernels --isa, which prints both;
/// docs/performance.md).
Eigen::MatrixXd gram(const RowBlock& X, const RowBlock& Y, long rows = -1);
/// Xᵀ Y for a product symmetric in exact arithmetic (Y = S X with S symmetric):
/// about half the work, the upper triangle computed and mirrored. X and Y of equal width.
Eigen::MatrixXd gram_symmetric(const RowBlock& X, const RowBlock& Y, long rows = -1);
/// Xᵀ diag(d) Y over the first `rows` rows (all when negative; d has at least that
/// many values), and Xᵀ diag(d) X (its upper triangle computed and mirrored): the
/// Gram matrices with a diagonal (lumped) mass matrix without forming M Y, X's
/// rows scaled as they are copied into the kernel's buffer. Why: M X, M W and M P
/// were three n x b blocks (a gigabyte of fresh memory at a million DOFs) and
/// three passes an iteration.
Eigen::MatrixXd gram_weighted(const RowBlock& X, const Eigen::VectorXd& d, const RowBlock& Y, long rows = -1);
Eigen::MatrixXd gram_weighted_symmetric(const RowBlock& X, const Eigen::VectorXd& d, long rows = -1);
/// Y = β Y + Σ_s B_s C_s, C split by rows along the blocks (a block of no columns
/// takes no rows), in one pass over the rows: [X W P] C without concatenating.
/// At most four blocks with columns; Y must not be one of them. Y is resized, and
/// its values ignored, when β = 0.
void times_dense_sum(const std::vector<const RowBlock*>& blocks, const Eigen::Ref<const Eigen::MatrixXd>& C,
                     double beta, RowBlock& Y);
/// Y = β Y + X C (X n x k row-major, C k x c); Y is not X. Y is resized, and its
/// values ignored, when β = 0. Reusing Y's storage matters: a fresh n x b block of
/// a million-DOF model is hundreds of megabytes of page faults.
void times_dense_into(const RowBlock& X, const Eigen::Ref<const Eigen::MatrixXd>& C, double beta, RowBlock& Y);

}  // namespace ssid::estimator::multilevel
