// Sky gradient and sun disk from the SylvaLighting block. Include as "render/lib/sky.glsl".
// CPU twin of sky_gradient: sylva::render::sky_gradient (sky.hpp); keep them identical.
#ifndef SYLVA_RENDER_SKY_GLSL
#define SYLVA_RENDER_SKY_GLSL

#include "render/lib/lighting.glsl"

// Gradient for a unit world direction: horizon -> zenith above (square-root ramp, so the
// horizon band is narrow), horizon -> ground over the first ~7 degrees below.
vec3 sky_gradient(vec3 dir) {
  float y = clamp(dir.y, -1.0, 1.0);
  if (y >= 0.0) return mix(sylva_horizon_color.rgb, sylva_zenith_color.rgb, sqrt(y));
  return mix(sylva_horizon_color.rgb, sylva_ground_color.rgb, clamp(-y * 8.0, 0.0, 1.0));
}

// Sun disk (about 0.5 degrees across, soft edge) plus a glow around it that fades within a
// few degrees (no tone mapping yet, so it must not saturate the whole view).
vec3 sun_glow(vec3 dir) {
  float c = dot(dir, sun_direction());
  float disk = smoothstep(0.99998, 0.99999, c);
  float glow = pow(max(c, 0.0), 1024.0) * 0.25 + pow(max(c, 0.0), 32.0) * 0.03;
  return sun_radiance() * (disk * 20.0 + glow);
}

vec3 sky_color(vec3 dir) { return sky_gradient(dir) + sun_glow(dir); }

#endif
