// grass/color.glsl: albedo and light of grass, shared by the blades, the clumps and the ground
// layer so that seed 003's three levels of detail show one field: same colours, same light, and
// far representations that reproduce the mean of what the blades show (field_color.hpp holds the
// CPU side: patches and clump hues, baked into per-blade, per-clump and per-vertex colours).
#ifndef SYLVA_GRASS_COLOR_GLSL
#define SYLVA_GRASS_COLOR_GLSL

#include "render/lib/lighting.glsl"

// Linear albedo of a dry (straw) grass tip.
const vec3 GRASS_STRAW = vec3(0.46, 0.40, 0.15);
// Mean tip dryness over blades (kMeanTipDryness in field_color.hpp; 0.8 * 0.45 / 2).
const float GRASS_MEAN_DRYNESS = 0.18;
// Where along a blade (0 root, 1 tip) the far representations take the blades' mean colour:
// from a distance the upper half of the blades is what is seen (the rest is hidden by neighbours).
const float GRASS_SEEN_V = 0.7;

// Per-blade tip dryness from a uniform random in [0, 1): 45 % of the blades turn partly to straw.
float grass_blade_dryness(float r) { return 0.8 * smoothstep(0.55, 1.0, r); }

// Albedo at height v along a blade: root colour to tip colour, the upper part turning to straw.
vec3 grass_albedo(vec3 base, vec3 tip, float v, float dryness) {
  vec3 top = mix(tip, GRASS_STRAW, dryness * smoothstep(0.3, 1.0, v));
  return mix(base, top, pow(v, 0.8));
}

// The mean albedo a far representation shows (the blades' colour at GRASS_SEEN_V, mean dryness).
vec3 grass_mean_albedo(vec3 base, vec3 tip) { return grass_albedo(base, tip, GRASS_SEEN_V, GRASS_MEAN_DRYNESS); }

// The blades' mean light, for the far representations (a canopy whose surface normal is `n`).
// blade.frag lights a blade with n_lit = normalize(0.6 n_blade + 0.4 up) = 0.832 n_blade +
// 0.555 up, n_blade horizontal at a uniformly random azimuth phi. With the sun at sine s above
// the surface (cosine c), n_lit . l = a cos(phi) + b, a = 0.832 c, b = 0.555 s, whose mean of
// max(., 0) over phi is b when b >= a, else (b acos(-b / a) + sqrt(a^2 - b^2)) / pi. Light through
// the blades: the mean of max(-n_blade . l, 0) is c / pi, times blade.frag's view factor (~0.6)
// and `translucency`. The sky is gathered with n_lit.y = 0.555. A flat layer lit by n . l instead
// is as bright as the blades only for a sun at ~35 degrees: brighter at noon, darker at dusk.
vec3 grass_canopy_light(vec3 n, float translucency, float shadow, float ambient) {
  vec3 l = sun_direction();
  float s = clamp(dot(n, l), -1.0, 1.0);
  float c = sqrt(max(1.0 - s * s, 0.0));
  float a = 0.832 * c, b = 0.555 * s;
  float diffuse = b >= a ? b : (a <= 1e-6 ? max(b, 0.0) : (b * acos(clamp(-b / a, -1.0, 1.0)) + sqrt(max(a * a - b * b, 0.0))) / 3.14159265);
  vec3 through = translucency * 0.6 * (c / 3.14159265) * vec3(1.0, 1.05, 0.55) * step(0.0, s);
  return sun_radiance() * (diffuse + through) * shadow + hemisphere_ambient(vec3(0.0, 0.555, 0.0)) * ambient;
}

#endif
