#pragma once
// The GL 4.5 renderer of the general-model chunk tree (seed 002 §4, model_tree.hpp): a
// render::Drawable over a ModelTree, i.e. a triangle mesh with overhangs split into a quadtree of
// segments whose borders are locked.
//
// One vertex buffer holds the tree's positions (relative to the root's ground-plane origin) and
// per-vertex normals of the original mesh (area-weighted normals of the leaf triangles, which are
// the original ones, §4.4); one index buffer holds every present segment's reduced triangles as a
// range. Both are uploaded once (tracked GPU memory, render/gpu_memory.hpp). update() selects
// segments with select_segments (the same screen-space tau and LodView as the height-field
// terrain, renderer.hpp); draw() issues one indexed draw per selected segment. Because every
// segment indexes the one shared vertex array and a locked border vertex is the same vertex at
// every level (§4.2), neighbouring segments of different levels meet in bit-identical vertices
// (gl_Position is invariant): no run-time seams, as in the seed. Shading: the height-field
// terrain's layered material (shaders/material.glsl) by altitude and slope from the vertex
// normal, sun, ambient, fog and, when the host binds them, cascaded shadows; the shadow pass
// draws the camera's LOD without its frustum into the active cascade.

#include <sylva/core/params.hpp>
#include <sylva/core/result.hpp>
#include <sylva/render/buffer.hpp>
#include <sylva/render/drawable.hpp>
#include <sylva/render/shader_library.hpp>
#include <sylva/render/texture.hpp>
#include <sylva/render/vertex_array.hpp>
#include <sylva/terrain/lod_view.hpp>
#include <sylva/terrain/material.hpp>
#include <sylva/terrain/model_tree.hpp>

#include <array>
#include <memory>
#include <vector>

namespace sylva::terrain {

// kLodColors: each segment tinted by its level; kFlat: one unlit colour (flat_color).
enum class ModelDebugView : std::uint8_t { kShaded, kLodColors, kFlat };
constexpr std::array<EnumName<ModelDebugView>, 3> enum_names(ModelDebugView) {
  return {{{ModelDebugView::kShaded, "shaded"}, {ModelDebugView::kLodColors, "lod_colors"},
           {ModelDebugView::kFlat, "flat"}}};
}

// The selection's settings: the screen-space rule of the height-field terrain (LodSettings'
// max_pixel_error and frustum_cull; morphing and crack fixes do not apply, the borders are locked).
struct ModelLodSettings {
  float max_pixel_error = 1.0f;  // tau [px], as LodSettings
  bool frustum_cull = true;

  template <class V>
  void visit(V& v) {
    v(max_pixel_error, "max_pixel_error", {.min = 0.05, .max = 64.0, .unit = "px",
      .help = "Largest allowed projected error of a segment (tau)", .log_scale = true});
    v(frustum_cull, "frustum_cull", {.help = "Skip segments outside the view frustum"});
  }
  LodSettings lod() const {
    LodSettings s;
    s.max_pixel_error = max_pixel_error;
    s.frustum_cull = frustum_cull;
    return s;
  }
};

struct ModelRenderSettings {
  ModelLodSettings lod;
  MaterialSettings material;
  ModelDebugView debug_view = ModelDebugView::kShaded;
  glm::vec3 flat_color{0.6f, 0.6f, 0.6f};
  bool wireframe = false;       // triangle edges over the shaded model
  bool receive_shadows = true;  // sample the host's cascaded shadows (needs ShadowMaps::bind())
  bool cast_shadows = true;

  template <class V>
  void visit(V& v) {
    v(lod, "lod");
    v(material, "material");
    v(debug_view, "debug_view", {.help = "shaded, lod_colors or flat"});
    v(flat_color, "flat_color", {.min = 0.0, .max = 1.0, .help = "Colour of the flat debug view (linear RGB)"});
    v(wireframe, "wireframe", {.help = "Draw triangle edges"});
    v(receive_shadows, "receive_shadows", {.help = "Receive cascaded shadows", .rebuild = Rebuild::kGpu});
    v(cast_shadows, "cast_shadows", {.help = "Cast into the shadow cascades"});
  }
};

struct ModelFrameStats {
  std::uint32_t segments = 0;       // drawn this frame
  std::uint32_t culled = 0;         // segments outside the frustum
  std::uint64_t triangles = 0;      // of the drawn segments
  std::vector<std::uint32_t> segments_per_level;
  double select_ms = 0.0;
  // LOD selections (tree traversals) run this frame: 1, shadows or not (the casters' selection
  // comes from the same traversal as the camera's).
  std::uint32_t selections = 0;
  double max_projected_error_px = 0.0;  // largest rho of a drawn segment (0 for leaves)
  std::size_t gpu_bytes = 0;        // vertex + index buffers
};

class ModelRenderer final : public render::Drawable {
 public:
  // Needs a current GL 4.5 context. Errors: kInvalidArgument (null tree, invalid settings, a tree
  // with no triangles), kGl (shader build).
  static Result<std::unique_ptr<ModelRenderer>> create(std::shared_ptr<const ModelTree> tree,
                                                       const ModelRenderSettings& settings);
  ~ModelRenderer() override;

  void update(const render::FrameContext& frame) override;
  void draw(render::Pass pass, const render::FrameContext& frame, render::PassStats& stats) override;

  // Latitude and season of the scene (the material's snow line); default Climate{}.
  void set_climate(const Climate& climate) { climate_ = climate; }

  ModelRenderSettings& settings() { return settings_; }
  const ModelRenderSettings& settings() const { return settings_; }
  const ModelTree& tree() const { return *tree_; }
  const ModelSelection& selection() const { return selection_; }
  // The shadow casters of the frame: the camera's LOD decisions without its frustum (empty
  // unless settings().cast_shadows); each cascade culls them by its own box.
  const ModelSelection& caster_selection() const { return shadow_selection_; }
  const ModelFrameStats& frame_stats() const { return stats_; }

  // The projected error rho = K * delta / (D - delta) of a segment seen from `view` (the rule of
  // select_segments; 0 for a leaf or an exact segment, +inf when the camera is within delta).
  static double projected_error(const ModelTree& tree, std::uint32_t segment, const LodView& view);
  // Unit per-vertex normals of the original mesh: the area-weighted normals of the leaf
  // triangles (the leaves hold the original triangles, seed §4.4). Unused vertices get +y.
  static std::vector<glm::vec3> vertex_normals(const ModelTree& tree);

 private:
  ModelRenderer() = default;
  Status init();
  Result<render::Program> shaded_program(bool shadows) const;
  void draw_segments(const render::Program& program, const ModelSelection& selection, bool tint,
                     render::PassStats& stats, const render::Frustum* cull);

  ModelRenderSettings settings_;
  std::shared_ptr<const ModelTree> tree_;
  glm::dvec3 origin_{0.0};  // world position of vertex-buffer coordinate 0
  ModelSelection selection_, shadow_selection_;
  ModelFrameStats stats_;
  Climate climate_;
  render::Program shaded_, depth_;
  bool shaded_with_shadows_ = false;
  render::Texture detail_;
  render::Buffer vertices_, indices_;
  render::VertexArray vao_;
  std::vector<std::uint32_t> first_index_;  // per segment: offset into the index buffer
};

}  // namespace sylva::terrain
