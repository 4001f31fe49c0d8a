#pragma once
// Settings structs used by the params tests: one field of every supported type, nested
// structs, enums declared at namespace scope and nested in a struct, and a non-int enum.

#include <sylva/core/params.hpp>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <array>
#include <cstdint>
#include <string>

namespace fixture {

enum class Criterion { kScreenSpace, kDistance };
constexpr std::array<sylva::EnumName<Criterion>, 2> enum_names(Criterion) {
  return {{{Criterion::kScreenSpace, "screen_space"}, {Criterion::kDistance, "distance"}}};
}

// A one-byte enum with gaps, to check enums are not assumed to be int-sized or dense.
enum class Quality : std::uint8_t { kLow = 1, kHigh = 200 };
inline constexpr sylva::EnumName<Quality> kQualityNames[] = {{Quality::kLow, "low"}, {Quality::kHigh, "high"}};
constexpr std::span<const sylva::EnumName<Quality>> enum_names(Quality) { return kQualityNames; }

struct Lod {
  float morph_fraction = 0.25f;
  int levels = 8;
  template <class V>
  void visit(V& v) {
    v(morph_fraction, "morph_fraction", {.min = 0.f, .max = 1.f, .help = "Share of a LOD range used to morph"});
    v(levels, "levels", {.min = 1, .max = 24});
  }
  bool operator==(const Lod&) const = default;
};

struct Terrain {
  float max_pixel_error = 1.0f;
  double world_scale = 2.5;
  int chunk_dim = 33;
  std::uint32_t seed = 7;
  std::int64_t offset = -5;
  std::uint64_t hash = 12345;
  bool skirts = true;
  std::string height_map = "maps/height.png";
  Criterion criterion = Criterion::kScreenSpace;
  Quality quality = Quality::kLow;
  glm::vec2 uv_scale{1.f, 1.f};
  glm::vec3 sun_dir{0.f, 1.f, 0.f};
  glm::vec4 tint{1.f, 1.f, 1.f, 1.f};
  glm::ivec2 tiles{4, 4};
  glm::dvec3 origin{0.0, 0.0, 0.0};
  glm::uvec3 grid{1u, 2u, 3u};
  Lod lod;

  template <class V>
  void visit(V& v) {
    v(max_pixel_error, "max_pixel_error",
      {.min = 0.05f, .max = 64.f, .unit = "px", .help = "Largest allowed projected height error", .log_scale = true});
    v(world_scale, "world_scale", {.min = 1e-3, .max = 1e4, .unit = "m", .rebuild = sylva::Rebuild::kOffline});
    v(chunk_dim, "chunk_dim", {.min = 3, .max = 1025, .rebuild = sylva::Rebuild::kOffline});
    v(seed, "seed");
    v(offset, "offset", {.min = -1e12, .max = 1e12});
    v(hash, "hash");
    v(skirts, "skirts", {.rebuild = sylva::Rebuild::kGpu});
    v(height_map, "height_map", {.max = 4096, .help = "Height map image path"});
    v(criterion, "criterion");
    v(quality, "quality");
    v(uv_scale, "uv_scale", {.min = 0.f, .max = 100.f, .step = 0.1});
    v(sun_dir, "sun_dir", {.min = -1.f, .max = 1.f});
    v(tint, "tint", {.min = 0.f, .max = 1.f});
    v(tiles, "tiles", {.min = 1, .max = 64});
    v(origin, "origin", {.unit = "m"});
    v(grid, "grid", {.max = 1000});
    v(lod, "lod");
  }
  bool operator==(const Terrain&) const = default;
};

struct Grass {
  enum class Mode { kBlades, kBillboards, kGround };
  friend constexpr std::array<sylva::EnumName<Mode>, 3> enum_names(Mode) {
    return {{{Mode::kBlades, "blades"}, {Mode::kBillboards, "billboards"}, {Mode::kGround, "ground"}}};
  }
  float density = 400.f;
  Mode mode = Mode::kBlades;
  std::string name;

  template <class V>
  void visit(V& v) {
    v(density, "density", {.min = 0.f, .max = 1e5f, .unit = "1/m^2"});
    v(mode, "mode");
    v(name, "name", {.min = 1, .max = 32});
  }
  bool operator==(const Grass&) const = default;
};

// The shape of a scene's settings: module sections nested in one struct.
struct Scene {
  Terrain terrain;
  Grass grass{.name = "meadow"};
  template <class V>
  void visit(V& v) {
    v(terrain, "terrain");
    v(grass, "grass");
  }
  bool operator==(const Scene&) const = default;
};

}  // namespace fixture
