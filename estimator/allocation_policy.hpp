#pragma once
/// \file allocation_policy.hpp
/// An opt-in allocator setting for programs that solve large models: the library
/// itself never changes process-wide state; `ssid` and the benchmarks call this
/// once at start.
///
/// Why: the multilevel eigen-solver's blocks are hundreds of megabytes at a
/// million DOFs (1M x 45 doubles = 360 MB) and change width as its modes converge.
/// glibc serves every block above 32 MB with its own mmap and returns it to the
/// kernel when freed, so each new block is page-faulted and zeroed by the kernel
/// again: 8 % of the CPU time of the 1M-DOF solve went to the kernel's page
/// clearing (perf), and keeping freed memory in the heap took the solve from 168 s
/// to 158 s (docs/performance.md). The price: the process gives little memory back
/// to the system before it exits (only a free top of the heap above 2 GiB, the
/// largest trim threshold glibc takes; peak RSS 11.6 -> 12.2 GiB there), which
/// suits a one-job command. Allocations in threads other than the main one may
/// still be mapped on their own (glibc's secondary arenas); the solver allocates its
/// blocks in the calling thread.
namespace ssid::estimator {

/// Serve large allocations from the heap and keep freed memory there (glibc:
/// mallopt M_MMAP_MAX = 0 and the largest M_TRIM_THRESHOLD). Returns false where
/// the C library has no such setting (nothing changed).
bool keep_freed_memory();

}  // namespace ssid::estimator
