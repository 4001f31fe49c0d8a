#version 450 core
// grass/clump.frag: strand-by-strand density and fade (a strand is drawn when its graded
// threshold is below the fade), coloured like the blades.
#include "render/lib/lighting.glsl"
#include "render/lib/fog.glsl"
#include "render/lib/shadows.glsl"

layout(binding = 0) uniform sampler2D u_atlas;

uniform vec3 u_base_color;
uniform vec3 u_tip_color;
uniform int u_receive_shadows;  // sun term times the render core's cascaded shadows

in vec3 c_rel_pos;
in vec2 c_uv;
in float c_v;
flat in vec3 c_color;
flat in float c_fade;
flat in vec3 c_normal;

out vec4 o_color;

void main() {
  vec4 t = texture(u_atlas, c_uv);
  if (!(t.a < c_fade)) discard;
  float lum = t.r;
  vec3 albedo = mix(u_base_color, u_tip_color, clamp(lum * 1.2 - 0.1, 0.0, 1.0)) * c_color;
  vec3 n = c_normal;
  float ao = mix(0.35, 1.0, smoothstep(0.0, 1.0, c_v));
  float lit = u_receive_shadows != 0 ? sylva_shadow(c_rel_pos, n) : 1.0;
  vec3 color = albedo * (sun_radiance() * (0.6 * max(dot(n, sun_direction()), 0.0) + 0.15) * lit + hemisphere_ambient(n) * 0.35) * ao;
  o_color = vec4(apply_fog(color, c_rel_pos), 1.0);
}
