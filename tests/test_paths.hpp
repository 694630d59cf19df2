#pragma once
/// \file test_paths.hpp
/// Where the tests find the source tree, their data and the built `ssid`.
/// Defined once, in a file CMake generates in the build folder (test_paths.cpp),
/// so that no test source is compiled with an absolute path on its command line:
/// a compiler cache then serves the same objects to every checkout.
/// Forced into every test source (`-include`, tests/CMakeLists.txt).

namespace ssid_test {
const char* source_dir();     ///< the repository root
const char* test_data_dir();  ///< tests/data
const char* ssid_exe();       ///< the `ssid` executable of this build
}  // namespace ssid_test

#define SSID_SOURCE_DIR ::ssid_test::source_dir()
#define SSID_TEST_DATA ::ssid_test::test_data_dir()
#define SSID_EXE ::ssid_test::ssid_exe()
