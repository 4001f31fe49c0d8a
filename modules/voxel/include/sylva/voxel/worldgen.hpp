#pragma once
// Procedural world generation, deterministic for a seed (seed 004 names the biomes but gives no
// algorithm, §7; this is ours). Terrain height from fBm noise; biomes from two slow noise fields,
// temperature and humidity; flora per biome: L-system trees and bushes (instanced plants, not
// voxels) and grass tufts and flowers (alpha-cut blocks).
//
//                 dry             medium           wet          (humidity)
//   hot           savanna         savanna          jungle
//   temperate     shrubland       plains           oak forest
//   cold          plains          birch forest     birch forest
//
// generate() is a pure function of (settings, chunk coordinate): any thread, any order, same
// result (tested with 1 and several workers). Plants are placed on a jittered global grid per
// species so spacing and placement never depend on chunk borders; a plant belongs to the chunk
// that holds the block it stands on.

#include <sylva/core/noise.hpp>
#include <sylva/core/params.hpp>
#include <sylva/core/result.hpp>
#include <sylva/voxel/block.hpp>
#include <sylva/voxel/chunk.hpp>
#include <sylva/voxel/coords.hpp>
#include <sylva/voxel/flora.hpp>
#include <sylva/voxel/plant.hpp>
#include <sylva/voxel/species.hpp>

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace sylva::voxel {

struct WorldGenSettings {
  std::uint64_t seed = 1;
  double base_height = 20.0;       // blocks: mean ground level
  double height_amplitude = 18.0;  // blocks: +- terrain relief
  double terrain_scale = 160.0;    // blocks per noise cell of the first terrain octave
  int terrain_octaves = 5;
  double climate_scale = 420.0;    // blocks per cell of the temperature / humidity fields
  double snow_line = 34.0;         // blocks: ground above is snow
  float flora_density = 1.0f;      // multiplies every plant and tuft probability
  int variants_per_species = 12;   // cached plant models per species (seed §4.7)

  template <class V>
  void visit(V& v) {
    v(seed, "seed", {.help = "World seed: same seed, same world", .rebuild = Rebuild::kOffline});
    v(base_height, "base_height", {.min = -1e6, .max = 1e6, .unit = "blocks", .help = "Mean ground level", .rebuild = Rebuild::kOffline});
    v(height_amplitude, "height_amplitude", {.min = 0.0, .max = 512.0, .unit = "blocks", .help = "Terrain relief above and below the mean", .rebuild = Rebuild::kOffline});
    v(terrain_scale, "terrain_scale", {.min = 4.0, .max = 1e5, .unit = "blocks", .help = "Size of the largest hills", .rebuild = Rebuild::kOffline, .log_scale = true});
    v(terrain_octaves, "terrain_octaves", {.min = 1, .max = 10, .help = "Noise layers of the terrain", .rebuild = Rebuild::kOffline});
    v(climate_scale, "climate_scale", {.min = 16.0, .max = 1e6, .unit = "blocks", .help = "Size of biome regions", .rebuild = Rebuild::kOffline, .log_scale = true});
    v(snow_line, "snow_line", {.min = -1e6, .max = 1e6, .unit = "blocks", .help = "Height above which the ground is snow", .rebuild = Rebuild::kOffline});
    v(flora_density, "flora_density", {.min = 0.0, .max = 8.0, .help = "Multiplier of all plant and grass densities", .rebuild = Rebuild::kOffline});
    v(variants_per_species, "variants_per_species", {.min = 1, .max = 256, .help = "Cached plant models per species (seed 004 §4.7)", .rebuild = Rebuild::kOffline});
  }
};

struct GeneratedChunk {
  ChunkCoord coord;
  Chunk blocks;
  std::vector<PlantInstance> plants;
};

// Most blocks the plant variant caches of one world may hold in the species' worst case
// (species.hpp), 32 bytes each: 512 MiB.
inline constexpr std::size_t kMaxCachedPlantParts = std::size_t{16} << 20;

class WorldGenerator {
 public:
  // Builds the plant variant caches from the seed (seed §4.7). `species` is a table read for
  // `palette` (species.hpp); null: the shipped table. Errors: a settings value out of range
  // (naming voxel.worldgen.<field>), a plant cache above kMaxCachedPlantParts blocks in the
  // species' worst case, or a grammar that fails to expand (naming the table and species).
  static Result<std::shared_ptr<const WorldGenerator>> create(const WorldGenSettings& settings,
                                                              const BlockPalette& palette = BlockPalette::standard(),
                                                              std::shared_ptr<const SpeciesTable> species = nullptr);

  const WorldGenSettings& settings() const { return settings_; }
  const BlockPalette& palette() const { return *palette_; }

  // Climate in [0, 1] and the biome of a block column.
  float temperature(std::int64_t x, std::int64_t z) const;
  float humidity(std::int64_t x, std::int64_t z) const;
  Biome biome(std::int64_t x, std::int64_t z) const;
  // Highest solid block of a column.
  std::int64_t ground_height(std::int64_t x, std::int64_t z) const;

  // Thread-safe and deterministic.
  GeneratedChunk generate(const ChunkCoord& c) const;

  const SpeciesTable& species() const { return *species_; }
  const PlantVariants& variants(SpeciesIndex s) const { return variants_[s]; }
  // Block laid by output array `output` of a species' model (air for unused outputs).
  BlockId part_block(SpeciesIndex s, int output) const;

 private:
  WorldGenerator() = default;
  void place_plants(const ChunkCoord& c, GeneratedChunk& out) const;

  WorldGenSettings settings_;
  const BlockPalette* palette_ = nullptr;
  FbmSettings terrain_, temperature_, humidity_;
  std::shared_ptr<const SpeciesTable> species_;
  std::vector<PlantVariants> variants_;  // by species index
  // Where each species grows: jittered grid spacing (blocks) and the chance a grid cell holds one.
  struct FloraRule {
    Biome biome;
    SpeciesIndex species;
    int spacing;
    float chance;
  };
  std::vector<FloraRule> flora_;
  struct Blocks {
    BlockId stone, dirt, grass, dry_grass, sand, snow, tall_grass, flowers;
  } b_{};
};

}  // namespace sylva::voxel
