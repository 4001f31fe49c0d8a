// Greedy meshing (Lysenko 2012): per face direction and slice, a 2D mask of face keys
// (block, face, AO) is swept row by row; each unvisited face grows right while the key repeats,
// then down while the whole run repeats. Faces with non-uniform AO stay unit quads.

#include <sylva/core/assert.hpp>

#include "mesher_impl.hpp"

namespace sylva::voxel::detail {
namespace {

class GreedyMesher final : public Mesher {
 public:
  explicit GreedyMesher(const MesherOptions& options) : options_(options) {}
  MesherKind kind() const override { return MesherKind::kGreedy; }

  void mesh(const PaddedBlocks& blocks, const BlockPalette& palette, ChunkMesh& out) override {
    SYLVA_ASSERT(blocks.n >= 1 && blocks.n <= 64, "chunk size {}", blocks.n);
    out.clear();
    const int n = blocks.n;
    mask_.assign(static_cast<std::size_t>(n * n), 0u);
    const AoSampler ao(blocks, palette.opaque_table(), options_.ambient_occlusion);
    const std::uint8_t* opaque = palette.opaque_table().data();
    const std::uint8_t* render = palette.render_table().data();
    const BlockId* ids = blocks.ids.data();
    const auto alpha_class = static_cast<std::uint8_t>(RenderClass::kAlphaCut);

    for (int f = 0; f < 6; ++f) {
      const int a = f >> 1;
      const int u = (a + 1) % 3;
      const int v = (a + 2) % 3;
      for (int d = 0; d < n; ++d) {
        // 1. Face keys of this slice: word1 of the unit quad, 0 where no face is visible.
        for (int j = 0; j < n; ++j) {
          for (int i = 0; i < n; ++i) {
            int p[3];
            p[a] = d;
            p[u] = i;
            p[v] = j;
            const int idx = ao.index(p[0], p[1], p[2]);
            const BlockId self = ids[idx];
            std::uint32_t key = 0;
            if (self != kAir && !(a == 1 && palette.sides_only(self))) {
              const BlockId nb = ids[idx + ao.front_offset(f)];
              const bool cull_same = render[self] == alpha_class && palette.culls_same(self);
              if (!opaque[nb] && !(cull_same && nb == self)) key = pack_word1(self, f, ao.face_bits(idx, f));
            }
            mask_[static_cast<std::size_t>(j * n + i)] = key;
          }
        }
        // 2. Sweep into maximal rectangles.
        for (int j = 0; j < n; ++j) {
          for (int i = 0; i < n;) {
            const std::uint32_t key = mask_[static_cast<std::size_t>(j * n + i)];
            if (key == 0) {
              ++i;
              continue;
            }
            int w = 1;
            int h = 1;
            if (ao_uniform(key >> 19)) {
              while (i + w < n && mask_[static_cast<std::size_t>(j * n + i + w)] == key) ++w;
              bool grow = true;
              while (grow && j + h < n) {
                for (int k = 0; k < w; ++k) {
                  if (mask_[static_cast<std::size_t>((j + h) * n + i + k)] != key) {
                    grow = false;
                    break;
                  }
                }
                if (grow) ++h;
              }
            }
            for (int jj = 0; jj < h; ++jj) {
              for (int ii = 0; ii < w; ++ii) mask_[static_cast<std::size_t>((j + jj) * n + i + ii)] = 0;
            }
            int p[3];
            p[a] = d;
            p[u] = i;
            p[v] = j;
            const PackedQuad q{pack_word0(p[0], p[1], p[2], w, h), key};
            const auto block = static_cast<BlockId>(key & 0xffffu);
            (render[block] == alpha_class ? out.alpha_cut : out.opaque).push_back(q);
            i += w;
          }
        }
      }
    }
  }

 private:
  MesherOptions options_;
  std::vector<std::uint32_t> mask_;
};

}  // namespace

std::unique_ptr<Mesher> make_greedy_mesher(const MesherOptions& options) { return std::make_unique<GreedyMesher>(options); }

}  // namespace sylva::voxel::detail
