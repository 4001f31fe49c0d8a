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

// Seed 003 §3.4 motion by colour: c = tex (k0 + k1 s), s = sin(freq t + phase), k0 = 1,
// k1 = motion.x; motion.y = 2 pi freq t (field_color.hpp color_motion_uniform), phase01 in [0, 1).
// motion.x = 0 gives exactly 1 (off).
float grass_color_pulse(vec2 motion, float phase01) { return 1.0 + motion.x * sin(motion.y + 6.2831853 * phase01); }

// Per-blade tip dryness from a uniform random in [0, 1): 45 % of the blades turn partly to straw.
float grass_blade_dryness(float r) { return 0.8 * smoothstep(0.55, 1.0, r); }

// Albedo at height v along a blade: root colour to tip colour, the upper part turning to straw.
vec3 grass_albedo(vec3 base, vec3 tip, float v, float dryness) {
  vec3 top = mix(tip, GRASS_STRAW, dryness * smoothstep(0.3, 1.0, v));
  return mix(base, top, pow(v, 0.8));
}

// The mean albedo a far representation shows (the blades' colour at GRASS_SEEN_V, mean dryness).
vec3 grass_mean_albedo(vec3 base, vec3 tip) { return grass_albedo(base, tip, GRASS_SEEN_V, GRASS_MEAN_DRYNESS); }

// Mean over phi in [lo, lo + pi] of max(a cos(phi) + b, 0), a >= 0 (the integral of a cos + b
// over the parts of the interval where it is positive, divided by pi).
float grass_half_mean(float a, float b, float lo) {
  const float PI = 3.14159265;
  float hi = lo + PI;
  if (b >= a) return a * (sin(hi) - sin(lo)) / PI + b;
  if (b <= -a) return 0.0;
  float p = acos(clamp(-b / a, -1.0, 1.0));  // positive on [2 pi k - p, 2 pi k + p]
  float sum = 0.0;
  for (int k = -1; k <= 1; ++k) {
    float x0 = max(lo, 2.0 * PI * float(k) - p), x1 = min(hi, 2.0 * PI * float(k) + p);
    if (x1 > x0) sum += a * (sin(x1) - sin(x0)) + b * (x1 - x0);
  }
  return sum / PI;
}

// The blades' mean light, for the far representations of a field of upright blades. blade.frag
// turns each blade's card normal towards the eye (two-sided) and lights it with n_lit =
// normalize(0.6 n + 0.4 up) = 0.832 n + 0.555 up. With the sun at sine s above the horizon
// (cosine c) and phi the azimuth of the blade's visible face from the sun's, n_lit . l = a cos(phi)
// + b, a = 0.832 c, b = 0.555 s; the visible faces' azimuths are uniform over the half circle
// centred on the direction to the eye (psi). So the mean diffuse is grass_half_mean(a, b, psi -
// pi/2), and the light through the blades, max(-n . l, 0) times blade.frag's view factor (0.5 +
// 0.5 max(view . l, 0)) and `translucency`, is grass_half_mean(c, 0, psi + pi/2) times those. The
// sky is gathered with n_lit.y = 0.555. A flat layer lit by n . l instead was as bright as the
// blades only for one sun elevation, and much brighter when looking against a low sun.
// `view` runs from the eye to the point.
vec3 grass_canopy_light(vec3 view, float translucency, float shadow, float ambient) {
  vec3 l = sun_direction();
  float s = clamp(l.y, -1.0, 1.0);
  float c = sqrt(max(1.0 - s * s, 0.0));
  vec2 sun_h = l.xz, eye_h = -view.xz;
  float psi = (dot(sun_h, sun_h) > 1e-12 && dot(eye_h, eye_h) > 1e-12)
                  ? atan(sun_h.x * eye_h.y - sun_h.y * eye_h.x, dot(sun_h, eye_h)) : 0.0;
  float diffuse = grass_half_mean(0.832 * c, 0.555 * s, psi - 1.5707963);
  float toward_sun = 0.5 + 0.5 * max(dot(view, l), 0.0);
  vec3 through = translucency * toward_sun * grass_half_mean(c, 0.0, psi + 1.5707963) * vec3(1.0, 1.05, 0.55) * step(0.0, s);
  return sun_radiance() * (diffuse + through) * shadow + hemisphere_ambient(vec3(0.0, 0.555, 0.0)) * ambient;
}

#endif
