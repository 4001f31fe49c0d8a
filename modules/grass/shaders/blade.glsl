// grass/blade.glsl: the blade record and the blade maths shared by the grass compute and
// tessellation shaders. Mirrors <sylva/grass/blade.hpp> and the formulas of
// <sylva/grass/culling.hpp> (same operations in the same order; the GL tests compare them).
#ifndef SYLVA_GRASS_BLADE_GLSL
#define SYLVA_GRASS_BLADE_GLSL

// Storage bindings used by the grass module (render's lighting block is uniform binding 0).
#define GRASS_BLADES_BINDING 0
#define GRASS_VISIBLE_BINDING 1
#define GRASS_JOBS_BINDING 2
#define GRASS_COMMAND_BINDING 3
#define GRASS_SPHERES_BINDING 4
#define GRASS_WIND_UBO_BINDING 1
#define GRASS_BATCHES_BINDING 6  // 5 is far.glsl's clumps

// Members of the per-chunk command block written by cull.comp (std430; mirrored by CommandBlock
// in src/grass_field.cpp). The first four are a DrawArraysIndirectCommand.
#define GRASS_COMMAND_MEMBERS \
  uint draw_count;         /* vertices (= visible blades; may exceed capacity, see overflow) */ \
  uint instance_count;     /* 1 */ \
  uint first_vertex;       /* 0 */ \
  uint base_instance;      /* 0 */ \
  uint considered;         /* blades tested */ \
  uint culled_density; \
  uint culled_distance; \
  uint culled_frustum; \
  uint culled_orientation; \
  uint segments;           /* sum of tessellation segments of the visible blades */ \
  uint capacity;           /* size of the visible list */ \
  uint overflow;           /* blades dropped because the list was full (never expected) */

struct Blade {
  vec4 v0;    // xyz root, w orientation [rad]
  vec4 v1;    // xyz control point, w height [m]
  vec4 v2;    // xyz tip, w width [m]
  vec4 up;    // xyz unit up, w stiffness [1/s]
  vec4 rest;  // xyz rest tip - root, w collision strength
  vec4 attr;  // x rank, y shade random, z packed RGB8 colour, w shape random
};

// One visible tile's work for the compute passes.
struct TileJob {
  uint first;   // first blade
  uint count;   // blades in the tile
  float dt;     // physics time step for this tile [s] (tiles out of view catch up later)
  uint flags;   // bit 0: simulate
};

// Duff et al. 2017 orthonormal frame, rotated so up = +y gives (+x, -z); see blade.cpp.
void grass_tangent_frame(vec3 up, out vec3 t1, out vec3 t2) {
  vec3 n = vec3(up.x, up.z, up.y);
  float s = n.z >= 0.0 ? 1.0 : -1.0;
  float a = -1.0 / (s + n.z);
  float b = n.x * n.y * a;
  vec3 b1 = vec3(1.0 + s * n.x * n.x * a, s * b, -s * n.x);
  vec3 b2 = vec3(b, s + n.y * n.y * a, -n.y);
  t1 = vec3(b1.x, b1.z, b1.y);
  t2 = -vec3(b2.x, b2.z, b2.y);
}

vec3 grass_width_dir(vec3 up, float orientation) {
  vec3 t1, t2;
  grass_tangent_frame(up, t1, t2);
  return cos(orientation) * t1 + sin(orientation) * t2;
}

vec3 grass_front_dir(vec3 up, float orientation) {
  return normalize(cross(grass_width_dir(up, orientation), up));
}

vec3 grass_bezier(vec3 p0, vec3 p1, vec3 p2, float t) {
  vec3 a = p0 + t * (p1 - p0);
  vec3 b = p1 + t * (p2 - p1);
  return a + t * (b - a);
}

// Unnormalised tangent dB/dt / 2.
vec3 grass_bezier_tangent(vec3 p0, vec3 p1, vec3 p2, float t) {
  return mix(p1 - p0, p2 - p1, t);
}

// Seed 001 eq. 2.4 control-point jitter (blade.hpp drawn_control, the CPU twin): a blade with
// attr.w >= 1 is drawn with v1 + up ((r4 - 1) dot(v1 - v0, up)) + r3 (side part of v2 - v0),
// r3 = 0.25 (2 s - 1), r4 = 0.75 + 0.5 fract(4096 s), s = fract(attr.w).
vec3 grass_drawn_control(Blade b) {
  if (!(b.attr.w >= 1.0)) return b.v1.xyz;
  float s = fract(b.attr.w);
  float r3 = 0.25 * (2.0 * s - 1.0);
  float r4 = 0.75 + 0.5 * fract(4096.0 * s);
  vec3 up = b.up.xyz;
  vec3 d = b.v2.xyz - b.v0.xyz;
  vec3 side = d - up * dot(d, up);
  return b.v1.xyz + up * ((r4 - 1.0) * dot(b.v1.xyz - b.v0.xyz, up)) + r3 * side;
}

vec3 grass_unpack_color(float packed_rgb) {
  uint bits = uint(clamp(packed_rgb, 0.0, 16777215.0));
  return vec3(float(bits & 255u), float((bits >> 8u) & 255u), float((bits >> 16u) & 255u)) / 255.0;
}

// --- culling and LOD (culling.hpp) ---
// u_thinning: x thinning_start, y near_distance, z thinning_min_keep, w distance_thinning (0/1)
float grass_distance_keep(float d, vec4 thinning) {
  if (thinning.w < 0.5) return d < thinning.y ? 1.0 : 0.0;
  if (!(d < thinning.y)) return 0.0;
  float start = min(thinning.x, thinning.y);
  if (d <= start) return 1.0;
  float t = (d - start) / max(thinning.y - start, 1e-6);
  return mix(1.0, thinning.z, clamp(t, 0.0, 1.0));
}

// Level along a blade for the tessellator (culling.hpp tessellation_level). tess: x
// max_tess_level, y pixels_per_segment, z law (0 projected size, 1 seed 001 eq. 2.3 distance
// law), w spacing (0 equal: ceil-ed; 1 fractional_even, 2 fractional_odd: not ceil-ed, the
// segments morph, seed 001 pitfall "LOD popping"); near_distance is eq. 2.3's d_max; ppr pixels
// per radian.
float grass_tess_level(vec3 p0, vec3 p1, vec3 p2, float height, vec3 camera, float ppr, vec4 tess, float near_distance) {
  bool ceiled = tess.w < 0.5;
  if (tess.z > 0.5) {
    float raw = tess.x * (1.0 - length(p0 - camera) / max(near_distance, 1e-3));
    return clamp(ceiled ? ceil(raw) : raw, 1.0, max(tess.x, 1.0));
  }
  vec3 mid = grass_bezier(p0, p1, p2, 0.5);
  float d = max(length(mid - camera), 1e-3);
  float px = height * ppr / d;
  float raw = px / max(tess.y, 1e-3);
  return clamp(ceiled ? ceil(raw) : raw, 1.0, max(tess.x, 1.0));
}

// Segments the tessellator makes of `level` (culling.hpp tessellation_segments/spacing_segments).
float grass_segments(float level, float spacing) {
  if (spacing < 0.5) return level;
  if (spacing < 1.5) return 2.0 * ceil(0.5 * clamp(level, 2.0, 64.0));
  return 2.0 * ceil(0.5 * (clamp(level, 1.0, 63.0) + 1.0)) - 1.0;
}

float grass_width_scale(float keep, float compensation) {
  float compensated = 1.0 / max(keep, 0.25);
  return mix(1.0, compensated, clamp(compensation, 0.0, 1.0));
}

#endif
