#pragma once
// GL side of LOD0 trees: a TreeAsset holds one model's GPU data (mesh, packed branch and leaf
// records, textures), the TreeRenderer holds the programs and per-frame blocks and draws instanced
// trees into the bound framebuffer for a pass.
//
// Passes (render::Pass): kOpaque draws bark and two-sided leaves with full shading; kShadow draws
// depth only with the very same vertex shaders (compiled with SYLVA_DEPTH_ONLY), so a shadow map
// sees the same deformation the camera sees (the Lighting issue plugs its cascades in through
// draw(kShadow, ...) with the light's view-projection). kTransparent draws nothing.
//
// Animation levels (seed table 5.5): kStatic draws rest positions, kTrunk bends the trunk only,
// kBranches every branch level, kLeaves branches and leaves (default). Programs are compiled on
// first use per level and pass.
//
// Binding points (shaders/lib/tree_data.glsl): uniform blocks wind 1, animation 4 (the render
// core's lighting 0, shadows 2 and point lights 3 stay free); storage buffers branches 3, leaves 4,
// instances 5, capture 7; texture units 0-2 leaf arrays, 3 season, 4-5 bark, 6 leaf coverage
// (box-filtered alpha); the shadow map stays at the render core's unit 15.
//
// Shadows (render/shadow_maps.hpp): kShadow draws are the casters' depth pass (the caller binds
// the cascade layer and sets the cascade's camera-relative matrix as view_proj). The colour pass
// receives through render/lib/shadows.glsl when TreeDrawParams::receive_shadows is set: the host
// must then have called ShadowMaps::bind(); otherwise the renderer binds a "shadows off" block.
//
// Failure: create() and draw() return kGl errors naming the shader file and line when a program
// does not build; asset creation returns kInvalidArgument for textures of the wrong shape and
// kLimit when the driver cannot hold them.

#include <sylva/core/image.hpp>
#include <sylva/core/result.hpp>
#include <sylva/core/wind.hpp>
#include <sylva/render/buffer.hpp>
#include <sylva/render/drawable.hpp>
#include <sylva/render/shader_library.hpp>
#include <sylva/render/texture.hpp>
#include <sylva/render/vertex_array.hpp>
#include <sylva/vegetation/animation.hpp>
#include <sylva/vegetation/shading.hpp>
#include <sylva/vegetation/textures.hpp>
#include <sylva/vegetation/tree_mesh.hpp>

#include <glm/glm.hpp>

#include <map>
#include <span>
#include <vector>

namespace sylva::vegetation {

inline constexpr GLuint kWindBinding = 1;
inline constexpr GLuint kAnimationBinding = 4;
inline constexpr GLuint kBranchBinding = 3;
inline constexpr GLuint kLeafBinding = 4;
inline constexpr GLuint kInstanceBinding = 5;
inline constexpr GLuint kCaptureBinding = 7;

enum class AnimationLevel { kStatic = 0, kTrunk = 1, kBranches = 2, kLeaves = 3 };
constexpr std::array<EnumName<AnimationLevel>, 4> enum_names(AnimationLevel) {
  return {{{AnimationLevel::kStatic, "static"}, {AnimationLevel::kTrunk, "trunk"},
           {AnimationLevel::kBranches, "branches"}, {AnimationLevel::kLeaves, "leaves"}}};
}

// Every image a tree needs: leaf maps per side, bark maps, the season column.
struct TreeTextureSet {
  LeafTextures leaves;
  BarkTextures bark;
  Image season;
};

// Procedural textures for a preset (textures.hpp); sizes must be powers of two.
Result<TreeTextureSet> make_texture_set(SpeciesPreset preset, std::uint32_t seed = 1, int leaf_size = 256,
                                        int bark_size = 256);

struct TreeAssetOptions {
  // Coverage-preserving alpha mipmaps for the leaf colour (textures.hpp); false gives plain box
  // mipmaps, with which distant leaves fade away under the alpha test (the seed's failure, kept
  // for comparison in tests and benchmarks).
  bool preserve_alpha_coverage = true;
};

class TreeAsset {
 public:
  // Needs a current GL 4.5 context.
  static Result<TreeAsset> create(const TreeMesh& mesh, const TreeTextureSet& textures, const TreeAssetOptions& options = {});
  TreeAsset() = default;

  std::size_t branch_index_count() const { return branch_index_count_; }
  std::size_t leaf_index_count() const { return leaf_index_count_; }
  std::size_t triangles() const { return (branch_index_count_ + leaf_index_count_) / 3; }
  std::size_t branch_vertex_count() const { return branch_vertex_count_; }
  std::size_t leaf_vertex_count() const { return leaf_vertex_count_; }
  glm::vec3 bounds_min() const { return bounds_min_; }
  glm::vec3 bounds_max() const { return bounds_max_; }

 private:
  friend class TreeRenderer;
  friend struct TreeAssetAccess;  // the slice bake (src/tree_asset_access.hpp) draws the rest pose
  render::Buffer branch_vbo_, branch_ibo_, leaf_vbo_, leaf_ibo_, branches_, leaves_;
  render::VertexArray branch_vao_, leaf_vao_;
  render::Texture leaf_color_, leaf_normal_, leaf_translucency_, leaf_coverage_, season_, bark_albedo_, bark_normal_;
  std::size_t branch_index_count_ = 0;
  std::size_t leaf_index_count_ = 0;
  std::size_t branch_vertex_count_ = 0;
  std::size_t leaf_vertex_count_ = 0;
  glm::vec3 bounds_min_{0.0f};
  glm::vec3 bounds_max_{0.0f};
};

struct TreeDrawParams {
  glm::mat4 view_proj{1.0f};                 // camera-relative view-projection of the pass
  ShadingSettings shading;                   // season, material, alpha mode
  AnimationLevel level = AnimationLevel::kLeaves;
  bool draw_bark = true;
  bool draw_leaves = true;
  // Sample the render core's shadow maps (bound by the host with ShadowMaps::bind()).
  bool receive_shadows = false;
};

class TreeRenderer {
 public:
  // Registers the module's shaders and builds the default (kLeaves) programs.
  static Result<TreeRenderer> create();
  TreeRenderer() = default;

  // Uploads the frame's animation and wind blocks (WindField::frame(time, camera origin).gpu).
  void set_frame(const AnimationGpu& animation, const WindGpuParams& wind);

  // Draws `count` instances starting at `first` of `instances` (InstanceGpu records) into the bound
  // framebuffer. Opaque: alpha-to-coverage when the target is multisampled (or as ShadingSettings
  // says). Adds draw calls, instances and triangles to `stats`.
  Status draw(render::Pass pass, const TreeAsset& asset, const render::Buffer& instances, std::uint32_t first,
              std::uint32_t count, const TreeDrawParams& params, render::PassStats& stats);

  // Test hook: draws instance `first` once with a program that also writes every vertex's
  // object-space position and normal (vec4 pairs, by vertex index) to a buffer, and returns them.
  // leaves = false captures the bark. The picture is drawn as in draw().
  Result<std::vector<glm::vec4>> capture(render::Pass pass, const TreeAsset& asset, const render::Buffer& instances,
                                         std::uint32_t first, const TreeDrawParams& params, bool leaves);

 private:
  struct Key {
    bool leaves;
    bool depth;
    int level;
    bool capture;
    auto operator<=>(const Key&) const = default;
  };
  Result<const render::Program*> program(const Key& key);
  Status draw_impl(render::Pass pass, const TreeAsset& asset, const render::Buffer& instances, std::uint32_t first,
                   std::uint32_t count, const TreeDrawParams& params, render::PassStats& stats, bool capture);

  std::map<Key, render::Program> programs_;
  render::Buffer no_shadows_ubo_;  // a SylvaShadows block with shadows disabled
  render::Buffer animation_ubo_;
  render::Buffer wind_ubo_;
};

}  // namespace sylva::vegetation
