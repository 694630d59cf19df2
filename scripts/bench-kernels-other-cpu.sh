#!/usr/bin/env bash
# The multilevel eigen-solver's kernels and the 94k-DOF lattice on another machine
# (issue 25: speed that travels across instruction sets and CPU models), in at most
# about 8 minutes on 16 cores: configures and builds bench_kernels and bench_eigen
# only (Release), then prints
#   1. the machine (lscpu, memory, compiler, the BLAS libblas.so.3 points to);
#   2. bench_kernels 25 --isa: every kernel version this CPU supports (generic,
#      avx2, avx512), repetition by repetition, with the system BLAS's dgemm for the
#      dense products (GFlop/s, and each version's speed as a multiple of BLAS's);
#   3. bench_eigen 25 (93 750 DOF, 41 modes): the multilevel method with each
#      supported kernel version, the direct method (CHOLMOD + block Lanczos), and
#      Auto (its choice and the reason), alternated twice.
# Every step has a time limit so that the whole stays within the budget; a step
# cut short says so ("timed out").
#
# Usage: scripts/bench-kernels-other-cpu.sh [BUILD_DIR]   (default build-bench)
# Environment: SSID_JOBS (build jobs, default 16).
# Exit status: 0 when everything ran, 2 when the build failed.
set -uo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build-bench}
jobs=${SSID_JOBS:-16}
t_start=$(date +%s)
elapsed() { echo $(($(date +%s) - t_start)); }
# Runs a step under a limit of at most $1 seconds, and never past 470 s from the start.
step() {
  local limit=$1
  shift
  local left=$((470 - $(elapsed)))
  ((left < limit)) && limit=$left
  if ((limit < 5)); then
    echo "== skipped (time budget spent): $*"
    return
  fi
  echo "== $* (limit ${limit} s, at $(elapsed) s)"
  timeout "$limit" "$@"
  local rc=$?
  ((rc == 124)) && echo "== timed out after ${limit} s: $*"
}

echo "== machine"
lscpu
free -g | head -2
c++ --version | head -1
echo "libblas.so.3 -> $(readlink -f /usr/lib/x86_64-linux-gnu/libblas.so.3 2>/dev/null || echo '?')"
env | grep -E '^OPENBLAS_' || true

echo "== build (Release, -j$jobs: bench_kernels bench_eigen)"
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
generator=()
command -v ninja >/dev/null && generator=(-G Ninja)
cmake -S "$root" -B "$build" "${generator[@]}" -DCMAKE_BUILD_TYPE=Release -DSSID_BUILD_TESTS=OFF \
  "${launcher[@]}" >/dev/null || exit 2
cmake --build "$build" -j"$jobs" --target bench_kernels bench_eigen >/dev/null || exit 2
echo "built in $(elapsed) s"

echo "== kernels"
kernels_out=$(mktemp)
step 120 "$build/bench/bench_kernels" 25 --isa --reps 7 | tee "$kernels_out"
isas=$(sed -n 's/^kernel versions this CPU supports: \(.*\) (a plain.*/\1/p' "$kernels_out")
rm -f "$kernels_out"
echo "supported kernel versions: ${isas:-?}"

echo "== bench_eigen 25 (93 750 DOF, 41 modes), alternated"
for round in 1 2; do
  for isa in $isas; do
    [ "$isa" = generic ] && continue
    step 60 env SSID_KERNEL_ISA="$isa" "$build/bench/bench_eigen" 25 --method multilevel
  done
  step 90 "$build/bench/bench_eigen" 25 --method direct
  step 90 "$build/bench/bench_eigen" 25
done
echo "== done in $(elapsed) s"
