// Binary greedy meshing. Occupancy is kept as 64-bit column masks along x (one per padded (y, z)
// row) and along y (one per padded (x, z) column). For a face direction and slice, each row of
// visible faces is a single expression, e.g. +Y at height s, row z:
//     faces = nonair_x[s][z] & ~opaque_x[s + 1][z]
// so visibility of 64 faces costs one AND-NOT and no neighbour lookups. Visible faces are then
// bucketed by key (block, AO) into per-slice bit planes, and each plane is merged into rectangles
// with count-trailing-zeros / count-trailing-ones on its rows.
//
// The public binary greedy mesher (cgerikj/binary-greedy-meshing) uses 62^3 chunks so its padded
// columns fit in 64 bits; here columns hold only the n <= 64 interior bits and the padding comes
// from neighbouring rows, so 64^3 chunks work too.

#include <sylva/core/assert.hpp>

#include "mesher_impl.hpp"

#include <algorithm>
#include <bit>

namespace sylva::voxel::detail {
namespace {

class BitmaskMesher final : public Mesher {
 public:
  MesherKind kind() const override { return MesherKind::kBitmask; }

  void mesh(const PaddedBlocks& blocks, const BlockPalette& palette, ChunkMesh& out) override {
    SYLVA_ASSERT(blocks.n >= 1 && blocks.n <= 64, "chunk size {}", blocks.n);
    out.clear();
    n_ = blocks.n;
    build_masks(blocks, palette);
    const AoSampler ao(blocks, palette.opaque_table());
    const std::uint8_t* render = palette.render_table().data();
    const BlockId* ids = blocks.ids.data();
    const int n = n_;
    const int p = n + 2;
    const auto alpha_class = static_cast<std::uint8_t>(RenderClass::kAlphaCut);

    for (int f = 0; f < 6; ++f) {
      const int front = ao.front_offset(f);
      for (int s = 0; s < n; ++s) {
        slot_count_ = 0;
        int last_slot = -1;
        for (int r = 0; r < n; ++r) {
          std::uint64_t faces = 0;
          switch (f) {
            case 0: faces = ay_[(s + 1) * p + r + 1] & ~oy_[(s + 2) * p + r + 1]; break;
            case 1: faces = ay_[(s + 1) * p + r + 1] & ~oy_[s * p + r + 1]; break;
            case 2: faces = ax_[(s + 1) * p + r + 1] & ~ox_[(s + 2) * p + r + 1]; break;
            case 3: faces = ax_[(s + 1) * p + r + 1] & ~ox_[s * p + r + 1]; break;
            case 4: faces = ax_[(r + 1) * p + s + 1] & ~ox_[(r + 1) * p + s + 2]; break;
            default: faces = ax_[(r + 1) * p + s + 1] & ~ox_[(r + 1) * p + s]; break;
          }
          while (faces) {
            const int b = std::countr_zero(faces);
            faces &= faces - 1;
            int x, y, z;
            origin(f, s, r, b, x, y, z);
            const int idx = ao.index(x, y, z);
            const BlockId self = ids[idx];
            const bool alpha = render[self] == alpha_class;
            if (alpha && ids[idx + front] == self && palette.culls_same(self)) continue;
            const std::uint32_t aob = ao.face_bits(idx, f);
            const std::uint32_t key = pack_word1(self, f, aob);
            if (!ao_uniform(aob)) {
              (alpha ? out.alpha_cut : out.opaque).push_back(PackedQuad{pack_word0(x, y, z, 1, 1), key});
              continue;
            }
            if (last_slot < 0 || keys_[static_cast<std::size_t>(last_slot)] != key) last_slot = find_slot(key);
            rows_[static_cast<std::size_t>(last_slot) * 64 + static_cast<std::size_t>(r)] |= std::uint64_t{1} << b;
          }
        }
        for (int k = 0; k < slot_count_; ++k) merge_slot(k, f, s, render, out);
      }
    }
  }

 private:
  void build_masks(const PaddedBlocks& blocks, const BlockPalette& palette) {
    const int n = n_;
    const int p = n + 2;
    const auto pp = static_cast<std::size_t>(p * p);
    ax_.assign(pp, 0);
    ox_.assign(pp, 0);
    ay_.assign(pp, 0);
    oy_.assign(pp, 0);
    const std::uint8_t* opaque = palette.opaque_table().data();
    const BlockId* ids = blocks.ids.data();
    for (int yy = 0; yy < p; ++yy) {
      const int y = yy - 1;
      const bool y_inside = y >= 0 && y < n;
      for (int zz = 0; zz < p; ++zz) {
        const BlockId* row = ids + static_cast<std::ptrdiff_t>(zz + p * yy) * p;
        std::uint64_t a = 0;
        std::uint64_t o = 0;
        for (int x = 0; x < n; ++x) {
          const BlockId id = row[x + 1];
          a |= static_cast<std::uint64_t>(id != kAir) << x;
          o |= static_cast<std::uint64_t>(opaque[id]) << x;
        }
        ax_[static_cast<std::size_t>(yy * p + zz)] = a;
        ox_[static_cast<std::size_t>(yy * p + zz)] = o;
        if (y_inside) {
          for (int xx = 0; xx < p; ++xx) {
            const BlockId id = row[xx];
            ay_[static_cast<std::size_t>(xx * p + zz)] |= static_cast<std::uint64_t>(id != kAir) << y;
            oy_[static_cast<std::size_t>(xx * p + zz)] |= static_cast<std::uint64_t>(opaque[id]) << y;
          }
        }
      }
    }
  }

  // Block coordinates of bit b in row r of slice s for face f (see the face-row table above).
  static void origin(int f, int s, int r, int b, int& x, int& y, int& z) {
    switch (f >> 1) {
      case 0: x = s; y = b; z = r; break;
      case 1: x = b; y = s; z = r; break;
      default: x = b; y = r; z = s; break;
    }
  }

  int find_slot(std::uint32_t key) {
    for (int k = 0; k < slot_count_; ++k) {
      if (keys_[static_cast<std::size_t>(k)] == key) return k;
    }
    const int k = slot_count_++;
    if (keys_.size() < static_cast<std::size_t>(slot_count_)) {
      keys_.resize(static_cast<std::size_t>(slot_count_));
      rows_.resize(static_cast<std::size_t>(slot_count_) * 64, 0);
    }
    keys_[static_cast<std::size_t>(k)] = key;
    return k;
  }

  void merge_slot(int k, int f, int s, const std::uint8_t* render, ChunkMesh& out) {
    const int n = n_;
    std::uint64_t* rows = rows_.data() + static_cast<std::size_t>(k) * 64;
    const std::uint32_t key = keys_[static_cast<std::size_t>(k)];
    const auto block = static_cast<BlockId>(key & 0xffffu);
    auto& list = render[block] == static_cast<std::uint8_t>(RenderClass::kAlphaCut) ? out.alpha_cut : out.opaque;
    const bool rows_are_u = (f >> 1) == 1;  // +-Y: rows run along u (z), bits along v (x)
    for (int r = 0; r < n; ++r) {
      while (rows[r]) {
        const int b = std::countr_zero(rows[r]);
        const int w = std::countr_one(rows[r] >> b);
        const std::uint64_t run = (w == 64 ? ~std::uint64_t{0} : ((std::uint64_t{1} << w) - 1)) << b;
        rows[r] &= ~run;
        int h = 1;
        while (r + h < n && (rows[r + h] & run) == run) {
          rows[r + h] &= ~run;
          ++h;
        }
        int x, y, z;
        origin(f, s, r, b, x, y, z);
        const int du = rows_are_u ? h : w;
        const int dv = rows_are_u ? w : h;
        list.push_back(PackedQuad{pack_word0(x, y, z, du, dv), key});
      }
    }
  }

  int n_ = 0;
  std::vector<std::uint64_t> ax_, ox_, ay_, oy_;
  std::vector<std::uint32_t> keys_;
  std::vector<std::uint64_t> rows_;
  int slot_count_ = 0;
};

}  // namespace

std::unique_ptr<Mesher> make_bitmask_mesher() { return std::make_unique<BitmaskMesher>(); }

}  // namespace sylva::voxel::detail
