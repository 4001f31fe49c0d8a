#include "chunk_blob.hpp"

#include <fmt/format.h>

namespace sylva::terrain::detail {

std::string encode_chunk_mesh(const ChunkMesh& m) {
  std::size_t edge_total = 0;
  for (const auto& e : m.edges) edge_total += e.size();
  std::string out(24 + m.vertices.size() * kChunkVertexBytes + (m.indices.size() + edge_total) * 4, '\0');
  std::size_t at = 0;
  put_le(out, at, static_cast<std::uint32_t>(m.vertices.size()));
  put_le(out, at + 4, static_cast<std::uint32_t>(m.indices.size()));
  for (std::size_t e = 0; e < 4; ++e) put_le(out, at + 8 + 4 * e, static_cast<std::uint32_t>(m.edges[e].size()));
  at = 24;
  for (const ChunkVertex& v : m.vertices) {
    put_le(out, at, v.gx);
    put_le(out, at + 4, v.gz);
    put_le(out, at + 8, v.height);
    put_le(out, at + 12, v.morph_target);
    put_le(out, at + kMorphErrorOffset, v.morph_error);
    put_le(out, at + 20, v.intro_level);
    put_le(out, at + 21, v.outside);
    at += kChunkVertexBytes;
  }
  std::memcpy(out.data() + at, m.indices.data(), m.indices.size() * 4);
  at += m.indices.size() * 4;
  for (const auto& e : m.edges) {
    std::memcpy(out.data() + at, e.data(), e.size() * 4);
    at += e.size() * 4;
  }
  return out;
}

std::string decode_chunk_mesh(std::string_view blob, std::uint32_t vertices, std::uint32_t indices, ChunkMesh& m) {
  if (blob.size() < 24) return "shorter than its 24-byte header";
  const auto nv = get_le<std::uint32_t>(blob.data(), 0), ni = get_le<std::uint32_t>(blob.data(), 4);
  std::uint64_t edge_total = 0;
  std::uint32_t ne[4];
  for (std::size_t q = 0; q < 4; ++q) {
    ne[q] = get_le<std::uint32_t>(blob.data(), 8 + 4 * q);
    edge_total += ne[q];
  }
  if (24 + static_cast<std::uint64_t>(nv) * kChunkVertexBytes + (static_cast<std::uint64_t>(ni) + edge_total) * 4 !=
          blob.size() ||
      nv != vertices || ni != indices) {
    return "its counts do not match its size";
  }
  m.vertices.resize(nv);
  std::size_t at = 24;
  for (ChunkVertex& v : m.vertices) {
    v.gx = get_le<std::uint32_t>(blob.data(), at);
    v.gz = get_le<std::uint32_t>(blob.data(), at + 4);
    v.height = get_le<float>(blob.data(), at + 8);
    v.morph_target = get_le<float>(blob.data(), at + 12);
    v.morph_error = get_le<float>(blob.data(), at + kMorphErrorOffset);
    v.intro_level = get_le<std::uint8_t>(blob.data(), at + 20);
    v.outside = get_le<std::uint8_t>(blob.data(), at + 21);
    at += kChunkVertexBytes;
  }
  m.indices.resize(ni);
  std::memcpy(m.indices.data(), blob.data() + at, static_cast<std::size_t>(ni) * 4);
  at += static_cast<std::size_t>(ni) * 4;
  for (std::size_t q = 0; q < 4; ++q) {
    m.edges[q].resize(ne[q]);
    std::memcpy(m.edges[q].data(), blob.data() + at, static_cast<std::size_t>(ne[q]) * 4);
    at += static_cast<std::size_t>(ne[q]) * 4;
  }
  for (std::uint32_t i : m.indices)
    if (i >= nv) return fmt::format("index {} beyond its {} vertices", i, nv);
  for (const auto& edge : m.edges)
    for (std::uint32_t i : edge)
      if (i >= nv) return fmt::format("edge vertex {} beyond its {} vertices", i, nv);
  return {};
}

}  // namespace sylva::terrain::detail
