// grass/far.glsl: the far-field records and fades (mirrors <sylva/grass/far_field.hpp>).
#ifndef SYLVA_GRASS_FAR_GLSL
#define SYLVA_GRASS_FAR_GLSL

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

#endif
