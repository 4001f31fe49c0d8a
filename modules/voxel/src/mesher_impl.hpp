#pragma once
// Internal helpers shared by the three meshers (not installed).

#include <sylva/voxel/mesher.hpp>

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

namespace sylva::voxel::detail {

inline std::uint32_t pack_ao(const std::uint8_t ao[4]) {
  return static_cast<std::uint32_t>(ao[0]) | static_cast<std::uint32_t>(ao[1]) << 2 |
         static_cast<std::uint32_t>(ao[2]) << 4 | static_cast<std::uint32_t>(ao[3]) << 6;
}
inline std::uint32_t pack_word1(BlockId block, int face, std::uint32_t ao_bits) {
  return static_cast<std::uint32_t>(block) | static_cast<std::uint32_t>(face) << 16 | ao_bits << 19;
}
inline std::uint32_t pack_word0(int x, int y, int z, int du, int dv) {
  return static_cast<std::uint32_t>(x) | static_cast<std::uint32_t>(y) << 6 | static_cast<std::uint32_t>(z) << 12 |
         static_cast<std::uint32_t>(du - 1) << 18 | static_cast<std::uint32_t>(dv - 1) << 24;
}
// AO bits with all four corners equal (the only ones that may merge).
inline bool ao_uniform(std::uint32_t ao_bits) { return ao_bits == (ao_bits & 3u) * 0x55u; }

// Samples opaque occupancy around faces by padded-array index arithmetic.
class AoSampler {
 public:
  AoSampler(const PaddedBlocks& blocks, const std::vector<std::uint8_t>& opaque, bool enabled = true)
      : ids_(blocks.ids.data()), opaque_(opaque.data()), enabled_(enabled) {
    const int p = blocks.pitch();
    const int stride[3] = {1, p * p, p};  // x, y, z
    for (int f = 0; f < 6; ++f) {
      const int a = f >> 1;
      const int s = (f & 1) ? -1 : 1;
      const int u = stride[(a + 1) % 3];
      const int v = stride[(a + 2) % 3];
      front_[f] = s * stride[a];
      // Neighbours in the layer in front of the face, around its centre.
      int k = 0;
      for (int dv = -1; dv <= 1; ++dv) {
        for (int du = -1; du <= 1; ++du) {
          if (du == 0 && dv == 0) continue;
          ring_[f][k++] = du * u + dv * v;
        }
      }
    }
    pitch_ = p;
  }

  int index(int x, int y, int z) const { return (x + 1) + pitch_ * ((z + 1) + pitch_ * (y + 1)); }
  int front_offset(int face) const { return front_[face]; }

  // AO bits (pack_ao order) of unit face `face` of the block at padded index idx.
  std::uint32_t face_bits(int idx, int face) const {
    if (!enabled_) return 0xffu;
    const int q = idx + front_[face];
    const auto& r = ring_[face];
    auto occ = [&](int k) -> int { return opaque_[ids_[q + r[k]]]; };
    // ring order: (-1,-1) (0,-1) (1,-1) (-1,0) (1,0) (-1,1) (0,1) (1,1)
    const int mm = occ(0), zm = occ(1), pm = occ(2), mz = occ(3), pz = occ(4), mp = occ(5), zp = occ(6), pp = occ(7);
    auto vertex = [](int s1, int s2, int c) -> std::uint32_t {
      return (s1 && s2) ? 0u : static_cast<std::uint32_t>(3 - (s1 + s2 + c));
    };
    const std::uint32_t a0 = vertex(mz, zm, mm);  // (u0, v0)
    const std::uint32_t a1 = vertex(pz, zm, pm);  // (u1, v0)
    const std::uint32_t a2 = vertex(pz, zp, pp);  // (u1, v1)
    const std::uint32_t a3 = vertex(mz, zp, mp);  // (u0, v1)
    return a0 | a1 << 2 | a2 << 4 | a3 << 6;
  }

  void face(int x, int y, int z, int face, std::uint8_t out[4]) const {
    const std::uint32_t bits = face_bits(index(x, y, z), face);
    for (int i = 0; i < 4; ++i) out[i] = static_cast<std::uint8_t>((bits >> (2 * i)) & 3u);
  }

 private:
  const BlockId* ids_;
  const std::uint8_t* opaque_;
  bool enabled_ = true;
  int front_[6] = {};
  std::array<std::array<int, 8>, 6> ring_{};
  int pitch_ = 0;
};

std::unique_ptr<Mesher> make_culled_mesher(const MesherOptions& options);
std::unique_ptr<Mesher> make_greedy_mesher(const MesherOptions& options);
std::unique_ptr<Mesher> make_bitmask_mesher(const MesherOptions& options);

}  // namespace sylva::voxel::detail
