# Instrumented builds (docs/fuzzing.md). Included before the layers so that every
# target, libraries included, is built the same way.
#
# SSID_SANITIZE: AddressSanitizer + UndefinedBehaviorSanitizer for the whole build,
#   GCC or clang. A UB report aborts (-fno-sanitize-recover), so a test that
#   triggers one fails.
# SSID_FUZZ: the libFuzzer harnesses of fuzz/ (clang only). Implies the sanitizers;
#   every source gets libFuzzer's coverage instrumentation. scripts/sanitize-tests
#   and scripts/fuzz-smoke share one such tree, build-asan/
#   (scripts/configure-sanitized): the tests run there too.
option(SSID_SANITIZE "Build with AddressSanitizer and UndefinedBehaviorSanitizer" OFF)
option(SSID_FUZZ "Build the libFuzzer harnesses in fuzz/ (clang only)" OFF)

if(SSID_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang")
    message(FATAL_ERROR "SSID_FUZZ needs clang (libFuzzer): configure with -DCMAKE_CXX_COMPILER=clang++ "
                        "-DCMAKE_C_COMPILER=clang (Debian clang, libclang-rt-dev)")
  endif()
  set(SSID_SANITIZE ON CACHE BOOL "" FORCE)
  add_compile_options(-fsanitize=fuzzer-no-link)
endif()

if(SSID_SANITIZE)
  # -O1 keeps the suite's run time bearable and the reports exact; no frame
  # pointer omission so that every report has a full stack. -g1 (line tables and
  # function names, all a report's stack needs) after the build type's -g: full
  # debug information of the Eigen-heavy sources costs a quarter to a third more
  # compile time (GCC, two sources: 50 s against 39 s, 32 s against 20 s).
  set(ssid_sanitize_flags -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer)
  add_compile_options(${ssid_sanitize_flags} -O1 -g1)
  add_link_options(${ssid_sanitize_flags})
endif()
