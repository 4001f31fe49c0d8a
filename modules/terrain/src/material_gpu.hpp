#pragma once
// The GL side of the terrain material (material.hpp, shaders/material.glsl): its textures and
// uniforms. Needs a current GL 4.5 context.

#include <sylva/core/height_field.hpp>
#include <sylva/core/result.hpp>
#include <sylva/render/shader_library.hpp>
#include <sylva/render/texture.hpp>
#include <sylva/terrain/edit_layer.hpp>
#include <sylva/terrain/material.hpp>

#include <array>

namespace sylva::terrain {

// The tiling detail noise as a mipmapped RGBA8 texture (256^2, repeat, trilinear; encoding in
// material_gpu.cpp), bound at unit 1.
render::Texture make_detail_texture();

// The field's shape (compute_terrain_shape) as an RGBA16_SNORM texture (values clamped to
// [-1, 1]: a curvature beyond is a 45-degree-deep pit or spike), texel (i, j) = sample (i, j),
// linear, clamped, bound at unit 2. SNORM, not half floats: llvmpipe filters it on a fast path. Errors: kLimit beyond GL_MAX_TEXTURE_SIZE (naming the size).
Result<render::Texture> make_shape_texture(const HeightField& field, float radius_m);
// Recomputes the samples an edit of [x0, x1) x [z0, z1) changes (the rectangle grown by the
// radius) and uploads only those; returns that grown rectangle (clamped to the field).
SampleRect update_shape_texture(const render::Texture& texture, const HeightField& field, float radius_m, int x0, int z0,
                          int x1, int z1);

// The finest detail scale (0-3; 3: none) that a fragment of ground at least min_depth_m in front
// of a camera with vertical field of view fov_y_rad [rad], aspect (width / height) and
// viewport_height [px] can show: finer scales have faded to 0 (material.glsl detail_fade) for
// every such fragment. The footprint's lower bound is depth / (focal length * (1 + tan^2 of the
// half fields of view)), below the smallest world step between two adjacent pixels' rays
// anywhere on the screen (2.3x below the true coarse derivatives at its tightest, test
// TerrainMaterialVariants), so no extra margin. Compiled in as SYLVA_TERRAIN_FIRST_SCALE.
int first_detail_scale(double min_depth_m, double fov_y_rad, double aspect, int viewport_height, float detail_scale_m);
// That footprint bound [m per pixel] (0 for a depth <= 0 or an empty viewport).
double min_pixel_footprint_m(double min_depth_m, double fov_y_rad, double aspect, int viewport_height);

// The material's uniforms (material.glsl: u_lines, u_layer, u_pole, the layer colours) for a
// material and climate. Compared by the renderer to know when the baked far material
// (far_material.hpp) is stale.
struct MaterialUniforms {
  glm::vec4 lines{0.0f};  // snow, rock, tree line, water level [m]
  glm::vec4 layer{0.0f};  // beach height [m], rock slope (1 - n.y), 1 / finest tile [1/m], detail strength
  glm::vec2 pole{0.0f};
  std::array<glm::vec3, 7> colors{};  // grass, meadow, dirt, scree, rock, snow, sand (linear)
  bool operator==(const MaterialUniforms&) const = default;
};
MaterialUniforms material_uniforms(const MaterialSettings& settings, const Climate& climate);
// Sets them on the bound program.
void set_material_uniforms(const render::Program& program, const MaterialUniforms& uniforms);
void set_material_uniforms(const render::Program& program, const MaterialSettings& settings, const Climate& climate);

}  // namespace sylva::terrain
