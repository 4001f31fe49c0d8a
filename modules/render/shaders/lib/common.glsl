// Small maths shared by every module's shaders. Include as "render/lib/common.glsl".
#ifndef SYLVA_RENDER_COMMON_GLSL
#define SYLVA_RENDER_COMMON_GLSL

const float PI = 3.14159265358979;
const float TWO_PI = 6.28318530717959;

float saturate(float x) { return clamp(x, 0.0, 1.0); }
vec3 saturate(vec3 x) { return clamp(x, 0.0, 1.0); }

// Maps x from [a, b] to [0, 1] (clamped); a != b.
float remap01(float x, float a, float b) { return saturate((x - a) / (b - a)); }

float luminance(vec3 c) { return dot(c, vec3(0.2126, 0.7152, 0.0722)); }

// sRGB transfer functions (exact piecewise form), per channel.
vec3 srgb_to_linear(vec3 c) {
  return mix(c / 12.92, pow((c + 0.055) / 1.055, vec3(2.4)), step(vec3(0.04045), c));
}
vec3 linear_to_srgb(vec3 c) {
  c = max(c, vec3(0.0));
  return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
}

// Integer hash (PCG-style output permutation): well mixed, no trig, identical on every GPU.
uint hash_u32(uint x) {
  x ^= x >> 16; x *= 0x7feb352du;
  x ^= x >> 15; x *= 0x846ca68bu;
  x ^= x >> 16;
  return x;
}
uint hash_u32(uvec2 v) { return hash_u32(v.x ^ hash_u32(v.y)); }
// Uniform float in [0, 1) from a hash.
float hash_to_unit(uint h) { return float(h >> 8) * (1.0 / 16777216.0); }

// Rotation of v around the unit axis by angle (radians), Rodrigues' formula.
vec3 rotate_axis(vec3 v, vec3 axis, float angle) {
  float c = cos(angle), s = sin(angle);
  return v * c + cross(axis, v) * s + axis * dot(axis, v) * (1.0 - c);
}

#endif
