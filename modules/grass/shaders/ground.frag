#version 450 core
// grass/ground.frag: seed 003 §2.5 far grass: a top-view grass texture whose (equalised noise)
// alpha is thresholded by density * fade per pixel, so neighbouring areas of different density
// join without seams and the layer appears texel by texel as it fades in.
#include "grass/far.glsl"
#include "render/lib/lighting.glsl"
#include "render/lib/fog.glsl"
#include "render/lib/shadows.glsl"

layout(binding = 0) uniform sampler2D u_ground;
layout(binding = 1) uniform sampler2D u_density;

uniform vec3 u_camera;
uniform vec4 u_fades;        // mid, mid_fade, far, far_fade
uniform float u_texture_scale;
uniform vec2 u_origin_xz;    // blade-set origin modulo the texture repeat
uniform vec2 u_map_min;      // density map rectangle, blade-set local x/z
uniform vec2 u_map_size;
uniform vec3 u_base_color;
uniform vec3 u_tip_color;
uniform int u_receive_shadows;  // sun term times the render core's cascaded shadows
uniform vec3 u_coverage;     // x tau_side, y tau_top, z gain (far_field.hpp coverage model)

in vec3 g_local;
in vec3 g_rel_pos;
in vec3 g_normal;

out vec4 o_color;

void main() {
  vec2 m = (g_local.xz - u_map_min) / u_map_size;
  if (any(lessThan(m, vec2(0.0))) || any(greaterThan(m, vec2(1.0)))) discard;
  // Image rows run along +z and uploads flip rows: v = 1 at the rectangle's min z.
  float density = texture(u_density, vec2(m.x, 1.0 - m.y)).r;
  float fade = grass_ground_fade(length(g_local - u_camera), u_fades);
  vec4 t = texture(u_ground, (g_local.xz + u_origin_xz) / u_texture_scale);
  vec3 n = normalize(g_normal);
  float s = clamp(abs(dot(normalize(g_rel_pos), n)), 0.05, 1.0);
  float cot_elevation = sqrt(max(1.0 - s * s, 0.0)) / s;
  float cover = 1.0 - exp(-u_coverage.z * (u_coverage.y + u_coverage.x * cot_elevation));
  if (!(t.a < density * fade * cover)) discard;
  vec3 albedo = mix(u_base_color, u_tip_color, 0.55) * t.rgb * 1.4;
  float lit = u_receive_shadows != 0 ? sylva_shadow(g_rel_pos, n) : 1.0;
  vec3 color = albedo * (sun_radiance() * (0.5 * max(dot(n, sun_direction()), 0.0) + 0.1) * lit + hemisphere_ambient(n) * 0.35);
  o_color = vec4(apply_fog(color, g_rel_pos), 1.0);
}
