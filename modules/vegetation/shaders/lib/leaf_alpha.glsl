// Leaf outline coverage for the three alpha modes of <sylva/vegetation/shading.hpp> (AlphaMode).
// Returns the alpha to write (alpha-to-coverage) or 1 / 0 (alpha tests; 0 means discard).
#ifndef SYLVA_VEGETATION_LEAF_ALPHA_GLSL
#define SYLVA_VEGETATION_LEAF_ALPHA_GLSL

#include "render/lib/noise.glsl"

// How far the leaf texture is minified: texels per pixel along the worse axis.
float sylva_leaf_footprint(sampler2DArray coverage, vec2 uv) {
  vec2 texel = uv * vec2(textureSize(coverage, 0).xy);
  return max(length(dFdx(texel)), length(dFdy(texel)));
}

// Hash of the object-space position in power-of-two cells of the pixel footprint (Wyman &
// McGuire 2017), so it stays put while the camera and the wind move.
uint sylva_position_hash(vec3 p) {
  float pix = max(length(dFdx(p)), length(dFdy(p)));
  float cell = exp2(ceil(log2(max(pix, 1.0e-8))));
  return sylva_hash(ivec3(floor(p / cell)), 0x6a09e667u);
}

// Hashed threshold in (0, 1).
float sylva_hashed_threshold(vec3 p) { return (float(sylva_position_hash(p) >> 8u) + 0.5) * (1.0 / 16777216.0); }

// Alpha-to-coverage with a hashed dither: k = floor(alpha n + jitter) of the n samples (so the
// expected covered share is alpha), starting at a hashed sample. The fixed alpha-to-mask patterns
// of GL_SAMPLE_ALPHA_TO_COVERAGE give overlapping leaves of equal alpha the same samples, so a
// distant crown (many overlapping sub-pixel leaves) would come out too thin; independent dithers
// cover overlaps as 1 - (1 - a)(1 - b). Returns the sample mask (0: discard).
int sylva_coverage_mask(float alpha, int samples, vec3 p) {
  int n = clamp(samples, 1, 31);
  uint h = sylva_position_hash(p);
  float jitter = (float(h >> 8u) + 0.5) * (1.0 / 16777216.0);
  int k = clamp(int(floor(clamp(alpha, 0.0, 1.0) * float(n) + jitter)), 0, n);
  uint full = (1u << uint(n)) - 1u;
  uint bits = (1u << uint(k)) - 1u;
  uint r = sylva_pcg_hash(h) % uint(n);
  return int(((bits << r) | (bits >> (uint(n) - r))) & full);
}

// mode: 0 alpha test at 0.5, 1 hashed alpha test, 2 alpha-to-coverage.
float sylva_leaf_alpha(int mode, float preserved_alpha, sampler2DArray coverage, vec2 uv, float layer, vec3 hash_position) {
  if (mode == 0) return preserved_alpha < 0.5 ? 0.0 : 1.0;
  // 0 where the texture is magnified or 1:1, 1 from two texels per pixel on.
  float minified = clamp(sylva_leaf_footprint(coverage, uv) - 1.0, 0.0, 1.0);
  float box = texture(coverage, vec3(uv, layer)).r;
  if (mode == 2) {
    // Sharpened near (Golus 2017), the covered share far.
    float sharp = (preserved_alpha - 0.5) / max(fwidth(preserved_alpha), 1.0e-4) + 0.5;
    return clamp(mix(sharp, box, minified), 0.0, 1.0);
  }
  float threshold = mix(0.5, sylva_hashed_threshold(hash_position), minified);
  float a = mix(preserved_alpha, box, minified);
  return a < threshold ? 0.0 : 1.0;
}

#endif
