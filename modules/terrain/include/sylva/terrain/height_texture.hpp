#pragma once
// The full-resolution height field on the GPU, for other modules' shaders (grass placement,
// water, decals) and for the terrain's own normals and materials. The CPU twin is the core
// HeightField itself (height(x, z), normal(x, z)), so no module needs the terrain to place things.
//
// Texel (i, j) = sample (i, j) in metres (GL_R32F, no scaling); linear filtering, clamped to the
// border. World (x, z) maps to texture coordinates ((x - origin.x) / spacing + 0.5) / columns and
// ((z - origin.y) / spacing + 0.5) / rows, which HeightTextureInfo::uv_scale/uv_offset encode.

#include <sylva/core/height_field.hpp>
#include <sylva/core/result.hpp>
#include <sylva/render/texture.hpp>

#include <glm/glm.hpp>

#include <cstdint>

namespace sylva::terrain {

struct HeightTextureInfo {
  glm::vec2 uv_scale{1.0f};   // uv = world_xz * uv_scale + uv_offset
  glm::vec2 uv_offset{0.0f};
  glm::vec2 height_range{0.0f, 0.0f};  // min, max sample [m]
};

// Needs a current GL 4.5 context. Errors: kInvalidArgument (empty field), kLimit when a side
// exceeds GL_MAX_TEXTURE_SIZE (the message names the field size and the limit).
Result<render::Texture> make_height_texture(const HeightField& field);
// Re-uploads only the samples [x0, x1) x [z0, z1) (x1/z1 exclusive, clamped to the field) of
// `field` into `texture`, which make_height_texture made from a field of the same columns x rows
// (one level, no mips to refresh). Per-stroke cost proportional to the stroke, not the field
// (issue 15). Returns the texels uploaded (0 for an empty rectangle). Needs a current context.
std::int64_t update_height_texture(const render::Texture& texture, const HeightField& field, int x0, int z0, int x1,
                                   int z1);
HeightTextureInfo height_texture_info(const HeightField& field);

}  // namespace sylva::terrain
