#pragma once
// Biomes, plant species and placed plants: the vocabulary shared by world generation, the world
// store and the renderer.

#include <sylva/voxel/coords.hpp>

#include <cstdint>
#include <string_view>

namespace sylva::voxel {

enum class Biome : std::uint8_t { kJungle, kSavanna, kPlains, kShrubland, kBirchForest, kOakForest };
inline constexpr int kBiomeCount = 6;
std::string_view to_string(Biome b);

// The L-system species of the world (seed §4.5.4, §4.6.1).
enum class Species : std::uint8_t { kAcacia, kBirch, kOak, kJungle, kForkedBush, kBerryBush };
inline constexpr int kSpeciesCount = 6;
std::string_view to_string(Species s);

// One plant standing on the block `ground` (its model's origin is that block's centre), turned
// by yaw_quarters * 90 degrees about y.
struct PlantInstance {
  Species species = Species::kAcacia;
  std::uint16_t variant = 0;
  std::uint8_t yaw_quarters = 0;
  BlockPos ground;
  bool operator==(const PlantInstance&) const = default;
};

}  // namespace sylva::voxel
