#pragma once
// Per-frame chunk selection (seed 002 §2.3 and Ulrich 2002), GL-free.
//
// Traverses the chunk tree from the root. A chunk outside the view frustum is skipped; a chunk
// is drawn when it is detailed enough (or a leaf), otherwise its children are examined.
//   kScreenSpaceError: rho = K * delta / (D - delta) <= tau, delta = the chunk's error_bound,
//     D = distance from the camera to the nearest point of the chunk's box. The box holds the
//     drawn surface; the field lies within delta of it, so every vertical error segment is at
//     least D - delta away and projects to at most rho pixels (Ulrich's K * delta / D, made
//     exact for errors that are not small against the distance).
//   kSeedDistance: spacing * lod_distance / d <= 1 with d the distance to the chunk's centre, as
//     in the seed; no error bound, no morphing.
//   kBruteForce: every chunk is refined down to the leaves (seed 002 Tab. 3.1, "unoptimised"):
//     the full-resolution mesh, no morphing, culled only when frustum_cull is on.
// After the traversal each drawn chunk learns, for each edge, whether the chunk across it is
// coarser, and which one: the seams are built from that.

#include <sylva/terrain/chunk_tree.hpp>
#include <sylva/terrain/lod_view.hpp>
#include <sylva/terrain/settings.hpp>

#include <array>
#include <cstdint>
#include <functional>
#include <vector>

namespace sylva::terrain {

inline constexpr std::uint32_t kNoChunk = 0xFFFFFFFFu;

struct SelectedChunk {
  std::uint32_t index = kNoChunk;
  // For each Edge: the drawn chunk across it when that chunk is coarser, else kNoChunk (same
  // level, finer, culled or outside the field).
  std::array<std::uint32_t, 4> coarser_neighbour{kNoChunk, kNoChunk, kNoChunk, kNoChunk};
  // For each Edge: the largest vertical deviation from the field of the drawn chunks across it
  // (their parent's error bound, since they may be morphing towards it), for the skirt depth.
  // Probed at the middle of the edge, and also at both ends when crack_fix is skirts.
  std::array<float, 4> neighbour_error{0.0f, 0.0f, 0.0f, 0.0f};
};

struct SelectionStats {
  double cpu_ms = 0.0;              // traversal + neighbour pass
  std::uint32_t chunks = 0;         // drawn chunks
  std::uint32_t culled = 0;         // chunks rejected by the frustum test
  std::uint32_t substituted = 0;    // chunks drawn in place of children that were not resident
  std::uint32_t visited = 0;        // chunks examined
  std::uint64_t triangles = 0;      // body triangles of the drawn chunks (seams/skirts excluded)
  int max_level_difference = 0;     // largest LOD difference across a drawn edge
  std::vector<std::uint32_t> chunks_per_level;
};

struct Selection {
  std::vector<SelectedChunk> chunks;
  SelectionStats stats;
  bool morph = false;               // morphing is in effect this frame
  // morph_fraction <= the tree's max_morph_fraction, so the tau bound holds while morphing.
  bool bound_certified = true;
};

// Streaming hooks (ChunkStreamer provides them). When a chunk should be refined but one of its
// children is not resident, the chunk itself is drawn instead (a missing chunk draws its parent)
// and the missing children are requested with the chunk's projected error as priority.
struct Residency {
  std::function<bool(std::uint32_t chunk)> resident;
  std::function<void(std::uint32_t chunk, double priority)> request;
};

class LodSelector {
 public:
  explicit LodSelector(const ChunkTree& tree);

  // The returned reference stays valid until the next call. With `residency`, only resident
  // chunks are drawn (the root must be resident for anything to be drawn).
  const Selection& select(const LodView& view, const LodSettings& settings, const Residency* residency = nullptr);

  // The drawn chunk that contains root-grid cell (cx, cz) (cell = [cx, cx+1] x [cz, cz+1]) after
  // the last select(), or kNoChunk.
  std::uint32_t drawn_chunk_at_cell(std::int64_t cx, std::int64_t cz) const;

  const ChunkTree& tree() const { return *tree_; }

 private:
  enum State : std::uint8_t { kUnseen = 0, kDrawn = 1, kRefined = 2, kCulled = 3 };
  // Projected error of a chunk (0 when it is detailed enough or a leaf), for acceptance and as
  // the streaming priority.
  bool accept(std::uint32_t index, const LodView& view, const LodSettings& settings, double* rho) const;

  const ChunkTree* tree_;
  std::vector<std::uint8_t> state_;
  std::vector<std::uint32_t> touched_;
  std::vector<std::pair<std::uint32_t, std::uint8_t>> stack_;  // chunk, frustum planes left to test
  Selection selection_;
};

}  // namespace sylva::terrain
