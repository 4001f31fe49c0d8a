#version 450 core
// Height and slope material (grass low, rock on steep slopes, snow high), sun + ambient + fog.
// u_tint is white normally; the LOD-colour debug view tints each chunk. Receives the sun's
// cascaded shadows (render/lib/shadows.glsl; the scene binds them every frame).
#include "render/lib/fog.glsl"
#include "render/lib/shadows.glsl"

in vec3 v_rel_position;
in vec3 v_normal;
in float v_height;
out vec4 o_color;

uniform float u_snow_line;  // metres
uniform vec3 u_tint;

void main() {
  vec3 n = normalize(v_normal);
  float slope = 1.0 - n.y;  // 0 flat, 1 vertical
  vec3 grass = vec3(0.22, 0.30, 0.13);
  vec3 rock = vec3(0.33, 0.30, 0.27);
  vec3 snow = vec3(0.85, 0.88, 0.92);
  vec3 albedo = mix(grass, rock, smoothstep(0.18, 0.35, slope));
  albedo = mix(albedo, snow, smoothstep(u_snow_line - 10.0, u_snow_line + 10.0, v_height) * (1.0 - smoothstep(0.35, 0.6, slope)));
  vec3 color = shade_diffuse(albedo * u_tint, n, sylva_shadow(v_rel_position, n));
  o_color = vec4(apply_fog(color, v_rel_position), 1.0);
}
