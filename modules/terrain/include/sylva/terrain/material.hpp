#pragma once
// The terrain material (issue 19): layers (lowland grass, alpine meadow, dirt, scree, rock, snow,
// sand at a water level) placed by ALTITUDE IN METRES, slope and curvature, with procedural
// detail at three scales. GL-free: the settings, the altitude lines a climate gives, and the CPU
// data the renderer uploads (the tiling detail noise and the per-sample shape: normal and
// curvature). The shader is shaders/material.glsl; the README ("Material") states the tuning.
//
// Altitude lines. Snow, rock and tree lines are given for latitude 45 degrees in high summer and
// scaled by the latitude factor F(phi) = 1 + cos(2 phi) = 2 cos^2(phi): 1 at 45, 2 at the
// equator, 0.5 at 60, 0 at the poles. Measured lines follow it within ~15 %: snow line Alps
// (46 N) ~2800-3000 m, Norway (61 N) ~1500 m, tropics ~4800-5500 m; tree line Alps ~2100 m,
// Scandinavia (68 N) ~500 m, tropics ~3800-4000 m. Only snow moves with the season: it drops by
// min(1, winter_snow_drop x |sin phi| / sin 45) of its summer altitude at the end of winter
// (season 0.9 north, 0.4 south) and is highest at the end of summer (0.4 north), a cosine in
// between. At the equator the snow line does not move; with the defaults it comes down to
// ~560 m at 45 N, ~300 m at 50 N and ~30 m at 60 N (Alps, Germany, southern Finland in
// February).

#include <sylva/core/height_field.hpp>
#include <sylva/core/image.hpp>
#include <sylva/core/params.hpp>

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace sylva::terrain {

struct MaterialSettings {
  // Altitude of the world's y = 0 above sea level [m]: 0 for real elevation data (its heights are
  // altitudes); a generated field sits at base_altitude_m + its own heights.
  float base_altitude_m = 0.0f;
  // Lines at latitude 45 deg in high summer [m above sea level]; latitude scales them (see above).
  float snow_line_m = 2800.0f;   // lowest altitude where snow lies on gentle slopes
  float rock_line_m = 2500.0f;   // above it bare rock and scree replace alpine meadow
  float tree_line_m = 2000.0f;   // above it lowland grass turns into alpine meadow
  float winter_snow_drop = 0.8f; // share of the summer snow line the snow descends at winter's end
  float water_level_m = 0.0f;    // altitude of a water surface [m above sea level]
  float beach_height_m = 0.0f;   // sand up to this many metres above the water level; 0 = no sand
  float rock_slope_deg = 38.0f;  // slopes steeper than this are rock at any altitude [deg]
  float curvature_radius_m = 24.0f;  // neighbourhood of the curvature (hollow vs ridge) [m]
  float detail_scale_m = 2.5f;   // tile of the finest detail noise [m]; coarser scales x5.3, x28
  float detail_strength = 1.0f;  // albedo and normal detail, 0 = flat layers
  glm::vec3 grass_color{0.075f, 0.11f, 0.032f};    // linear albedo
  glm::vec3 meadow_color{0.13f, 0.13f, 0.055f};
  glm::vec3 dirt_color{0.16f, 0.115f, 0.075f};
  glm::vec3 scree_color{0.26f, 0.245f, 0.22f};
  glm::vec3 rock_color{0.2f, 0.185f, 0.17f};
  glm::vec3 snow_color{0.82f, 0.86f, 0.92f};
  glm::vec3 sand_color{0.42f, 0.36f, 0.25f};

  template <class V>
  void visit(V& v) {
    v(base_altitude_m, "base_altitude_m", {.min = -1.0e4, .max = 1.0e4, .unit = "m",
      .help = "Altitude above sea level of world height 0 (0 for real elevation data)"});
    v(snow_line_m, "snow_line_m", {.min = 0.0, .max = 1.0e4, .unit = "m",
      .help = "Snow line at 45 deg latitude in summer (scaled by latitude, lowered by season)"});
    v(rock_line_m, "rock_line_m", {.min = 0.0, .max = 1.0e4, .unit = "m",
      .help = "Altitude at 45 deg latitude above which rock and scree replace meadow"});
    v(tree_line_m, "tree_line_m", {.min = 0.0, .max = 1.0e4, .unit = "m",
      .help = "Altitude at 45 deg latitude above which grass turns into alpine meadow"});
    v(winter_snow_drop, "winter_snow_drop", {.min = 0.0, .max = 1.0,
      .help = "Share of the summer snow line the snow descends at the end of winter (at 45 deg)"});
    v(water_level_m, "water_level_m", {.min = -1.0e4, .max = 1.0e4, .unit = "m", .help = "Altitude of a water surface"});
    v(beach_height_m, "beach_height_m", {.min = 0.0, .max = 1.0e3, .unit = "m",
      .help = "Sand up to this height above the water level (0 = no sand)"});
    v(rock_slope_deg, "rock_slope_deg", {.min = 0.0, .max = 90.0, .unit = "deg", .help = "Slopes steeper than this are rock"});
    v(curvature_radius_m, "curvature_radius_m", {.min = 0.0, .max = 1.0e4, .unit = "m",
      .help = "Neighbourhood that tells hollows from ridges", .rebuild = Rebuild::kGpu});
    v(detail_scale_m, "detail_scale_m", {.min = 0.05, .max = 100.0, .unit = "m", .help = "Tile of the finest detail noise",
      .log_scale = true});
    v(detail_strength, "detail_strength", {.min = 0.0, .max = 2.0, .help = "Albedo and normal detail strength"});
    v(grass_color, "grass_color", {.min = 0.0, .max = 1.0, .unit = "linear albedo"});
    v(meadow_color, "meadow_color", {.min = 0.0, .max = 1.0, .unit = "linear albedo"});
    v(dirt_color, "dirt_color", {.min = 0.0, .max = 1.0, .unit = "linear albedo"});
    v(scree_color, "scree_color", {.min = 0.0, .max = 1.0, .unit = "linear albedo"});
    v(rock_color, "rock_color", {.min = 0.0, .max = 1.0, .unit = "linear albedo"});
    v(snow_color, "snow_color", {.min = 0.0, .max = 1.0, .unit = "linear albedo"});
    v(sand_color, "sand_color", {.min = 0.0, .max = 1.0, .unit = "linear albedo"});
  }
};

// Where the scene is: the environment's latitude and season (scene/environment.hpp).
struct Climate {
  float latitude_deg = 45.0f;  // [-90, 90], negative = southern hemisphere
  float season = 0.4f;         // year fraction from the (northern) spring equinox, [0, 1)
};

// The lines the shader uses, in world heights (altitude - base_altitude_m) [m].
struct MaterialLines {
  float snow = 0.0f;
  float rock = 0.0f;
  float tree = 0.0f;
  float water = 0.0f;
};

// F(phi) = 1 + cos(2 phi), in [0, 2]; latitude clamped to [-90, 90].
float latitude_factor(float latitude_deg);
// The lines for a climate (formulas in the header comment). Non-finite climate values are taken
// as Climate's defaults; the latitude is clamped to [-90, 90].
MaterialLines material_lines(const MaterialSettings& settings, const Climate& climate);

// The tiling detail noise (size x size, 4 float channels, every channel periodic with the tile):
// r, g: two uncorrelated fBm, mean 0, standard deviation 0.4 (albedo variation, layer breakup);
// b, a: the gradient (d/du, d/dv) of a third fBm, the detail relief, scaled to unit RMS.
// size: a power of two >= 16 (asserted). Deterministic for a seed.
Image make_detail_noise(int size, std::uint32_t seed);

// Per-sample shape of a field, 4 floats per sample, row-major like the field: x, z components of
// the unit normal (central differences), curvature = (mean height within radius_m - height) /
// radius_m (> 0 in hollows, < 0 on ridges; 0 when radius_m < spacing / 2), and a macro variation
// (3-octave fBm of ~400 m features at the sample's position from the field's origin, in [-1, 1],
// sd ~0.25) for the samples
// of [x0, x1) x [z0, z1) (clamped to the field): `out` is resized to that rectangle, row-major.
// Memory beyond `out`: one double per sample of the rectangle grown by the radius, so callers
// with huge fields compute bands of rows.
void compute_terrain_shape(const HeightField& field, float radius_m, int x0, int z0, int x1, int z1,
                           std::vector<float>& out);

}  // namespace sylva::terrain
