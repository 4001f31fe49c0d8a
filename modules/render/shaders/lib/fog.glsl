// Aerial perspective: the air (Rayleigh + aerosols of the atmosphere, thinning with height)
// plus an optional ground haze, both fading a surface toward the sky colour of its view
// direction. Include as "render/lib/fog.glsl". CPU twin of the haze term:
// sylva::render::fog_transmittance; of the sky it fades into: sylva::render::sky_radiance.
#ifndef SYLVA_RENDER_FOG_GLSL
#define SYLVA_RENDER_FOG_GLSL

#include "render/lib/lighting.glsl"
#include "render/lib/sky.glsl"

// Mean density along the ray relative to the density at the camera for an exponential layer
// exp(-k y): (1 - exp(-k dy)) / (k dy), dy = rel.y; k dy clamped so exp cannot overflow.
float layer_along(float k, float dy) {
  float kdy = clamp(k * dy, -60.0, 60.0);
  return abs(kdy) > 1.0e-4 ? (1.0 - exp(-kdy)) / kdy : 1.0;
}

// Share of the surface colour that passes the ground haze, in [0, 1].
// rel_pos = fragment position - camera position (camera-relative, metres).
// Density at world height y is density * exp(-falloff * (y - camera_y)).
float fog_transmittance(vec3 rel_pos) {
  return clamp(exp(-sylva_fog.a * length(rel_pos) * layer_along(sylva_params.x, rel_pos.y)), 0.0, 1.0);
}

// Optical depth of the air itself (per channel): Rayleigh and aerosol extinction with their
// scale heights, world y taken as the altitude above sea level (clamped at 0).
vec3 air_optical_depth(vec3 rel_pos) {
  float d = length(rel_pos);
  float cam_y = max(sylva_params.y, 0.0);
  float rayleigh = exp(-sylva_rayleigh.w * cam_y) * d * layer_along(sylva_rayleigh.w, rel_pos.y);
  float mie = exp(-sylva_mie.y * cam_y) * d * layer_along(sylva_mie.y, rel_pos.y);
  return sylva_rayleigh.rgb * rayleigh + sylva_mie.x * mie;
}

// Transmittance of the air itself (per channel).
vec3 air_transmittance(vec3 rel_pos) { return exp(-air_optical_depth(rel_pos)); }

// The surface colour seen through the air and haze: what passes, plus the light scattered in,
// which tends to the sky radiance of the same direction far away (Hillaire 2020 sec. 5.4
// uses a froxel volume; a ray as long as the scene's depth sees the sky's own colour at its
// end, so here in-scattering = sky * (1 - transmittance)): far terrain meets the horizon in
// exactly the sky's colour.
vec3 apply_fog(vec3 color, vec3 rel_pos) {
  float len = length(rel_pos);
  vec3 dir = len > 0.0 ? rel_pos / len : vec3(0.0, 0.0, -1.0);
  vec3 t = air_transmittance(rel_pos) * fog_transmittance(rel_pos);
  // Near surfaces (under 0.2 % in-scattering, below half a display step) skip the sky look-up.
  if (min(t.r, min(t.g, t.b)) > 0.998) return color * t;
  return color * t + atmosphere_radiance(dir) * (1.0 - t);
}

// apply_fog split for evaluation at a vertex (the terrain's per-vertex aerial perspective): the
// extinction of air and haze per metre along the view ray (optical depth / distance, per
// channel), which depends on the ray's direction and varies smoothly across a triangle, so a
// vertex shader evaluates and interpolates it. air_from_vertex multiplies it by the pixel's own
// distance and applies the exponential, the near-surface cut-off and the sky look-up per pixel:
// interpolating the transmittance itself missed by up to 4/255 on the far shore of the shipped
// lake, the optical depth by 23/255 where a big near triangle's vertices are far from the camera
// and its inside is not, and the sky radiance by 3/255 along the horizon, where the sky table's
// rows go with sqrt(dir.y).
vec3 air_extinction(vec3 rel_pos) {
  float len = length(rel_pos);
  vec3 depth = air_optical_depth(rel_pos) + sylva_fog.a * len * layer_along(sylva_params.x, rel_pos.y);
  return len > 0.0 ? depth / len : vec3(0.0);
}

vec3 air_from_vertex(vec3 color, vec3 rel_pos, vec3 extinction) {
  float len = length(rel_pos);
  vec3 t = exp(-extinction * len);
  if (min(t.r, min(t.g, t.b)) > 0.998) return color * t;
  vec3 dir = len > 0.0 ? rel_pos / len : vec3(0.0, 0.0, -1.0);
  return color * t + atmosphere_radiance(dir) * (1.0 - t);
}

#endif
