#pragma once
// Chunk meshing: three interchangeable algorithms behind one interface.
//
//  * kCulled  : one quad per visible unit face (hidden-face removal; seed 004 §2.1 culled
//               back faces per cube on the GPU, this removes faces between blocks on the CPU).
//  * kGreedy  : visible faces of one slice merged into maximal rectangles by a scalar scan
//               (Lysenko's "greedy meshing", 0fps.net 2012).
//  * kBitmask : binary greedy meshing: face visibility of a whole column at once from 64-bit
//               occupancy masks (mask & ~shifted neighbour mask), then rectangles merged with
//               bit operations on rows of a slice.
//
// All three produce exactly the same visible surface: every visible unit face is covered by
// exactly one quad, with the same block and the same four ambient-occlusion values (tested).
// Faces merge only when block and AO agree and the AO is equal at all four corners, so merged
// quads shade exactly like the unit faces they replace.
//
// Visibility rule (one place: face_visible()): a face of block A towards neighbour B is drawn
// iff A is not air, B is not opaque, not (A is alpha-cut with cull_same and B == A), and not
// (A is sides_only and the face points along y).
// Ambient occlusion (per vertex, 0 = darkest .. 3 = open; Lysenko 2012): for a vertex with two
// side neighbours s1, s2 and a corner neighbour c in the layer in front of the face,
// ao = (s1 && s2) ? 0 : 3 - (s1 + s2 + c); only opaque blocks occlude.

#include <sylva/core/params.hpp>
#include <sylva/voxel/block.hpp>

#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <string_view>
#include <vector>

namespace sylva::voxel {

// A chunk's blocks plus a one-block ring from its 26 neighbours, which decides border-face
// visibility and border AO. Size n in [1, 64]; (n+2)^3 ids; index (x+1) + P*((z+1) + P*(y+1))
// with P = n + 2 and x, y, z in [-1, n].
struct PaddedBlocks {
  int n = 0;
  std::vector<BlockId> ids;

  PaddedBlocks() = default;
  explicit PaddedBlocks(int size, BlockId fill = kAir);
  int pitch() const { return n + 2; }
  int index(int x, int y, int z) const { return (x + 1) + pitch() * ((z + 1) + pitch() * (y + 1)); }
  BlockId at(int x, int y, int z) const { return ids[static_cast<std::size_t>(index(x, y, z))]; }
  void set(int x, int y, int z, BlockId id) { ids[static_cast<std::size_t>(index(x, y, z))] = id; }
};

// One quad in 8 bytes, read by the vertex shader (vertex pulling, 6 vertices per quad).
//  word0: x | y << 6 | z << 12 | (du - 1) << 18 | (dv - 1) << 24      (bits 30..31 zero)
//  word1: block | face << 16 | ao0 << 19 | ao1 << 21 | ao2 << 23 | ao3 << 25
// (x, y, z) is the minimum block covered (0..63); the quad lies on that block's `face` and
// spans du blocks along the face's u axis and dv along its v axis, u = (axis + 1) % 3,
// v = (axis + 2) % 3. AO corners in order (u, v) = (0,0), (1,0), (1,1), (0,1).
struct PackedQuad {
  std::uint32_t word0 = 0;
  std::uint32_t word1 = 0;
  bool operator==(const PackedQuad&) const = default;
};

struct Quad {
  int x = 0, y = 0, z = 0;
  int du = 1, dv = 1;
  int face = 0;
  BlockId block = kAir;
  std::uint8_t ao[4] = {3, 3, 3, 3};
};

PackedQuad pack_quad(const Quad& q);
Quad unpack_quad(const PackedQuad& p);

// The output of meshing one chunk: opaque and alpha-cut quads in separate lists, so the
// renderer draws the opaque ones first with back-face culling and early-z (seed §2.2, §3.7.1).
struct ChunkMesh {
  std::vector<PackedQuad> opaque;
  std::vector<PackedQuad> alpha_cut;
  void clear() {
    opaque.clear();
    alpha_cut.clear();
  }
  std::size_t quad_count() const { return opaque.size() + alpha_cut.size(); }
  bool empty() const { return opaque.empty() && alpha_cut.empty(); }
};

enum class MesherKind : std::uint8_t { kCulled, kGreedy, kBitmask };
constexpr std::array<EnumName<MesherKind>, 3> enum_names(MesherKind) {
  return {{{MesherKind::kCulled, "culled"}, {MesherKind::kGreedy, "greedy"}, {MesherKind::kBitmask, "bitmask"}}};
}
std::string_view to_string(MesherKind kind);
// Parses "culled", "greedy" or "bitmask"; kInvalidArgument naming the value otherwise.
Result<MesherKind> parse_mesher_kind(std::string_view name);

// A mesher keeps scratch memory between calls; use one instance per thread.
class Mesher {
 public:
  virtual ~Mesher() = default;
  virtual MesherKind kind() const = 0;
  // Replaces out's contents with the mesh of `blocks` (n in [1, 64], asserted).
  virtual void mesh(const PaddedBlocks& blocks, const BlockPalette& palette, ChunkMesh& out) = 0;
};

struct MesherOptions {
  // false: every AO value is 3 (open) and faces merge on block alone. Shading then loses the
  // corner darkening; kept for comparing with binary greedy meshers that have no AO.
  bool ambient_occlusion = true;
};

std::unique_ptr<Mesher> make_mesher(MesherKind kind, const MesherOptions& options = {});

// The shared definitions all meshers implement (and the tests check against).
bool face_visible(BlockId self, BlockId neighbour, int face, const BlockPalette& palette);
// AO of the four corners of unit face `face` of block (x, y, z), in PackedQuad corner order.
void face_ao(const PaddedBlocks& blocks, const BlockPalette& palette, int x, int y, int z, int face,
             std::uint8_t out[4]);

}  // namespace sylva::voxel
