#pragma once
// Biomes, plant species and placed plants: the vocabulary shared by world generation, the world
// store and the renderer.

#include <sylva/core/params.hpp>
#include <sylva/voxel/coords.hpp>

#include <array>
#include <cstdint>
#include <string_view>

namespace sylva::voxel {

enum class Biome : std::uint8_t { kJungle, kSavanna, kPlains, kShrubland, kBirchForest, kOakForest };
inline constexpr int kBiomeCount = 6;
constexpr std::array<EnumName<Biome>, kBiomeCount> enum_names(Biome) {
  return {{{Biome::kJungle, "jungle"},
           {Biome::kSavanna, "savanna"},
           {Biome::kPlains, "plains"},
           {Biome::kShrubland, "shrubland"},
           {Biome::kBirchForest, "birch_forest"},
           {Biome::kOakForest, "oak_forest"}}};
}
std::string_view to_string(Biome b);

// A plant species: an index into the world's species table (species.hpp; the shipped one is
// data/species.json: acacia, birch, oak, jungle, forked_bush, berry_bush, seed §4.5.4, §4.6.1).
using SpeciesIndex = std::uint16_t;

// One plant standing on the block `ground` (its model's origin is that block's centre), turned
// by yaw_quarters * 90 degrees about y.
struct PlantInstance {
  SpeciesIndex species = 0;
  std::uint16_t variant = 0;
  std::uint8_t yaw_quarters = 0;
  BlockPos ground;
  bool operator==(const PlantInstance&) const = default;
};

}  // namespace sylva::voxel
