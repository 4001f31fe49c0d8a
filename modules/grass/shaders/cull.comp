#version 450 core
// grass/cull.comp: per-blade culling of the visible tiles (the GPU twin of cull_blade() in
// src/culling.cpp). Survivors are appended to the visible list and counted into the indirect
// draw command (one GL_PATCHES vertex per blade; draw_batches.comp splits it into sub-draws);
// culls are tallied by reason for statistics.
#include "grass/blade.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = GRASS_BLADES_BINDING) readonly buffer Blades { Blade blades[]; };
layout(std430, binding = GRASS_VISIBLE_BINDING) writeonly buffer Visible { uint visible[]; };
layout(std430, binding = GRASS_JOBS_BINDING) readonly buffer Jobs { TileJob jobs[]; };
layout(std430, binding = GRASS_COMMAND_BINDING) buffer Command { GRASS_COMMAND_MEMBERS };

uniform vec4 u_planes[4];     // left, right, bottom, top (blade-set local)
uniform vec3 u_camera;        // blade-set local
uniform vec3 u_forward;
uniform float u_ppr;          // pixels per radian
uniform vec4 u_thinning;      // start, near_distance, min_keep, enabled
uniform vec4 u_cull;          // x density_scale, y width_compensation, z frustum on, w orientation on
uniform vec2 u_orientation;   // x threshold, y max px
uniform vec4 u_tess;          // x max level, y pixels per segment, z distance law, w spacing (blade.glsl grass_tess_level)

shared uint s_counts[6];

bool sphere_outside(vec3 c, float r) {
  for (int i = 0; i < 4; ++i) {
    if (dot(u_planes[i].xyz, c) + u_planes[i].w < -r) return true;
  }
  return dot(u_forward, c - u_camera) < -r;
}

// 0 visible, 1 density, 2 distance, 3 frustum, 4 orientation
uint cull(Blade b) {
  float rank = b.attr.x;
  float density_scale = u_cull.x;
  if (!(rank < density_scale)) return 1u;
  vec3 v0 = b.v0.xyz;
  float d = length(v0 - u_camera);
  float keep = grass_distance_keep(d, u_thinning) * density_scale;
  if (!(rank < keep)) return 2u;
  float half_width = 0.5 * b.v2.w * grass_width_scale(keep, u_cull.y);
  if (u_cull.z > 0.5) {
    vec3 v1 = grass_drawn_control(b);  // the drawn curve's hull (seed 001 eq. 2.4 jitter)
    vec3 lo = min(min(v0, v1), b.v2.xyz);
    vec3 hi = max(max(v0, v1), b.v2.xyz);
    vec3 c = 0.5 * (lo + hi);
    float r = 0.5 * length(hi - lo) + half_width;
    if (sphere_outside(c, r)) return 3u;
  }
  if (u_cull.w > 0.5 && d > 0.0) {
    vec3 view_dir = (v0 - u_camera) / d;
    float c = abs(dot(view_dir, grass_width_dir(b.up.xyz, b.v0.w)));
    if (c > u_orientation.x) {
      float edge_px = 2.0 * half_width * sqrt(max(1.0 - c * c, 0.0)) * u_ppr / d;
      if (edge_px < u_orientation.y) return 4u;
    }
  }
  return 0u;
}

uint segments_of(Blade b) {
  float level = grass_tess_level(b.v0.xyz, grass_drawn_control(b), b.v2.xyz, b.v1.w, u_camera, u_ppr, u_tess, u_thinning.y);
  return uint(grass_segments(level, u_tess.w));
}

void main() {
  if (gl_LocalInvocationIndex < 6u) s_counts[gl_LocalInvocationIndex] = 0u;
  barrier();
  TileJob job = jobs[gl_WorkGroupID.x];
  for (uint i = gl_LocalInvocationID.x; i < job.count; i += gl_WorkGroupSize.x) {
    uint index = job.first + i;
    Blade b = blades[index];
    uint r = cull(b);
    if (r == 0u) {
      uint slot = atomicAdd(draw_count, 1u);
      if (slot < capacity) {
        visible[slot] = index;
      } else {
        atomicAdd(overflow, 1u);
      }
      atomicAdd(s_counts[5], segments_of(b));
    } else {
      atomicAdd(s_counts[r], 1u);
    }
    atomicAdd(s_counts[0], 1u);
  }
  barrier();
  if (gl_LocalInvocationIndex == 0u) {
    atomicAdd(considered, s_counts[0]);
    atomicAdd(culled_density, s_counts[1]);
    atomicAdd(culled_distance, s_counts[2]);
    atomicAdd(culled_frustum, s_counts[3]);
    atomicAdd(culled_orientation, s_counts[4]);
    atomicAdd(segments, s_counts[5]);
  }
}
