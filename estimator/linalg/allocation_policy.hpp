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
/// suits a one-job command.
///
/// One arena for every thread (M_ARENA_MAX = 1): memory freed by one thread is then
/// reused by the next allocation of any other. Why: with glibc's secondary arenas,
/// the threaded setup's products (the prolongator) lived in arenas the solver's
/// own thread never allocates from, so memory handed back before LOBPCG was not
/// reused and its blocks touched fresh pages; the 94k lattice, alternated: peak RSS
/// 726 -> 705 MiB and 6.2-6.4 -> 5.4 s (docs/performance.md). The threads allocate
/// little inside their loops, so the one lock is not contended.
namespace ssid::estimator {

/// Serve large allocations from the heap, keep freed memory there and share one
/// heap among threads (glibc: mallopt M_MMAP_MAX = 0, the largest
/// M_TRIM_THRESHOLD, M_ARENA_MAX = 1). Returns false where the C library has no
/// such setting (nothing changed) or one of them failed (those before it stay).
bool keep_freed_memory();

/// Runs the program again, at once, with glibc's malloc asked to advise
/// transparent huge pages for all its memory (GLIBC_TUNABLES=glibc.malloc.hugetlb=1,
/// a setting glibc reads only when a process starts, hence the re-execution of
/// /proc/self/exe with the same arguments). Does nothing and returns false when
/// GLIBC_TUNABLES is already set (the caller's own tunables win, and the re-executed
/// program finds it set), when SSID_HUGE_PAGE_HEAP=0, outside Linux with glibc,
/// when the program was started through the dynamic loader by hand or runs in
/// secure-execution mode (setuid, capabilities), or when the re-execution fails;
/// otherwise it does not return. Call it first thing in main, before any thread or
/// output. Under valgrind or a debugger, set SSID_HUGE_PAGE_HEAP=0: the tool would
/// otherwise follow (or not) an exec it did not expect.
///
/// Why: on the virtual machines measured, a page fault costs far more than the
/// arithmetic around it, and only blocks of 64 MiB and more get huge pages
/// otherwise (resize_block); the setup's sparse products, the factors and the
/// smaller blocks were faulted in 4 KiB pages. On the 1M-DOF lattice it saved about
/// 5 % with the same peak memory (alternated runs, docs/performance.md). glibc before 2.35 ignores
/// the tunable.
bool restart_with_huge_page_heap(char** argv);

}  // namespace ssid::estimator
