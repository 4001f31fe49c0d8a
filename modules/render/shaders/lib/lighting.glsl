// The frame's sun, sky and fog as the SylvaLighting uniform block (C++: LightingUniforms,
// binding kLightingBinding = 0) plus diffuse/specular helpers. Include as
// "render/lib/lighting.glsl". All colours linear RGB, directions world space, y up.
#ifndef SYLVA_RENDER_LIGHTING_GLSL
#define SYLVA_RENDER_LIGHTING_GLSL

#include "render/lib/common.glsl"

layout(std140, binding = 0) uniform SylvaLighting {
  vec4 sylva_sun_direction;  // xyz: unit vector toward the sun
  vec4 sylva_sun_radiance;   // rgb: sun colour * intensity
  vec4 sylva_ambient;        // rgb: sky light of an upward face (cosine-weighted sky mean)
  vec4 sylva_horizon_color;  // rgb: sky at the horizon (mean over azimuth)
  vec4 sylva_zenith_color;   // rgb: sky straight up
  vec4 sylva_ground_color;   // rgb: light of a downward face (ground bounce)
  vec4 sylva_fog;            // rgb: clear colour, a: ground-haze density [1/m]
  vec4 sylva_params;         // x: haze height falloff [1/m], y: camera height [m], z: time [s]
  vec4 sylva_rayleigh;       // rgb: air scattering at sea level [1/m], w: 1 / scale height [1/m]
  vec4 sylva_mie;            // x: aerosol extinction [1/m], y: 1 / scale height, z: phase g, w: cos(sun radius)
  // The precomputed sky (C++ SkyTable, atmosphere.hpp): 16 elevation rows x 5 azimuth
  // columns, two vec4 per cell (Rayleigh rgb, Mie rgb in-scattering without phase).
  vec4 sylva_sky_table[160];
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

// Ambient for a unit normal: the sky's irradiance (from the atmosphere) for faces looking up,
// the ground's bounce for faces looking down, blended linearly in between.
vec3 hemisphere_ambient(vec3 n) {
  return mix(sylva_ground_color.rgb, sylva_ambient.rgb, n.y * 0.5 + 0.5);
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
