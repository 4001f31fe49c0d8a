// Point lights (C++: PointLightUniforms in sylva/render/point_lights.hpp, UBO binding 3).
// Include as "render/lib/point_lights.glsl". Attenuation is the seed's 1 / (Kc + Kl d + Kq d^2)
// (seed 004 §2.3.3.2) times the range window (1 - (d/range)^4)^2; at most 16 lights.
#ifndef SYLVA_RENDER_POINT_LIGHTS_GLSL
#define SYLVA_RENDER_POINT_LIGHTS_GLSL

#define SYLVA_MAX_POINT_LIGHTS 16

layout(std140, binding = 3) uniform SylvaPointLights {
  vec4 sylva_point_position[SYLVA_MAX_POINT_LIGHTS];     // xyz camera-relative [m], w range [m]
  vec4 sylva_point_color[SYLVA_MAX_POINT_LIGHTS];        // rgb colour * intensity
  vec4 sylva_point_constants[SYLVA_MAX_POINT_LIGHTS];    // x Kc, y Kl, z Kq
  ivec4 sylva_point_count;                               // x number of lights
};

int sylva_point_light_count() { return min(sylva_point_count.x, SYLVA_MAX_POINT_LIGHTS); }

// Attenuation of light i at distance d [m] (same numbers as point_light_attenuation on the CPU).
float sylva_point_attenuation(int i, float d) {
  vec3 k = sylva_point_constants[i].xyz;
  float denom = max(k.x + k.y * d + k.z * d * d, 1.0);
  float x = clamp(d / sylva_point_position[i].w, 0.0, 1.0);
  float x2 = x * x;
  float window = (1.0 - x2 * x2) * (1.0 - x2 * x2);
  return window / denom;
}

// Lambert irradiance from every point light at a camera-relative position with unit normal.
vec3 sylva_point_lights_diffuse(vec3 rel_pos, vec3 normal) {
  vec3 sum = vec3(0.0);
  int n = sylva_point_light_count();
  for (int i = 0; i < n; ++i) {
    vec3 to_light = sylva_point_position[i].xyz - rel_pos;
    float d = length(to_light);
    vec3 l = d > 1e-6 ? to_light / d : normal;
    sum += sylva_point_color[i].rgb * (sylva_point_attenuation(i, d) * max(dot(normal, l), 0.0));
  }
  return sum;
}

#endif
