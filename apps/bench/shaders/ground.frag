#version 450 core
// Slope and height material (meadow, rock, snow) lit by the frame's sun and sky, with fog.
#include "render/lib/fog.glsl"
#include "render/lib/lighting.glsl"

in vec3 v_rel_position;
in vec3 v_normal;
in float v_height;
out vec4 o_color;

uniform float u_snow_line;  // metres

void main() {
  vec3 n = normalize(v_normal);
  float steep = smoothstep(0.15, 0.4, 1.0 - n.y);
  vec3 albedo = mix(vec3(0.20, 0.31, 0.12), vec3(0.36, 0.32, 0.28), steep);
  float snow = smoothstep(u_snow_line - 8.0, u_snow_line + 8.0, v_height) * (1.0 - steep);
  albedo = mix(albedo, vec3(0.86, 0.88, 0.93), snow);
  o_color = vec4(apply_fog(shade_diffuse(albedo, n, 1.0), v_rel_position), 1.0);
}
