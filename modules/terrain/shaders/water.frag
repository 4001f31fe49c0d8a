#version 450 core
// terrain/water.frag: the water plane (seed 002 §3.3; issue 15), see terrain/water.hpp.
// Output through dual-source blending: framebuffer = o_color + framebuffer x o_transmit, i.e.
// the water's own light (reflection, glint, scattering, fog) plus what passes from behind.
#include "render/lib/fog.glsl"

uniform mat4 u_view_projection;      // camera-relative world -> clip (reversed Z)
uniform mat4 u_inv_view_projection;
uniform vec4 u_viewport;             // x, y, width, height [px]
uniform float u_height;              // water level - camera height [m], < 0
uniform bool u_has_depth;            // u_scene_depth holds the scene's depth
uniform vec3 u_color;                // deep water's scattering albedo
uniform vec3 u_absorption;           // [1/m]
uniform float u_shore_fade;          // [m]
uniform float u_sun_glint;
uniform vec4 u_waves[8];             // k.x, k.y [rad/m], phase at the camera [rad], slope
uniform vec4 u_warp[2];              // k.x, k.y [rad/m], phase at the camera [rad], amplitude [m]
uniform float u_pixel_angle;         // pixel footprint per metre of distance

layout(binding = 0) uniform sampler2D u_scene_depth;

layout(location = 0, index = 0) out vec4 o_color;
layout(location = 0, index = 1) out vec4 o_transmit;

const float kF0 = 0.02;          // ((1.33 - 1) / (1.33 + 1))^2
const float kInvIor = 1.0 / 1.33;
const float kMaxDistance = 1.0e7;  // [m] beyond this the plane is the horizon

vec3 camera_relative(vec2 ndc, float depth) {
  vec4 p = u_inv_view_projection * vec4(ndc, depth, 1.0);
  return p.xyz / p.w;
}

// Unit normal of the rippled surface at camera-relative xz; waves smaller than ~2 footprints
// fade out (the mean slope of an unresolved ripple is what a mirror shows).
vec3 ripple_normal(vec2 rel_xz, float footprint) {
  // A slow domain warp (two long waves, u_warp) bends the crests of the shorter ones.
  vec2 warp = vec2(sin(dot(u_warp[0].xy, rel_xz) + u_warp[0].z), sin(dot(u_warp[1].xy, rel_xz) + u_warp[1].z)) *
              u_warp[0].w;
  vec2 slope = vec2(0.0);
  for (int i = 0; i < 8; ++i) {
    vec2 k = u_waves[i].xy;
    float wavelength = 6.2831853 / max(length(k), 1.0e-6);
    float fade = 1.0 - smoothstep(0.08, 0.5, footprint / wavelength);
    vec2 p = i == 0 ? rel_xz : rel_xz + warp;
    slope += u_waves[i].w * fade * cos(dot(k, p) + u_waves[i].z) * normalize(k);
  }
  return normalize(vec3(-slope.x, 1.0, -slope.y));
}

void main() {
  vec2 ndc = (gl_FragCoord.xy - u_viewport.xy) / u_viewport.zw * 2.0 - 1.0;
  vec3 dir = normalize(camera_relative(ndc, 1.0));  // toward the near plane (reversed Z)
  if (dir.y > -1.0e-6) discard;                      // at or above the horizon
  float t = min(u_height / dir.y, kMaxDistance);
  vec3 rel = dir * t;
  vec4 clip = u_view_projection * vec4(rel, 1.0);
  float depth = clamp(clip.z / clip.w, 0.0, 1.0);

  // The scene behind the water: its vertical depth below the surface (deep where nothing is).
  float water_depth = 1.0e4;
  if (u_has_depth) {
    float scene = texelFetch(u_scene_depth, ivec2(gl_FragCoord.xy), 0).r;
    if (scene > depth) discard;  // nearer ground (the depth test would reject it anyway)
    if (scene > 0.0) water_depth = clamp(u_height - camera_relative(ndc, scene).y, 0.0, 1.0e4);
  }
  gl_FragDepth = depth;

  vec3 v = -dir;
  vec3 n = ripple_normal(rel.xz, t * u_pixel_angle / max(-dir.y, 0.05));
  float cos_i = clamp(dot(n, v), 0.0, 1.0);
  float fresnel = kF0 + (1.0 - kF0) * pow(1.0 - cos_i, 5.0);
  vec3 r = reflect(dir, n);
  r.y = abs(r.y);  // a ripple tilted past the view reflects the sky near the horizon, never the ground
  vec3 sky = atmosphere_radiance(normalize(r));

  // Refracted path through the water (Snell) down to the bed, Beer-Lambert per channel.
  float sin_t = kInvIor * sqrt(max(1.0 - cos_i * cos_i, 0.0));
  float cos_t = sqrt(max(1.0 - sin_t * sin_t, 0.0));
  float path = min(water_depth / max(cos_t, 0.5), 1.0e4);
  vec3 transmittance = exp(-u_absorption * path);
  vec3 sun = sun_direction();
  vec3 light = sun_radiance() * max(sun.y, 0.0) + sylva_ambient.rgb;
  vec3 body = u_color * light * (1.0 - transmittance);

  float glint = 0.0;
  if (u_sun_glint > 0.0) {
    float shininess = 600.0;
    float sun_fresnel = kF0 + (1.0 - kF0) * pow(1.0 - clamp(dot(normalize(v + sun), v), 0.0, 1.0), 5.0);
    glint = u_sun_glint * sun_fresnel * blinn_phong(n, v, sun, shininess) * smoothstep(0.0, 0.05, sun.y);
  }
  vec3 surface = fresnel * sky + glint * sun_radiance() + (1.0 - fresnel) * body;
  vec3 through = (1.0 - fresnel) * transmittance;

  // Aerial perspective to the water point (fog.glsl's apply_fog, split for the blend), then the
  // shore fade-in: out = mix(behind, fog(surface + through x behind), edge).
  vec3 air = air_transmittance(rel) * fog_transmittance(rel);
  vec3 haze = atmosphere_radiance(dir) * (1.0 - air);
  float edge = u_has_depth ? smoothstep(0.0, max(u_shore_fade, 1.0e-4), water_depth) : 1.0;
  o_color = vec4(edge * (air * surface + haze), 1.0);
  o_transmit = vec4(vec3(1.0 - edge) + edge * air * through, 1.0);
}
