#version 450 core
// Slice bake, bark (slice_bake.hpp): unshaded albedo, slice-space normal (bark normal map as in
// bark.frag), the level-1 branch and the x coordinates into three render targets.
in vec3 v_normal;  // object space (the bake draws an identity instance)
in vec3 v_axis;
in vec2 v_uv;
flat in int v_level1;
flat in int v_root;
in vec2 v_x;

layout(binding = 4) uniform sampler2D u_bark_albedo;
layout(binding = 5) uniform sampler2D u_bark_normal;
uniform vec3 u_slice_axis;    // a_j
uniform vec3 u_slice_normal;  // n_j (toward the bake camera)

layout(location = 0) out vec4 o_color;
layout(location = 1) out vec4 o_normal;
layout(location = 2) out vec4 o_branch;

void main() {
  vec3 n = normalize(v_normal);
  vec3 b = v_axis - dot(v_axis, n) * n;
  b = length(b) > 1.0e-6 ? normalize(b) : vec3(0.0, 1.0, 0.0);
  vec3 t = cross(b, n);
  vec3 nts = texture(u_bark_normal, v_uv).xyz * 2.0 - 1.0;
  vec3 N = normalize(t * nts.x + b * nts.y + n * nts.z);
  if (!gl_FrontFacing) N = -N;
  vec3 ns = vec3(dot(N, u_slice_axis), N.y, dot(N, u_slice_normal));
  o_color = vec4(texture(u_bark_albedo, v_uv).rgb, 1.0);
  o_normal = vec4(ns * 0.5 + 0.5, 0.0);
  o_branch = vec4(float(v_level1), v_x.x, v_x.y, float(v_root + 1));
}
