#pragma once
/// \file arena.hpp
/// A bump allocator for the deck's field texts and field lists. A million-card
/// deck would otherwise spend most of its time and memory in small heap
/// allocations; the arena keeps about 10 bytes per field and frees all at once.
#include <cstddef>
#include <memory>
#include <new>
#include <string_view>
#include <type_traits>
#include <vector>

namespace ssid::formats {

class Arena {
public:
  Arena() = default;
  Arena(const Arena&) = delete;
  Arena& operator=(const Arena&) = delete;

  void* allocate(std::size_t bytes, std::size_t align) {
    std::size_t pad = (align - reinterpret_cast<std::uintptr_t>(m_ptr) % align) % align;
    if (bytes + pad > m_left) {
      std::size_t size = std::max(bytes + align, kBlock);
      m_blocks.emplace_back(new std::byte[size]);
      m_ptr = m_blocks.back().get();
      m_left = size;
      pad = (align - reinterpret_cast<std::uintptr_t>(m_ptr) % align) % align;
    }
    std::byte* p = m_ptr + pad;
    m_ptr = p + bytes;
    m_left -= bytes + pad;
    return p;
  }

  /// An array of n default-constructed T; T must be trivially destructible.
  template <typename T>
  T* make_array(std::size_t n) {
    static_assert(std::is_trivially_destructible_v<T>, "Arena holds trivially destructible types only");
    if (n == 0) return nullptr;
    T* p = static_cast<T*>(allocate(sizeof(T) * n, alignof(T)));
    for (std::size_t i = 0; i < n; ++i) new (p + i) T();
    return p;
  }

  std::string_view copy(std::string_view s) {
    if (s.empty()) return {};
    char* p = static_cast<char*>(allocate(s.size(), 1));
    for (std::size_t i = 0; i < s.size(); ++i) p[i] = s[i];
    return {p, s.size()};
  }

  /// Copy in upper case (NASTRAN is case-insensitive; ASCII only).
  std::string_view copy_upper(std::string_view s) {
    if (s.empty()) return {};
    char* p = static_cast<char*>(allocate(s.size(), 1));
    for (std::size_t i = 0; i < s.size(); ++i) {
      char c = s[i];
      p[i] = (c >= 'a' && c <= 'z') ? static_cast<char>(c - 32) : c;
    }
    return {p, s.size()};
  }

private:
  static constexpr std::size_t kBlock = 1 << 20;
  std::vector<std::unique_ptr<std::byte[]>> m_blocks;
  std::byte* m_ptr = nullptr;
  std::size_t m_left = 0;
};

}  // namespace ssid::formats
