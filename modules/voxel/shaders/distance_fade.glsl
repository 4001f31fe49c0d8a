// The edge of a voxel world's view: geometry fades into the sky colour between u_fade.x and
// u_fade.y blocks of horizontal distance from the camera (the classic voxel game's fog end at
// the view distance), and the horizon skirt (horizon.vert) covers everything farther in the same
// colour, so neither the world's edge nor the void behind it is ever seen.
#ifndef SYLVA_VOXEL_DISTANCE_FADE_GLSL
#define SYLVA_VOXEL_DISTANCE_FADE_GLSL
#include "render/lib/sky.glsl"

uniform vec2 u_fade;  // horizontal distance where the fade starts / is complete [blocks]

// The sky toward a point, taken at the horizon for points below it: a point beyond the view
// distance melts into the horizon band, not into the sky's dark ground colour.
vec3 voxel_horizon_color(vec3 rel_pos) {
  vec3 d = vec3(rel_pos.x, max(rel_pos.y, 0.0), rel_pos.z);
  float len = length(d);
  return sky_color(len > 0.0 ? d / len : vec3(0.0, 0.0, -1.0));
}

vec3 voxel_distance_fade(vec3 color, vec3 rel_pos) {
  float f = smoothstep(u_fade.x, u_fade.y, length(rel_pos.xz));
  // Nearer than the fade's start nothing changes (mix(c, h, 0) == c exactly): skip the sky
  // look-up there, which llvmpipe otherwise runs for every pixel of the world (issue #18).
  if (f <= 0.0) return color;
  return mix(color, voxel_horizon_color(rel_pos), f);
}

#endif
