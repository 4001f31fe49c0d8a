#version 450 core
// HDR -> display (C++: ToneMapper, tone_mapping.hpp, with CPU twins of every step).
#include "render/lib/common.glsl"

layout(binding = 0) uniform sampler2D u_hdr;
uniform float u_exposure;
uniform int u_operator;  // 0 = ACES fit (Narkowicz 2015), 1 = Reinhard
uniform bool u_srgb;

in vec2 v_uv;
layout(location = 0) out vec4 o_color;

vec3 aces_fit(vec3 x) {
  return clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
}

void main() {
  vec3 c = texelFetch(u_hdr, ivec2(gl_FragCoord.xy), 0).rgb;
  // NaN and negative -> 0 (isnan is unreliable under fast-math drivers, so also test c != c).
  bvec3 bad = bvec3(isnan(c.r) || c.r != c.r, isnan(c.g) || c.g != c.g, isnan(c.b) || c.b != c.b);
  c = mix(max(c, vec3(0.0)), vec3(0.0), bad);
  c = min(c * u_exposure, vec3(6.0e4));  // +inf -> white, no inf/inf in the curve
  vec3 t = u_operator == 0 ? aces_fit(c) : c / (1.0 + c);
  o_color = vec4(u_srgb ? linear_to_srgb(t) : t, 1.0);
}
