// Receiving the sun's cascaded shadows (C++: ShadowMaps in sylva/render/shadow_maps.hpp).
// Include as "render/lib/shadows.glsl" and call
//   float sylva_shadow(vec3 rel_pos, vec3 normal)   // 1 = lit, 0 = fully shadowed
// with the CAMERA-RELATIVE position (world - camera position) and the unit world-space normal
// of the shaded surface (for two-sided surfaces: the side facing the viewer). The host binds the
// data once per frame with ShadowMaps::bind(): the SylvaShadows block at binding 2 and the
// depth array at texture unit 15. Cascade count, resolution, bias and PCF radius are uniforms,
// so changing them never recompiles a shader (seed 004 §3.6.2 had to).
//
// Depth is reversed (1 = nearest to the sun); the comparison sampler is GL_GEQUAL with
// bilinear filtering, so each PCF tap is a 2x2 percentage-closer sample.
#ifndef SYLVA_RENDER_SHADOWS_GLSL
#define SYLVA_RENDER_SHADOWS_GLSL

#define SYLVA_MAX_SHADOW_CASCADES 8  // kMaxShadowCascades
#define SYLVA_SHADOW_CASCADE_VEC4S 2  // per-cascade scalars, four to a vec4

layout(std140, binding = 2) uniform SylvaShadows {
  mat4 sylva_shadow_matrix[SYLVA_MAX_SHADOW_CASCADES];  // camera-relative -> (u, v, depth)
  vec4 sylva_shadow_split_far[SYLVA_SHADOW_CASCADE_VEC4S];   // far view depth of each cascade [m]
  vec4 sylva_shadow_texel[SYLVA_SHADOW_CASCADE_VEC4S];       // world size of one texel per cascade [m]
  vec4 sylva_shadow_bias_scale[SYLVA_SHADOW_CASCADE_VEC4S];  // per-cascade bias factor (the seed's cascadeBiases)
  vec4 sylva_shadow_view;         // xyz: camera forward (world), w: blend fraction
  vec4 sylva_shadow_light;        // xyz: unit vector toward the sun
  vec4 sylva_shadow_bias;         // x: slope bias, y: min bias, z: normal offset factor
  ivec4 sylva_shadow_params;      // x: cascade count, y: PCF radius, z: enabled, w: resolution
};

layout(binding = 15) uniform sampler2DArrayShadow sylva_shadow_map;

// Cascade i's far view depth, texel size and bias factor.
float sylva_shadow_split(int i) { return sylva_shadow_split_far[i >> 2][i & 3]; }
float sylva_shadow_texel_size(int i) { return sylva_shadow_texel[i >> 2][i & 3]; }
float sylva_shadow_bias_factor(int i) { return sylva_shadow_bias_scale[i >> 2][i & 3]; }

// Cascade index for a camera-relative position by view depth (seed §3.6: selection by
// distance); returns the cascade count when the point is beyond the last cascade.
int sylva_shadow_cascade(vec3 rel_pos) {
  float depth = dot(rel_pos, sylva_shadow_view.xyz);
  int count = sylva_shadow_params.x;
  for (int i = 0; i < count; ++i) {
    if (depth < sylva_shadow_split(i)) return i;
  }
  return count;
}

// Filtered visibility in one cascade (1 = lit).
float sylva_shadow_in_cascade(int c, vec3 rel_pos, vec3 normal) {
  // Normal offset of (pcf_radius + 1) texels * sin(angle N, L) and the seed's slope-scaled bias
  // (§3.3) in units of 100 texels of depth, times the per-cascade factor (§3.6.1); see
  // shadow_cascades.hpp for why these units.
  float n_dot_l = dot(normal, sylva_shadow_light.xyz);
  float sin_angle = sqrt(max(1.0 - n_dot_l * n_dot_l, 0.0));
  float texel = sylva_shadow_texel_size(c);
  vec3 p = rel_pos + normal * (sylva_shadow_bias.z * float(sylva_shadow_params.y + 1) * texel * sin_angle);
  vec3 t = (sylva_shadow_matrix[c] * vec4(p, 1.0)).xyz;
  if (any(lessThan(t.xy, vec2(0.0))) || any(greaterThan(t.xy, vec2(1.0)))) return 1.0;
  float nl = clamp(n_dot_l, 0.0, 1.0);
  float bias = max(sylva_shadow_bias.x * (1.0 - nl), sylva_shadow_bias.y) * sylva_shadow_bias_factor(c);
  float ref = t.z + bias * 100.0 / float(sylva_shadow_params.w);  // reversed depth: sunward is larger
  int r = sylva_shadow_params.y;
  float step = 1.0 / float(sylva_shadow_params.w);
  float sum = 0.0;
  for (int y = -r; y <= r; ++y) {
    for (int x = -r; x <= r; ++x) {
      sum += texture(sylva_shadow_map, vec4(t.xy + vec2(x, y) * step, float(c), ref));
    }
  }
  float taps = float((2 * r + 1) * (2 * r + 1));
  return sum / taps;
}

// Visibility of the sun at a camera-relative position with unit normal `normal`: 1 = lit.
// Cross-fades into the next cascade over the last blend fraction of each cascade and fades to
// lit at the end of the last one.
float sylva_shadow(vec3 rel_pos, vec3 normal) {
  if (sylva_shadow_params.z == 0) return 1.0;
  int count = sylva_shadow_params.x;
  int c = sylva_shadow_cascade(rel_pos);
  if (c >= count) return 1.0;
  float depth = dot(rel_pos, sylva_shadow_view.xyz);
  float near_c = c == 0 ? 0.0 : sylva_shadow_split(c - 1);
  float far_c = sylva_shadow_split(c);
  float band_start = far_c - sylva_shadow_view.w * (far_c - near_c);
  float s = sylva_shadow_in_cascade(c, rel_pos, normal);
  if (depth > band_start && far_c > band_start) {
    float w = clamp((depth - band_start) / (far_c - band_start), 0.0, 1.0);
    float next = c + 1 < count ? sylva_shadow_in_cascade(c + 1, rel_pos, normal) : 1.0;
    s = mix(s, next, w);
  }
  return s;
}

#endif
