#pragma once
// The GL 4.5 terrain renderer: a render::Drawable over a chunk tree (in memory or streamed).
//
// update(): builds a LodView from the frame's camera, selects chunks (streaming: only resident
// ones, requesting the rest), and assembles the per-frame seam (or skirt) batch. draw(): the
// opaque pass draws every selected chunk (one indexed draw each, meshes uploaded on first use
// and kept in an LRU GPU cache), then the seam batch with the same program, then the debug
// overlays; the shadow pass draws depth into the active cascade. Shading: normals and curvature
// from the full-resolution shape texture, the layered material of material.hpp (altitude bands
// in metres for the climate set by set_climate, slope, curvature, tiling detail at three scales,
// triplanar cliffs), sun, ambient, fog (render/lib) and, when the host binds them, cascaded
// shadows.

#include <sylva/core/height_field.hpp>
#include <sylva/core/result.hpp>
#include <sylva/render/buffer.hpp>
#include <sylva/render/drawable.hpp>
#include <sylva/render/frustum.hpp>
#include <sylva/render/shader_library.hpp>
#include <sylva/render/texture.hpp>
#include <sylva/render/vertex_array.hpp>
#include <sylva/terrain/chunk_tree.hpp>
#include <sylva/terrain/material.hpp>
#include <sylva/terrain/seams.hpp>
#include <sylva/terrain/selection.hpp>
#include <sylva/terrain/settings.hpp>
#include <sylva/terrain/streaming.hpp>
#include <sylva/terrain/vertex_position.hpp>

#include <array>
#include <cstdint>
#include <memory>
#include <unordered_map>
#include <vector>

namespace sylva::terrain {

class FarMaterialBake;

// kMaterials: unlit layer colours (snow white, rock and scree grey, dirt brown, sand yellow,
// grass and meadow green), where the material put each layer.
enum class DebugView : std::uint8_t { kShaded, kLodColors, kMorph, kFlat, kMaterials };
constexpr std::array<EnumName<DebugView>, 5> enum_names(DebugView) {
  return {{{DebugView::kShaded, "shaded"}, {DebugView::kLodColors, "lod_colors"}, {DebugView::kMorph, "morph"},
           {DebugView::kFlat, "flat"}, {DebugView::kMaterials, "materials"}}};
}

// The air between the camera and the ground (render/lib/fog.glsl: Rayleigh and aerosol
// extinction, haze, in-scattering toward the sky's colour). kPerPixel evaluates it all for every
// pixel (apply_fog); kPerVertex (default) evaluates the extinction per metre at the chunk
// vertices (air_extinction) and interpolates it, the pixel keeping its own distance, exponential
// and sky look-up (air_from_vertex): within 1/255 of kPerPixel on the race view and the shipped
// terrain and lake scenes (README "vs CDLOD"), a few per cent cheaper; kOff draws the ground
// without air, as BaronVerde/cdlod does (the race scene's "fog off"; far ground then no longer
// meets the horizon in the sky's colour).
enum class AerialPerspective : std::uint8_t { kPerPixel, kPerVertex, kOff };
constexpr std::array<EnumName<AerialPerspective>, 3> enum_names(AerialPerspective) {
  return {{{AerialPerspective::kPerPixel, "per_pixel"},
           {AerialPerspective::kPerVertex, "per_vertex"},
           {AerialPerspective::kOff, "off"}}};
}

// The material of far chunks, those that draw no detail scale (issue 18). kComputed (default)
// evaluates the layer arithmetic for every pixel, as nearer chunks always do; kBaked reads the
// albedo and occlusion from a texture baked once per field sample on the GPU
// (src/far_material.hpp: the same material.glsl, re-baked where the field is edited and when the
// material or climate changes) for chunks whose field samples span at most 4 pixels (the bake's
// bilinear magnification is then invisible) and mip-filters it where samples are smaller than a
// pixel. Not the default: on llvmpipe one filtered fetch costs about what the far material's
// arithmetic does (README "vs CDLOD": the race view gains nothing measurable).
enum class FarMaterial : std::uint8_t { kBaked, kComputed };
constexpr std::array<EnumName<FarMaterial>, 2> enum_names(FarMaterial) {
  return {{{FarMaterial::kBaked, "baked"}, {FarMaterial::kComputed, "computed"}}};
}

struct TerrainRenderSettings {
  LodSettings lod;
  MaterialSettings material;
  DebugView debug_view = DebugView::kShaded;
  AerialPerspective aerial_perspective = AerialPerspective::kPerVertex;
  FarMaterial far_material = FarMaterial::kComputed;
  bool wireframe = false;       // chunk triangles as lines over the shaded terrain
  bool chunk_bounds = false;    // bounding boxes of the drawn chunks
  // Sample the host's cascaded shadows (needs ShadowMaps::bind()) on frames whose shadow pass ran
  // (draw(kShadow) with an active cascade); other frames draw without the receiving code.
  bool receive_shadows = true;
  bool cast_shadows = true;
  double gpu_cache_mb = 512.0;  // uploaded chunk meshes kept on the GPU

  template <class V>
  void visit(V& v) {
    v(lod, "lod");
    v(material, "material");
    v(debug_view, "debug_view", {.help = "shaded, lod_colors, morph, flat or materials"});
    v(aerial_perspective, "aerial_perspective",
      {.help = "The air over the ground: per_vertex (extinction interpolated), per_pixel or off"});
    v(far_material, "far_material",
      {.help = "Far ground's material: computed per pixel, or baked (a texture per field sample)"});
    v(wireframe, "wireframe", {.help = "Draw triangle edges"});
    v(chunk_bounds, "chunk_bounds", {.help = "Draw the drawn chunks' bounding boxes"});
    v(receive_shadows, "receive_shadows", {.help = "Receive cascaded shadows", .rebuild = Rebuild::kGpu});
    v(cast_shadows, "cast_shadows", {.help = "Cast into the shadow cascades"});
    v(gpu_cache_mb, "gpu_cache_mb", {.min = 1.0, .max = 1e6, .unit = "MiB", .help = "GPU chunk mesh cache",
      .log_scale = true});
  }
};

struct TerrainFrameStats {
  SelectionStats selection;
  std::uint64_t seam_triangles = 0;
  std::uint64_t skirt_triangles = 0;
  std::uint64_t uploads = 0;      // chunk meshes uploaded this frame
  std::uint32_t far_baked_chunks = 0;  // chunks drawn with the baked far material (far_material)
  std::uint32_t beyond_shadow_chunks = 0;  // chunks outside every shadow map, drawn without receiving
  double update_ms = 0.0;         // selection + batch assembly
  std::size_t gpu_bytes = 0;      // resident GPU meshes
};

class TerrainRenderer final : public render::Drawable {
 public:
  // In-memory tree (built with keep_meshes). `field` (may be null) gives the height texture for
  // normals and materials; without it normals come from the triangles. Needs a current GL 4.5
  // context. Errors: kInvalidArgument (tree without meshes), kGl (shader build).
  static Result<std::unique_ptr<TerrainRenderer>> create(std::shared_ptr<const ChunkTree> tree, const HeightField* field,
                                                         const TerrainRenderSettings& settings);
  // Streamed tree: meshes come from the streamer (owned by the renderer).
  static Result<std::unique_ptr<TerrainRenderer>> create(std::unique_ptr<ChunkStreamer> streamer,
                                                         const HeightField* field,
                                                         const TerrainRenderSettings& settings);
  ~TerrainRenderer() override;

  // Live height editing (issue 9): applies an edit of the samples [x0, x1) x [z0, z1) (x1/z1
  // exclusive) of `field`, the whole edited field the tree was built from. The renderer's tree
  // is replaced by a copy updated with ChunkTree::rebuild_region (the old tree may be shared, so
  // it is never modified); only the rebuilt/updated chunks' GPU meshes are dropped (re-uploaded
  // on their next draw) and only the seams touching them rebuilt; the height texture is
  // re-uploaded. A streamed renderer hands the edit to ChunkStreamer::apply_height_edit (the
  // chunks it reaches rebuilt from `field` by the bake's code, issue 15) and drops every GPU mesh
  // and seam. Errors: rebuild_region's or the streamer's; the renderer is unchanged on error.
  // Needs the renderer's GL context current.
  Result<RegionRebuild> apply_height_edit(const HeightField& field, int x0, int z0, int x1, int z1);

  void update(const render::FrameContext& frame) override;
  void draw(render::Pass pass, const render::FrameContext& frame, render::PassStats& stats) override;

  // Latitude and season of the scene (the material's snow line); default Climate{}.
  void set_climate(const Climate& climate) { climate_ = climate; }
  const Climate& climate() const { return climate_; }

  TerrainRenderSettings& settings() { return settings_; }
  const TerrainRenderSettings& settings() const { return settings_; }
  const ChunkTree& tree() const { return *tree_; }
  const Selection& selection() const { return *selection_; }
  const VertexFrame& vertex_frame() const { return frame_; }
  const TerrainFrameStats& frame_stats() const { return stats_; }
  ChunkStreamer* streamer() { return streamer_.get(); }
  // The full-resolution height texture (make_height_texture) when a field was given and fits
  // GL_MAX_TEXTURE_SIZE, else null. Other modules may sample it (height_texture_info for uv).
  const render::Texture* height_texture() const { return has_heights_ ? &heights_ : nullptr; }
  // Texels of the height texture re-uploaded by apply_height_edit so far: only each edit's
  // rectangle (update_height_texture), independent of the field size (issue 15).
  std::int64_t height_texels_uploaded() const { return height_texels_uploaded_; }
  // Whether the last colour pass drew with the shadow-receiving programs: receive_shadows and a
  // shadow pass in the same frame (the program a frame without one runs has no receiving code).
  bool shadows_received() const { return shaded_with_shadows_; }
  // Field samples the baked far material has evaluated so far (all of them per full bake, each
  // edit's grown rectangle after): 0 before the first frame that draws with it.
  std::int64_t far_material_texels_baked() const;

  // The LodView a camera and viewport give (what update() selects with).
  static LodView view_for(const render::Camera& camera, glm::ivec2 viewport);

 private:
  TerrainRenderer() = default;
  Status init(const HeightField* field);
  struct GpuMesh {
    render::VertexArray vao;
    render::Buffer vertices, indices;
    std::uint32_t index_count = 0;
    std::size_t bytes = 0;
    std::uint64_t last_used = 0;
  };
  GpuMesh* gpu_mesh(std::uint32_t chunk);
  Result<RegionRebuild> apply_streamed_edit(const HeightField& field, int x0, int z0, int x1, int z1);
  void update_height_textures(const HeightField& field, int x0, int z0, int x1, int z1);
  void set_frame_uniforms(const render::Program& program, const glm::mat4& view_projection) const;
  struct BatchVertex;
  // shadow: the unculled caster selection and its batch; cull: chunk boxes outside are skipped;
  // chunk_programs: one per selected chunk (its frame uniforms set) to draw it with instead.
  void draw_geometry(const render::Program& program, const glm::mat4& view_projection, bool debug_levels,
                     render::PassStats& stats, bool shadow, const render::Frustum* cull,
                     const std::vector<const render::Program*>* chunk_programs = nullptr);
  void assemble_batch(const Selection& selection, std::vector<BatchVertex>& batch);

  TerrainRenderSettings settings_;
  std::shared_ptr<const ChunkTree> tree_;
  std::unique_ptr<ChunkStreamer> streamer_;
  MeshSource meshes_;
  std::unique_ptr<LodSelector> selector_, shadow_selector_;
  const Selection* selection_ = nullptr;
  const Selection* shadow_selection_ = nullptr;  // casters: the camera's LOD, not its frustum
  Selection empty_selection_;
  SeamCache seams_;
  VertexFrame frame_;
  TerrainFrameStats stats_;
  std::uint64_t frame_number_ = 0;
  std::uint64_t shadow_pass_frame_ = 0;  // the last frame whose shadow pass reached draw(kShadow)
  // The side planes (camera-relative, inward) of that pass's cascades and a margin [m] covering
  // the receiver's normal offset and PCF reach: a chunk outside one side plane of every cascade
  // by the margin gets sylva_shadow = 1 on every pixel (shadows.glsl), so it is drawn without it.
  struct CascadeFootprint {
    std::array<glm::vec4, 4> sides;
    glm::dvec3 origin{0.0};
    double margin_m = 0.0;
  };
  std::vector<CascadeFootprint> shadow_cascades_;
  bool beyond_shadow_maps(const glm::dvec3& lo, const glm::dvec3& hi) const;

  // shaded_ is compiled for one debug view and the shadow switch (terrain.frag); flat_ draws the
  // wireframe overlay, compiled when first asked for.
  render::Program shaded_, flat_, depth_, bounds_;
  // shaded_ without the detail scales finer than 1, 2, 3 (none), for chunks beyond their fades
  // (first_detail_scale); compiled for the shaded and materials views only. [3]: no detail scale
  // and the air's sky radiance per vertex too (per_vertex only), for such chunks wholly below
  // the camera, where the sky below the horizon varies smoothly with the view direction.
  render::Program shaded_coarse_[4];
  // far_material baked: shaded_coarse_[2] and [3] reading the baked far material instead of
  // computing it (SYLVA_TERRAIN_BAKED), for chunks whose field samples span few pixels.
  render::Program shaded_baked_[2];
  // With shadows received: shaded_coarse_[2] and [3] without the receiving code, for chunks
  // beyond every shadow map (beyond_shadow_maps).
  render::Program unshadowed_far_[2];
  FarMaterial shaded_far_ = FarMaterial::kComputed;
  std::vector<const render::Program*> chunk_programs_;  // per selected chunk, this frame (reused)
  bool shaded_with_shadows_ = false;
  DebugView shaded_view_ = DebugView::kShaded;
  AerialPerspective shaded_air_ = AerialPerspective::kPerVertex;
  render::Texture heights_;
  bool has_heights_ = false;
  std::int64_t height_texels_uploaded_ = 0;
  // Material: the tiling detail noise, the field's normal + curvature (when the heights fit on
  // the GPU) and the curvature radius it was computed with.
  render::Texture detail_, shape_;
  float shape_radius_m_ = 0.0f;
  float field_spacing_m_ = 1.0f;
  // The baked far material, made on the first frame that draws with it (null before and when it
  // could not be made: then far chunks compute their material).
  std::unique_ptr<FarMaterialBake> far_bake_;
  bool far_bake_failed_ = false;
  // Makes (once) and refreshes far_bake_; false where there is none.
  bool bake_far_material();
  Climate climate_;
  std::unordered_map<std::uint32_t, GpuMesh> gpu_;
  std::size_t gpu_bytes_ = 0;
  // Per-frame batches: seams or skirts (vertex = grid, height/target/error, skirt depth).
  struct BatchVertex {
    std::uint32_t gx, gz;
    float height, morph_target, morph_error, skirt;
  };
  std::vector<BatchVertex> batch_, shadow_batch_;
  render::Buffer batch_buffer_, shadow_batch_buffer_;
  bool batch_uploaded_ = false, shadow_batch_uploaded_ = false;
  render::VertexArray batch_vao_;
  std::vector<glm::vec3> bounds_lines_;
  render::Buffer bounds_buffer_;
  render::VertexArray bounds_vao_;
};

}  // namespace sylva::terrain
