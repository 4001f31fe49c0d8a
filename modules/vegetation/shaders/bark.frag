#version 450 core
// Bark: procedural albedo and normal map (tangent space x around the branch, y along it), sun
// diffuse + a weak specular lobe (shadowed by the render core's cascades), hemisphere ambient, fog.
#include "render/lib/fog.glsl"
#include "render/lib/shadows.glsl"
#include "vegetation/lib/leaf_alpha.glsl"

in vec3 v_rel;
in vec3 v_normal;
in vec3 v_axis;
in vec2 v_uv;
flat in float v_fade;
in vec3 v_hash_position;

layout(binding = 4) uniform sampler2D u_bark_albedo;
layout(binding = 5) uniform sampler2D u_bark_normal;
uniform float u_bark_specular;

out vec4 o_color;

void main() {
  // LOD transitions: dithered fade on the rest position (derivatives before the discard).
  float fade_threshold = sylva_hashed_threshold(v_hash_position * 1.37 + 11.0);
  if (v_fade < fade_threshold) discard;
  vec3 n = normalize(v_normal);
  vec3 b = v_axis - dot(v_axis, n) * n;
  b = length(b) > 1.0e-6 ? normalize(b) : vec3(0.0, 1.0, 0.0);
  vec3 t = cross(b, n);
  vec3 nts = texture(u_bark_normal, v_uv).xyz * 2.0 - 1.0;
  vec3 N = normalize(t * nts.x + b * nts.y + n * nts.z);
  if (!gl_FrontFacing) N = -N;
  vec3 albedo = texture(u_bark_albedo, v_uv).rgb;
  vec3 V = normalize(-v_rel);
  vec3 L = sun_direction();
  vec3 geometric = gl_FrontFacing ? n : -n;
  float shadow = sylva_shadow(v_rel, geometric);  // 1 when the host bound no shadow maps
  vec3 color = shade_diffuse(albedo, N, shadow) + sun_radiance() * (shadow * u_bark_specular * blinn_phong(N, V, L, 24.0) * lambert(N, L));
  o_color = vec4(apply_fog(color, v_rel), 1.0);
}
