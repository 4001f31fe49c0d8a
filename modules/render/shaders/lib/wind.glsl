// render/lib/wind.glsl: the shared wind field on the GPU (DESIGN.md §2 "shared world services").
//
// The GLSL twin of sylva::WindField::evaluate(const WindFrame&, vec3 local) in
// modules/core/src/wind.cpp: same operations, same order, same noise (render/lib/noise.glsl), so
// trees and grass on the GPU move in exactly the wind the CPU sees (agreement to float rounding is
// tested by modules/render/tests/wind_glsl_gl_test.cpp). See <sylva/core/wind.hpp> for the model.
//
// Usage: upload WindField::frame(time, camera_origin).gpu (sylva::WindGpuParams, 112 bytes,
// std140/std430 compatible) into a uniform block or storage buffer and call
//
//   layout(std140, binding = N) uniform SylvaWindBlock { SylvaWind u_wind; };
//   vec3 v = sylva_wind(u_wind, local_position);   // m/s, at world = camera_origin + local
//
// `local` is the camera-relative position in metres (the frame was built for that origin).
// All time dependence (gust phase, advection offset) is folded into the frame on the CPU in double
// precision, so t = 1e7 s and positions 1e6 m from the world origin stay smooth.

#ifndef SYLVA_RENDER_WIND_GLSL
#define SYLVA_RENDER_WIND_GLSL

#include "render/lib/noise.glsl"

struct SylvaWind {
  vec4 direction_strength;  // xyz unit direction, w strength [m/s]
  vec4 gust;                // x gust amplitude [m/s], y gust phase offset [cells]
  vec4 gust_spatial;        // xyz direction / (gust front speed * gust period) [cells/m]
  vec4 turbulence;          // x amplitude [m/s], y vertical ratio, z 1/scale [cells/m], w octaves
  vec4 turbulence_offset;   // xyz offset of the origin inside its cell
  ivec4 cells;              // xyz turbulence cell of the origin, w gust cell
  uvec4 seeds;              // x gust seed, yzw turbulence seeds of the x, y, z components
};

// fBm with lacunarity 2 and persistence 0.5 on the split lattice (cell << k) + offset * 2^k.
float sylva_wind_fbm(ivec3 cell, vec3 offset, int octaves, uint seed) {
  float sum = 0.0;
  float amp = 1.0;
  float norm = 0.0;
  float scale = 1.0;
  for (int k = 0; k < octaves; ++k) {
    ivec3 c = ivec3(uvec3(cell) << uint(k));
    sum += amp * sylva_noise3(c, offset * scale, sylva_octave_seed(seed, k));
    norm += amp;
    amp *= 0.5;
    scale *= 2.0;
  }
  return sum / norm;
}

// Wind velocity in m/s at world position frame_origin + local.
vec3 sylva_wind(SylvaWind w, vec3 local) {
  vec3 d = w.direction_strength.xyz;

  // Directional part with gusts travelling downwind.
  float s = w.gust.y - dot(local, w.gust_spatial.xyz);
  float gust = 0.5 + 0.5 * sylva_noise1(w.cells.w, s, w.seeds.x);
  float speed = w.direction_strength.w + w.gust.x * gust;

  // Turbulence advected with the wind.
  vec3 offset = w.turbulence_offset.xyz + local * w.turbulence.z;
  ivec3 cell = w.cells.xyz;
  int octaves = int(w.turbulence.w);
  vec3 turb = vec3(sylva_wind_fbm(cell, offset, octaves, w.seeds.y),
                   w.turbulence.y * sylva_wind_fbm(cell, offset, octaves, w.seeds.z),
                   sylva_wind_fbm(cell, offset, octaves, w.seeds.w));
  return d * speed + w.turbulence.x * turb;
}

#endif  // SYLVA_RENDER_WIND_GLSL
