#version 450 core
// Phong shading of voxel faces and plant parts (seed 004 §2.3): ambient scaled by ambient
// occlusion, sun diffuse and specular (specular map, §2.3.2), point lights from emissive blocks
// with attenuation 1 / (Kc + Kl d + Kq d^2) (§2.3.3.2), the host's point lights from the render
// core (UBO 3), emission, the air (aerial perspective per pixel or per vertex, SYLVA_VOXEL_AIR),
// and the fade into the sky at the view distance
// (distance_fade.glsl). The ambient term is the render core's sky hemisphere plus sun light
// bounced off the lit ground onto faces looking sideways or down, so a face turned away from the
// sun is lit by sky and bounce light and never black. ALPHA_CUT builds the cut-out variant
// (discard below u_alpha_cutoff, two-sided normals); CROSS_QUADS the tuft variant (tinted, its
// normal already faces the viewer); TRANSLUCENT the blended variant for glass, water and ice
// (seed §2.2: alpha = texture alpha x the block's opacity, texels below u_translucent_cutoff
// discarded, the seed's 0.05). SYLVA_VOXEL_POINT_LIGHTS 0 leaves out both point-light loops: on
// llvmpipe a loop's body runs once per pixel even for zero lights, at about a sixth of the
// frame at the shipped spawn; SYLVA_VOXEL_SHADOWS 0 leaves out the shadow hook (lit = 1, what
// the disabled shadow block returns), which llvmpipe runs in full under a mask otherwise
// (VoxelRenderer picks both per frame; issue #18).
#include "voxel/common.glsl"
#include "render/lib/lighting.glsl"
#include "render/lib/fog.glsl"
#include "render/lib/point_lights.glsl"
#include "voxel/distance_fade.glsl"
#include "voxel/shadow_hook.glsl"

#ifndef SYLVA_VOXEL_POINT_LIGHTS
#define SYLVA_VOXEL_POINT_LIGHTS 1
#endif
#ifndef SYLVA_VOXEL_SHADOWS
#define SYLVA_VOXEL_SHADOWS 1
#endif
// SYLVA_VOXEL_FADE 0: geometry wholly nearer than the fade's start (mix by exactly 0 there).
#ifndef SYLVA_VOXEL_FADE
#define SYLVA_VOXEL_FADE 1
#endif

#if !defined(ALPHA_CUT) && !defined(TRANSLUCENT)
layout(early_fragment_tests) in;
#endif

const int kMaxLights = 32;
uniform int u_light_count;
uniform vec4 u_light_pos[kMaxLights];    // xyz camera-relative
uniform vec4 u_light_color[kMaxLights];  // rgb
uniform vec3 u_attenuation;              // Kc, Kl, Kq
uniform float u_ao_strength;
uniform float u_specular_scale;
uniform float u_sky_light;  // multiplier of the render core's hemisphere ambient
uniform float u_bounce;  // albedo of the ground that reflects the sun onto shaded faces
#ifdef TRANSLUCENT
uniform float u_translucent_cutoff;
#endif

in vec3 v_rel_pos;
in vec3 v_normal;
in vec2 v_uv;
in float v_ao;
#ifdef CROSS_QUADS
in vec3 v_tint;
#endif
flat in uint v_layer;
flat in uint v_block;
#if SYLVA_VOXEL_AIR == 1
in vec3 v_air_extinction;
#endif

out vec4 o_color;

// The air between the camera and the face (SYLVA_VOXEL_AIR, common.glsl).
vec3 voxel_air(vec3 color) {
#if SYLVA_VOXEL_AIR == 0
  return apply_fog(color, v_rel_pos);
#elif SYLVA_VOXEL_AIR == 1
  return air_from_vertex(color, v_rel_pos, v_air_extinction);
#else
  return color;
#endif
}

float phong(vec3 n, vec3 view, vec3 l, float shininess) {
  return dot(n, l) > 0.0 ? pow(max(dot(view, reflect(-l, n)), 0.0), shininess) : 0.0;
}

void main() {
  vec4 albedo = texture(u_diffuse, vec3(v_uv, float(v_layer)));
#ifdef ALPHA_CUT
  if (albedo.a < u_alpha_cutoff) discard;
#endif
#ifdef TRANSLUCENT
  float alpha = albedo.a * voxel_blocks[v_block].material.z;
  if (alpha < u_translucent_cutoff) discard;
#endif
#ifdef CROSS_QUADS
  albedo.rgb *= v_tint;
#endif
  VoxelBlock b = voxel_blocks[v_block];
  vec3 n = normalize(v_normal);
#if defined(ALPHA_CUT) && !defined(CROSS_QUADS)
  if (!gl_FrontFacing) n = -n;
#endif
  vec3 view = normalize(-v_rel_pos);
  // Most of the world (grass, dirt, logs) has no specular: skip the specular map and the Phong
  // lobes there (their product would be exactly 0), which llvmpipe otherwise runs per pixel.
  bool specular = b.material.x > 0.0 && u_specular_scale > 0.0;
  float spec_map = specular ? texture(u_specular, vec3(v_uv, float(v_layer))).r * b.material.x * u_specular_scale : 0.0;
  float shininess = max(b.material.y, 1.0);
  float ao = mix(1.0, v_ao, u_ao_strength);

  vec3 l = sun_direction();
#if SYLVA_VOXEL_SHADOWS
  float lit = voxel_shadow(v_rel_pos, n);
#else
  float lit = 1.0;
#endif
  // Bounce: sun on the ground (irradiance ~ sun * max(l.y, 0)) reflected with albedo u_bounce,
  // seen by a face in proportion to how much of the ground it faces, (1 - n.y) / 2.
  vec3 bounce = sun_radiance() * (max(l.y, 0.0) * u_bounce * (0.5 - 0.5 * n.y));
  // Blocky worlds have no indirect light but this term: a brighter sky (u_sky_light) keeps the
  // shaded sides and the ground under crowns readable, as games light them.
  vec3 color = (u_sky_light * hemisphere_ambient(n) + bounce) * ao * albedo.rgb;
  vec3 sun_lit = lambert(n, l) * albedo.rgb;
  if (specular) sun_lit += phong(n, view, l, shininess) * spec_map;
  color += sun_radiance() * lit * sun_lit;
#if SYLVA_VOXEL_POINT_LIGHTS
  for (int i = 0; i < u_light_count; ++i) {
    vec3 d = u_light_pos[i].xyz - v_rel_pos;
    float dist = length(d);
    vec3 ld = d / max(dist, 1e-4);
    float att = 1.0 / (u_attenuation.x + u_attenuation.y * dist + u_attenuation.z * dist * dist);
    vec3 point_lit = lambert(n, ld) * albedo.rgb;
    if (specular) point_lit += phong(n, view, ld, shininess) * spec_map;
    color += att * u_light_color[i].rgb * point_lit;
  }
  // The host's point lights (e.g. the scene's), same attenuation family, diffuse only.
  color += albedo.rgb * sylva_point_lights_diffuse(v_rel_pos, n);
#endif
  color += b.emission.rgb * albedo.rgb * 2.0;
#ifdef TRANSLUCENT
  o_color = vec4(voxel_distance_fade(voxel_air(color), v_rel_pos), alpha);
#else
#if SYLVA_VOXEL_FADE
  o_color = vec4(voxel_distance_fade(voxel_air(color), v_rel_pos), 1.0);
#else
  o_color = vec4(voxel_air(color), 1.0);
#endif
#endif
}
