#include <sylva/voxel/mesher.hpp>

#include <sylva/core/assert.hpp>

#include "mesher_impl.hpp"

#include <fmt/format.h>

namespace sylva::voxel {

PaddedBlocks::PaddedBlocks(int size, BlockId fill) : n(size) {
  SYLVA_ASSERT(size >= 1 && size <= 64, "padded chunk size {} outside [1, 64]", size);
  const auto p = static_cast<std::size_t>(size + 2);
  ids.assign(p * p * p, fill);
}

PackedQuad pack_quad(const Quad& q) {
  SYLVA_ASSERT(q.x >= 0 && q.x < 64 && q.y >= 0 && q.y < 64 && q.z >= 0 && q.z < 64, "quad origin ({}, {}, {})", q.x,
               q.y, q.z);
  SYLVA_ASSERT(q.du >= 1 && q.du <= 64 && q.dv >= 1 && q.dv <= 64, "quad size {}x{}", q.du, q.dv);
  SYLVA_ASSERT(q.face >= 0 && q.face < 6, "quad face {}", q.face);
  PackedQuad p;
  p.word0 = static_cast<std::uint32_t>(q.x) | static_cast<std::uint32_t>(q.y) << 6 |
            static_cast<std::uint32_t>(q.z) << 12 | static_cast<std::uint32_t>(q.du - 1) << 18 |
            static_cast<std::uint32_t>(q.dv - 1) << 24;
  p.word1 = detail::pack_word1(q.block, q.face, detail::pack_ao(q.ao));
  return p;
}

Quad unpack_quad(const PackedQuad& p) {
  Quad q;
  q.x = static_cast<int>(p.word0 & 63u);
  q.y = static_cast<int>((p.word0 >> 6) & 63u);
  q.z = static_cast<int>((p.word0 >> 12) & 63u);
  q.du = static_cast<int>((p.word0 >> 18) & 63u) + 1;
  q.dv = static_cast<int>((p.word0 >> 24) & 63u) + 1;
  q.block = static_cast<BlockId>(p.word1 & 0xffffu);
  q.face = static_cast<int>((p.word1 >> 16) & 7u);
  for (int i = 0; i < 4; ++i) q.ao[i] = static_cast<std::uint8_t>((p.word1 >> (19 + 2 * i)) & 3u);
  return q;
}

std::string_view to_string(MesherKind kind) {
  switch (kind) {
    case MesherKind::kCulled: return "culled";
    case MesherKind::kGreedy: return "greedy";
    case MesherKind::kBitmask: return "bitmask";
  }
  return "?";
}

Result<MesherKind> parse_mesher_kind(std::string_view name) {
  for (auto k : {MesherKind::kCulled, MesherKind::kGreedy, MesherKind::kBitmask}) {
    if (to_string(k) == name) return k;
  }
  return make_error(ErrorCode::kInvalidArgument,
                    fmt::format("voxel.mesher: '{}' is not one of culled, greedy, bitmask", name));
}

bool face_visible(BlockId self, BlockId neighbour, int face, const BlockPalette& palette) {
  if (self == kAir || palette.is_opaque(neighbour)) return false;
  if (face_axis(face) == 1 && palette.sides_only(self)) return false;
  if (self == neighbour && palette.render(self) == RenderClass::kAlphaCut && palette.culls_same(self)) return false;
  return true;
}

void face_ao(const PaddedBlocks& blocks, const BlockPalette& palette, int x, int y, int z, int face,
             std::uint8_t out[4]) {
  detail::AoSampler sampler(blocks, palette.opaque_table());
  sampler.face(x, y, z, face, out);
}

std::unique_ptr<Mesher> make_mesher(MesherKind kind, const MesherOptions& options) {
  switch (kind) {
    case MesherKind::kCulled: return detail::make_culled_mesher(options);
    case MesherKind::kGreedy: return detail::make_greedy_mesher(options);
    case MesherKind::kBitmask: return detail::make_bitmask_mesher(options);
  }
  SYLVA_ASSERT(false, "unknown mesher kind {}", static_cast<int>(kind));
  return nullptr;
}

}  // namespace sylva::voxel
