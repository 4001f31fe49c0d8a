// Voxel stability cases for --stability from the public API of modules/voxel: the three meshers
// on empty, full, enclosed and checkerboard chunks (same visible surface), an exploding
// L-system stopped by its cap, and block coordinates at +-1e6 chunks. GL-free.
#include "stability.hpp"

#include <sylva/voxel/block.hpp>
#include <sylva/voxel/coords.hpp>
#include <sylva/voxel/lsystem.hpp>
#include <sylva/voxel/mesher.hpp>

#include <fmt/format.h>

namespace sylva::bench {
namespace {

voxel::BlockId first_opaque(const voxel::BlockPalette& palette) {
  for (std::size_t id = 1; id < palette.size(); ++id) {
    if (palette.is_opaque(static_cast<voxel::BlockId>(id))) return static_cast<voxel::BlockId>(id);
  }
  return voxel::kAir;
}

// Face area (sum of du * dv over every quad) and quad count of one mesher's output.
struct MeshSummary {
  std::uint64_t area = 0;
  std::size_t quads = 0;
};

MeshSummary summarize(const voxel::ChunkMesh& mesh) {
  MeshSummary s;
  for (const auto* list : {&mesh.opaque, &mesh.alpha_cut}) {
    for (const voxel::PackedQuad& p : *list) {
      const voxel::Quad q = voxel::unpack_quad(p);
      s.area += static_cast<std::uint64_t>(q.du) * static_cast<std::uint64_t>(q.dv);
    }
    s.quads += list->size();
  }
  return s;
}

// All three meshers on `blocks`: the covered face area must agree and equal `expected_area`.
StabilityOutcome meshers_agree(const voxel::PaddedBlocks& blocks, std::uint64_t expected_area) {
  const voxel::BlockPalette& palette = voxel::BlockPalette::standard();
  StabilityOutcome o;
  o.passed = true;
  std::string detail;
  for (voxel::MesherKind kind : {voxel::MesherKind::kCulled, voxel::MesherKind::kGreedy, voxel::MesherKind::kBitmask}) {
    auto mesher = voxel::make_mesher(kind);
    voxel::ChunkMesh mesh;
    mesher->mesh(blocks, palette, mesh);
    const MeshSummary s = summarize(mesh);
    o.passed = o.passed && s.area == expected_area;
    detail += fmt::format("{}{}: {} quads, face area {}", detail.empty() ? "" : "; ", voxel::to_string(kind), s.quads,
                          s.area);
  }
  o.detail = fmt::format("{} (expected area {})", detail, expected_area);
  return o;
}

StabilityOutcome empty_chunk() { return meshers_agree(voxel::PaddedBlocks(32, voxel::kAir), 0); }

StabilityOutcome full_chunk_open() {
  const voxel::BlockId stone = first_opaque(voxel::BlockPalette::standard());
  voxel::PaddedBlocks b(32, voxel::kAir);
  for (int y = 0; y < 32; ++y) {
    for (int z = 0; z < 32; ++z) {
      for (int x = 0; x < 32; ++x) b.set(x, y, z, stone);
    }
  }
  return meshers_agree(b, 6u * 32u * 32u);
}

StabilityOutcome full_chunk_enclosed() {
  const voxel::BlockId stone = first_opaque(voxel::BlockPalette::standard());
  return meshers_agree(voxel::PaddedBlocks(32, stone), 0);
}

StabilityOutcome checkerboard() {
  const voxel::BlockId stone = first_opaque(voxel::BlockPalette::standard());
  const int n = 16;
  voxel::PaddedBlocks b(n, voxel::kAir);
  std::uint64_t cubes = 0;
  for (int y = 0; y < n; ++y) {
    for (int z = 0; z < n; ++z) {
      for (int x = 0; x < n; ++x) {
        if ((x + y + z) % 2 == 0) {
          b.set(x, y, z, stone);
          ++cubes;
        }
      }
    }
  }
  // No two solid blocks share a face, so every solid block shows all six faces.
  return meshers_agree(b, 6u * cubes);
}

StabilityOutcome exploding_grammar() {
  auto systems = voxel::parse_lsystems("20 20 0.9\nF\nF > FF[+F][-F]\n", "<bench exploding grammar>");
  StabilityOutcome o;
  if (!systems.ok() || systems->empty()) {
    o.detail = systems.ok() ? "no system parsed" : "parse failed: " + systems.error().message;
    return o;
  }
  auto derived = voxel::derive(systems->front(), 40, 7);
  o.passed = !derived.ok() && derived.error().code == ErrorCode::kLimit;
  o.detail = derived.ok() ? fmt::format("40 derivations gave {} symbols without hitting the cap", derived->size())
                          : "stopped: " + derived.error().message;
  return o;
}

StabilityOutcome far_coordinates() {
  StabilityOutcome o;
  o.passed = true;
  std::size_t checked = 0;
  for (std::int64_t base : {std::int64_t{0}, std::int64_t{32'000'000}, std::int64_t{-32'000'000},
                            std::int64_t{1} << 40, -(std::int64_t{1} << 40)}) {
    for (std::int64_t d : {-33, -32, -1, 0, 1, 31, 32}) {
      const voxel::BlockPos p{base + d, -(base + d), base - 2 * d};
      const voxel::ChunkCoord c = voxel::chunk_of(p);
      const voxel::BlockPos o0 = voxel::chunk_origin(c);
      const voxel::BlockPos back{o0.x + voxel::local_of(p.x), o0.y + voxel::local_of(p.y), o0.z + voxel::local_of(p.z)};
      o.passed = o.passed && back == p;
      ++checked;
    }
  }
  o.detail = fmt::format("{} positions up to +-2^40 blocks: chunk origin + local offset gives the block back", checked);
  return o;
}

}  // namespace

void add_voxel_stability_cases(std::vector<StabilityCase>& cases) {
  cases.push_back({"voxel", "mesh_empty_chunk", "all three meshers give no quads for an empty chunk", false, empty_chunk});
  cases.push_back({"voxel", "mesh_full_chunk_open", "a full 32^3 chunk in open air: every mesher covers exactly the "
                   "6 x 32^2 outer faces", false, full_chunk_open});
  cases.push_back({"voxel", "mesh_full_chunk_enclosed", "a full chunk among full neighbours: no quads from any mesher",
                   false, full_chunk_enclosed});
  cases.push_back({"voxel", "mesh_checkerboard", "16^3 checkerboard: every mesher shows all 6 faces of every block",
                   false, checkerboard});
  cases.push_back({"voxel", "lsystem_explosion_capped", "a grammar doubling every step is stopped with kLimit at its "
                   "symbol cap, never running out of memory", false, exploding_grammar});
  cases.push_back({"voxel", "coordinates_far_from_origin", "chunk/local split round-trips block positions up to "
                   "+-2^40 blocks", false, far_coordinates});
}

}  // namespace sylva::bench
