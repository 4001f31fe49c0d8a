#version 450 core
// terrain/far_material_bake.frag: the baked far material (far_material.hpp). One fragment per
// texel (i, j) of the bake = field sample (i, j): terrain_surface of material.glsl compiled
// without detail scales (SYLVA_TERRAIN_FIRST_SCALE 3), fed with the sample's own height and
// shape texel, so the far chunks' baked variant of terrain.frag reads the same function of the
// same inputs, only interpolated after instead of before (README "vs CDLOD").
#include "terrain/material.glsl"

layout(binding = 2) uniform sampler2D u_shape;    // RGBA16_SNORM, material_gpu.hpp
layout(binding = 4) uniform sampler2D u_heights;  // R32F world heights [m], height_texture.hpp

out vec4 o_albedo_occlusion;  // linear albedo, sky occlusion (SRGB8_ALPHA8 target: encoded by GL)

void main() {
  const ivec2 texel = ivec2(gl_FragCoord.xy);
  const float h = texelFetch(u_heights, texel, 0).r;
  const ShapeSample shape = decode_shape(texelFetch(u_shape, texel, 0));
  // The position feeds only the detail scales, compiled out here.
  const vec3 p = vec3(float(texel.x), h, float(texel.y));
  const TerrainSurface s = terrain_surface(p, shape.normal, shape.curvature, h, shape.macro);
  o_albedo_occlusion = vec4(s.albedo, s.occlusion);
}
