#pragma once
// Streams chunk meshes from a ChunkFile on a loader thread, by priority, within a memory budget.
//
// Per frame (main thread): update() integrates finished loads and evicts, then the selection runs
// with residency() (a chunk whose children are not resident is drawn instead of them, and the
// missing children are requested with their parent's projected error as priority), then the
// frame is drawn with meshes(). Eviction only happens in update(), so nothing drawn in a frame is
// evicted before it is drawn; the root is loaded when the streamer is created and never evicted.
// The budget is never exceeded: a load that does not fit after evicting everything not used in
// the current or previous frame is dropped; it is asked for again only once what could be evicted
// would make room for it (stats: budget_refused, budget_limited), so a view that needs more than
// the budget settles with parents drawn for the chunks that do not fit. A chunk that fails to load
// (corrupt data) is reported once and never requested again; its parent keeps being drawn.

#include <sylva/core/params.hpp>
#include <sylva/terrain/chunk_file.hpp>
#include <sylva/terrain/edit_layer.hpp>
#include <sylva/terrain/seams.hpp>
#include <sylva/terrain/selection.hpp>

#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <unordered_map>
#include <vector>

namespace sylva::terrain {

namespace detail {
class StreamEdits;  // stream_edits.hpp
struct RebuildSource;
}  // namespace detail

struct StreamingSettings {
  double memory_budget_mb = 256.0;  // resident chunk meshes [MiB]

  template <class V>
  void visit(V& v) {
    v(memory_budget_mb, "budget_mb", {.min = 0.01, .max = 1e6, .unit = "MiB",
      .help = "Memory for resident chunk meshes", .rebuild = Rebuild::kGpu, .log_scale = true});
  }
};

struct StreamingStats {
  std::size_t resident_chunks = 0;
  std::size_t resident_bytes = 0;
  std::size_t budget_bytes = 0;
  std::size_t pending_requests = 0;
  std::uint64_t loads = 0;       // meshes made resident
  std::uint64_t evictions = 0;
  std::uint64_t dropped = 0;     // loads that did not fit the budget
  std::uint64_t failures = 0;    // chunks that could not be read
  std::uint64_t requests = 0;    // chunks newly asked for (once until loaded, however often repeated)
  std::uint64_t misses = 0;      // chunks drawn in place of non-resident children, summed over frames
  // Chunks the last frame's selection wanted that were dropped before and still do not fit the
  // budget (nothing it could evict frees enough): not asked for again; their parents are drawn.
  std::size_t budget_refused = 0;
  // Settled within the budget: every chunk the view wants is resident or refused by the budget
  // (budget_refused > 0), and nothing is pending, being read or waiting to be integrated.
  bool budget_limited = false;
  std::string last_error;
};

class ChunkStreamer {
 public:
  // Loads the root synchronously. Errors: the root cannot be read or does not fit the budget.
  static Result<std::unique_ptr<ChunkStreamer>> create(std::shared_ptr<const ChunkFile> file,
                                                       const StreamingSettings& settings);
  ~ChunkStreamer();
  ChunkStreamer(const ChunkStreamer&) = delete;
  ChunkStreamer& operator=(const ChunkStreamer&) = delete;

  // The file's tree, or after height edits the edited field's (errors, bounds, height ranges).
  const ChunkTree& tree() const { return *tree_; }
  // Integrates finished loads and evicts; call once per frame before selecting.
  void update();
  Residency residency();
  MeshSource meshes() const;
  const ChunkMesh* mesh(std::uint32_t chunk) const;
  bool resident(std::uint32_t chunk) const;

  // Evicts every chunk except the root (for tests and memory pressure).
  void evict_all();
  // Blocks until no request is pending or loading, then integrates (tests, warm-up).
  void wait_idle();
  StreamingStats stats() const;

  // Height edits (issue 15, painting a streamed terrain; stream_edits.hpp): the samples
  // [x0, x1) x [z0, z1) of `field`, the whole edited field of the file's grid, changed. The chunks
  // the edit reaches are rebuilt from `field` by the bake's code and substituted for the file's,
  // every other chunk gets its morph data recomputed when it becomes resident, and the resident
  // chunks are updated at once, so every resident chunk equals ChunkTree::build(field)'s. tree()
  // may then be another object: re-create selectors. Rebuilt meshes count against the budget like
  // the file's: the resident ones are swapped (others evicted, least recently used first, to fit), the
  // rest dropped and built again by the loader from the edits when asked for. Errors
  // (kInvalidArgument): another grid, a non-RTIN file, NaN/Inf samples; nothing changes then.
  // Main thread only.
  Result<RegionRebuild> apply_height_edit(const HeightField& field, int x0, int z0, int x1, int z1);
  // The same for several edited rectangles at once (one pass over the field: opening a scene
  // with an edit layer, one rectangle per edited tile).
  Result<RegionRebuild> apply_height_edit(const HeightField& field, const std::vector<SampleRect>& rects);
  // Chunks rebuilt from edits so far (0 without edits).
  std::size_t edited_chunks() const;
  // Adds a frame's substituted chunks (SelectionStats::substituted) to stats().misses; the
  // renderer calls it after each selection.
  void count_misses(std::uint32_t substituted) { stats_.misses += substituted; }

 private:
  ChunkStreamer(std::shared_ptr<const ChunkFile> file, const StreamingSettings& settings);
  void loader();
  static std::size_t bytes_of(const ChunkMesh& m);
  // Evicts chunks not used in this or the previous frame (or any, `recently_used_too`; never the
  // root), least recently used first, until `bytes` more fit; false if they do not.
  bool make_room(std::size_t bytes, bool recently_used_too = false);
  // Sets reclaimable_ after update() integrated and starts the frame's budget_refused count.
  void update_reclaimable();

  struct Resident {
    std::shared_ptr<const ChunkMesh> mesh;
    std::size_t bytes = 0;
    std::uint64_t last_used = 0;
  };
  struct Request {
    double priority = 0.0;
    std::uint64_t frame = 0;
  };

  std::shared_ptr<const ChunkFile> file_;
  const ChunkTree* tree_ = nullptr;            // file_->tree(), or edits_->tree()
  std::unique_ptr<detail::StreamEdits> edits_;  // main thread only; null until the first edit
  std::size_t budget_ = 0;
  std::uint64_t frame_ = 1;
  std::unordered_map<std::uint32_t, Resident> resident_;  // main thread only
  std::vector<std::uint8_t> failed_;                      // main thread only
  std::size_t resident_bytes_ = 0;
  // Chunks dropped because they did not fit, with their size (main thread only): asked for again
  // only when reclaimable_ (free bytes + chunks the last selection did not use) can hold them.
  struct Refusal {
    std::size_t bytes = 0;
    std::uint64_t counted_frame = 0;  // budget_refused counts each chunk once per frame
  };
  std::unordered_map<std::uint32_t, Refusal> refused_;
  std::size_t reclaimable_ = 0;
  StreamingStats stats_;

  mutable std::mutex mutex_;  // guards the fields below
  std::condition_variable wake_;
  std::condition_variable idle_;
  std::unordered_map<std::uint32_t, Request> requests_;
  struct Loaded {
    std::uint32_t chunk = kNoChunk;
    Result<ChunkMesh> mesh;
    std::uint64_t generation = 0;  // of the edits it was made under (stale after a later edit)
  };
  std::vector<Loaded> done_;
  std::shared_ptr<const detail::RebuildSource> edit_source_;  // rebuilt chunks are built from it
  std::uint32_t loading_ = kNoChunk;
  std::uint64_t current_frame_ = 1;
  bool stop_ = false;
  std::thread thread_;
};

}  // namespace sylva::terrain
