// grass/far.glsl: the far-field records and fades (mirrors <sylva/grass/far_field.hpp>).
#ifndef SYLVA_GRASS_FAR_GLSL
#define SYLVA_GRASS_FAR_GLSL

#include "render/lib/noise.glsl"

#define GRASS_CLUMPS_BINDING 5
#define GRASS_WIND_UBO_BINDING 1

struct Clump {
  vec4 root;   // xyz root (blade-set local), w rotation [rad]
  vec4 size;   // x width, y height, z rank (wide billboards: strand keep), w atlas cell
  vec4 color;  // rgb colour multiplier, w sway phase
};

float grass_ramp(float d, float a, float b) {
  if (!(b > a)) return d >= b ? 1.0 : 0.0;
  return clamp((d - a) / (b - a), 0.0, 1.0);
}

// fades: x near_distance, y clump_fade_in, z mid_distance, w mid_fade
float grass_clump_fade(float d, vec4 fades) {
  return grass_ramp(d, fades.x - fades.y, fades.x) * (1.0 - grass_ramp(d, fades.z - fades.w, fades.z));
}

// fades: x mid_distance, y mid_fade, z far_distance, w far_fade
float grass_ground_fade(float d, vec4 fades) {
  return grass_ramp(d, fades.x - fades.y, fades.x) * (1.0 - grass_ramp(d, fades.z - fades.w, fades.z));
}

// Seed 003 §2.5 noise sub-region of far tile `tile` (far_field.hpp noise_subregion(), bit-exact
// twin): xy offset in texture repeats, z quarter turns 0..3.
vec3 grass_noise_subregion(ivec2 tile, uint seed) {
  uint h = sylva_hash(tile, seed);
  return vec3(float(h & 0xffffu) / 65536.0, float((h >> 16u) & 0xfffu) / 4096.0, float(h >> 30u));
}

#endif
