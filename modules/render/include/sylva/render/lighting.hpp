#pragma once
// The light every module shades with in a frame: sun, ambient and fog (DESIGN.md §2b
// "Lighting"). Colours are linear RGB; directions are unit vectors in world space, y up.
// Shaders receive it through render/lib/lighting.glsl (uniforms named in set_lighting_uniforms).

#include <glm/glm.hpp>

namespace sylva::render {

// Unit vector toward the sun for an azimuth (radians, 0 = toward -z/north, positive toward +x)
// and an elevation above the horizon (radians, pi/2 = straight up).
glm::vec3 sun_direction(float azimuth, float elevation);

struct Lighting {
  glm::vec3 sun_direction = glm::normalize(glm::vec3(0.4f, 0.6f, -0.5f));  // toward the sun
  glm::vec3 sun_color{1.0f, 0.95f, 0.85f};   // radiance scale, linear RGB
  float sun_intensity = 3.0f;                // multiplier on sun_color
  glm::vec3 ambient{0.25f, 0.3f, 0.38f};     // sky ambient, linear RGB
  glm::vec3 horizon_color{0.72f, 0.80f, 0.88f};  // sky gradient at the horizon
  glm::vec3 zenith_color{0.22f, 0.42f, 0.75f};   // sky gradient straight up
  glm::vec3 ground_color{0.30f, 0.28f, 0.25f};   // below the horizon
  glm::vec3 fog_color{0.70f, 0.78f, 0.86f};
  float fog_density = 1.5e-4f;               // exponential fog [1/m], 0 = no fog
  float fog_height_falloff = 0.0f;           // [1/m], 0 = uniform fog

  template <class V>
  void visit(V& v) {
    v(sun_direction, "sun_direction", {.help = "Unit vector toward the sun (world, y up)"});
    v(sun_color, "sun_color", {.min = 0.0f, .max = 100.0f, .help = "Sun colour, linear RGB"});
    v(sun_intensity, "sun_intensity", {.min = 0.0f, .max = 100.0f, .help = "Sun brightness multiplier"});
    v(ambient, "ambient", {.min = 0.0f, .max = 100.0f, .help = "Ambient sky light, linear RGB"});
    v(horizon_color, "horizon_color", {.min = 0.0f, .max = 100.0f, .help = "Sky colour at the horizon"});
    v(zenith_color, "zenith_color", {.min = 0.0f, .max = 100.0f, .help = "Sky colour straight up"});
    v(ground_color, "ground_color", {.min = 0.0f, .max = 100.0f, .help = "Sky colour below the horizon"});
    v(fog_color, "fog_color", {.min = 0.0f, .max = 100.0f, .help = "Fog colour, linear RGB"});
    v(fog_density, "fog_density", {.min = 0.0f, .max = 1.0f, .unit = "1/m", .help = "Exponential fog density"});
    v(fog_height_falloff, "fog_height_falloff",
      {.min = 0.0f, .max = 1.0f, .unit = "1/m", .help = "Fog thinning with height, 0 = uniform"});
  }
};

// Fog transmittance for a ray of `distance` metres (CPU twin of fog.glsl's fog_factor with no
// height falloff): exp(-density * distance), in [0, 1].
float fog_transmittance(float density, float distance);

}  // namespace sylva::render
