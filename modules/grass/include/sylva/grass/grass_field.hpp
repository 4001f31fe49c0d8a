#pragma once
// GrassField: the GL renderer of one field of blades (a render::Drawable).
//
// Per frame (update): the CPU tests each tile's box against the frustum and near_distance and
// lists the visible tiles; grass/physics.comp advances the blades of those tiles (a tile that
// was out of view catches up with one larger step when it comes back, which the unconditionally
// stable integrator allows); grass/cull.comp culls blade by blade and appends the survivors to
// an index list whose length is the count of an indirect draw command. draw(kOpaque) then issues
// one indirect draw of GL_PATCHES (one vertex per blade) through blade.vert/.tesc/.tese/
// .frag, split into sub-draws of blades_per_draw() blades (culling.hpp says why) by
// grass/draw_batches.comp and issued as one glMultiDrawArraysIndirect per chunk. The far field (billboards and ground layer of seed 003) is a separate drawable,
// far_field.hpp, fed by the same settings.
//
// Ownership: the field owns its GPU buffers and a copy of the tiles; the blade array is moved to
// the GPU (read_blades() reads it back for tests). Needs a current GL 4.5 context for every
// call, including destruction. The lighting uniform block (render::LightingUniforms) must be
// bound by the caller before draw(), as for every module.
//
// Shadows (render core, modules/render/README.md "Lighting and shadows"): draw(kShadow) inside
// render::ShadowMaps::render() (render::active_shadow_cascade() non-null) casts the blades into
// the first `shadow_cascades` cascades: per cascade the CPU picks the tiles inside the light
// frustum whose nearest point is within min(near_distance, shadow_distance) of the camera (a
// cost bound; the cut moves tile by tile with the camera), cull.comp culls their blades against the light
// frustum with the camera's distance thinning and no orientation test (edge-on to the camera is
// not edge-on to the sun), and the blade tessellation shaders draw them with the cascade matrix
// and the same uniforms as the colour pass, so the shadow is the simulated, tessellated blade the
// camera sees. Tiles outside the camera's view keep the pose of their last simulated frame.
// The colour pass receives through render/lib/shadows.glsl when the caller bound
// ShadowMaps::bind() (UBO 2, texture unit 15) and shading.receive_shadows is on; with no shadow
// block bound the blades are lit (the block is never read unbound).
//
// Storage: blades are split at tile boundaries into chunks of at most
// GL_MAX_SHADER_STORAGE_BLOCK_SIZE / 96 blades (1.39 M on llvmpipe's 128 MB), one storage
// buffer, visible list and indirect draw per chunk, so one field holds any count up to
// kMaxBlades (2 M blades = 2 chunks). Callers see one field; blade indices stay global.
//
// Failure: create() returns kGl when a shader does not compile (message names file:line),
// kInvalidArgument when tiles overlap or point outside the blade array, and kLimit when one tile
// alone exceeds the storage limit.

#include <sylva/core/params.hpp>
#include <sylva/core/result.hpp>
#include <sylva/core/wind.hpp>
#include <sylva/grass/culling.hpp>
#include <sylva/grass/generator.hpp>
#include <sylva/grass/physics.hpp>
#include <sylva/grass/settings.hpp>
#include <sylva/render/buffer.hpp>
#include <sylva/render/camera.hpp>
#include <sylva/render/drawable.hpp>
#include <sylva/render/queries.hpp>
#include <sylva/render/shader_library.hpp>
#include <sylva/render/shadow_maps.hpp>
#include <sylva/render/vertex_array.hpp>

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace sylva::grass {

// Blade outline (Jahrmann & Wimmer 2017 shape functions) applied on seed 001's two splines.
enum class BladeShape { kQuad, kTriangle, kQuadratic, kTriangleTip };
constexpr std::array<EnumName<BladeShape>, 4> enum_names(BladeShape) {
  return {{{BladeShape::kQuad, "quad"},
           {BladeShape::kTriangle, "triangle"},
           {BladeShape::kQuadratic, "quadratic"},
           {BladeShape::kTriangleTip, "triangle_tip"}}};
}

// Everything the renderer reads per frame (no rebuild needed when it changes).
struct GrassRenderSettings {
  PhysicsSettings physics;
  CullSettings cull;
  ShadingSettings shading;
  BladeShape shape = BladeShape::kQuadratic;
  glm::vec3 base_color{0.045f, 0.16f, 0.035f};  // linear RGB at the root
  glm::vec3 tip_color{0.32f, 0.50f, 0.13f};     // linear RGB at the tip (a less saturated, warmer green reads as grass under tone mapping)
  bool simulate = true;                         // physics on/off (off: blades keep their pose)
  bool cast_shadows = true;                     // draw into the sun's shadow cascades
  int shadow_cascades = 2;                      // cast into cascades 0 .. shadow_cascades - 1 only
  float shadow_distance = 10.0f;                // only tiles nearer the camera than this cast [m]

  template <class V>
  void visit(V& v) {
    v(physics, "physics");
    v(cull, "cull");
    v(shading, "shading");
    v(shape, "shape", {.help = "Blade outline: quad, triangle, quadratic or triangle_tip"});
    v(base_color, "base_color", {.min = 0.0f, .max = 1.0f, .unit = "linear RGB", .help = "Colour at the root"});
    v(tip_color, "tip_color", {.min = 0.0f, .max = 1.0f, .unit = "linear RGB", .help = "Colour at the tip"});
    v(simulate, "simulate", {.help = "Run the blade physics"});
    v(cast_shadows, "cast_shadows", {.help = "Blades cast into the sun's shadow cascades"});
    v(shadow_cascades, "shadow_cascades", {.min = 0.0f, .max = 4.0f,
                                           .help = "Blades cast only into the nearest this many cascades (cost bound)"});
    v(shadow_distance, "shadow_distance", {.min = 0.0f, .max = 5000.0f, .unit = "m",
                                           .help = "Only tiles nearer the camera than this cast (cost bound)"});
  }
};

// Counters of one frame (GPU counters are read back on request, see read_frame_stats()).
struct GrassFrameStats {
  std::uint64_t blades_total = 0;
  std::uint64_t tiles_total = 0;
  std::uint64_t tiles_visible = 0;
  CullCounts counts;               // per-blade results of cull.comp (considered = blades in visible tiles)
  std::uint64_t blades_in_culled_tiles = 0;
  std::uint64_t overflow = 0;      // survivors that did not fit the visible list (always 0)
  std::size_t chunks = 0;          // storage buffers the blades are split into
};

// Counters of the last shadow pass (all cascades drawn since the previous update()).
struct GrassShadowStats {
  std::uint64_t cascades = 0;      // cascades the blades were drawn into
  std::uint64_t considered = 0;    // blades in tiles inside a light frustum (summed over cascades)
};

class GrassField : public render::Drawable {
 public:
  GrassField() = default;
  // Uploads `blades` and builds the programs. The blades are moved to the GPU.
  // `max_blades_per_buffer` (0 = the GL limit) lowers the chunk size (tests split small fields).
  static Result<GrassField> create(BladeSet blades, const GrassRenderSettings& settings = {},
                                   std::size_t max_blades_per_buffer = 0);

  // Replaces the blades (a regenerated set, e.g. after regenerate_tiles) without rebuilding the
  // programs: what a map edit costs on the GPU side is one upload. Physics state restarts.
  // Errors as create() (the field is unchanged on error).
  Status set_blades(const BladeSet& blades);

  GrassField(GrassField&&) noexcept = default;
  GrassField& operator=(GrassField&&) noexcept = default;

  GrassRenderSettings& settings() { return settings_; }
  const GrassRenderSettings& settings() const { return settings_; }

  // Colliders in world coordinates (converted to blade-set local). At most kMaxColliders - 1
  // (one slot is kept for settings().physics.camera_collider_radius). Only blades of tiles in
  // view are simulated, so a collider acts on the grass the camera sees.
  static constexpr std::size_t kMaxColliders = 64;
  void set_colliders(std::span<const glm::dvec3> centers, std::span<const float> radii);

  // CPU tile culling, physics and blade culling on the GPU (see the header comment).
  void update(const render::FrameContext& frame) override;
  // kOpaque: the blades. kShadow: inside ShadowMaps::render() casts into the active cascade
  // (see the header comment), else nothing. kTransparent: nothing.
  void draw(render::Pass pass, const render::FrameContext& frame, render::PassStats& stats) override;
  // The caster entry point for one cascade (what draw(kShadow) calls); needs update() first.
  void draw_shadow(const render::ShadowCasterContext& cascade, render::PassStats* stats = nullptr);

  // Same as update() with explicit inputs (tools and tests without a scene).
  void update(const render::Camera& camera, glm::ivec2 viewport, double time, float dt, const WindField& wind);
  void draw_blades(const render::Camera& camera, render::PassStats* stats = nullptr);

  // Blades per sub-draw: 0 (default) = blades_per_draw(max_tess_level, tess_spacing of settings().cull), the
  // llvmpipe-safe size (culling.hpp); any other value is used as is (tests compare sizes; a
  // driver without the limit could draw in fewer calls). Reallocates the command buffers.
  void set_blades_per_draw(std::uint32_t blades);

  // Draw order. cull.comp appends the visible blades in the order its atomics happen to run,
  // which changes from frame to frame and run to run, and a picture can differ where two blades
  // meet at exactly the same depth. On: every visible list is read back and sorted by blade index
  // after culling (a stall; for reference renders and tests that compare pictures), so the same
  // blades always give the same picture.
  void set_sorted_draw_order(bool on) { sorted_draw_order_ = on; }

  const glm::dvec3& origin() const { return origin_; }
  const std::vector<GrassTile>& tiles() const { return tiles_; }
  std::size_t blade_count() const { return blade_count_; }
  std::size_t chunk_count() const { return chunks_.size(); }
  const GrassShadowStats& shadow_stats() const { return shadow_stats_; }
  float max_height() const { return max_height_; }

  // Stalling read-backs for tests and benchmarks.
  std::vector<Blade> read_blades() const;
  GrassFrameStats read_frame_stats() const;
  // GPU time of the last completed frames' passes [ms] (non-stalling; nullopt until available).
  struct GpuTimes {
    double simulate_ms = 0.0;
    double cull_ms = 0.0;
    double draw_ms = 0.0;
    std::uint64_t primitives = 0;  // GL_PRIMITIVES_GENERATED by the blade draw
  };
  std::optional<GpuTimes> gpu_times(bool wait = false);

 private:
  struct TileJob {
    std::uint32_t first;
    std::uint32_t count;
    float dt;
    std::uint32_t flags;
  };
  // One pass's culling state of a chunk (the colour and the shadow pass each have their own,
  // so the colour list survives the shadow pass).
  struct PassLists {
    std::vector<TileJob> job_list;  // visible tiles; kept to reuse its capacity
    render::Buffer jobs;            // job_list on the GPU
    render::Buffer visible;         // indices of the blades that survived cull.comp
    render::Buffer command;         // CommandBlock: cull count and statistics
    render::Buffer batches;         // sub-draw commands (draw_batches.comp)
    std::uint32_t batch_count = 0;  // commands written into `batches` this frame
  };
  // One storage buffer's worth of blades: a contiguous blade range [first_blade, + blade_count)
  // holding whole tiles. Visible lists and draw commands are per chunk and per pass.
  struct Chunk {
    std::uint32_t first_blade = 0;
    std::uint32_t blade_count = 0;
    render::Buffer blades;
    PassLists colour;
    PassLists shadow;
  };
  std::uint32_t blades_per_sub_draw() const;
  void allocate_draw_batches();
  // Resets every chunk's command block of the pass and uploads its job list.
  void reset_pass(PassLists Chunk::*lists);
  // Runs cull.comp over every chunk with jobs (the caller set the cull uniforms), then
  // draw_batches.comp, with the barriers the indirect draw needs.
  void cull_chunks(PassLists Chunk::*lists);
  // set_sorted_draw_order(): sorts each chunk's visible list of the pass (after cull.comp).
  void sort_visible_lists(PassLists Chunk::*lists);
  // Draws every chunk's sub-draws with the bound blade program.
  void draw_chunks(PassLists Chunk::*lists, render::PassStats* stats) const;
  void set_cull_uniforms(const render::Program& program, const CullView& view) const;
  void set_blade_uniforms(const render::Program& program, const glm::mat4& relative_view_projection,
                          const render::Camera& camera) const;

  bool sorted_draw_order_ = false;
  GrassRenderSettings settings_;
  glm::dvec3 origin_{0.0};
  std::vector<GrassTile> tiles_;
  std::vector<std::uint32_t> tile_chunk_;  // chunk of each tile
  std::size_t max_blades_per_buffer_ = 0;  // create()'s limit (0 = the GL limit)
  double time_ = 0.0;                  // simulation time of the last update() [s] (colour motion)
  std::vector<double> tile_sim_time_;  // last time each tile was simulated; < 0: never
  std::size_t blade_count_ = 0;
  float max_height_ = 0.0f;

  std::vector<Chunk> chunks_;
  render::Buffer spheres_;
  render::Buffer wind_;
  render::VertexArray vao_;
  render::Program physics_;
  render::Program cull_;
  render::Program draw_;
  render::Program depth_;
  TessSpacing blade_spacing_ = TessSpacing::kEqual;  // the cull.tess_spacing draw_ and depth_ were built for
  render::Program batch_;
  std::uint32_t blades_per_draw_override_ = 0;
  GrassShadowStats shadow_stats_;
  render::PassQuery sim_query_;
  render::PassQuery cull_query_;
  render::PassQuery draw_query_;
  std::uint64_t frame_ = 0;
  std::vector<glm::vec4> colliders_;  // blade-set local centre, radius
  std::size_t job_count_ = 0;
  std::uint64_t blades_in_culled_tiles_ = 0;
  CullView view_{};
  float ppr_ = 1.0f;
  glm::vec3 camera_local_{0.0f};
};

}  // namespace sylva::grass
