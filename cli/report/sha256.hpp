#pragma once
/// \file sha256.hpp
/// SHA-256 (FIPS 180-4) of a file, for the report's list of inputs: the same
/// digest `sha256sum FILE` prints, so a reader can check which files a report saw.
#include <string>

namespace ssid::cli::report {

/// Lower-case hex digest of the file's bytes. Throws formats::InputError when
/// the file cannot be read.
std::string sha256_file(const std::string& path);
/// Lower-case hex digest of `bytes`.
std::string sha256(const std::string& bytes);

}  // namespace ssid::cli::report
