#pragma once
// One chunk's mesh as bytes (the blobs of chunk files and of the bake's share files), and the
// little-endian field access both formats use. Layout: vertex count, index count, 4 edge counts
// (u32 each), then 24-byte vertices (gx, gz u32; height, morph_target, morph_error f32;
// intro_level, outside u8; 2 bytes 0), indices (u32), edge lists (u32).

#include <sylva/terrain/chunk_tree.hpp>

#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>

namespace sylva::terrain::detail {

inline constexpr std::size_t kChunkVertexBytes = 24;
// Offset of morph_error inside a vertex record (the bake patches it once the bounds are known).
inline constexpr std::size_t kMorphErrorOffset = 16;

template <class T>
void put_le(std::string& out, std::size_t at, const T& v) {
  std::memcpy(out.data() + at, &v, sizeof(T));
}
template <class T>
T get_le(const char* in, std::size_t at) {
  T v;
  std::memcpy(&v, in + at, sizeof(T));
  return v;
}

std::string encode_chunk_mesh(const ChunkMesh& mesh);

// Decodes a blob whose checksum was verified; `vertices`/`indices` are the directory's counts.
// Returns "" on success, else what is wrong (counts not matching the size, indices out of range).
std::string decode_chunk_mesh(std::string_view blob, std::uint32_t vertices, std::uint32_t indices, ChunkMesh& out);

}  // namespace sylva::terrain::detail
