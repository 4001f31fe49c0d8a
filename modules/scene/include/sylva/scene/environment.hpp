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
  // Multiplier of the sky light (ambient) the atmosphere gives (render::derive_sky_lighting).
  // 1 = physical; the old display-value compensation of 1.6 is gone with tone mapping on.
  float ambient = 1.0f;
  glm::vec3 color{1.0f, 1.0f, 1.0f};  // linear RGB straight overhead; the atmosphere reddens it lower
  float fog_density = 4.0e-4f;  // ground haze on top of the air's own aerial perspective [1/m]
  float fog_height_falloff = 0.0f;  // haze thinning with height [1/m], 0 = uniform

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
  // Render into an HDR target and tone-map it (ACES + sRGB, issue 19). Materials are linear
  // albedos; the sky and sun are physical (render/atmosphere.hpp). Off: modules' linear HDR
  // values are written to the display unencoded (only for tests that read raw values).
  bool tone_map = true;
  // Exposure kExposure, photographic ("sunny 16"): albedo 0.18 lit by the default sun
  // (intensity 3) at 45 deg plus the sky reaches ~0.19 before the curve, ~0.57 in sRGB (middle
  // grey); a white face under the overhead sun ~1.5 (sRGB ~0.95); the clear zenith sky with a
  // 28 deg sun (40, 73, 124)/255 (measured, ground.json looking up).
  static constexpr float kExposure = 0.5f;
  render::ToneMapSettings tone{.exposure = kExposure};  // render/tone_mapping.hpp
  // Samples per pixel of the colour passes: 1 = off; 2, 4, 8 = MSAA, resolved (before tone
  // mapping) into the caller's target. Leaves and slices switch to alpha-to-coverage on
  // multisampled targets (vegetation AlphaMode::kAuto), so their edges get fractional coverage.
  int msaa_samples = 4;

  template <class V>
  void visit(V& v) {
    v(shadows, "shadows");
    v(msaa_samples, "msaa_samples", {.min = 1, .max = 8, .help = "Samples per pixel (1 off, 2, 4 or 8 MSAA)"});
    v(tone_map, "tone_map", {.help = "Render in HDR and tone-map to the display (off: raw linear values)"});
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
