#pragma once
// The environment every module of a scene shares: sun (position, colour, fog), clock (time of
// day, season, latitude) and, in scene_document.hpp, the one WindSettings. The scene turns these
// into one render::Lighting per frame; trees and grass never keep their own sun.
//
// The sun either stays where azimuth_deg / elevation_deg put it, or (follow_clock) is placed by
// the clock with the standard solar-position approximation (declination 23.44 deg * sin(2 pi
// season), hour angle 15 deg per hour from solar noon); see sun_from_clock().

#include <sylva/core/params.hpp>
#include <sylva/render/lighting.hpp>
#include <sylva/render/shadow_cascades.hpp>
#include <sylva/render/tone_mapping.hpp>

#include <glm/glm.hpp>

namespace sylva::scene {

struct SunSettings {
  bool follow_clock = false;    // true: position from environment.time_of_day_h / season / latitude
  float azimuth_deg = 35.0f;    // compass heading of the sun: 0 = toward -z (north), 90 = +x (east)
  float elevation_deg = 28.0f;  // above the horizon; 90 = straight up
  float intensity = 3.0f;       // multiplier of the sun colour at full daylight
  // Multiplier of the render core's sky ambient. Above 1 by default because the modules write
  // display values (tone mapping off, SceneRenderSettings): with the core's linear ambient
  // (~0.3) a surface facing away from the sun or in shadow came out near black (scenes/ground.json).
  float ambient = 1.6f;
  glm::vec3 color{1.0f, 0.95f, 0.85f};  // linear RGB at high elevation (reddened toward the horizon)
  float fog_density = 4.0e-4f;  // exponential distance fog [1/m]
  float fog_height_falloff = 0.0f;  // fog thinning with height [1/m], 0 = uniform

  template <class V>
  void visit(V& v) {
    v(follow_clock, "follow_clock", {.help = "Place the sun from the time of day, season and latitude"});
    v(azimuth_deg, "azimuth_deg", {.min = -360.0, .max = 360.0, .unit = "deg", .help = "Sun heading (0 = north/-z, 90 = east/+x)"});
    v(elevation_deg, "elevation_deg", {.min = -10.0, .max = 90.0, .unit = "deg", .help = "Sun height above the horizon"});
    v(intensity, "intensity", {.min = 0.0, .max = 100.0, .help = "Sun brightness in full daylight"});
    v(color, "color", {.min = 0.0, .max = 10.0, .unit = "linear RGB", .help = "Sun colour high in the sky"});
    v(ambient, "ambient", {.min = 0.0, .max = 20.0, .help = "Sky (ambient) light multiplier: how bright shadowed sides are"});
    v(fog_density, "fog_density", {.min = 0.0, .max = 0.1, .unit = "1/m", .help = "Distance fog density", .log_scale = true});
    v(fog_height_falloff, "fog_height_falloff", {.min = 0.0, .max = 1.0, .unit = "1/m", .help = "Fog thinning with height"});
  }
};

struct EnvironmentSettings {
  float time_of_day_h = 10.0f;  // local solar time [h], 12 = noon
  float season = 0.15f;         // fraction of the year from the spring equinox: 0 spring, 0.25 summer,
                                // 0.5 autumn, 0.75 winter (vegetation colours follow it too)
  float latitude_deg = 45.0f;   // for the sun's path; negative = southern hemisphere

  template <class V>
  void visit(V& v) {
    v(time_of_day_h, "time_of_day_h", {.min = 0.0, .max = 24.0, .unit = "h", .help = "Local solar time, 12 = noon"});
    v(season, "season", {.min = 0.0, .max = 1.0, .help = "Year fraction from the spring equinox (0.25 summer, 0.5 autumn, 0.75 winter)"});
    v(latitude_deg, "latitude_deg", {.min = -90.0, .max = 90.0, .unit = "deg", .help = "Latitude of the scene"});
  }
};

// How the scene is rendered as a whole (DESIGN.md §2b): the sun's cascaded shadow maps every
// module casts into and receives from, and the HDR -> display tone mapping at the end.
struct SceneRenderSettings {
  render::ShadowSettings shadows;      // render/shadow_cascades.hpp
  // Render into an HDR target and tone-map it (ACES + sRGB by default). Off by default: the
  // modules' materials (terrain, grass, trees, voxels) are authored as display values, and through
  // the HDR path they come out washed out (measured on scenes/forest.json); switch it on per
  // scene once materials are linear.
  bool tone_map = false;
  render::ToneMapSettings tone;        // render/tone_mapping.hpp
  // Samples per pixel of the colour passes: 1 = off; 2, 4, 8 = MSAA, resolved (before tone
  // mapping) into the caller's target. Leaves and slices switch to alpha-to-coverage on
  // multisampled targets (vegetation AlphaMode::kAuto), so their edges get fractional coverage.
  int msaa_samples = 4;

  template <class V>
  void visit(V& v) {
    v(shadows, "shadows");
    v(msaa_samples, "msaa_samples", {.min = 1, .max = 8, .help = "Samples per pixel (1 off, 2, 4 or 8 MSAA)"});
    v(tone_map, "tone_map", {.help = "Render in HDR and tone-map to the display (off: modules write display values directly)"});
    v(tone, "tone");
  }
};

struct SunPosition {
  float azimuth_deg = 0.0f;    // compass heading, [0, 360)
  float elevation_deg = 0.0f;  // [-90, 90]
};

// Solar position for a solar time, a season (year fraction from the spring equinox) and a
// latitude. At noon the sun is due south (180) in the northern hemisphere and due north (0) in
// the southern one; at the equinox it rises due east (90).
SunPosition sun_from_clock(float time_of_day_h, float season, float latitude_deg);

// The sun position a scene uses (clock or fixed).
SunPosition sun_position(const SunSettings& sun, const EnvironmentSettings& environment);

// The frame's Lighting: sun direction, colour dimmed and reddened near the horizon (off below
// it), sky colours darkening toward night, fog.
render::Lighting make_lighting(const SunSettings& sun, const EnvironmentSettings& environment);

}  // namespace sylva::scene
