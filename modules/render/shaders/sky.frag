#version 450 core
// The dome's table colours interpolated, times the phase functions of this pixel's direction
// (the Mie peak around the sun is too sharp to interpolate), plus the sun disk.
#include "render/lib/sky.glsl"

in vec3 v_rayleigh;
in vec3 v_mie;
in vec3 v_phase_dir;
out vec4 o_color;

void main() {
  vec3 dir = normalize(v_phase_dir);
  o_color = vec4(atmosphere_phase_radiance(v_rayleigh, v_mie, dir) + sun_disk(dir), 1.0);
}
