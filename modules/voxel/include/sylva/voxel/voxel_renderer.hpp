#pragma once
// GL renderer of a voxel World (seed 004 §1-§3): a render::Drawable.
//
//  * Chunk meshes are drawn by vertex pulling: each chunk's PackedQuads sit in one shader
//    storage buffer, 6 vertices per quad are generated from gl_VertexID. Opaque quads first with
//    back-face culling and a fragment shader without discard (early-z), then alpha-cut quads
//    without culling and with an alpha test (seed §2.1, §2.2, §3.7.1).
//  * Block textures come from a texture array of procedurally generated tiles (diffuse sRGB +
//    specular map), one layer per TextureId; the top/side/bottom layer of a block comes from a
//    block table in a storage buffer (seed §1.3's three-part grass block).
//  * Phong lighting (seed §2.3): ambient (hemisphere, scaled by per-vertex AO), sun diffuse,
//    specular from the specular map, and up to max_point_lights point lights from emissive
//    blocks nearest the camera with attenuation 1 / (Kc + Kl d + Kq d^2) (Kc = 1, Kl = 0.045,
//    Kq = 0.0075), plus the host's point lights (render/lib/point_lights.glsl, UBO 3, bound by
//    the host with PointLightUniforms::bind; none when nothing is bound). The sun term is multiplied by the render core's cascaded shadows
//    (render/lib/shadows.glsl, bound by the host with ShadowMaps::bind); set_shadow_receiver
//    replaces that lookup (tests, other shadow techniques).
//  * Shadow casting (seed §3.7.1): opaque chunk quads and opaque plant parts draw depth with an
//    empty early-z fragment shader, alpha-cut quads and parts with the alpha test, so leaves cast
//    cut-out shadows. Chunks are culled against the cascade's light frustum (which reaches toward
//    the sun), not the camera frustum: off-screen pillars and trees shadow the view.
//  * Camera-relative: every chunk is drawn with the offset (chunk origin - camera position)
//    computed in double, so chunks 1e6 blocks from the origin render exactly like at the origin.
//  * Chunk frustum culling on the CPU against the chunk box grown by its plants' bounds.
//  * L-system plants: one instance per turtle-placed block (position, size, rotation, block),
//    batched per chunk, drawn as instanced cubes (the seed's flyweight, §1.4).
//  * Grass tufts and flowers (sides-only blocks) are not drawn from the chunk mesh: each is an
//    instanced pair of crossed cut-out quads, jittered, sized, turned and tinted by a hash of its
//    position (tufts.hpp), so they stand in no grid rows. They receive shadows but cast none.
//  * View distance: geometry fades into the sky at the horizon between (1 - fade_share) x and 1 x
//    the view distance (horizontal, from the camera); chunks wholly beyond it are not drawn and a
//    horizon skirt in the same colour (a disc under the lowest loaded block) covers what lies
//    farther, so the edge of the loaded area and the void behind it never show.
//  * Plant cubes draw only the three faces turned to the eye (18 vertices) when the rest cannot
//    show: opaque parts always, leaf parts beyond leaf_back_faces_within.
//  * Colour shader variants per frame for what it lacks (issue #18: llvmpipe runs both sides of
//    a branch and an empty loop's body for every pixel): no point-light loops without lights, no
//    shadow look-up while the host's shadows are disabled, no fade for chunks nearer than its
//    start (stats point_light_shaders, shadow_lookup_shaders, chunks_faded). Plants and tufts
//    are drawn before the chunks, so early depth tests keep shading off the ground they hide.
// One block = 1 world unit (metre).

#include <sylva/core/result.hpp>
#include <sylva/render/buffer.hpp>
#include <sylva/render/drawable.hpp>
#include <sylva/render/frustum.hpp>
#include <sylva/render/shader_library.hpp>
#include <sylva/render/point_lights.hpp>
#include <sylva/render/shadow_maps.hpp>
#include <sylva/render/texture.hpp>
#include <sylva/render/vertex_array.hpp>
#include <sylva/voxel/mesher.hpp>
#include <sylva/voxel/world.hpp>
#include <sylva/voxel/worldgen.hpp>

#include <cstdint>
#include <functional>
#include <array>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

namespace sylva::voxel {

class PlantFaceCache;  // plant_batch.hpp (internal)

// Fragment shaders of the shadow (depth) pass, seed 004 §3.7.1 (R1): `discard` switches early depth
// tests off, so the seed split the casters: an empty shader with early tests for opaque geometry and
// an alpha-testing one for cut-out textures only. The two single-shader variants are the thesis's
// comparison rows: alpha-test everything (correct, slower) or early-z everything (fast, but
// cut-out leaves cast solid squares).
enum class ShadowPassShaders {
  kSplit,        // opaque: empty shader + early tests; alpha-cut: alpha test (the seed's choice)
  kAlphaTested,  // every caster alpha-tested
  kEarlyZ,       // every caster through the empty shader (cut-outs cast as solid quads)
};
constexpr std::array<EnumName<ShadowPassShaders>, 3> enum_names(ShadowPassShaders) {
  return {{{ShadowPassShaders::kSplit, "split"},
           {ShadowPassShaders::kAlphaTested, "alpha_tested"},
           {ShadowPassShaders::kEarlyZ, "early_z"}}};
}

// The air between the camera and a face (render/lib/fog.glsl, the terrain's twin setting):
// kPerPixel runs apply_fog in shade.frag (five exp per pixel); kPerVertex evaluates the air's
// extinction per metre in the vertex shaders (air_extinction), interpolates it and keeps the
// pixel's own distance, exponential, near cut-off and sky look-up (air_from_vertex): within
// 2/255 of kPerPixel at the shipped spawn (README "vs fogleman/Craft"); kOff draws no air (the
// distance fade into the sky at view_distance stays).
enum class AerialPerspective : std::uint8_t { kPerPixel, kPerVertex, kOff };
constexpr std::array<EnumName<AerialPerspective>, 3> enum_names(AerialPerspective) {
  return {{{AerialPerspective::kPerPixel, "per_pixel"},
           {AerialPerspective::kPerVertex, "per_vertex"},
           {AerialPerspective::kOff, "off"}}};
}

struct VoxelRenderSettings {
  float alpha_cutoff = 0.5f;        // alpha-cut threshold (the seed used 0.05 for its textures)
  float translucent_cutoff = 0.05f; // translucent blocks: texels with lower alpha are discarded (the seed's threshold, §2.2)
  int max_point_lights = 16;        // emissive blocks lit per frame, nearest first (<= 32)
  float light_kc = 1.0f;            // attenuation 1 / (Kc + Kl d + Kq d^2), seed §2.3.3.2
  float light_kl = 0.045f;
  float light_kq = 0.0075f;
  float light_range = 64.0f;        // blocks: lights farther than this from the camera are skipped
  float ao_strength = 0.75f;        // 0 = no ambient occlusion, 1 = fully dark in closed corners
  float specular_scale = 1.0f;
  bool frustum_culling = true;
  bool draw_plants = true;
  float leaf_back_faces_within = 48.0f;  // blocks: nearer leaf cubes also draw the faces turned away
  bool plant_hidden_faces = true;   // skip plant faces inside other parts (and parts with all six inside)
  // Blocks, [0, 1e6]: chunks at least this far draw their plants as far shells (plant_faces.hpp's
  // snap_to_grid: parts on a grid of the start block size, inner cubes and faces between cubes
  // dropped, leaves opaque) in one draw; the colour pass only, shadows keep the exact plants.
  float plant_far_beyond = 96.0f;
  float plant_far_cell = 1.0f;       // far grid edge in start block sizes, [1, 8]: 2 = coarser shells, fewer cubes
  // Far shells baked per chunk into one static indexed mesh (plant_mesh.hpp), face groups turned
  // away from the eye skipped; off: instanced cubes (plant.vert). The same picture (issue #18).
  bool plant_far_mesh = true;
  // Near plants' exact parts baked per chunk the same way (opaque parts and leaves in two meshes,
  // plants in order inside each face group for per-plant culling; leaves within
  // leaf_back_faces_within drawn two-sided, beyond it back-face culled); off: instanced cubes.
  // The colour pass only: shadows keep the instanced cubes. The same picture (issue #18).
  bool plant_near_mesh = true;
  // Colour pass in two steps: depth only, then colour with GL_EQUAL, so each pixel is shaded
  // once (the same picture; fewer shaded fragments where surfaces overlap). Off by default:
  // with plants drawn before the ground and no empty point-light loops the second run through
  // the vertices costs more than the fragments it saves (issue #18, voxel README).
  bool depth_prepass = false;
  AerialPerspective aerial_perspective = AerialPerspective::kPerVertex;  // the air over faces and plants
  int texture_size = 16;            // texels per block side
  bool cast_shadows = true;         // draw into the render core's cascades (draw(kShadow), shadow_caster())
  bool receive_shadows = true;      // sample them in the colour pass (lit when no ShadowMaps is bound)
  ShadowPassShaders shadow_shaders = ShadowPassShaders::kSplit;  // seed 004 R1
  bool shadow_chunk_culling = true; // cast only chunks in the cascade's light frustum (seed 004 §3.7.2, R2)
  float sky_light = 1.5f;           // multiplier of the render core's sky / ground ambient, [0, 8]
  float bounce = 0.25f;             // albedo of the sunlit ground lighting shaded faces, [0, 1]
  // Blocks, horizontal, [0, 1e6]: 0 = no fade, no skirt, no distance culling; otherwise the fade
  // ends at this distance or, for a camera inside the loaded area, at the area's inscribed radius
  // around the camera if that is nearer (the scene module uses 1e5: the area's edge).
  float view_distance = 0.0f;
  float fade_share = 0.3f;          // share of the view distance over which geometry fades into the sky, (0, 1]
  bool horizon_skirt = true;        // with a view distance: a disc under the world in the horizon colour hides the void

  template <class V>
  void visit(V& v) {
    v(alpha_cutoff, "alpha_cutoff", {.min = 0.0, .max = 1.0, .help = "Texels with lower alpha are cut out"});
    v(translucent_cutoff, "translucent_cutoff",
      {.min = 0.0, .max = 1.0, .help = "Translucent blocks (blended after the opaque pass): texels with lower alpha are discarded (seed 004 §2.2: 0.05)"});
    v(max_point_lights, "max_point_lights", {.min = 0, .max = 32, .help = "Emissive blocks lit per frame (nearest first)"});
    v(light_kc, "light_kc", {.min = 1.0, .max = 16.0, .help = "Constant attenuation (>= 1 never amplifies)"});
    v(light_kl, "light_kl", {.min = 0.0, .max = 4.0, .unit = "1/block", .help = "Linear attenuation"});
    v(light_kq, "light_kq", {.min = 0.0, .max = 4.0, .unit = "1/block^2", .help = "Quadratic attenuation"});
    v(light_range, "light_range", {.min = 1.0, .max = 4096.0, .unit = "blocks", .help = "Farthest light considered"});
    v(ao_strength, "ao_strength", {.min = 0.0, .max = 1.0, .help = "Darkening by per-vertex ambient occlusion"});
    v(specular_scale, "specular_scale", {.min = 0.0, .max = 8.0, .help = "Multiplier of every specular map"});
    v(frustum_culling, "frustum_culling", {.help = "Skip chunks outside the view frustum"});
    v(draw_plants, "draw_plants", {.help = "Draw the L-system plants"});
    v(leaf_back_faces_within, "leaf_back_faces_within", {.min = 0.0, .max = 1.0e6, .unit = "blocks", .help = "Leaf cubes nearer than this also draw their far faces (seen through their holes); farther ones only the three faces turned to the camera"});
    v(plant_hidden_faces, "plant_hidden_faces", {.help = "Skip plant faces hidden inside other parts, and parts with every face hidden (the same picture, fewer triangles)", .rebuild = Rebuild::kGpu});
    v(plant_far_beyond, "plant_far_beyond", {.min = 0.0, .max = 1.0e6, .unit = "blocks", .help = "Chunks at least this far draw plants as their outer shell on a block grid, leaves opaque, one draw per chunk (shadows keep the exact plants); 1e6 = never"});
    v(plant_far_cell, "plant_far_cell", {.min = 1.0, .max = 8.0, .help = "Edge of the far plants' grid in start block sizes (1 = the plant's own block size; 2 = coarser shells, fewer cubes)", .rebuild = Rebuild::kGpu});
    v(plant_far_mesh, "plant_far_mesh", {.help = "Far plant shells as one baked mesh per chunk (faces pre-transformed, indexed, face groups turned away skipped) instead of instanced cubes (the same picture)", .rebuild = Rebuild::kGpu});
    v(plant_near_mesh, "plant_near_mesh", {.help = "Near plants' exact parts as baked meshes per chunk (faces pre-transformed, indexed, per-plant culling kept) instead of instanced cubes (the same picture)", .rebuild = Rebuild::kGpu});
    v(depth_prepass, "depth_prepass", {.help = "Draw depth first, then colour with an equal depth test: each pixel shaded once, every vertex twice (the same picture)"});
    v(aerial_perspective, "aerial_perspective",
      {.help = "The air over blocks and plants: per_vertex (extinction interpolated), per_pixel or off"});
    v(cast_shadows, "cast_shadows", {.help = "Chunks and plants cast into the sun's cascaded shadow maps"});
    v(receive_shadows, "receive_shadows", {.help = "Chunks and plants receive the sun's cascaded shadows"});
    v(shadow_shaders, "shadow_shaders", {.help = "Shadow pass: split (opaque early-z, cut-outs alpha-tested), alpha_tested (all) or early_z (all; cut-outs cast solid)"});
    v(shadow_chunk_culling, "shadow_chunk_culling", {.help = "Shadow pass casts only chunks inside the cascade's light frustum (off: every chunk)"});
    v(sky_light, "sky_light", {.min = 0.0, .max = 8.0, .help = "Multiplier of the sky and ground ambient light on every face"});
    v(bounce, "bounce", {.min = 0.0, .max = 1.0, .help = "Sun light bounced off the ground onto shaded faces (ground albedo)"});
    v(view_distance, "view_distance", {.min = 0.0, .max = 1.0e6, .unit = "blocks", .help = "Horizontal distance where the world has faded into the sky (0 = no fade; capped by the loaded area's edge)"});
    v(fade_share, "fade_share", {.min = 0.01, .max = 1.0, .help = "Share of the view distance over which the world fades into the sky"});
    v(horizon_skirt, "horizon_skirt", {.help = "With a view distance: a disc under the world in the horizon colour hides the void past its edge"});
    v(texture_size, "texture_size", {.min = 4, .max = 256, .unit = "texels", .help = "Block texture resolution", .rebuild = Rebuild::kGpu});
  }
};

// Where the sun's visibility comes from: a GLSL file (registered in the shader library as
// "voxel/shadow_hook.glsl") defining `float voxel_shadow(vec3 rel_pos, vec3 normal)` (1 = lit),
// and a callback binding its uniforms and textures to a program before each pass. The default
// (empty source) is the render core's cascades: `return sylva_shadow(rel_pos, normal);`, with the
// data the host bound through render::ShadowMaps::bind() (UBO 2, texture unit 15).
struct ShadowReceiver {
  std::string glsl_source;  // full text of the hook; empty restores the render core's cascades
  std::function<void(GLuint program)> bind;
  // True when the hook returns 1 wherever the render core's shadow block says "disabled" (it
  // only samples the core's cascades): the renderer then leaves it out in such frames, as it
  // does the default hook. False: the hook runs in every frame.
  bool lit_when_core_shadows_disabled = false;
};

struct VoxelFrameStats {
  std::size_t chunks_total = 0;
  std::size_t chunks_drawn = 0;
  std::size_t quads_drawn = 0;
  std::size_t plant_parts_drawn = 0;
  std::size_t plant_triangles = 0;      // of plant faces not hidden, colour pass (front-face draws: at most)
  std::size_t plant_parts_hidden = 0;   // loaded plant parts left out, every face inside other parts
  std::size_t plant_far_chunks = 0;     // chunks whose plants were drawn as far shells
  std::size_t plant_mesh_triangles = 0; // plant triangles drawn from baked meshes (plant_far_mesh, plant_near_mesh)
  std::size_t plant_mesh_groups_skipped = 0;  // their chunks' face groups left out, turned away from the eye
  std::size_t plants_culled = 0;        // plants outside the frustum inside chunks it cuts (colour and shadow passes)
  std::size_t tufts_drawn = 0;
  float view_distance = 0.0f;  // blocks: where the fade into the sky ended this frame (0: no fade)
  std::size_t point_lights = 0;
  // 1 when the colour passes ran the shaders with point-light loops (emissive blocks lit this
  // frame or a host point-light block bound), 0 when they ran the variant without them.
  std::size_t point_light_shaders = 0;
  // 1 when the colour passes sampled the sun's shadows (shadow_lookups_needed), 0 when they
  // ran the variant without the look-up (lit everywhere, as the disabled block says).
  std::size_t shadow_lookup_shaders = 0;
  // Read-backs of the host block's "enabled" flag this frame: 0 unless the host bound a block of
  // its own (not a render::ShadowMaps') and ran no shadow pass (a read-back waits for a GPU).
  std::size_t shadow_flag_reads = 0;
  std::size_t chunks_faded = 0;  // drawn with the fade into the sky; the others lie wholly nearer than its start
  std::size_t uploads = 0;  // chunk buffers (re)built in the last update
  std::size_t shadow_chunks_cast = 0;  // chunks drawn into shadow cascades since the last update, summed over cascades
  std::size_t translucent_quads_drawn = 0;  // in draw(kTransparent), also counted in quads_drawn
  std::size_t translucent_sorts = 0;        // chunks whose translucent faces were re-sorted (eye moved)
};

class VoxelRenderer final : public render::Drawable {
 public:
  // Needs a current GL 4.5 context. `generator` (may be null: no plants) supplies plant models and
  // their blocks. The world and generator must outlive the renderer. Errors: kGl (shader
  // compile/link naming file:line), texture creation failures.
  // Errors also name voxel.render.<field> for a setting out of range.
  static Result<std::unique_ptr<VoxelRenderer>> create(const World& world,
                                                      std::shared_ptr<const WorldGenerator> generator,
                                                      const VoxelRenderSettings& settings = {});
  ~VoxelRenderer() override;

  VoxelRenderSettings& settings() { return settings_; }
  const VoxelFrameStats& frame_stats() const { return stats_; }

  // Uploads changed chunk meshes and plants, culls, picks point lights.
  void update(const render::FrameContext& frame) override;
  // kOpaque draws opaque then alpha-cut geometry (receiving shadows when receive_shadows);
  // kShadow, inside render::ShadowMaps::render (render::active_shadow_cascade() non-null), casts
  // into the cascade being drawn (see draw_shadow); otherwise and for kTransparent nothing.
  void draw(render::Pass pass, const render::FrameContext& frame, render::PassStats& stats) override;
  // Casts into one cascade: depth of the chunks and plants inside context.light_frustum, opaque
  // ones early-z, alpha-cut ones alpha-tested; counts go to *context.stats. No-op when
  // cast_shadows is off. Needs the cascade's depth target bound (ShadowMaps::render does).
  void draw_shadow(const render::ShadowCasterContext& context);
  // A caster to register with render::ShadowMaps::add_caster (calls draw_shadow). Owned by the
  // renderer: remove_caster before destroying the renderer.
  render::ShadowCaster& shadow_caster();
  // Depth-only draw of every chunk and plant (alpha-tested where needed) with an arbitrary
  // view-projection applied to positions relative to `origin` (world, double). Culls nothing.
  // Called inside ShadowMaps::render for a cascade this renderer already cast into through
  // draw(kShadow) (same cascade and matrix), it draws nothing: a host registering both paths
  // (the scene's voxel caster and its kShadow pass) casts each cascade once.
  void draw_depth(const glm::mat4& relative_view_projection, const glm::dvec3& origin, render::PassStats& stats);

  // Replaces the shadow hook and recompiles the programs (kGl on compile errors).
  Status set_shadow_receiver(ShadowReceiver receiver);

 private:
  VoxelRenderer() = default;
  struct ChunkGpu;
  struct BakedMesh;
  Status build_programs();
  // The colour programs of one shader variant: kPointLightLoops (SYLVA_VOXEL_POINT_LIGHTS in
  // shade.frag) and kShadowLookup (SYLVA_VOXEL_SHADOWS) bits; each is built on the first frame
  // that needs it.
  struct ColourPrograms;
  // kDistanceFade: SYLVA_VOXEL_FADE, for chunks reaching past the fade's start.
  static constexpr unsigned kPointLightLoops = 1u, kShadowLookup = 2u, kDistanceFade = 4u;
  static constexpr unsigned kFullVariant = kPointLightLoops | kShadowLookup | kDistanceFade, kColourVariants = 8u;
  Status build_colour_programs(unsigned variant);
  const ColourPrograms* colour_programs(unsigned variant);
  void upload_chunk(const ChunkCoord& c, ChunkGpu& gpu);
  void upload_plants(const ChunkCoord& c, ChunkGpu& gpu);
  // gpu.plant's parts [first, first + count) -> `out` (plant_mesh.hpp), one cluster per entry of
  // `plant_starts` (relative to `first`; empty: one cluster); `out` stays empty without faces.
  static void bake_range(const ChunkGpu& gpu, std::uint32_t first, std::uint32_t count,
                         std::span<const std::uint32_t> plant_starts, BakedMesh& out);
  void upload_tufts(const ChunkCoord& c, ChunkGpu& gpu);
  void update_view_distance(const glm::dvec3& eye);
  void draw_tufts(const render::Program& program, std::span<ChunkGpu* const> chunks, const glm::mat4& view_projection,
                  const glm::dvec3& origin, render::PassStats& stats);
  // The programs of one run through the opaque pass's geometry: colour, or depth only (pre-pass).
  struct OpaquePrograms {
    const render::Program *chunks = nullptr, *plants = nullptr, *mesh = nullptr;
    const render::Program *chunks_alpha = nullptr, *plants_alpha = nullptr, *mesh_alpha = nullptr, *tufts = nullptr;
  };
  // Chunks, plants (instanced and baked) and tufts of visible_, opaque then cut-out, with `p`
  // (`frame` null for the depth programs). Leaves back-face culling off.
  void draw_opaque_geometry(std::span<ChunkGpu* const> chunks, const OpaquePrograms& p,
                            const render::FrameContext* frame, const glm::mat4& vp,
                            const glm::dvec3& eye, const render::Frustum* culling, render::PassStats& stats);
  void draw_horizon(const glm::mat4& view_projection, const glm::dvec3& origin, render::PassStats& stats);
  void draw_translucent(const render::FrameContext& frame, render::PassStats& stats);
  void sort_translucent(ChunkGpu& gpu, const glm::dvec3& eye);
  void bind_common(const render::Program& program, const render::FrameContext* frame) const;
  void draw_chunks(std::span<ChunkGpu* const> chunks, const render::Program& quads, const render::Program& plants,
                   bool alpha_cut, const glm::mat4& view_projection, const glm::dvec3& origin,
                   double full_cubes_within, double far_beyond, const render::Frustum* culling,
                   render::PassStats& stats, bool baked_plants = false);
  // The far chunks' baked shells (plant_far_mesh), in the opaque colour pass after draw_chunks.
  // `program` is bound by the caller.
  void draw_far_meshes(const render::Program& program, const glm::dvec3& origin, const render::Frustum* culling,
                       render::PassStats& stats);
  // The near chunks' baked plants (plant_near_mesh) of one class (opaque / cut-out), colour pass;
  // `program` is bound by the caller. Cut-out chunks at least `full_within` away are drawn
  // back-face culled (only the faces turned to the eye, as the instanced front-face draws).
  void draw_near_meshes(bool alpha_cut, const render::Program& program, const glm::dvec3& origin,
                        double full_within, const render::Frustum* culling, render::PassStats& stats);
  // Draws `mesh`'s groups in `groups` (bits), whole or per plant (`plant_seen`, one flag per
  // cluster; empty: all plants). Counts triangles and draws; returns the plants left out.
  std::size_t draw_baked(const BakedMesh& mesh, std::uint32_t groups, std::span<const std::uint8_t> plant_seen,
                         render::PassStats& stats);
  // `culling` (may be null): per-plant culling inside chunks the frustum cuts.
  void draw_depth_list(std::span<ChunkGpu* const> chunks, const glm::mat4& relative_view_projection,
                       const glm::dvec3& origin, const render::Frustum* culling, render::PassStats& stats);
  // Binds `fallback` (an all-zero "disabled" block) at uniform binding `index` unless use_host
  // and the host bound one there; returns the previous binding so it can be restored.
  struct UboBinding {
    GLuint index = 0;
    GLint buffer = 0;
    GLint64 start = 0, size = 0;
    bool replaced = false;
  };
  static UboBinding bind_fallback_block(GLuint index, const render::Buffer& fallback, bool use_host);
  static void restore_block(const UboBinding& b);
  // Whether this frame's colour passes need the point-light loops: emissive blocks picked in
  // update(), or a host block at kPointLightBinding (`host_lights` not replaced by the empty
  // fallback). Records the answer in stats_.point_light_shaders.
  bool point_lights_shaded(const UboBinding& host_lights);
  // Whether this frame's colour passes sample the sun's shadows: always with a custom
  // ShadowReceiver (unless lit_when_core_shadows_disabled); with the render core's (the
  // default) only when receive_shadows is on and the host bound a shadow block that is
  // enabled: known on the CPU when a shadow pass ran since update() or the block is a
  // render::ShadowMaps' (render::shadow_block_enabled: the scene's, with shadows on or off); only
  // a host's own block is read back, 4 bytes a pass (a read-back waits for a hardware GPU).
  // Records it in stats_.shadow_lookup_shaders.
  bool shadow_lookups_needed(const UboBinding& host_shadows);
  bool host_shadows_enabled(const UboBinding& host_shadows);
  // This frame's colour variant (kPointLightLoops | kShadowLookup), decided once after update()
  // by the first colour pass (opaque, then translucent reuses it): the host's blocks do not
  // change within a frame, and a host's own shadow block costs a read-back per decision.
  unsigned frame_colour_variant(const UboBinding& host_lights, const UboBinding& host_shadows);
  std::optional<unsigned> colour_variant_;

  const World* world_ = nullptr;
  std::shared_ptr<const WorldGenerator> generator_;
  VoxelRenderSettings settings_;
  // By variant bits (null until built). llvmpipe runs both sides of every branch and every loop
  // body at least once per pixel, so an empty light loop costs as much as one light and a
  // disabled shadow look-up as an enabled one: the shipped spawn has neither (issue #18).
  std::unique_ptr<ColourPrograms> colour_[kColourVariants];
  bool shadow_pass_ran_ = false;  // a shadow pass (any cast path) ran since update()
  GLint shadow_enabled_offset_ = -1;  // bytes: sylva_shadow_params.z in SylvaShadows (-1: unknown)
  render::Program horizon_program_;
  render::Program depth_program_, depth_alpha_program_, plant_depth_program_, plant_depth_opaque_program_;
  render::Program plant_mesh_depth_program_, plant_mesh_depth_alpha_program_, tuft_depth_program_;
  OpaquePrograms depth_programs_;
  AerialPerspective programs_air_ = AerialPerspective::kPerVertex;  // the air the programs were built with
  render::Buffer no_shadows_ubo_;
  render::Buffer no_point_lights_ubo_;
  std::unique_ptr<render::ShadowCaster> caster_;
  // The cascade last cast into through draw(kShadow), for draw_depth's de-duplication.
  const render::ShadowCasterContext* cast_context_ = nullptr;
  int cast_cascade_ = -1;
  glm::mat4 cast_matrix_{0.0f};
  std::vector<ChunkGpu*> shadow_list_;
  std::vector<ChunkGpu*> all_list_;
  render::Texture diffuse_, specular_;
  render::Buffer block_table_;
  render::VertexArray vao_;
  std::unordered_map<ChunkCoord, std::unique_ptr<ChunkGpu>, ChunkCoordHash> chunks_;
  std::uint64_t mesh_epoch_ = ~std::uint64_t{0};
  std::uint64_t plant_epoch_ = ~std::uint64_t{0};
  std::vector<ChunkGpu*> visible_;
  std::vector<ChunkGpu*> unfaded_, faded_;  // visible_ split by the fade's start, this frame
  std::span<ChunkGpu* const> drawn_;        // the chunks draw_opaque_geometry is drawing
  std::vector<std::uint8_t> plant_seen_;  // draw_near_meshes' per-plant flags, kept between chunks
  std::unique_ptr<PlantFaceCache> face_cache_;  // hidden-face masks per plant model
  std::vector<std::pair<float, PackedQuad>> sort_keys_;  // sort_translucent's scratch, kept between frames
  glm::vec2 fade_{0.0f};      // fade start / end [blocks] this frame
  double lowest_block_ = 0.0; // world y of the lowest loaded chunk's bottom (the skirt's height)
  std::vector<glm::vec4> light_pos_;    // camera-relative xyz
  std::vector<glm::vec4> light_color_;  // rgb
  ShadowReceiver shadow_;
  VoxelFrameStats stats_;
};

}  // namespace sylva::voxel
