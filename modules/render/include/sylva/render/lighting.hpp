#pragma once
// The light every module shades with in a frame: sun, ambient and fog (DESIGN.md §2b
// "Lighting"). Colours are linear RGB; directions are unit vectors in world space, y up.
// Shaders receive it through render/lib/lighting.glsl (uniforms named in set_lighting_uniforms).

#include <sylva/render/atmosphere.hpp>

#include <glm/glm.hpp>

namespace sylva::render {

// Unit vector toward the sun for an azimuth (radians, 0 = toward -z/north, positive toward +x)
// and an elevation above the horizon (radians, pi/2 = straight up).
glm::vec3 sun_direction(float azimuth, float elevation);

struct Lighting {
  glm::vec3 sun_direction = glm::normalize(glm::vec3(0.4f, 0.6f, -0.5f));  // toward the sun
  glm::vec3 sun_color{1.0f, 0.95f, 0.85f};   // at the viewer (after the atmosphere), linear RGB
  float sun_intensity = 3.0f;                // multiplier on sun_color
  // Ambient light of an upward-facing surface (engine radiance, atmosphere.hpp). The scene
  // derives it and the four colours below from the atmosphere (derive_sky_lighting, sky.hpp);
  // the sky itself is always drawn from the atmosphere and the sun.
  glm::vec3 ambient{0.25f, 0.3f, 0.38f};
  glm::vec3 horizon_color{0.72f, 0.80f, 0.88f};  // sky radiance at the horizon (azimuth mean)
  glm::vec3 zenith_color{0.22f, 0.42f, 0.75f};   // sky radiance straight up
  glm::vec3 ground_color{0.1125f, 0.126f, 0.1425f};  // ambient of a downward face (ground bounce)
  glm::vec3 fog_color{0.70f, 0.78f, 0.86f};      // clear colour (= horizon_color when derived)
  float fog_density = 1.5e-4f;  // ground haze on top of the air [1/m], 0 = air only
  float fog_height_falloff = 0.0f;           // [1/m], 0 = uniform haze
  AtmosphereSettings atmosphere;             // sky colour and aerial perspective

  template <class V>
  void visit(V& v) {
    v(sun_direction, "sun_direction", {.help = "Unit vector toward the sun (world, y up)"});
    v(sun_color, "sun_color", {.min = 0.0f, .max = 100.0f, .help = "Sun colour, linear RGB"});
    v(sun_intensity, "sun_intensity", {.min = 0.0f, .max = 100.0f, .help = "Sun brightness multiplier"});
    v(ambient, "ambient", {.min = 0.0f, .max = 100.0f, .help = "Ambient sky light, linear RGB"});
    v(horizon_color, "horizon_color", {.min = 0.0f, .max = 100.0f, .help = "Sky colour at the horizon"});
    v(zenith_color, "zenith_color", {.min = 0.0f, .max = 100.0f, .help = "Sky colour straight up"});
    v(ground_color, "ground_color", {.min = 0.0f, .max = 100.0f, .help = "Ambient light of downward faces (ground bounce)"});
    v(fog_color, "fog_color", {.min = 0.0f, .max = 100.0f, .help = "Fog colour, linear RGB"});
    v(fog_density, "fog_density", {.min = 0.0f, .max = 1.0f, .unit = "1/m", .help = "Exponential fog density"});
    v(fog_height_falloff, "fog_height_falloff",
      {.min = 0.0f, .max = 1.0f, .unit = "1/m", .help = "Fog thinning with height, 0 = uniform"});
    v(atmosphere, "atmosphere");
  }
};

// Ground-haze transmittance for a ray of `distance` metres (CPU twin of fog.glsl's
// fog_transmittance with no height falloff; the air's own extinction is separate):
// exp(-density * distance), in [0, 1].
float fog_transmittance(float density, float distance);

}  // namespace sylva::render
