#pragma once
// GL side of the image-based levels (seed 000 §2.6-2.10, §2.13): a SliceAsset holds one species'
// baked slices (slice_bake.hpp) as texture arrays (one layer per slice instead of the seed's atlas,
// so filtering and mipmaps never bleed between slices), the SliceRenderer draws instanced slice
// clusters into the bound framebuffer.
//
// Drawing: one glDrawArraysInstanced per LOD and queue (6 vertices per slice generated in the
// vertex shader from gl_VertexID). The fragment shader runs the backward transform of
// shaders/lib/slices.glsl with the LOD0 animation blocks (same wind, control signals, noise seeds,
// phases and per-instance time offsets as TreeRenderer), so slices sway with the geometry. kShadow
// draws depth only and writes the baked depth offset (gl_FragDepth), fading slices by the light
// direction when TreeDrawParams-like `view_direction` is given (w = 1).
//
// Bindings: uniform blocks wind 1, animation 4, slice set 5 (shadows 2 as the render core says);
// storage buffers branches 3, leaves 4, instances 5; texture units 3 season, 8-12 slice maps and
// the leaf displacement field, 15 the render core's shadow maps.

#include <sylva/core/result.hpp>
#include <sylva/core/wind.hpp>
#include <sylva/render/buffer.hpp>
#include <sylva/render/drawable.hpp>
#include <sylva/render/shader_library.hpp>
#include <sylva/render/texture.hpp>
#include <sylva/render/vertex_array.hpp>
#include <sylva/vegetation/animation.hpp>
#include <sylva/vegetation/lod_settings.hpp>
#include <sylva/vegetation/shading.hpp>
#include <sylva/vegetation/slice_bake.hpp>
#include <sylva/vegetation/tree_renderer.hpp>

#include <map>

namespace sylva::vegetation {

inline constexpr GLuint kSliceSetBinding = 5;

class SliceAsset {
 public:
  // Uploads a bake (needs a current GL context). kInvalidArgument for inconsistent images.
  // leaf_transmittance in [0, 1]: the share of light a leaf passes straight through
  // (mean_leaf_transmittance of the species' leaf textures), the slices' translucency strength.
  static Result<SliceAsset> create(const BakedTree& baked, float leaf_transmittance = 0.35f);
  SliceAsset() = default;

  const SliceLayout& layout(int lod) const { return lods_[static_cast<std::size_t>(lod - 1)].layout; }
  int slices(int lod) const { return layout(lod).count(); }

 private:
  friend class SliceRenderer;
  struct Level {
    SliceLayout layout;
    int resolution = 0;
    render::Texture color, normal, depth, branch;
    mutable render::Buffer block;  // SliceSetGpu, rewritten per draw
  };
  std::array<Level, 2> lods_;
  float leaf_transmittance_ = 0.35f;
};

struct SliceDrawParams {
  glm::mat4 view_proj{1.0f};        // camera-relative view-projection of the pass
  ShadingSettings shading;          // season, material, alpha mode
  AnimationLevel level = AnimationLevel::kLeaves;
  bool receive_shadows = false;     // the host bound the shadow maps (ShadowMaps::bind())
  glm::vec4 view_direction{0.0f};   // w = 1: fade slices by this world direction (shadow passes)
};

class SliceRenderer {
 public:
  static Result<SliceRenderer> create();
  SliceRenderer() = default;

  // Per frame: the animation and wind blocks (the ones TreeRenderer gets), scene time [s] for the
  // scrolling leaf displacement, and the LOD settings (fades, displacement).
  void set_frame(const AnimationGpu& animation, const WindGpuParams& wind, double time, const LodSettings& lod);

  // Draws `count` instances (InstanceGpu records from `first`) of level `lod` (1 or 2).
  // `tree` supplies the branch records and the season texture.
  Status draw(render::Pass pass, const TreeAsset& tree, const SliceAsset& slices, int lod, const render::Buffer& instances,
              std::uint32_t first, std::uint32_t count, const SliceDrawParams& params, render::PassStats& stats);

 private:
  struct Key {
    bool depth;
    int level;
    auto operator<=>(const Key&) const = default;
  };
  Result<const render::Program*> program(const Key& key);

  std::map<Key, render::Program> programs_;
  render::Buffer animation_ubo_, wind_ubo_, no_shadows_ubo_;
  render::Texture leaf_displacement_;
  render::VertexArray empty_vao_;
  glm::vec4 leaf_scroll_{0.0f};
  LodSettings lod_;
};

}  // namespace sylva::vegetation
