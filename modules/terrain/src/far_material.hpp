#pragma once
// The baked far material (issue 18): where a chunk draws no detail scale (first_detail_scale 3),
// material.glsl's terrain_surface depends only on the field sample's height and shape texel and
// on the material uniforms, so it is evaluated once per field sample on the GPU (the same GLSL,
// far_material_bake.frag) into a mipmapped SRGB8_ALPHA8 texture the size of the shape texture:
// rgb the linear albedo, a the sky occlusion. terrain.frag's baked variant (SYLVA_TERRAIN_BAKED)
// reads it instead of running the layer arithmetic per pixel.
//
// Format: 8-bit sRGB, not RGBA8 or RGB10_A2: the albedo is stored with the same perceptual steps
// as the 8-bit sRGB picture it ends up in (lit by at most ~1, a step of the bake is at most a step
// of the output: no new banding); RGB10_A2's 2-bit alpha cannot hold the occlusion (0.6-1, 1/255
// steps here). Mips are averaged in linear space (GL_FRAMEBUFFER_SRGB blits).
//
// Needs a current GL 4.5 context for every call; owns its GL objects.

#include <sylva/core/result.hpp>
#include <sylva/render/framebuffer.hpp>
#include <sylva/render/shader_library.hpp>
#include <sylva/render/texture.hpp>
#include <sylva/render/vertex_array.hpp>

#include "material_gpu.hpp"

#include <cstdint>

namespace sylva::terrain {

class FarMaterialBake {
 public:
  FarMaterialBake() = default;
  // Storage for a columns x rows field (full mip chain) and the bake program.
  // Errors: kGl (the program), kLimit beyond GL_MAX_TEXTURE_SIZE.
  static Result<FarMaterialBake> create(int columns, int rows);

  // Field samples whose height or shape texel changed (an edit: update_shape_texture's rectangle);
  // baked on the next refresh. Rectangles accumulate as their bounding box.
  void mark_dirty(const SampleRect& rect);
  // Brings the bake up to date with `heights` (make_height_texture) and `shape`
  // (make_shape_texture) of the same size and the material: everything on the
  // first call and whenever `material` differs from the last bake's, else the dirty rectangle
  // only, then the mips over the re-evaluated rectangle only. Restores the target state it
  // touches (render::SavedTargetState); leaves no program and no vertex array bound.
  void refresh(const render::Texture& heights, const render::Texture& shape, const MaterialUniforms& material);

  const render::Texture& texture() const { return texture_; }
  explicit operator bool() const { return static_cast<bool>(texture_); }
  // Level-0 texels evaluated so far (each bake's rectangle): what an edit costs (tests).
  std::int64_t texels_baked() const { return texels_baked_; }

 private:
  render::Texture texture_;
  render::Program program_;
  render::VertexArray empty_vao_;  // the full-screen triangle needs no attributes
  render::GlHandle<render::FramebufferDeleter> draw_fbo_, read_fbo_;
  std::int64_t texels_baked_ = 0;
  bool baked_ = false;
  MaterialUniforms baked_with_;
  SampleRect dirty_;  // empty when x0 >= x1

  void bake(const render::Texture& heights, const render::Texture& shape, const MaterialUniforms& material,
            SampleRect rect);
};

}  // namespace sylva::terrain
