// Leaf shading of seed 000 §3.2 in its standard forms (see <sylva/vegetation/shading.hpp>, the CPU
// twins): diffuse N.L, Cook-Torrance specular with the Beckmann distribution, the full Fresnel term
// and the geometric attenuation, and translucency reconstructed from Half-Life-2 coefficients.
#ifndef SYLVA_VEGETATION_LEAF_SHADING_GLSL
#define SYLVA_VEGETATION_LEAF_SHADING_GLSL

#include "render/lib/common.glsl"

float sylva_beckmann(float nh, float sigma) {
  nh = max(nh, 1.0e-4);
  float nh2 = nh * nh;
  float s2 = sigma * sigma;
  return exp((nh2 - 1.0) / (s2 * nh2)) / (s2 * nh2 * nh2);
}

float sylva_fresnel(float c, float n) {
  c = clamp(c, 0.0, 1.0);
  float g = sqrt(max(n * n + c * c - 1.0, 0.0));
  float a = (g - c) / (g + c);
  float b = (c * (g + c) - 1.0) / (c * (g - c) + 1.0);
  return 0.5 * a * a * (1.0 + b * b);
}

float sylva_geometric(float nh, float ne, float nl, float eh) {
  eh = max(eh, 1.0e-4);
  return min(1.0, min(2.0 * nh * ne / eh, 2.0 * nh * nl / eh));
}

// BRDF * N.L of the Cook-Torrance model; n, l, e unit vectors (e towards the eye).
float sylva_cook_torrance(vec3 n, vec3 l, vec3 e, float sigma, float ior) {
  float nl = dot(n, l);
  float ne = dot(n, e);
  if (nl <= 0.0 || ne <= 0.0) return 0.0;
  vec3 h = normalize(l + e);
  float nh = max(dot(n, h), 0.0);
  float eh = max(dot(e, h), 0.0);
  return sylva_beckmann(nh, sigma) * sylva_fresnel(eh, ior) * sylva_geometric(nh, ne, nl, eh) /
         (PI * max(ne, 1.0e-4));
}

// Eq. 3.32 without the light intensity: rho * max(0, sum h_i sqrt(3/2pi) H_i . l), with l in the
// tangent space of the side the light enters (z = that side's normal).
float sylva_hl2_translucency(vec3 h, float rho, vec3 l) {
  const vec3 H1 = vec3(-0.40824829, -0.70710678, 0.57735027);
  const vec3 H2 = vec3(-0.40824829, 0.70710678, 0.57735027);
  const vec3 H3 = vec3(0.81649658, 0.0, 0.57735027);
  const float k = 0.69098829;  // sqrt(3 / (2 pi))
  float sum = h.x * k * dot(H1, l) + h.y * k * dot(H2, l) + h.z * k * dot(H3, l);
  return rho * max(sum, 0.0);
}

#endif
