#include <sylva/terrain/streaming.hpp>

#include "stream_edits.hpp"

#include <sylva/core/log.hpp>

#include <algorithm>

namespace sylva::terrain {

std::size_t ChunkStreamer::bytes_of(const ChunkMesh& m) {
  std::size_t b = sizeof(ChunkMesh) + m.vertices.size() * sizeof(ChunkVertex) + m.indices.size() * 4;
  for (const auto& e : m.edges) b += e.size() * 4;
  return b;
}

ChunkStreamer::ChunkStreamer(std::shared_ptr<const ChunkFile> file, const StreamingSettings& settings)
    : file_(std::move(file)),
      tree_(&file_->tree()),
      budget_(static_cast<std::size_t>(settings.memory_budget_mb * 1024.0 * 1024.0)),
      failed_(file_->tree().chunk_count(), 0) {
  stats_.budget_bytes = budget_;
}

Result<std::unique_ptr<ChunkStreamer>> ChunkStreamer::create(std::shared_ptr<const ChunkFile> file,
                                                             const StreamingSettings& settings) {
  SYLVA_TRY(validate_params(settings, "terrain.stream"));
  std::unique_ptr<ChunkStreamer> s(new ChunkStreamer(std::move(file), settings));
  auto root = s->file_->read_chunk(0);
  if (!root.ok()) return root.error();
  const std::size_t bytes = bytes_of(*root);
  if (bytes > s->budget_) {
    return make_error(ErrorCode::kLimit, fmt::format("terrain.stream.budget_mb: {:.3f} MiB cannot hold "
                                                     "even the root chunk ({:.3f} MiB)",
                                                     settings.memory_budget_mb, bytes / 1048576.0));
  }
  s->resident_[0] = Resident{std::make_shared<const ChunkMesh>(std::move(root).value()), bytes, s->frame_};
  s->resident_bytes_ = bytes;
  s->stats_.loads = 1;
  s->thread_ = std::thread([p = s.get()] { p->loader(); });
  return s;
}

ChunkStreamer::~ChunkStreamer() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  if (thread_.joinable()) thread_.join();
}

void ChunkStreamer::loader() {
  for (;;) {
    std::uint32_t chunk = kNoChunk;
    std::shared_ptr<const detail::RebuildSource> source;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      wake_.wait(lock, [&] { return stop_ || !requests_.empty(); });
      if (stop_) return;
      // Highest priority among the requests of the last two frames; older ones are stale.
      double best = -1.0;
      for (auto it = requests_.begin(); it != requests_.end();) {
        if (it->second.frame + 1 < current_frame_) {
          it = requests_.erase(it);
          continue;
        }
        if (it->second.priority > best) {
          best = it->second.priority;
          chunk = it->first;
        }
        ++it;
      }
      if (chunk == kNoChunk) {
        idle_.notify_all();
        continue;
      }
      requests_.erase(chunk);
      loading_ = chunk;
      source = edit_source_;
    }
    // A chunk rebuilt by edits comes from them (stream_edits.hpp), every other from the file.
    Result<ChunkMesh> mesh = source && source->is_rebuilt(chunk) ? Result<ChunkMesh>(source->build(chunk))
                                                                  : file_->read_chunk(chunk);
    {
      std::lock_guard<std::mutex> lock(mutex_);
      done_.push_back(Loaded{chunk, std::move(mesh), source ? source->generation : 0});
      loading_ = kNoChunk;
      if (requests_.empty()) idle_.notify_all();
    }
  }
}

void ChunkStreamer::update() {
  std::vector<Loaded> done;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    done.swap(done_);
    current_frame_ = ++frame_;
  }
  bool edited_nodes = false;
  for (auto& [chunk, mesh, generation] : done) {
    if (!mesh.ok()) {
      if (!failed_[chunk]) log_warn("terrain streaming: {}", mesh.error().message);
      failed_[chunk] = 1;
      ++stats_.failures;
      stats_.last_error = mesh.error().message;
      continue;
    }
    if (resident_.count(chunk)) continue;
    // Made before the latest edit rebuilt it: stale (asked for again while needed).
    if (edits_ && edits_->rebuilt(chunk) && generation != edits_->generation()) continue;
    std::shared_ptr<const ChunkMesh> loaded = std::make_shared<const ChunkMesh>(std::move(mesh).value());
    if (edits_) {
      loaded = edits_->resolve(chunk, std::move(loaded));  // the edited field's chunk
      edited_nodes = true;
    }
    const std::size_t bytes = bytes_of(*loaded);
    if (!make_room(bytes)) {
      ++stats_.dropped;
      refused_[chunk] = Refusal{bytes, 0};
      continue;
    }
    refused_.erase(chunk);
    resident_[chunk] = Resident{std::move(loaded), bytes, frame_};
    resident_bytes_ += bytes;
    ++stats_.loads;
  }
  if (edited_nodes) edits_->refresh_nodes();  // the resolved chunks' height ranges
  update_reclaimable();
}

void ChunkStreamer::update_reclaimable() {
  // What make_room could free for a load integrated in a later frame: the free bytes and every
  // chunk the last selection did not use (for a still view, the same chunks next frame).
  reclaimable_ = budget_ - resident_bytes_;
  for (const auto& [id, r] : resident_)
    if (id != 0 && r.last_used + 1 < frame_) reclaimable_ += r.bytes;
  stats_.budget_refused = 0;
}

bool ChunkStreamer::make_room(std::size_t bytes, bool recently_used_too) {
  if (resident_bytes_ + bytes <= budget_) return true;
  std::vector<std::pair<std::uint64_t, std::uint32_t>> candidates;
  for (const auto& [id, r] : resident_)
    if (id != 0 && (recently_used_too || r.last_used + 1 < frame_)) candidates.emplace_back(r.last_used, id);
  std::sort(candidates.begin(), candidates.end());
  for (const auto& [used, id] : candidates) {
    if (resident_bytes_ + bytes <= budget_) break;
    resident_bytes_ -= resident_.at(id).bytes;
    resident_.erase(id);
    ++stats_.evictions;
  }
  return resident_bytes_ + bytes <= budget_;
}

Result<RegionRebuild> ChunkStreamer::apply_height_edit(const HeightField& field, int x0, int z0, int x1, int z1) {
  return apply_height_edit(field, std::vector<SampleRect>{{x0, z0, x1, z1}});
}

Result<RegionRebuild> ChunkStreamer::apply_height_edit(const HeightField& field, const std::vector<SampleRect>& rects) {
  if (!edits_) edits_ = std::make_unique<detail::StreamEdits>(file_->tree());
  detail::RebuiltMeshes rebuilt;
  auto changed = edits_->apply(field, rects, rebuilt);  // unchanged on error
  if (!changed.ok()) return changed.error();
  {
    std::lock_guard<std::mutex> lock(mutex_);
    edit_source_ = edits_->source();
  }
  // Every resident chunk becomes the edited field's: rebuilt ones swapped, the others re-patched
  // (their triangles stay as they were, only morph data and height range change).
  resident_bytes_ = 0;
  for (auto& [id, r] : resident_) {
    auto fresh = rebuilt.find(id);
    r.mesh = fresh != rebuilt.end() ? fresh->second : edits_->resolve(id, r.mesh);
    r.bytes = bytes_of(*r.mesh);
    resident_bytes_ += r.bytes;
  }
  // Rebuilt meshes may be bigger: other chunks make room (the root stays: it is always drawn).
  // Any of them may go, as every selection and mesh pointer is renewed after an edit.
  make_room(0, true);
  refused_.clear();  // their sizes were the unedited meshes'
  edits_->refresh_nodes();
  tree_ = &edits_->tree();
  return changed;
}

std::size_t ChunkStreamer::edited_chunks() const { return edits_ ? edits_->rebuilt_count() : 0; }

Residency ChunkStreamer::residency() {
  Residency r;
  r.resident = [this](std::uint32_t chunk) {
    auto it = resident_.find(chunk);
    if (it == resident_.end()) return false;
    it->second.last_used = frame_;
    return true;
  };
  r.request = [this](std::uint32_t chunk, double priority) {
    if (failed_[chunk] || resident_.count(chunk)) return;
    // Dropped before and still cannot fit: reading it again would only drop it again, and the
    // view would never settle. Its parent is drawn instead, as for any missing chunk.
    if (auto refused = refused_.find(chunk); refused != refused_.end() && refused->second.bytes > reclaimable_) {
      if (refused->second.counted_frame != frame_) ++stats_.budget_refused;  // once per frame
      refused->second.counted_frame = frame_;
      return;
    }
    {
      std::lock_guard<std::mutex> lock(mutex_);
      // Being read or read and not yet integrated: asking again would read it twice.
      if (chunk == loading_ ||
          std::any_of(done_.begin(), done_.end(), [chunk](const Loaded& d) { return d.chunk == chunk; })) {
        return;
      }
      auto [it, fresh] = requests_.try_emplace(chunk);
      if (fresh) ++stats_.requests;
      Request& q = it->second;
      q.priority = std::max(q.frame == frame_ ? q.priority : 0.0, priority);
      q.frame = frame_;
    }
    wake_.notify_one();
  };
  return r;
}

const ChunkMesh* ChunkStreamer::mesh(std::uint32_t chunk) const {
  auto it = resident_.find(chunk);
  return it == resident_.end() ? nullptr : it->second.mesh.get();
}

bool ChunkStreamer::resident(std::uint32_t chunk) const { return resident_.count(chunk) != 0; }

MeshSource ChunkStreamer::meshes() const {
  return [this](std::uint32_t chunk) { return mesh(chunk); };
}

void ChunkStreamer::evict_all() {
  for (auto it = resident_.begin(); it != resident_.end();) {
    if (it->first == 0) {
      ++it;
      continue;
    }
    resident_bytes_ -= it->second.bytes;
    ++stats_.evictions;
    it = resident_.erase(it);
  }
}

void ChunkStreamer::wait_idle() {
  {
    std::unique_lock<std::mutex> lock(mutex_);
    idle_.wait(lock, [&] { return requests_.empty() && loading_ == kNoChunk; });
  }
  // Integrate without advancing past the requests' frame more than once.
  update();
}

StreamingStats ChunkStreamer::stats() const {
  StreamingStats s = stats_;
  s.resident_chunks = resident_.size();
  s.resident_bytes = resident_bytes_;
  std::lock_guard<std::mutex> lock(mutex_);
  s.pending_requests = requests_.size();
  s.budget_limited = s.budget_refused > 0 && requests_.empty() && loading_ == kNoChunk && done_.empty();
  return s;
}

}  // namespace sylva::terrain
