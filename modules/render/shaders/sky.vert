#version 450 core
// The sky dome (SkyRenderer, sky_dome.hpp): unit directions around the camera, drawn at depth 0
// (the point at infinity in reversed-Z). Each vertex looks the atmosphere table up
// (atmosphere_sample); sky.frag only applies the phase functions and the sun disk, so the
// per-pixel work on a software rasteriser is a few dozen operations instead of the table's
// eight dynamically indexed block reads and the below-horizon branch.
#include "render/lib/sky.glsl"

// Its x axis points at the sun's azimuth and y up: the rings of columns line up with the
// table's columns whatever the sun's azimuth.
layout(location = 0) in vec3 a_direction;

uniform mat4 u_view_projection;  // projection * view_rotation

out vec3 v_rayleigh;
out vec3 v_mie;
out vec3 v_phase_dir;
out vec3 v_direction;  // for sky_nadir.frag

void main() {
  vec3 sun = sun_direction();
  float sun_h = length(sun.xz);
  vec2 s = sun_h > 1.0e-6 ? sun.xz / sun_h : vec2(0.0, -1.0);
  vec3 dir = vec3(a_direction.x * s.x - a_direction.z * s.y, a_direction.y,
                  a_direction.x * s.y + a_direction.z * s.x);
  SkySample sky = atmosphere_sample(dir);
  v_rayleigh = sky.rayleigh;
  v_mie = sky.mie;
  v_phase_dir = sky.phase_dir;
  if (dir.y < 0.0) {
    // Below the horizon phase_dir is the unit horizon (x, 0, z) / h down to 30 degrees from the
    // nadir: times h it is dir's own (x, 0, z), which interpolates across a triangle to the
    // pixel's exactly (normalized per pixel); nearer the nadir the azimuth fades out anyway.
    // A slightly negative y keeps sun_disk (dir.y < 0: none) off and moves mu by < 1e-5.
    v_phase_dir *= max(length(dir.xz), SYLVA_SKY_NADIR_FADE);
    v_phase_dir.y = min(v_phase_dir.y, -1.0e-5);
  }
  v_direction = dir;
  vec4 clip = u_view_projection * vec4(dir, 0.0);
  // Depth 0 (like the far plane at infinity); directions behind the camera are clipped by
  // gl_ClipDistance, not by the depth range, whose plane z <= w would meet them at w = 0.
  gl_Position = vec4(clip.xy, 0.0, clip.w);
  gl_ClipDistance[0] = clip.w - 1.0e-5;
}
