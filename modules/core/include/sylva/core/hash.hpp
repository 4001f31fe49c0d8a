#pragma once
// FNV-1a 64-bit: the content hash of Sylva's caches and file checksums (chunk files, slice
// caches, terrain tree cache). Not cryptographic; chosen for being tiny, stable across platforms
// and byte-order independent as long as callers feed bytes in a fixed order.
#include <cstddef>
#include <cstdint>

namespace sylva {

inline constexpr std::uint64_t kFnv1a64Offset = 0xcbf29ce484222325ull;

// Hash of `bytes` bytes at `data`, continuing from `seed` (pass a previous result to chain).
inline std::uint64_t fnv1a64(const void* data, std::size_t bytes, std::uint64_t seed = kFnv1a64Offset) {
  const auto* p = static_cast<const unsigned char*>(data);
  std::uint64_t h = seed;
  for (std::size_t i = 0; i < bytes; ++i) {
    h ^= p[i];
    h *= 0x100000001b3ull;
  }
  return h;
}

}  // namespace sylva
