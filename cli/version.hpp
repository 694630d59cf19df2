#pragma once
/// \file version.hpp
/// The version `ssid --version` prints and every report states.
namespace ssid::cli {
inline constexpr const char* kSsidVersion = "0.1.0";
}  // namespace ssid::cli
