// Hidden-face removal: one quad per visible unit face.

#include <sylva/core/assert.hpp>

#include "mesher_impl.hpp"

namespace sylva::voxel::detail {
namespace {

class CulledMesher final : public Mesher {
 public:
  explicit CulledMesher(const MesherOptions& options) : options_(options) {}
  MesherKind kind() const override { return MesherKind::kCulled; }

  void mesh(const PaddedBlocks& blocks, const BlockPalette& palette, ChunkMesh& out) override {
    SYLVA_ASSERT(blocks.n >= 1 && blocks.n <= 64, "chunk size {}", blocks.n);
    out.clear();
    const int n = blocks.n;
    const AoSampler ao(blocks, palette.opaque_table(), options_.ambient_occlusion);
    const std::uint8_t* opaque = palette.opaque_table().data();
    const std::uint8_t* render = palette.render_table().data();
    const BlockId* ids = blocks.ids.data();
    for (int y = 0; y < n; ++y) {
      for (int z = 0; z < n; ++z) {
        for (int x = 0; x < n; ++x) {
          const int idx = ao.index(x, y, z);
          const BlockId self = ids[idx];
          if (self == kAir) continue;
          const bool alpha = render[self] == static_cast<std::uint8_t>(RenderClass::kAlphaCut);
          const bool cull_same = alpha && palette.culls_same(self);
          const bool sides_only = palette.sides_only(self);
          for (int f = 0; f < 6; ++f) {
            if (sides_only && face_axis(f) == 1) continue;
            const BlockId nb = ids[idx + ao.front_offset(f)];
            if (opaque[nb] || (cull_same && nb == self)) continue;
            const PackedQuad q{pack_word0(x, y, z, 1, 1), pack_word1(self, f, ao.face_bits(idx, f))};
            (alpha ? out.alpha_cut : out.opaque).push_back(q);
          }
        }
      }
    }
  }

 private:
  MesherOptions options_;
};

}  // namespace

std::unique_ptr<Mesher> make_culled_mesher(const MesherOptions& options) { return std::make_unique<CulledMesher>(options); }

}  // namespace sylva::voxel::detail
