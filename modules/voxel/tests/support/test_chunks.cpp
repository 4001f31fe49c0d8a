#include "test_chunks.hpp"

#include <sylva/core/rng.hpp>

#include <cmath>

namespace sylva::voxel::testing {

std::string to_string(Pattern p) {
  switch (p) {
    case Pattern::kRandom: return "random";
    case Pattern::kTerrain: return "terrain";
    case Pattern::kCheckerboard: return "checkerboard";
    case Pattern::kEmpty: return "empty";
    case Pattern::kFull: return "full";
    case Pattern::kMixedAlpha: return "mixed_alpha";
  }
  return "?";
}

const BlockPalette& test_palette() {
  static const BlockPalette palette = [] {
    BlockPalette p;
    auto add = [&p](const char* name, RenderClass r, bool cull_same, float emission, bool sides_only = false) {
      BlockType t;
      t.name = name;
      t.render = r;
      t.cull_same = cull_same;
      t.sides_only = sides_only;
      t.emission = glm::vec3(emission);
      (void)p.add(t);
    };
    add("stone", RenderClass::kOpaque, true, 0.0f);
    add("dirt", RenderClass::kOpaque, true, 0.0f);
    add("grass", RenderClass::kOpaque, true, 0.0f);
    add("leaves", RenderClass::kAlphaCut, false, 0.0f);
    add("glass", RenderClass::kAlphaCut, true, 0.0f);
    add("lamp", RenderClass::kOpaque, true, 1.0f);
    add("tuft", RenderClass::kAlphaCut, false, 0.0f, true);
    return p;
  }();
  return palette;
}

PaddedBlocks make_pattern(Pattern pattern, int n, std::uint64_t seed) {
  PaddedBlocks b(n);
  Pcg32 rng(seed, 7);
  for (int y = -1; y <= n; ++y) {
    for (int z = -1; z <= n; ++z) {
      for (int x = -1; x <= n; ++x) {
        BlockId id = kAir;
        switch (pattern) {
          case Pattern::kRandom:
            // 50 % solid, mostly one block so merging has something to do.
            if (rng.next_below(2) == 0) id = rng.next_below(8) == 0 ? 2 : 1;
            break;
          case Pattern::kTerrain: {
            const double h = n * 0.5 + n * 0.2 * std::sin(0.21 * x + 0.3 * static_cast<double>(seed % 5)) +
                             n * 0.15 * std::cos(0.17 * z) + 1.5 * std::sin(0.9 * x * z * 0.05);
            if (y < h - 3) id = 1;
            else if (y < h - 1) id = 2;
            else if (y < h) id = 3;
            else if (y < h + 1 && (x * 7 + z * 13) % 11 == 0) id = 4;  // a leaf tuft on top
            break;
          }
          case Pattern::kCheckerboard:
            if (((x + y + z) & 1) == 0) id = 1;
            break;
          case Pattern::kEmpty: break;
          case Pattern::kFull: id = 1; break;
          case Pattern::kMixedAlpha: {
            const auto r = rng.next_below(10);
            id = r < 3 ? kAir : r < 5 ? 4 : r < 6 ? 5 : r < 7 ? 7 : r < 9 ? 1 : 6;
            break;
          }
        }
        b.set(x, y, z, id);
      }
    }
  }
  return b;
}

FaceCoverage coverage_of(const ChunkMesh& mesh, int n) {
  FaceCoverage c;
  c.n = n;
  const auto total = static_cast<std::size_t>(n * n * n * 6);
  c.count.assign(total, 0);
  c.block.assign(total, 0);
  c.ao.assign(total, 0);
  c.list.assign(total, 0);
  for (int l = 0; l < 2; ++l) {
    for (const PackedQuad& pq : l == 0 ? mesh.opaque : mesh.alpha_cut) {
      const Quad q = unpack_quad(pq);
      const int a = q.face >> 1, u = (a + 1) % 3, v = (a + 2) % 3;
      for (int j = 0; j < q.dv; ++j) {
        for (int i = 0; i < q.du; ++i) {
          int p[3] = {q.x, q.y, q.z};
          p[u] += i;
          p[v] += j;
          if (p[0] >= n || p[1] >= n || p[2] >= n) {
            c.count[0] = 200;  // out of the chunk: flags a failure in any comparison
            continue;
          }
          const auto k = c.index(p[0], p[1], p[2], q.face);
          ++c.count[k];
          c.block[k] = q.block;
          c.ao[k] = static_cast<std::uint8_t>(q.ao[0] | q.ao[1] << 2 | q.ao[2] << 4 | q.ao[3] << 6);
          c.list[k] = static_cast<std::uint8_t>(l);
        }
      }
    }
  }
  return c;
}

FaceCoverage reference_coverage(const PaddedBlocks& blocks, const BlockPalette& palette) {
  const int n = blocks.n;
  FaceCoverage c;
  c.n = n;
  const auto total = static_cast<std::size_t>(n * n * n * 6);
  c.count.assign(total, 0);
  c.block.assign(total, 0);
  c.ao.assign(total, 0);
  c.list.assign(total, 0);
  const int d[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (int y = 0; y < n; ++y)
    for (int z = 0; z < n; ++z)
      for (int x = 0; x < n; ++x)
        for (int f = 0; f < 6; ++f) {
          const BlockId self = blocks.at(x, y, z);
          const BlockId nb = blocks.at(x + d[f][0], y + d[f][1], z + d[f][2]);
          if (!face_visible(self, nb, f, palette)) continue;
          const auto k = c.index(x, y, z, f);
          c.count[k] = 1;
          c.block[k] = self;
          // AO written out independently of the meshers' index arithmetic.
          const int a = f >> 1, u = (a + 1) % 3, v = (a + 2) % 3;
          int q[3] = {x + d[f][0], y + d[f][1], z + d[f][2]};
          auto occ = [&](int du, int dv) -> int {
            int r[3] = {q[0], q[1], q[2]};
            r[u] += du;
            r[v] += dv;
            return palette.is_opaque(blocks.at(r[0], r[1], r[2])) ? 1 : 0;
          };
          const int corners[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
          int bits = 0;
          for (int i = 0; i < 4; ++i) {
            const int s1 = occ(corners[i][0], 0), s2 = occ(0, corners[i][1]);
            const int cc = occ(corners[i][0], corners[i][1]);
            const int ao = (s1 && s2) ? 0 : 3 - (s1 + s2 + cc);
            bits |= ao << (2 * i);
          }
          c.ao[k] = static_cast<std::uint8_t>(bits);
          c.list[k] = palette.render(self) == RenderClass::kAlphaCut ? 1 : 0;
        }
  return c;
}

}  // namespace sylva::voxel::testing
