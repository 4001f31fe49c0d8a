#version 450 core
// Phong shading of voxel faces and plant parts (seed 004 §2.3): ambient scaled by ambient
// occlusion, sun diffuse and specular (specular map, §2.3.2), point lights from emissive blocks
// with attenuation 1 / (Kc + Kl d + Kq d^2) (§2.3.3.2), the host's point lights from the render
// core (UBO 3), emission, fog. ALPHA_CUT builds the
// cut-out variant (discard below u_alpha_cutoff, two-sided normals).
#include "voxel/common.glsl"
#include "render/lib/lighting.glsl"
#include "render/lib/fog.glsl"
#include "render/lib/point_lights.glsl"
#include "voxel/shadow_hook.glsl"

#ifndef ALPHA_CUT
layout(early_fragment_tests) in;
#endif

const int kMaxLights = 32;
uniform int u_light_count;
uniform vec4 u_light_pos[kMaxLights];    // xyz camera-relative
uniform vec4 u_light_color[kMaxLights];  // rgb
uniform vec3 u_attenuation;              // Kc, Kl, Kq
uniform float u_ao_strength;
uniform float u_specular_scale;

in vec3 v_rel_pos;
in vec3 v_normal;
in vec2 v_uv;
in float v_ao;
flat in uint v_layer;
flat in uint v_block;

out vec4 o_color;

float phong(vec3 n, vec3 view, vec3 l, float shininess) {
  return dot(n, l) > 0.0 ? pow(max(dot(view, reflect(-l, n)), 0.0), shininess) : 0.0;
}

void main() {
  vec4 albedo = texture(u_diffuse, vec3(v_uv, float(v_layer)));
#ifdef ALPHA_CUT
  if (albedo.a < u_alpha_cutoff) discard;
#endif
  VoxelBlock b = voxel_blocks[v_block];
  vec3 n = normalize(v_normal);
#ifdef ALPHA_CUT
  if (!gl_FrontFacing) n = -n;
#endif
  vec3 view = normalize(-v_rel_pos);
  float spec_map = texture(u_specular, vec3(v_uv, float(v_layer))).r * b.material.x * u_specular_scale;
  float shininess = max(b.material.y, 1.0);
  float ao = mix(1.0, v_ao, u_ao_strength);

  vec3 l = sun_direction();
  float lit = voxel_shadow(v_rel_pos, n);
  vec3 color = hemisphere_ambient(n) * ao * albedo.rgb;
  color += sun_radiance() * lit * (lambert(n, l) * albedo.rgb + phong(n, view, l, shininess) * spec_map);
  for (int i = 0; i < u_light_count; ++i) {
    vec3 d = u_light_pos[i].xyz - v_rel_pos;
    float dist = length(d);
    vec3 ld = d / max(dist, 1e-4);
    float att = 1.0 / (u_attenuation.x + u_attenuation.y * dist + u_attenuation.z * dist * dist);
    color += att * u_light_color[i].rgb * (lambert(n, ld) * albedo.rgb + phong(n, view, ld, shininess) * spec_map);
  }
  // The host's point lights (e.g. the scene's), same attenuation family, diffuse only.
  color += albedo.rgb * sylva_point_lights_diffuse(v_rel_pos, n);
  color += b.emission.rgb * albedo.rgb * 2.0;
  o_color = vec4(apply_fog(color, v_rel_pos), 1.0);
}
