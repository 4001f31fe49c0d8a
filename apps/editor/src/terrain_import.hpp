#pragma once
// File > Import terrain... and the `import_terrain` / `wait_import` / `cancel_import` script
// commands (issue 15: "the editor opens [the source file] from File > Import terrain... with a
// progress bar"). GL-free work on a worker thread, applied to the EditorSession on the caller's
// (GL) thread by poll().
//
// Flow: start_read(FILE) reads the source on the worker: an elevation raster (anything
// core/elevation_raster.hpp reads: GeoTIFF, .hgt, .asc, PNG, EXR) with the target section's
// `elevation.*` read options and `size` (so the numbers are the ones the scene will use), or a
// mesh (.obj, .iv, .gltf, .glb: terrain/mesh.hpp load_mesh). info() then says what was read.
// use_directly() points the scene at the file; start_bake(OUT) bakes the raster into a chunk
// file (terrain/bake.hpp bake_chunk_file, the engine of `sylva-bake terrain`, with the section's
// `terrain.tree.*` settings) on the worker, and poll() applies it when it is done. Each applied
// import is ONE undo entry (a SectionEdit of the section before and after).
//
// What an import writes into the scene (paths relative to the scene file, absolute without one):
//  - raster, use directly: `<section>.elevation.file`, `baked_file` cleared, `maps.height` dropped
//    (a height map file would win over the raster). Section: "terrain", else "ground", else a
//    new "terrain" section.
//  - raster, bake: the same plus `terrain.baked_file` = OUT (the scene's ground then comes from
//    the file's own heights; modules/terrain/README.md "Baked terrain in a scene") and
//    `terrain.center` = the middle of the baked field (the bake keeps a raster's origin at
//    (0, 0)), so the raster named by elevation.file lies where the baked terrain did if
//    baked_file is cleared later. Needs a "terrain" section (added when the scene has no ground
//    section; refused beside a "ground" one).
//  - mesh: `model_terrain.file` (the section is added when missing).
//
// Failure (the scene is unchanged, nothing is pushed on the undo stack): the reader's error,
// which names the file (missing, unreadable, all nodata, not a mesh); unsaved painting on the
// ground's height map (it would win over the raster: save or undo it first); a bake error
// naming OUT, or cancellation (cancel(): the bake stops at its next chunk and leaves no file at
// OUT, not even a temporary; bake.hpp). Only one job at a time (kInvalidArgument while busy).
// The destructor cancels a running job and waits for it.

#include <sylva/core/elevation_raster.hpp>
#include <sylva/core/result.hpp>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <filesystem>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

namespace sylva::scene {
class Scene;
}

namespace sylva::editor {

class EditorSession;

// What start_read found in the file.
struct TerrainSourceInfo {
  enum class Kind { kRaster, kMesh } kind = Kind::kRaster;
  std::filesystem::path file;
  // kRaster (core ElevationRaster):
  std::string reader;            // "GDAL GTiff", "OpenImageIO", ...
  std::string crs;               // "" without a coordinate system
  int columns = 0, rows = 0;     // samples after resampling to square spacing
  double spacing = 0.0;          // metres between samples (georeferencing or the overrides)
  double source_spacing_x = 0.0, source_spacing_z = 0.0;  // the file's own pixel size [m]
  float min_height = 0.0f, max_height = 0.0f;             // [m]
  std::size_t nodata_filled = 0;
  // kMesh:
  std::size_t vertices = 0, faces = 0;
  // One line for the dialog and the script output: "dem.tif (GDAL GTiff): 257 x 257 samples,
  // 10 m apart (file 10 x 10 m), heights 12.0 to 310.5 m, 0 nodata filled".
  std::string summary() const;
};

class TerrainImport {
 public:
  enum class State { kIdle, kReading, kRead, kBaking };

  TerrainImport() = default;
  TerrainImport(const TerrainImport&) = delete;
  TerrainImport& operator=(const TerrainImport&) = delete;
  ~TerrainImport();

  // Reads `file` on the worker (State kReading); the target section's read options are taken
  // from the session's scene now.
  Status start_read(EditorSession& session, const std::filesystem::path& file);
  // Points the scene at the file read (State kRead): one undo entry. Back to kIdle on success.
  Status use_directly(EditorSession& session);
  // Bakes the raster read (State kRead) into `out` on the worker (State kBaking). hold = true
  // (tests): the bake waits at its first progress report until release() or cancel(), so a
  // cancel always lands in the middle of the bake.
  Status start_bake(EditorSession& session, const std::filesystem::path& out, bool hold = false);
  void release();
  // Blocks until a held bake is parked at its first progress report (or has ended), so what a
  // window draws next is the bake in progress (tests).
  void wait_until_held();
  // Stops a running job (the bake at its next chunk); poll() then reports it.
  void cancel();
  // Drops the file read (State kRead -> kIdle); a running job is cancelled first.
  void reset();

  // On the GL thread, every frame: when the worker has finished, applies its result and returns
  // what to tell the user ("read ...", "baked ... and set terrain.baked_file", or the error).
  // nullopt while nothing finished.
  std::optional<Result<std::string>> poll(EditorSession& session);
  // Blocks until the worker is done (scripts), then poll() and take_last().
  std::optional<Result<std::string>> wait(EditorSession& session);
  // The result the last poll() returned, once (nullopt when it was taken): the window polls every
  // frame, so a script waiting on the same import may find its result already applied.
  std::optional<Result<std::string>> take_last();

  State state() const { return state_; }
  bool busy() const { return state_ == State::kReading || state_ == State::kBaking; }
  const std::optional<TerrainSourceInfo>& info() const { return info_; }
  const std::filesystem::path& bake_output() const { return out_; }
  // The bake's share done in [0, 1], its elapsed time and estimated time left [s] (< 0: unknown).
  float progress() const { return progress_.load(); }
  double elapsed_s() const;
  double eta_s() const;

 private:
  void join();
  Result<std::string> finish(EditorSession& session);  // the worker's result, applied
  Status apply(EditorSession& session, bool baked);

  State state_ = State::kIdle;
  std::thread worker_;
  std::atomic<bool> done_{false};
  std::atomic<bool> cancel_{false};
  std::atomic<float> progress_{0.0f};
  std::mutex hold_mutex_;
  std::condition_variable hold_cv_;
  bool hold_ = false;
  bool held_ = false;
  std::chrono::steady_clock::time_point started_;

  std::filesystem::path file_, out_;
  const scene::Scene* scene_ = nullptr;  // the scene the job was started for
  std::string section_;                  // "terrain", "ground" or "model_terrain"
  std::optional<TerrainSourceInfo> info_;
  std::optional<ElevationRaster> raster_;  // kept between read and bake
  std::optional<Status> job_status_;       // set by the worker before done_
  std::optional<Result<std::string>> last_;  // what poll() returned last, until taken
};

}  // namespace sylva::editor
