#pragma once
// Placing trees on the ground (a core HeightField, so the module never depends on terrain).
// GL-free and deterministic for a seed.
//
//  * place_poisson_disk: Bridson's algorithm ("Fast Poisson disk sampling in arbitrary
//    dimensions", SIGGRAPH 2007 sketch) over the field's extent: no two trees closer than
//    min_distance, no large gaps. An optional density map thins the samples (a sample is kept with
//    probability equal to the map value there), so painted clearings stay empty.
//  * place_by_density: world-anchored stratified sampling: the world is cut into cells of
//    1 / sqrt(density) metres; each cell holds at most one tree, kept with probability
//    density_map(x) and jittered inside the cell. Every random number is a hash of (seed, cell),
//    so a region places the same trees whatever field or extent it is computed for.
// Both reject ground steeper than max_slope_deg, sink the trunk base by `sink` metres into the
// ground, and give each tree a random yaw, scale, animation phase, season offset (the seed's
// per-instance seasonCoord term, §4.6) and colour variation.
//
// Density map: any 1-4 channel image stretched over the field extent (u along x, v along z, image
// row 0 at the field's max z like a map seen from above), channel 0 in [0, 1], bilinear.
// Failure: invalid settings (kInvalidArgument naming the parameter), an empty field or map
// (kInvalidArgument), more than max_instances trees (kLimit naming the count).

#include <sylva/core/height_field.hpp>
#include <sylva/core/image.hpp>
#include <sylva/core/params.hpp>
#include <sylva/core/result.hpp>
#include <sylva/vegetation/animation.hpp>

#include <cstdint>
#include <vector>

namespace sylva::vegetation {

struct PlacementSettings {
  float min_distance = 6.0f;        // Poisson disk radius [m]
  float density = 0.015f;           // trees per square metre where the density map is 1 (stratified)
  float max_slope_deg = 35.0f;      // steeper ground stays bare
  float scale_min = 0.85f;          // uniform random scale range
  float scale_max = 1.15f;
  float sink = 0.1f;                // trunk base below the ground [m]
  float time_offset_range = 100.0f; // animation phase range [s]
  float season_spread = 0.06f;      // season offset in [-spread, 0] (instances lag by up to this)
  float color_variation = 0.04f;    // per-instance colour variation amplitude (linear RGB)
  std::uint32_t seed = 1;
  std::size_t max_instances = 200000;

  template <class V>
  void visit(V& v) {
    v(min_distance, "min_distance", {.min = 0.05, .max = 1000.0, .unit = "m", .help = "Smallest distance between two trees", .rebuild = Rebuild::kOffline});
    v(density, "density", {.min = 1e-6, .max = 10.0, .unit = "1/m^2", .help = "Trees per square metre at density 1", .rebuild = Rebuild::kOffline});
    v(max_slope_deg, "max_slope_deg", {.min = 0.0, .max = 90.0, .unit = "deg", .help = "Steepest ground that carries trees", .rebuild = Rebuild::kOffline});
    v(scale_min, "scale_min", {.min = 0.01, .max = 100.0, .help = "Smallest random scale", .rebuild = Rebuild::kOffline});
    v(scale_max, "scale_max", {.min = 0.01, .max = 100.0, .help = "Largest random scale", .rebuild = Rebuild::kOffline});
    v(sink, "sink", {.min = 0.0, .max = 10.0, .unit = "m", .help = "Trunk base below the ground", .rebuild = Rebuild::kOffline});
    v(time_offset_range, "time_offset_range", {.min = 0.0, .max = 100.0, .unit = "s", .help = "Range of per-tree animation phases", .rebuild = Rebuild::kOffline});
    v(season_spread, "season_spread", {.min = 0.0, .max = 1.0, .help = "Range of per-tree season offsets", .rebuild = Rebuild::kOffline});
    v(color_variation, "color_variation", {.min = 0.0, .max = 1.0, .help = "Per-tree colour variation amplitude", .rebuild = Rebuild::kOffline});
    v(seed, "seed", {.min = 0.0, .max = 4294967295.0, .help = "Random seed of the placement", .rebuild = Rebuild::kOffline});
    v(max_instances, "max_instances", {.min = 1.0, .max = 1.0e7, .help = "Cap on the number of trees", .rebuild = Rebuild::kOffline});
  }
};

Result<std::vector<TreeInstance>> place_poisson_disk(const HeightField& ground, const PlacementSettings& settings,
                                                      const Image* density_map = nullptr);
Result<std::vector<TreeInstance>> place_by_density(const HeightField& ground, const Image& density_map,
                                                    const PlacementSettings& settings);

// The density map value at world (x, z) over the field's extent (bilinear, clamped), for tests.
float density_at(const HeightField& ground, const Image& density_map, double x, double z);

}  // namespace sylva::vegetation
