// The frame's sun, sky and fog as the SylvaLighting uniform block (C++: LightingUniforms,
// binding kLightingBinding = 0) plus diffuse/specular helpers. Include as
// "render/lib/lighting.glsl". All colours linear RGB, directions world space, y up.
#ifndef SYLVA_RENDER_LIGHTING_GLSL
#define SYLVA_RENDER_LIGHTING_GLSL

#include "render/lib/common.glsl"

layout(std140, binding = 0) uniform SylvaLighting {
  vec4 sylva_sun_direction;  // xyz: unit vector toward the sun
  vec4 sylva_sun_radiance;   // rgb: sun colour * intensity
  vec4 sylva_ambient;        // rgb: sky ambient
  vec4 sylva_horizon_color;  // rgb
  vec4 sylva_zenith_color;   // rgb
  vec4 sylva_ground_color;   // rgb
  vec4 sylva_fog;            // rgb: fog colour, a: density [1/m]
  vec4 sylva_params;         // x: fog height falloff [1/m], y: camera height [m], z: time [s]
};

vec3 sun_direction() { return sylva_sun_direction.xyz; }
vec3 sun_radiance() { return sylva_sun_radiance.rgb; }
float scene_time() { return sylva_params.z; }

float lambert(vec3 n, vec3 l) { return max(dot(n, l), 0.0); }
// Wrapped diffuse (Half-Life 2 style), softer terminator for foliage.
float half_lambert(vec3 n, vec3 l) {
  float h = dot(n, l) * 0.5 + 0.5;
  return h * h;
}

// Ambient from a two-colour hemisphere: sky ambient above, ground bounce below.
vec3 hemisphere_ambient(vec3 n) {
  return mix(sylva_ground_color.rgb * sylva_ambient.rgb * 1.5, sylva_ambient.rgb, n.y * 0.5 + 0.5);
}

// Normalised Blinn-Phong specular lobe; n, v (toward the eye), l unit vectors.
float blinn_phong(vec3 n, vec3 v, vec3 l, float shininess) {
  vec3 h = normalize(v + l);
  return (shininess + 8.0) / (8.0 * PI) * pow(max(dot(n, h), 0.0), shininess);
}

// Diffuse surface lit by the sun and the hemisphere ambient. `shadow` in [0, 1] (1 = lit).
vec3 shade_diffuse(vec3 albedo, vec3 n, float shadow) {
  return albedo * (sun_radiance() * lambert(n, sun_direction()) * shadow + hemisphere_ambient(n));
}

#endif
