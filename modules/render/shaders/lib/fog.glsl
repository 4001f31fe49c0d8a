// Distance fog with optional exponential height falloff, using the SylvaLighting block.
// Include as "render/lib/fog.glsl". CPU twin (uniform fog): sylva::render::fog_transmittance.
#ifndef SYLVA_RENDER_FOG_GLSL
#define SYLVA_RENDER_FOG_GLSL

#include "render/lib/lighting.glsl"

// Share of the surface colour that reaches the eye through the fog, in [0, 1].
// rel_pos = fragment position - camera position (camera-relative, metres).
// Density at world height y is density * exp(-falloff * (y - camera_y)); the optical depth
// along the ray has the closed form density * d * (1 - exp(-k dy)) / (k dy).
float fog_transmittance(vec3 rel_pos) {
  float density = sylva_fog.a;
  float k = sylva_params.x;
  float d = length(rel_pos);
  float along = 1.0;
  float kdy = k * rel_pos.y;
  if (abs(kdy) > 1.0e-4) along = (1.0 - exp(-kdy)) / kdy;
  return clamp(exp(-density * d * along), 0.0, 1.0);
}

// Fog colour seen along a view direction: brighter toward the sun (forward scattering).
vec3 fog_color(vec3 view_dir) {
  float toward_sun = pow(max(dot(view_dir, sun_direction()), 0.0), 8.0);
  return sylva_fog.rgb + sun_radiance() * (0.08 * toward_sun);
}

vec3 apply_fog(vec3 color, vec3 rel_pos) {
  float len = length(rel_pos);
  vec3 dir = len > 0.0 ? rel_pos / len : vec3(0.0, 0.0, -1.0);
  return mix(fog_color(dir), color, fog_transmittance(rel_pos));
}

#endif
