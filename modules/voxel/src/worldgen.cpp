#include <sylva/voxel/worldgen.hpp>

#include <sylva/core/assert.hpp>
#include <sylva/core/rng.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace sylva::voxel {

std::string_view to_string(Biome b) {
  for (const auto& n : enum_names(Biome{})) {
    if (n.value == b) return n.name;
  }
  return "?";
}

namespace {

// Grass tufts and flowers per column.
struct GroundCover {
  float grass;
  float flowers;
};
constexpr GroundCover kCover[kBiomeCount] = {
    {0.35f, 0.0f},   // jungle
    {0.12f, 0.0f},   // savanna
    {0.40f, 0.05f},  // plains
    {0.10f, 0.0f},   // shrubland
    {0.20f, 0.01f},  // birch forest
    {0.20f, 0.02f},  // oak forest
};

std::uint32_t lo32(std::int64_t v) { return static_cast<std::uint32_t>(static_cast<std::uint64_t>(v)); }
std::uint32_t hi32(std::int64_t v) { return static_cast<std::uint32_t>(static_cast<std::uint64_t>(v) >> 32); }

// A hash of a column, a purpose tag and the world seed, as a float in [0, 1).
float column_random(std::int64_t x, std::int64_t z, std::uint32_t tag, std::uint32_t seed) {
  const std::uint32_t h = hash_u32(lo32(x), hi32(x) ^ tag, lo32(z), hi32(z) ^ seed);
  return static_cast<float>(h >> 8) * (1.0f / 16777216.0f);
}

std::int64_t floor_div(std::int64_t a, std::int64_t b) {
  std::int64_t q = a / b;
  if ((a % b != 0) && ((a < 0) != (b < 0))) --q;
  return q;
}

Status check(bool ok, const char* field, const std::string& what) {
  if (ok) return ok_status();
  return make_error(ErrorCode::kInvalidArgument, fmt::format("voxel.worldgen.{}: {}", field, what));
}

}  // namespace

Result<std::shared_ptr<const WorldGenerator>> WorldGenerator::create(const WorldGenSettings& settings,
                                                                     const BlockPalette& palette,
                                                                     std::shared_ptr<const SpeciesTable> species) {
  SYLVA_TRY(check(std::isfinite(settings.base_height), "base_height", "must be finite"));
  SYLVA_TRY(check(settings.height_amplitude >= 0.0 && settings.height_amplitude <= 512.0, "height_amplitude",
                  fmt::format("{} outside [0, 512]", settings.height_amplitude)));
  SYLVA_TRY(check(settings.terrain_scale >= 4.0 && settings.terrain_scale <= 1e5, "terrain_scale",
                  fmt::format("{} outside [4, 1e5]", settings.terrain_scale)));
  SYLVA_TRY(check(settings.terrain_octaves >= 1 && settings.terrain_octaves <= 10, "terrain_octaves",
                  fmt::format("{} outside [1, 10]", settings.terrain_octaves)));
  SYLVA_TRY(check(settings.climate_scale >= 16.0 && settings.climate_scale <= 1e6, "climate_scale",
                  fmt::format("{} outside [16, 1e6]", settings.climate_scale)));
  SYLVA_TRY(check(std::isfinite(settings.snow_line), "snow_line", "must be finite"));
  SYLVA_TRY(check(settings.flora_density >= 0.0f && settings.flora_density <= 8.0f, "flora_density",
                  fmt::format("{} outside [0, 8]", settings.flora_density)));
  SYLVA_TRY(check(settings.variants_per_species >= 1 && settings.variants_per_species <= 256, "variants_per_species",
                  fmt::format("{} outside [1, 256]", settings.variants_per_species)));

  std::shared_ptr<WorldGenerator> g(new WorldGenerator());
  g->settings_ = settings;
  g->palette_ = &palette;
  const auto seed32 = static_cast<std::uint32_t>(settings.seed ^ (settings.seed >> 32));
  g->terrain_.octaves = settings.terrain_octaves;
  g->terrain_.frequency = static_cast<float>(1.0 / settings.terrain_scale);
  g->terrain_.seed = hash_u32(seed32, 1u);
  g->temperature_.octaves = 3;
  g->temperature_.frequency = static_cast<float>(1.0 / settings.climate_scale);
  g->temperature_.seed = hash_u32(seed32, 2u);
  g->humidity_ = g->temperature_;
  g->humidity_.seed = hash_u32(seed32, 3u);

  auto block = [&palette](const char* name) -> Result<BlockId> { return palette.find(name); };
  if (!species) {
    auto shipped = builtin_species_table(palette);
    if (!shipped.ok()) return shipped.error();
    if (!shipped->rejected.empty()) return shipped->rejected.front();  // a palette without the shipped blocks
    species = std::make_shared<const SpeciesTable>(std::move(*shipped));
  }
  if (species->palette != &palette) {
    return make_error(ErrorCode::kInvalidArgument, fmt::format("{}: species table read for another block palette", species->source));
  }
  if (species->species.size() > kMaxSpecies) {
    return make_error(ErrorCode::kLimit, fmt::format("{}: {} species, above the limit of {}", species->source,
                                                     species->species.size(), kMaxSpecies));
  }
  // Every species caches variants_per_species models (seed §4.7): bound their blocks before
  // building them from the species' worst case (species.hpp).
  double cached_parts = 0.0;
  for (const SpeciesDef& def : species->species) cached_parts += def.worst_parts * settings.variants_per_species;
  if (cached_parts > static_cast<double>(kMaxCachedPlantParts)) {
    return make_error(ErrorCode::kLimit,
                      fmt::format("{}: the plant cache may hold {:.3g} blocks ({} variants per species), above the limit of {}; "
                                  "lower voxel.worldgen.variants_per_species or the species' derivations",
                                  species->source, cached_parts, settings.variants_per_species, kMaxCachedPlantParts));
  }
  g->species_ = species;
  g->variants_.reserve(species->species.size());
  for (std::size_t i = 0; i < species->species.size(); ++i) {
    const SpeciesDef& def = species->species[i];
    // The salt is the species' index in the table (the shipped table keeps the order it had as
    // a compiled enum, so the default world is unchanged).
    auto variants = PlantVariants::build(def.lsystem, def.growth, settings.seed, static_cast<std::uint32_t>(i) + 101u,
                                         settings.variants_per_species);
    if (!variants.ok()) {
      return make_error(variants.error().code, fmt::format("{}: species[{}] ({}): {}", species->source, i, def.name,
                                                           variants.error().message));
    }
    g->variants_.push_back(std::move(*variants));
  }
  // Placement rules, biome by biome in biome order, species in table order within a biome.
  for (int b = 0; b < kBiomeCount; ++b) {
    for (std::size_t i = 0; i < species->species.size(); ++i) {
      for (const SpeciesHabitat& h : species->species[i].habitats) {
        if (static_cast<int>(h.biome) == b) g->flora_.push_back({h.biome, static_cast<SpeciesIndex>(i), h.spacing, h.chance});
      }
    }
  }
  const char* names[] = {"stone", "dirt", "grass", "dry_grass", "sand", "snow", "tall_grass", "flowers"};
  BlockId* slots[] = {&g->b_.stone, &g->b_.dirt,  &g->b_.grass,      &g->b_.dry_grass,
                      &g->b_.sand,  &g->b_.snow,  &g->b_.tall_grass, &g->b_.flowers};
  for (int i = 0; i < 8; ++i) {
    auto id = block(names[i]);
    if (!id.ok()) return id.error();
    *slots[i] = *id;
  }
  return std::shared_ptr<const WorldGenerator>(std::move(g));
}

float WorldGenerator::temperature(std::int64_t x, std::int64_t z) const {
  const float f = fbm2(glm::dvec2(static_cast<double>(x), static_cast<double>(z)), temperature_);
  return std::clamp(0.5f + 1.7f * f, 0.0f, 1.0f);
}

float WorldGenerator::humidity(std::int64_t x, std::int64_t z) const {
  const float f = fbm2(glm::dvec2(static_cast<double>(x), static_cast<double>(z)), humidity_);
  return std::clamp(0.5f + 1.7f * f, 0.0f, 1.0f);
}

Biome WorldGenerator::biome(std::int64_t x, std::int64_t z) const {
  const float t = temperature(x, z);
  const float h = humidity(x, z);
  const int ti = t > 0.62f ? 2 : t > 0.38f ? 1 : 0;
  const int hi = h > 0.62f ? 2 : h > 0.38f ? 1 : 0;
  static constexpr Biome kTable[3][3] = {
      {Biome::kPlains, Biome::kBirchForest, Biome::kBirchForest},  // cold
      {Biome::kShrubland, Biome::kPlains, Biome::kOakForest},      // temperate
      {Biome::kSavanna, Biome::kSavanna, Biome::kJungle},          // hot
  };
  return kTable[ti][hi];
}

std::int64_t WorldGenerator::ground_height(std::int64_t x, std::int64_t z) const {
  const float f = fbm2(glm::dvec2(static_cast<double>(x), static_cast<double>(z)), terrain_);
  // A touch of cubic shaping gives flatter lowlands and steeper hills.
  const double shaped = 0.75 * f + 0.9 * f * f * f;
  return static_cast<std::int64_t>(std::floor(settings_.base_height + settings_.height_amplitude * shaped));
}

BlockId WorldGenerator::part_block(SpeciesIndex s, int output) const {
  if (output < 0 || output >= kPlantOutputs || s >= species_->species.size()) return kAir;
  return species_->species[s].blocks[static_cast<std::size_t>(output)];
}

GeneratedChunk WorldGenerator::generate(const ChunkCoord& c) const {
  GeneratedChunk out;
  out.coord = c;
  const BlockPos o = chunk_origin(c);
  const auto seed32 = static_cast<std::uint32_t>(settings_.seed ^ (settings_.seed >> 32));
  std::int64_t heights[kChunkSize][kChunkSize];
  Biome biomes[kChunkSize][kChunkSize];
  std::int64_t hmin = std::numeric_limits<std::int64_t>::max();
  std::int64_t hmax = std::numeric_limits<std::int64_t>::lowest();
  for (int z = 0; z < kChunkSize; ++z) {
    for (int x = 0; x < kChunkSize; ++x) {
      const std::int64_t h = ground_height(o.x + x, o.z + z);
      heights[z][x] = h;
      hmin = std::min(hmin, h);
      hmax = std::max(hmax, h);
    }
  }
  const std::int64_t y0 = o.y;
  const std::int64_t y1 = o.y + kChunkSize - 1;
  if (y0 > hmax + 1) {
    // Only air (tufts stand at most one block above the ground).
  } else if (y1 < hmin - 3) {
    out.blocks = Chunk(b_.stone);
  } else {
    const double sand_below = settings_.base_height - 0.45 * settings_.height_amplitude;
    for (int z = 0; z < kChunkSize; ++z) {
      for (int x = 0; x < kChunkSize; ++x) {
        const std::int64_t h = heights[z][x];
        const std::int64_t wx = o.x + x, wz = o.z + z;
        biomes[z][x] = biome(wx, wz);
        BlockId surface = b_.grass;
        if (static_cast<double>(h) > settings_.snow_line) {
          surface = b_.snow;
        } else if (static_cast<double>(h) < sand_below) {
          surface = b_.sand;
        } else if (biomes[z][x] == Biome::kSavanna || biomes[z][x] == Biome::kShrubland) {
          surface = b_.dry_grass;
        }
        const std::int64_t top = std::min(h, y1);
        for (std::int64_t y = y0; y <= top; ++y) {
          const BlockId id = y == h ? surface : y >= h - 3 ? (surface == b_.sand ? b_.sand : b_.dirt) : b_.stone;
          out.blocks.set(x, static_cast<int>(y - y0), z, id);
        }
        // Grass tufts and flowers on grassy ground.
        if (h + 1 >= y0 && h + 1 <= y1 && (surface == b_.grass || surface == b_.dry_grass)) {
          const GroundCover cover = kCover[static_cast<int>(biomes[z][x])];
          const float r = column_random(wx, wz, 0x7475u, seed32);
          const float d = settings_.flora_density;
          if (r < cover.flowers * d) {
            out.blocks.set(x, static_cast<int>(h + 1 - y0), z, b_.flowers);
          } else if (r < (cover.flowers + cover.grass) * d) {
            out.blocks.set(x, static_cast<int>(h + 1 - y0), z, b_.tall_grass);
          }
        }
      }
    }
    out.blocks.compact();
  }
  if (y0 <= hmax && y1 >= hmin) place_plants(c, out);
  return out;
}

void WorldGenerator::place_plants(const ChunkCoord& c, GeneratedChunk& out) const {
  const BlockPos o = chunk_origin(c);
  const auto seed32 = static_cast<std::uint32_t>(settings_.seed ^ (settings_.seed >> 32));
  for (const FloraRule& rule : flora_) {
    const std::int64_t s = rule.spacing;
    const auto tag = static_cast<std::uint32_t>(rule.species) * 977u + static_cast<std::uint32_t>(rule.biome) * 31u + 5u;
    for (std::int64_t cz = floor_div(o.z, s); cz <= floor_div(o.z + kChunkSize - 1, s); ++cz) {
      for (std::int64_t cx = floor_div(o.x, s); cx <= floor_div(o.x + kChunkSize - 1, s); ++cx) {
        // One candidate per grid cell at a hashed position inside it.
        const std::uint32_t h = hash_u32(lo32(cx), hi32(cx) ^ tag, lo32(cz), hi32(cz) ^ seed32);
        const std::int64_t px = cx * s + static_cast<std::int64_t>(h % static_cast<std::uint32_t>(s));
        const std::int64_t pz = cz * s + static_cast<std::int64_t>((h >> 8) % static_cast<std::uint32_t>(s));
        if (px < o.x || px >= o.x + kChunkSize || pz < o.z || pz >= o.z + kChunkSize) continue;
        if (static_cast<float>(h >> 20) * (1.0f / 4096.0f) >= rule.chance * settings_.flora_density) continue;
        if (biome(px, pz) != rule.biome) continue;
        const std::int64_t ground = ground_height(px, pz);
        if (ground < o.y || ground >= o.y + kChunkSize) continue;
        if (static_cast<double>(ground) > settings_.snow_line ||
            static_cast<double>(ground) < settings_.base_height - 0.45 * settings_.height_amplitude) {
          continue;  // nothing grows on snow or sand
        }
        PlantInstance p;
        p.species = rule.species;
        p.variant = static_cast<std::uint16_t>(variants(rule.species).index_for(px, pz));
        p.yaw_quarters = static_cast<std::uint8_t>((h >> 16) & 3u);
        p.ground = {px, ground, pz};
        // The plant's own block column replaces any tuft there.
        const int lx = local_of(px), lz = local_of(pz);
        if (ground + 1 < o.y + kChunkSize) {
          const int ly = static_cast<int>(ground + 1 - o.y);
          const BlockId above = out.blocks.get(lx, ly, lz);
          if (above == b_.tall_grass || above == b_.flowers) out.blocks.set(lx, ly, lz, kAir);
        }
        out.plants.push_back(p);
      }
    }
  }
}

}  // namespace sylva::voxel
