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

// Grounds above this many samples are read every 2nd, 4th, ... sample (8193^2 floats = 256 MiB,
// the generator's largest ground): a 16385^2 bake gives a 4 m ground of a 2 m field.
inline constexpr std::uint64_t kMaxBakedGroundSamples = std::uint64_t{8193} * 8193;

// The file's ground heights [m] as a height grid. Errors name the file (and the height tile):
// kNotFound, kCorrupt, kUnsupported (another version: "re-bake it with `sylva-bake terrain`", or a
// program built without the terrain module), kInvalidArgument (a file without heights).
Result<MapGrid> read_baked_ground(const std::filesystem::path& file, std::uint64_t max_samples = kMaxBakedGroundSamples);

}  // namespace sylva::scene
