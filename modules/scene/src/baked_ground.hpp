#pragma once
// The scene's ground from a baked chunk file (issue 15, "a baked file carries its ground"): a
// terrain section naming terrain.baked_file gets its grass, trees, camera height and ground clamp
// from the heights `sylva-bake terrain` stored in the file (terrain/chunk_file.hpp), placed where
// the file's chunks are (its origin and spacing; terrain.center and size do not move it).

#include <sylva/core/result.hpp>
#include <sylva/scene/map_grid.hpp>

#include <cstdint>
#include <filesystem>

namespace sylva::scene {

// Whether `file` starts like a Sylva chunk file (its 8-byte magic); false when unreadable.
bool is_chunk_file(const std::filesystem::path& file);

// Grounds above this many samples are read every 2nd, 4th, ... sample (4097^2 floats = 64 MiB):
// an 8193^2 bake gives a 4 m ground of a 2 m field, a 16385^2 bake an 8 m one, both read from
// the file's overview (terrain/chunk_file.hpp: the bake stores every 2nd/4th/... sample at most
// 4097^2 once more), so opening reads 64 MiB, not the field's 1 GiB. Why not more: a ground that
// matches the chunk grid also shades the terrain, and the renderer's height and shape textures of
// an 8193^2 ground took 15 s to the first frame on llvmpipe (README).
inline constexpr std::uint64_t kMaxBakedGroundSamples = std::uint64_t{4097} * 4097;

// The limit the scene reads its ground with: ScopedBakedGroundLimit's, else the environment
// variable SYLVA_BAKED_GROUND_MAX_SAMPLES (a sample count >= 4; anything else is a warning and the
// default), else kMaxBakedGroundSamples. Tests lower it to give a small field the decimated ground
// of a large one (a 513^2 bake read every 4th sample) through the scene's own path, in process or
// in the shipped editor and player; not a scene key: the limit is the first frame's budget.
std::uint64_t baked_ground_limit();
// Sets baked_ground_limit() for this process until the object goes away (tests; not thread-safe:
// set it before opening a scene).
class ScopedBakedGroundLimit {
 public:
  explicit ScopedBakedGroundLimit(std::uint64_t max_samples);
  ~ScopedBakedGroundLimit();
  ScopedBakedGroundLimit(const ScopedBakedGroundLimit&) = delete;
  ScopedBakedGroundLimit& operator=(const ScopedBakedGroundLimit&) = delete;

 private:
  std::uint64_t previous_;
};

// What reading the ground cost (tests and logs).
struct BakedGroundRead {
  std::uint64_t bytes = 0;    // height tile bytes read
  bool overview = false;      // read from the file's overview
};

// The file's ground heights [m] as a height grid. Errors name the file (and the height tile):
// kNotFound, kCorrupt, kUnsupported (another version: "re-bake it with `sylva-bake terrain`", or a
// program built without the terrain module), kInvalidArgument (a file without heights). A
// version-2 file (no overview) above max_samples is read from every tile, with a log line saying
// that re-baking makes it faster.
Result<MapGrid> read_baked_ground(const std::filesystem::path& file, std::uint64_t max_samples = baked_ground_limit(),
                                  BakedGroundRead* read = nullptr);

}  // namespace sylva::scene
