#version 450 core
// Normals from the full-resolution field (a texture), so a coarse LOD keeps its shading and the
// image error measures the geometry: silhouettes, occlusion and where the light falls.
#include "render/lib/fog.glsl"
#include "render/lib/lighting.glsl"

in vec3 v_rel_position;
in vec2 v_field_xz;
in float v_height;
out vec4 o_color;

uniform sampler2D u_normals;   // xyz unit normal per field sample, texel (i, j) = sample (i, j)
uniform vec2 u_field_size;     // samples (columns, rows)
uniform float u_spacing;       // metres per sample
uniform vec2 u_height_range;   // lowest and highest sample [m]

void main() {
  vec2 uv = (v_field_xz / u_spacing + 0.5) / u_field_size;
  vec3 n = normalize(texture(u_normals, uv).xyz);
  float steep = smoothstep(0.2, 0.45, 1.0 - n.y);
  float h = (v_height - u_height_range.x) / max(u_height_range.y - u_height_range.x, 1e-3);
  vec3 albedo = mix(vec3(0.21, 0.30, 0.13), vec3(0.38, 0.34, 0.29), steep);
  albedo = mix(albedo, vec3(0.86, 0.88, 0.93), smoothstep(0.72, 0.78, h) * (1.0 - steep));
  o_color = vec4(apply_fog(shade_diffuse(albedo, n, 1.0), v_rel_position), 1.0);
}
