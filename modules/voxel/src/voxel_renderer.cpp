#include <sylva/voxel/voxel_renderer.hpp>

#include <sylva/core/assert.hpp>
#include <sylva/core/log.hpp>
#include <sylva/render/blend_state.hpp>
#include <sylva/render/frustum.hpp>
#include <sylva/render/vertex_array.hpp>
#include <sylva/voxel/block_textures.hpp>
#include <sylva/voxel/plant_mesh.hpp>
#include <sylva/voxel/tufts.hpp>

#include "plant_batch.hpp"

#include <fmt/format.h>

#include <glm/gtc/packing.hpp>
#include <glm/gtc/quaternion.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace sylva::render::embedded {
void register_voxel_shaders();
}  // namespace sylva::render::embedded

namespace sylva::voxel {

namespace {

// `image` (RGBA) at `size` x `size` in the layout of `like` (a procedural layer): the mean of the
// texels each target texel covers when shrinking, the nearest texel when enlarging.
Image resample_rgba(const Image& image, int size, const Image& like) {
  Image out = like;
  for (int y = 0; y < size; ++y) {
    const int y0 = y * image.height() / size;
    const int y1 = std::max(y0 + 1, (y + 1) * image.height() / size);
    for (int x = 0; x < size; ++x) {
      const int x0 = x * image.width() / size;
      const int x1 = std::max(x0 + 1, (x + 1) * image.width() / size);
      for (int c = 0; c < 4; ++c) {
        float sum = 0.0f;
        for (int v = y0; v < y1; ++v)
          for (int u = x0; u < x1; ++u) sum += image.at(u, v, c);
        out.at(x, y, c) = sum / static_cast<float>((y1 - y0) * (x1 - x0));
      }
    }
  }
  return out;
}

constexpr GLuint kQuadBinding = 1;
constexpr GLuint kPlantBinding = 2;
constexpr GLuint kBlockBinding = 3;
constexpr int kMaxLights = 32;
constexpr double kNever = std::numeric_limits<double>::infinity();  // a distance no chunk reaches
constexpr const char* kShadowHook = "voxel/shadow_hook.glsl";

struct BlockGpu {
  std::uint32_t layers[4];
  float emission[4];
  float material[4];
};
static_assert(sizeof(BlockGpu) == 48);

// The horizon skirt's outer radius [blocks]: the scene's far plane is infinite, and a skirt 200
// blocks below the eye ends 0.001 degrees under the horizon there, far below a pixel.
constexpr float kSkirtOuterRadius = 1.0e7f;

// Horizontal (xz) distance from a point to a box (0 inside its footprint).
double horizontal_distance(const render::Aabb& box, const glm::dvec3& p) {
  const double dx = std::max({box.min.x - p.x, 0.0, p.x - box.max.x});
  const double dz = std::max({box.min.z - p.z, 0.0, p.z - box.max.z});
  return std::sqrt(dx * dx + dz * dz);
}

// Farthest horizontal (xz) distance from a point to a box's corners.
double farthest_horizontal_distance(const render::Aabb& box, const glm::dvec3& p) {
  const double dx = std::max(std::fabs(box.min.x - p.x), std::fabs(box.max.x - p.x));
  const double dz = std::max(std::fabs(box.min.z - p.z), std::fabs(box.max.z - p.z));
  return std::sqrt(dx * dx + dz * dz);
}

// Distance from a point to a box (0 inside).
double distance(const render::Aabb& box, const glm::dvec3& p) {
  const glm::dvec3 d = glm::max(glm::max(box.min - p, glm::dvec3(0.0)), p - box.max);
  return glm::length(d);
}

// Sets a uniform only when the program uses it: the opaque variants compile the alpha cut-off
// away and plants have no AO, and Program::set would warn about every such inactive name.
template <class T>
void set_if_active(const render::Program& p, const char* name, const T& value) {
  if (glGetUniformLocation(p.id(), name) >= 0) p.set(name, value);
}

}  // namespace

// A baked plant mesh on the GPU (plant_mesh.hpp): vertices pulled from an SSBO by index, the
// index buffer in its own VAO; groups and per-plant clusters without their vertices.
struct VoxelRenderer::BakedMesh {
  render::Buffer vertices, indices;
  render::VertexArray vao;
  std::array<PlantMesh::Group, kPlantMeshGroups> groups{};
  std::vector<PlantMesh::Cluster> clusters;
  bool ready = false;
};

struct VoxelRenderer::ChunkGpu {
  ChunkCoord coord;
  render::Buffer quads;
  std::uint32_t opaque_quads = 0;
  std::uint32_t alpha_quads = 0;
  std::uint32_t translucent_quads = 0;  // after the alpha-cut ones
  std::vector<PackedQuad> translucent;   // their CPU copy, re-sorted back to front as the eye moves
  glm::ivec3 sorted_for{std::numeric_limits<int>::min()};  // eye half-block cell of the last sort
  std::uint64_t revision = ~std::uint64_t{0};
  render::Buffer plants;       // plant_batch.hpp's layout
  PlantBatch plant;          // its ranges and counts (the parts themselves are in `plants`)
  std::uint32_t plant_parts() const { return plant.count[0][0] + plant.count[0][1]; }
  BakedMesh far_mesh;      // the far shells baked (settings plant_far_mesh)
  BakedMesh near_mesh[2];  // the near parts baked (plant_near_mesh): [opaque 0 / cut-out 1], one cluster per plant
  render::Buffer tufts;
  std::uint32_t tuft_count = 0;
  render::Aabb box;          // chunk box grown by its plants (world)
  render::Aabb plant_box;    // plants only (empty when min > max)
  struct Light {
    glm::dvec3 position;  // world, block centre
    glm::vec3 color;
  };
  std::vector<Light> lights;
  glm::dvec3 origin{0.0};
};

struct VoxelRenderer::ColourPrograms {
  render::Program opaque, alpha, translucent, plant_opaque, plant_alpha, tuft, plant_mesh, plant_mesh_alpha;
  OpaquePrograms opaque_pass() const {
    return {&opaque, &plant_opaque, &plant_mesh, &alpha, &plant_alpha, &plant_mesh_alpha, &tuft};
  }
};

VoxelRenderer::~VoxelRenderer() = default;

Result<std::unique_ptr<VoxelRenderer>> VoxelRenderer::create(const World& world,
                                                            std::shared_ptr<const WorldGenerator> generator,
                                                            const VoxelRenderSettings& settings) {
  if (settings.texture_size < 4 || settings.texture_size > 256) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("voxel.render.texture_size: {} outside [4, 256]", settings.texture_size));
  }
  if (!(settings.leaf_back_faces_within >= 0.0f && settings.leaf_back_faces_within <= 1.0e6f)) {
    return make_error(ErrorCode::kInvalidArgument, fmt::format("voxel.render.leaf_back_faces_within: {} outside [0, 1e6] blocks",
                                                               settings.leaf_back_faces_within));
  }
  if (!(settings.plant_far_beyond >= 0.0f && settings.plant_far_beyond <= 1.0e6f)) {
    return make_error(ErrorCode::kInvalidArgument, fmt::format("voxel.render.plant_far_beyond: {} outside [0, 1e6] blocks",
                                                               settings.plant_far_beyond));
  }
  if (!(settings.plant_far_cell >= 1.0f && settings.plant_far_cell <= 8.0f)) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("voxel.render.plant_far_cell: {} outside [1, 8] start block sizes", settings.plant_far_cell));
  }
  if (!(settings.sky_light >= 0.0f && settings.sky_light <= 8.0f)) {
    return make_error(ErrorCode::kInvalidArgument, fmt::format("voxel.render.sky_light: {} outside [0, 8]", settings.sky_light));
  }
  if (!(settings.bounce >= 0.0f && settings.bounce <= 1.0f)) {
    return make_error(ErrorCode::kInvalidArgument, fmt::format("voxel.render.bounce: {} outside [0, 1]", settings.bounce));
  }
  if (!(settings.view_distance >= 0.0f && settings.view_distance <= 1.0e6f)) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("voxel.render.view_distance: {} outside [0, 1e6] blocks", settings.view_distance));
  }
  if (!(settings.fade_share > 0.0f && settings.fade_share <= 1.0f)) {
    return make_error(ErrorCode::kInvalidArgument, fmt::format("voxel.render.fade_share: {} outside (0, 1]", settings.fade_share));
  }
  if (settings.max_point_lights < 0 || settings.max_point_lights > kMaxLights) {
    return make_error(ErrorCode::kInvalidArgument, fmt::format("voxel.render.max_point_lights: {} outside [0, {}]",
                                                               settings.max_point_lights, kMaxLights));
  }
  render::embedded::register_render_shaders();
  render::embedded::register_voxel_shaders();
  std::unique_ptr<VoxelRenderer> r(new VoxelRenderer());
  r->world_ = &world;
  r->generator_ = std::move(generator);
  r->settings_ = settings;
  r->face_cache_ = std::make_unique<PlantFaceCache>(settings.plant_far_cell);
  r->vao_ = render::VertexArray::create();
  r->no_shadows_ubo_ = render::make_disabled_shadow_block();
  r->no_point_lights_ubo_ = render::make_empty_point_light_block();
  VoxelRenderer* self = r.get();
  r->caster_ = std::make_unique<render::CallbackShadowCaster>(
      [self](const render::ShadowCasterContext& c) { self->draw_shadow(c); });
  SYLVA_TRY(r->set_shadow_receiver({}));

  // Texture arrays: one layer per TextureId, then the palette's images (palette_file.hpp)
  // resampled to texture_size (box filter when smaller, nearest texel when larger: pixel art
  // stays crisp) with no specular map.
  const BlockPalette& palette = world.palette();
  std::vector<Image> diffuse, specular;
  for (int i = 0; i < kTextureCount; ++i) {
    auto t = generate_block_texture(static_cast<TextureId>(i), settings.texture_size);
    diffuse.push_back(std::move(t.diffuse));
    specular.push_back(std::move(t.specular));
  }
  for (const Image& image : palette.images()) {
    diffuse.push_back(resample_rgba(image, settings.texture_size, diffuse.front()));
    Image none = specular.front();
    std::fill(none.data().begin(), none.data().end(), 0.0f);
    specular.push_back(std::move(none));
  }
  const int layers = static_cast<int>(diffuse.size());
  render::TextureOptions opt;
  opt.encoding = render::TextureEncoding::kSrgb8;
  opt.min_filter = GL_NEAREST_MIPMAP_LINEAR;
  opt.mag_filter = GL_NEAREST;  // crisp pixel-art blocks
  auto d = render::Texture::from_images(diffuse, opt);
  if (!d.ok()) return d.error();
  opt.encoding = render::TextureEncoding::kUnorm8;
  auto s = render::Texture::from_images(specular, opt);
  if (!s.ok()) return s.error();
  r->diffuse_ = std::move(*d);
  r->specular_ = std::move(*s);

  std::vector<BlockGpu> table(palette.size());
  for (std::size_t i = 0; i < palette.size(); ++i) {
    const BlockType& t = palette[static_cast<BlockId>(i)];
    BlockGpu& g = table[i];
    g.layers[0] = static_cast<std::uint32_t>(std::clamp(t.texture_top, 0, layers - 1));
    g.layers[1] = static_cast<std::uint32_t>(std::clamp(t.texture_side, 0, layers - 1));
    g.layers[2] = static_cast<std::uint32_t>(std::clamp(t.texture_bottom, 0, layers - 1));
    g.layers[3] = (t.render == RenderClass::kAlphaCut ? 1u : 0u) | (t.emits_light() ? 2u : 0u);
    g.emission[0] = t.emission.x;
    g.emission[1] = t.emission.y;
    g.emission[2] = t.emission.z;
    g.emission[3] = 0.0f;
    g.material[0] = t.specular;
    g.material[1] = t.shininess;
    g.material[2] = t.opacity;
    g.material[3] = 0.0f;
  }
  r->block_table_ = render::Buffer::immutable(std::span<const BlockGpu>(table));
  return r;
}

Status VoxelRenderer::set_shadow_receiver(ShadowReceiver receiver) {
  std::string hook = receiver.glsl_source;
  if (hook.empty()) {
    auto def = render::shader_source("voxel/shadow_hook_default.glsl");
    if (!def.ok()) return def.error();
    hook = *def;
  }
  render::register_shader_source(kShadowHook, hook);
  shadow_ = std::move(receiver);
  return build_programs();
}

namespace {

// A program of `stages` with `defines` and the air's variant (SYLVA_VOXEL_AIR, common.glsl).
Status make_program(std::initializer_list<std::string_view> stages, const render::ShaderDefines& defines,
                    AerialPerspective air, render::Program& out) {
  render::ShaderDefines with_air = defines;
  with_air.emplace_back("SYLVA_VOXEL_AIR", std::to_string(static_cast<int>(air)));
  auto p = render::Program::create(stages, with_air);
  if (!p.ok()) return p.error();
  out = std::move(*p);
  return ok_status();
}

const render::ShaderDefines kAlphaCut = {{"ALPHA_CUT", "1"}};
const render::ShaderDefines kTuft = {{"ALPHA_CUT", "1"}, {"CROSS_QUADS", "1"}};

}  // namespace

Status VoxelRenderer::build_colour_programs(unsigned variant) {
  const AerialPerspective air = settings_.aerial_perspective;
  auto with_variant = [variant](render::ShaderDefines d) {
    d.emplace_back("SYLVA_VOXEL_POINT_LIGHTS", (variant & kPointLightLoops) != 0 ? "1" : "0");
    d.emplace_back("SYLVA_VOXEL_SHADOWS", (variant & kShadowLookup) != 0 ? "1" : "0");
    d.emplace_back("SYLVA_VOXEL_FADE", (variant & kDistanceFade) != 0 ? "1" : "0");
    return d;
  };
  auto set = std::make_unique<ColourPrograms>();
  SYLVA_TRY(make_program({"voxel/chunk.vert", "voxel/shade.frag"}, with_variant({}), air, set->opaque));
  SYLVA_TRY(make_program({"voxel/chunk.vert", "voxel/shade.frag"}, with_variant(kAlphaCut), air, set->alpha));
  SYLVA_TRY(make_program({"voxel/chunk.vert", "voxel/shade.frag"}, with_variant({{"TRANSLUCENT", "1"}}), air, set->translucent));
  SYLVA_TRY(make_program({"voxel/plant.vert", "voxel/shade.frag"}, with_variant({}), air, set->plant_opaque));
  SYLVA_TRY(make_program({"voxel/plant.vert", "voxel/shade.frag"}, with_variant(kAlphaCut), air, set->plant_alpha));
  SYLVA_TRY(make_program({"voxel/plant.vert", "voxel/shade.frag"}, with_variant(kTuft), air, set->tuft));
  SYLVA_TRY(make_program({"voxel/plant_mesh.vert", "voxel/shade.frag"}, with_variant({}), air, set->plant_mesh));
  SYLVA_TRY(make_program({"voxel/plant_mesh.vert", "voxel/shade.frag"}, with_variant(kAlphaCut), air, set->plant_mesh_alpha));
  colour_[variant] = std::move(set);
  return ok_status();
}

const VoxelRenderer::ColourPrograms* VoxelRenderer::colour_programs(unsigned variant) {
  if (!colour_[variant]) {
    // First frame of this variant. On a compile error the full variant (built by
    // build_programs) draws and the log says why.
    if (Status built = build_colour_programs(variant); !built.ok()) {
      log_warn("voxel: colour shader variant {}: {}", variant, built.error().message);
      return colour_[kFullVariant].get();
    }
  }
  return colour_[variant].get();
}

Status VoxelRenderer::build_programs() {
  // Every program gets the air's variant, the depth ones too, so the pre-pass runs the very
  // vertex shaders of the colour pass (the horizon's ignores it).
  const AerialPerspective air = settings_.aerial_perspective;
  auto make = [air](std::initializer_list<std::string_view> stages, const render::ShaderDefines& defines,
                    render::Program& out) { return make_program(stages, defines, air, out); };
  for (auto& set : colour_) set.reset();  // rebuilt with the new air when next needed
  SYLVA_TRY(build_colour_programs(kFullVariant));  // the fallback of every variant
  shadow_enabled_offset_ = -1;
  if (shadow_.glsl_source.empty() || shadow_.lit_when_core_shadows_disabled) {
    const GLuint program = colour_[kFullVariant]->opaque.id();
    const GLuint params = glGetProgramResourceIndex(program, GL_UNIFORM, "sylva_shadow_params");
    if (params != GL_INVALID_INDEX) {
      const GLenum property = GL_OFFSET;
      GLint offset = -1;
      glGetProgramResourceiv(program, GL_UNIFORM, params, 1, &property, 1, nullptr, &offset);
      if (offset >= 0) shadow_enabled_offset_ = offset + 2 * static_cast<GLint>(sizeof(GLint));  // .z
    }
  }
  SYLVA_TRY(make({"voxel/horizon.vert", "voxel/horizon.frag"}, {}, horizon_program_));
  SYLVA_TRY(make({"voxel/chunk.vert", "voxel/depth.frag"}, {}, depth_program_));
  SYLVA_TRY(make({"voxel/chunk.vert", "voxel/depth.frag"}, kAlphaCut, depth_alpha_program_));
  SYLVA_TRY(make({"voxel/plant.vert", "voxel/depth.frag"}, kAlphaCut, plant_depth_program_));
  SYLVA_TRY(make({"voxel/plant.vert", "voxel/depth.frag"}, {}, plant_depth_opaque_program_));
  // The depth pre-pass (depth_prepass): the colour programs' vertex shaders with the same
  // defines, so every vertex lands on the same depth in both passes.
  SYLVA_TRY(make({"voxel/plant_mesh.vert", "voxel/depth.frag"}, {}, plant_mesh_depth_program_));
  SYLVA_TRY(make({"voxel/plant_mesh.vert", "voxel/depth.frag"}, kAlphaCut, plant_mesh_depth_alpha_program_));
  SYLVA_TRY(make({"voxel/plant.vert", "voxel/depth.frag"}, kTuft, tuft_depth_program_));
  depth_programs_ = {&depth_program_, &plant_depth_opaque_program_, &plant_mesh_depth_program_, &depth_alpha_program_,
                     &plant_depth_program_, &plant_mesh_depth_alpha_program_, &tuft_depth_program_};
  programs_air_ = air;
  return ok_status();
}

void VoxelRenderer::upload_chunk(const ChunkCoord& c, ChunkGpu& gpu) {
  const ChunkMesh* mesh = world_->mesh(c);
  gpu.coord = c;
  const BlockPos o = chunk_origin(c);
  gpu.origin = glm::dvec3(static_cast<double>(o.x), static_cast<double>(o.y), static_cast<double>(o.z));
  const BlockPalette& palette = world_->palette();
  gpu.quads = {};
  gpu.opaque_quads = gpu.alpha_quads = gpu.translucent_quads = 0;
  gpu.translucent.clear();
  if (mesh && mesh->opaque.size() + mesh->alpha_cut.size() > 0) {
    std::vector<PackedQuad> all, translucent;
    all.reserve(mesh->opaque.size() + mesh->alpha_cut.size());
    all.insert(all.end(), mesh->opaque.begin(), mesh->opaque.end());
    // Sides-only blocks are drawn as tufts (upload_tufts), not as the mesher's side faces;
    // translucent blocks (meshed as alpha-cut) go last, for the translucent pass.
    for (const PackedQuad& q : mesh->alpha_cut) {
      const auto block = static_cast<BlockId>(q.word1 & 0xffffu);
      if (palette.translucent(block)) {
        translucent.push_back(q);
      } else if (!palette.sides_only(block)) {
        all.push_back(q);
      }
    }
    gpu.opaque_quads = static_cast<std::uint32_t>(mesh->opaque.size());
    gpu.alpha_quads = static_cast<std::uint32_t>(all.size()) - gpu.opaque_quads;
    gpu.translucent_quads = static_cast<std::uint32_t>(translucent.size());
    all.insert(all.end(), translucent.begin(), translucent.end());
    // Updatable only when the translucent range is re-sorted in draw_translucent.
    if (!all.empty()) gpu.quads = render::Buffer::immutable(std::span<const PackedQuad>(all), !translucent.empty());
    gpu.translucent = std::move(translucent);
  }
  gpu.sorted_for = glm::ivec3(std::numeric_limits<int>::min());
  upload_tufts(c, gpu);
  // Point lights: the emissive blocks of the chunk (seed §2.3.3.2).
  gpu.lights.clear();
  const Chunk* chunk = world_->find(c);
  if (chunk && !chunk->is_uniform()) {
    const auto blocks = chunk->blocks();
    for (int i = 0; i < kChunkVolume; ++i) {
      const BlockType& t = palette[blocks[static_cast<std::size_t>(i)]];
      if (!t.emits_light()) continue;
      const int x = i % kChunkSize, z = (i / kChunkSize) % kChunkSize, y = i / (kChunkSize * kChunkSize);
      gpu.lights.push_back({gpu.origin + glm::dvec3(x + 0.5, y + 0.5, z + 0.5), t.emission});
    }
  }
  gpu.revision = world_->revision(c);
}

void VoxelRenderer::upload_tufts(const ChunkCoord& c, ChunkGpu& gpu) {
  gpu.tufts = {};
  gpu.tuft_count = 0;
  const Chunk* chunk = world_->find(c);
  if (!chunk) return;
  std::vector<Tuft> tufts;
  place_tufts(*chunk, c, world_->palette(), tufts);
  if (tufts.empty()) return;
  std::vector<PlantPartGpu> parts;
  parts.reserve(tufts.size());
  for (const Tuft& t : tufts) {
    // plant.vert (CROSS_QUADS) reads tint / 2 and width / 2 as unorm8 from data.w.
    const std::uint32_t extra = glm::packUnorm4x8(glm::vec4(t.tint * 0.5f, t.width * 0.5f));
    parts.push_back(make_part(t.foot, t.height, glm::angleAxis(t.yaw, glm::vec3(0, 1, 0)), t.block, extra));
  }
  gpu.tuft_count = static_cast<std::uint32_t>(parts.size());
  gpu.tufts = render::Buffer::immutable(std::span<const PlantPartGpu>(parts));
}

void VoxelRenderer::bake_range(const ChunkGpu& gpu, std::uint32_t first, std::uint32_t count,
                               std::span<const std::uint32_t> plant_starts, BakedMesh& out) {
  out = {};
  std::vector<PlantMeshPart> parts;
  parts.reserve(count);
  for (std::uint32_t i = first; i < first + count; ++i) {
    const PlantPartGpu& g = gpu.plant.parts[i];
    const glm::vec2 xy = glm::unpackSnorm2x16(g.data[0]), zw = glm::unpackSnorm2x16(g.data[1]);
    PlantMeshPart p;
    p.center = glm::vec3(g.center_size[0], g.center_size[1], g.center_size[2]);
    p.size = g.center_size[3];
    p.orientation = glm::quat(zw.y, xy.x, xy.y, zw.x);
    p.block = static_cast<BlockId>(g.data[2]);
    p.hidden = static_cast<std::uint8_t>(g.data[3]);
    parts.push_back(p);
  }
  PlantMesh mesh = bake_plant_mesh(parts, plant_starts);
  if (mesh.indices.empty()) return;
  out.vertices = render::Buffer::immutable(std::span<const PlantMeshVertex>(mesh.vertices));
  out.indices = render::Buffer::immutable(std::span<const std::uint32_t>(mesh.indices));
  out.vao = render::VertexArray::create();
  out.vao.index_buffer(out.indices);
  out.groups = mesh.groups;
  out.clusters = std::move(mesh.clusters);
  out.ready = true;
}

void VoxelRenderer::upload_plants(const ChunkCoord& c, ChunkGpu& gpu) {
  gpu.plants = {};
  gpu.plant = {};
  gpu.plant_box = {glm::dvec3(1e300), glm::dvec3(-1e300)};
  if (!generator_) return;
  gpu.plant = build_plant_batch(*world_, *generator_, c, settings_.plant_hidden_faces, *face_cache_);
  gpu.plant_box = gpu.plant.box;
  gpu.far_mesh = {};
  gpu.near_mesh[0] = {};
  gpu.near_mesh[1] = {};
  const PlantBatch& b = gpu.plant;
  // The far range: opaque then cut-out shells (plant_batch.hpp), one mesh, one cluster.
  if (settings_.plant_far_mesh) bake_range(gpu, b.first[1][0], b.count[1][0] + b.count[1][1], {}, gpu.far_mesh);
  if (settings_.plant_near_mesh) {
    std::vector<std::uint32_t> starts(b.plants.size());
    for (int cut = 0; cut < 2; ++cut) {
      for (std::size_t i = 0; i < b.plants.size(); ++i) starts[i] = b.plants[i].first[0][cut] - b.first[0][cut];
      bake_range(gpu, b.first[0][cut], b.count[0][cut], starts, gpu.near_mesh[cut]);
    }
  }
  if (!gpu.plant.parts.empty()) gpu.plants = render::Buffer::immutable(std::span<const PlantPartGpu>(gpu.plant.parts));
  gpu.plant.parts = {};
}

void VoxelRenderer::update(const render::FrameContext& frame) {
  stats_ = {};
  cast_context_ = nullptr;
  shadow_pass_ran_ = false;
  colour_variant_.reset();
  const bool meshes_changed = world_->mesh_epoch() != mesh_epoch_;
  const bool plants_changed = world_->plant_epoch() != plant_epoch_;
  if (meshes_changed || plants_changed) {
    // Drop chunks that were unloaded.
    for (auto it = chunks_.begin(); it != chunks_.end();) {
      it = world_->find(it->first) ? std::next(it) : chunks_.erase(it);
    }
    const auto dirty = world_->dirty_chunks();
    auto is_dirty = [&dirty](const ChunkCoord& c) { return std::binary_search(dirty.begin(), dirty.end(), c); };
    world_->for_each_chunk([&](const ChunkCoord& c, const Chunk&) {
      auto& slot = chunks_[c];
      const bool fresh = !slot;
      if (fresh) slot = std::make_unique<ChunkGpu>();
      // A stale (dirty) chunk keeps drawing its previous mesh until it is re-meshed.
      if ((fresh || slot->revision != world_->revision(c)) && !is_dirty(c)) {
        upload_chunk(c, *slot);
        ++stats_.uploads;
      } else if (fresh) {
        slot->coord = c;
        const BlockPos o = chunk_origin(c);
        slot->origin = glm::dvec3(static_cast<double>(o.x), static_cast<double>(o.y), static_cast<double>(o.z));
      }
      if (fresh || plants_changed) upload_plants(c, *slot);
      slot->box.min = slot->origin;
      slot->box.max = slot->origin + glm::dvec3(kChunkSize);
      if (slot->plant_box.min.x <= slot->plant_box.max.x) {
        slot->box.min = glm::min(slot->box.min, slot->plant_box.min);
        slot->box.max = glm::max(slot->box.max, slot->plant_box.max);
      }
    });
    mesh_epoch_ = world_->mesh_epoch();
    plant_epoch_ = world_->plant_epoch();
  }

  // Chunk frustum culling (seed §3.7.2 culled by chunk corners in NDC; a box-plane test has
  // neither its pitch restriction nor its narrow-FOV misses).
  const render::Frustum frustum = frame.camera.frustum();
  const glm::dvec3 eye = frame.camera.position();
  update_view_distance(eye);
  visible_.clear();
  for (auto& [c, gpu] : chunks_) {
    ++stats_.chunks_total;
    stats_.plant_parts_hidden += gpu->plant.parts_hidden;
    const bool empty = gpu->opaque_quads + gpu->alpha_quads + gpu->translucent_quads + gpu->tuft_count == 0 &&
                       gpu->plant_parts() == 0;
    if (empty) continue;
    if (settings_.frustum_culling && !frustum.intersects(gpu->box)) continue;
    if (fade_.y > 0.0f && horizontal_distance(gpu->box, eye) > fade_.y) continue;  // wholly faded into the sky
    visible_.push_back(gpu.get());
  }
  // Stable order (front to back helps early-z).
  std::sort(visible_.begin(), visible_.end(), [&eye](const ChunkGpu* a, const ChunkGpu* b) {
    const glm::dvec3 ca = a->origin + glm::dvec3(kChunkSize * 0.5) - eye;
    const glm::dvec3 cb = b->origin + glm::dvec3(kChunkSize * 0.5) - eye;
    const double da = glm::dot(ca, ca), db = glm::dot(cb, cb);
    return da != db ? da < db : a->coord < b->coord;
  });
  stats_.chunks_drawn = visible_.size();

  // Point lights nearest the camera.
  struct Candidate {
    double d2;
    glm::dvec3 p;
    glm::vec3 color;
  };
  std::vector<Candidate> lights;
  const double range2 = static_cast<double>(settings_.light_range) * settings_.light_range;
  for (auto& [c, gpu] : chunks_) {
    for (const auto& l : gpu->lights) {
      const glm::dvec3 d = l.position - eye;
      const double d2 = glm::dot(d, d);
      if (d2 <= range2) lights.push_back({d2, l.position, l.color});
    }
  }
  const auto keep = std::min<std::size_t>(lights.size(), static_cast<std::size_t>(std::clamp(settings_.max_point_lights, 0, kMaxLights)));
  std::partial_sort(lights.begin(), lights.begin() + static_cast<std::ptrdiff_t>(keep), lights.end(),
                    [](const Candidate& a, const Candidate& b) { return a.d2 < b.d2; });
  light_pos_.clear();
  light_color_.clear();
  for (std::size_t i = 0; i < keep; ++i) {
    light_pos_.emplace_back(glm::vec3(lights[i].p - eye), 1.0f);
    light_color_.emplace_back(lights[i].color, 1.0f);
  }
  stats_.point_lights = keep;
}

void VoxelRenderer::bind_common(const render::Program& program, const render::FrameContext* frame) const {
  program.use();
  diffuse_.bind(0);
  specular_.bind(1);
  block_table_.bind_base(GL_SHADER_STORAGE_BUFFER, kBlockBinding);
  set_if_active(program, "u_alpha_cutoff", settings_.alpha_cutoff);
  set_if_active(program, "u_translucent_cutoff", settings_.translucent_cutoff);
  if (frame) {
    set_if_active(program, "u_light_count", static_cast<int>(light_pos_.size()));
    if (!light_pos_.empty()) {
      set_if_active(program, "u_light_pos", std::span<const glm::vec4>(light_pos_));
      set_if_active(program, "u_light_color", std::span<const glm::vec4>(light_color_));
    }
    set_if_active(program, "u_attenuation", glm::vec3(settings_.light_kc, settings_.light_kl, settings_.light_kq));
    set_if_active(program, "u_ao_strength", settings_.ao_strength);
    set_if_active(program, "u_specular_scale", settings_.specular_scale);
    set_if_active(program, "u_bounce", std::clamp(settings_.bounce, 0.0f, 1.0f));
    set_if_active(program, "u_sky_light", std::clamp(settings_.sky_light, 0.0f, 8.0f));
    // No fade: start and end past any distance a float holds.
    set_if_active(program, "u_fade", fade_.y > 0.0f ? fade_ : glm::vec2(3.0e38f));
    if (shadow_.bind) shadow_.bind(program.id());
  }
}

void VoxelRenderer::draw_chunks(std::span<ChunkGpu* const> chunks, const render::Program& quads,
                                const render::Program& plants, bool alpha_cut, const glm::mat4& view_projection,
                                const glm::dvec3& origin, double full_cubes_within, double far_beyond,
                                const render::Frustum* culling, render::PassStats& stats, bool baked_plants) {
  quads.use();
  quads.set("u_view_projection", view_projection);
  for (ChunkGpu* gpu : chunks) {
    const std::uint32_t count = alpha_cut ? gpu->alpha_quads : gpu->opaque_quads;
    if (count == 0) continue;
    quads.set("u_chunk_offset", glm::vec3(gpu->origin - origin));
    quads.set("u_quad_base", alpha_cut ? gpu->opaque_quads : 0u);
    gpu->quads.bind_base(GL_SHADER_STORAGE_BUFFER, kQuadBinding);
    glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(count) * 6);
    ++stats.draw_calls;
    stats.triangles += 2ull * count;
    stats_.quads_drawn += count;
  }
  if (!settings_.draw_plants) return;
  plants.use();
  plants.set("u_view_projection", view_projection);
  const int cut = alpha_cut ? 1 : 0;
  // Draws parts [first, first + n) of a chunk's buffer with `triangles` faces not hidden.
  auto draw = [&](std::uint32_t first, std::uint32_t n, bool full, std::uint64_t triangles) {
    if (n == 0) return;
    plants.set("u_instance_base", first);
    glDrawArraysInstanced(GL_TRIANGLES, 0, full ? 36 : 18, static_cast<GLsizei>(n));
    ++stats.draw_calls;
    stats.triangles += triangles;
    stats.instances += n;
    stats_.plant_parts_drawn += n;
    stats_.plant_triangles += triangles;
  };
  for (ChunkGpu* gpu : chunks) {
    const PlantBatch& b = gpu->plant;
    if (b.plants.empty()) continue;
    const double d = distance(gpu->box, origin);
    // Far chunks draw their plants' shells (plant_batch.hpp) in the opaque pass, leaves without
    // the cut-out test (the crown's holes are below a pixel there).
    const bool far = d >= far_beyond;
    if (far && alpha_cut) continue;
    if (baked_plants && far && settings_.plant_far_mesh) continue;  // draw_far_meshes
    if (baked_plants && !far && settings_.plant_near_mesh) continue;  // draw_near_meshes
    const render::Containment seen = culling ? culling->classify(gpu->plant_box) : render::Containment::kInside;
    if (seen == render::Containment::kOutside) continue;
    plants.set("u_chunk_offset", glm::vec3(gpu->origin - origin));
    // All six faces, or only the three turned toward the eye (plant.vert): half the vertices.
    const bool full = !far && d < full_cubes_within;
    plants.set("u_front_faces_only", full ? 0 : 1);
    gpu->plants.bind_base(GL_SHADER_STORAGE_BUFFER, kPlantBinding);
    const int lod = far ? 1 : 0;
    if (far) ++stats_.plant_far_chunks;
    const auto& tri = full ? b.triangles_all : b.triangles_front;
    if (seen == render::Containment::kInside) {
      // The whole chunk: one draw (far: its opaque and leaf shells are one range).
      const std::uint32_t first = b.first[lod][far ? 0 : cut];
      const std::uint32_t n = far ? b.count[1][0] + b.count[1][1] : b.count[0][cut];
      draw(first, n, full, far ? tri[1][0] + tri[1][1] : tri[0][cut]);
      continue;
    }
    // Per plant: runs of neighbouring plants inside the frustum, one draw each.
    for (int k = far ? 0 : cut; k <= (far ? 1 : cut); ++k) {
      const std::uint32_t end = b.first[lod][k] + b.count[lod][k];
      const std::uint64_t tri_end = tri[lod][k];
      auto start_of = [&](std::size_t i) { return i < b.plants.size() ? b.plants[i].first[lod][k] : end; };
      auto tri_of = [&](std::size_t i) {
        return i < b.plants.size() ? (full ? b.plants[i].triangles_all : b.plants[i].triangles_front)[lod][k] : tri_end;
      };
      std::size_t i = 0;
      while (i < b.plants.size()) {
        if (!culling->intersects(b.plants[i].box)) {
          if (k == 0) ++stats_.plants_culled;  // counted once per chunk and pass pair
          ++i;
          continue;
        }
        std::size_t j = i + 1;
        while (j < b.plants.size() && culling->intersects(b.plants[j].box)) ++j;
        draw(start_of(i), start_of(j) - start_of(i), full, tri_of(j) - tri_of(i));
        i = j;
      }
    }
  }
}

std::size_t VoxelRenderer::draw_baked(const BakedMesh& mesh, std::uint32_t groups, std::span<const std::uint8_t> plant_seen,
                                      render::PassStats& stats) {
  auto draw = [&](std::uint32_t first, std::uint32_t count) {
    if (count == 0) return;
    glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(count), GL_UNSIGNED_INT,
                   reinterpret_cast<const void*>(static_cast<std::uintptr_t>(first) * sizeof(std::uint32_t)));
    ++stats.draw_calls;
    stats.triangles += count / 3;
    stats_.plant_triangles += count / 3;
    stats_.plant_mesh_triangles += count / 3;
  };
  for (int g = 0; g < kPlantMeshGroups; ++g) {
    const auto gi = static_cast<std::size_t>(g);
    const PlantMesh::Group& group = mesh.groups[gi];
    if (group.count == 0) continue;
    if (((groups >> g) & 1u) == 0) {
      ++stats_.plant_mesh_groups_skipped;
      continue;
    }
    if (plant_seen.empty()) {
      draw(group.first, group.count);
      continue;
    }
    // Runs of neighbouring plants in view: one range of the group each.
    std::size_t i = 0;
    while (i < plant_seen.size()) {
      if (plant_seen[i] == 0) {
        ++i;
        continue;
      }
      std::size_t j = i + 1;
      while (j < plant_seen.size() && plant_seen[j] != 0) ++j;
      const PlantMesh::Cluster& last = mesh.clusters[j - 1];
      draw(mesh.clusters[i].first[gi], last.first[gi] + last.count[gi] - mesh.clusters[i].first[gi]);
      i = j;
    }
  }
  return static_cast<std::size_t>(std::count(plant_seen.begin(), plant_seen.end(), std::uint8_t{0}));
}

void VoxelRenderer::draw_far_meshes(const render::Program& program, const glm::dvec3& origin,
                                    const render::Frustum* culling, render::PassStats& stats) {
  for (ChunkGpu* gpu : drawn_) {
    const BakedMesh& mesh = gpu->far_mesh;
    if (!mesh.ready || distance(gpu->box, origin) < settings_.plant_far_beyond) continue;
    if (culling && culling->classify(gpu->plant_box) == render::Containment::kOutside) continue;
    const glm::vec3 offset(gpu->origin - origin);
    program.set("u_chunk_offset", offset);
    mesh.vertices.bind_base(GL_SHADER_STORAGE_BUFFER, kPlantBinding);
    mesh.vao.bind();
    ++stats_.plant_far_chunks;
    // Eye in the chunk's frame: -offset (the mesh is chunk-relative).
    PlantMesh probe;  // visible_groups reads the groups only
    probe.groups = mesh.groups;
    draw_baked(mesh, probe.visible_groups(-offset), {}, stats);
  }
  vao_.bind();
}

void VoxelRenderer::draw_near_meshes(bool alpha_cut, const render::Program& program, const glm::dvec3& origin,
                                     double full_within, const render::Frustum* culling, render::PassStats& stats) {
  const int cut = alpha_cut ? 1 : 0;
  bool culled_faces = !alpha_cut;  // the opaque pass culls back faces already
  for (ChunkGpu* gpu : drawn_) {
    const BakedMesh& mesh = gpu->near_mesh[cut];
    if (!mesh.ready) continue;
    const double d = distance(gpu->box, origin);
    if (d >= settings_.plant_far_beyond) continue;  // far shells
    const render::Containment seen = culling ? culling->classify(gpu->plant_box) : render::Containment::kInside;
    if (seen == render::Containment::kOutside) continue;
    const glm::vec3 offset(gpu->origin - origin);
    program.set("u_chunk_offset", offset);
    mesh.vertices.bind_base(GL_SHADER_STORAGE_BUFFER, kPlantBinding);
    mesh.vao.bind();
    // Within full_within cut-out parts show every face (seen through their holes), unculled;
    // beyond, only the faces turned to the eye: back-face culling and whole groups skipped.
    const bool full = d < full_within;
    std::uint32_t groups = (1u << kPlantMeshGroups) - 1u;
    if (!full) {
      PlantMesh probe;  // visible_groups reads the groups only
      probe.groups = mesh.groups;
      groups = probe.visible_groups(-offset);
    }
    if (alpha_cut && culled_faces == full) {
      if (full) {
        glDisable(GL_CULL_FACE);
      } else {
        glEnable(GL_CULL_FACE);
      }
      culled_faces = !full;
    }
    if (seen == render::Containment::kInside) {
      draw_baked(mesh, groups, {}, stats);
      continue;
    }
    const std::vector<PlantBatch::Plant>& plants = gpu->plant.plants;
    plant_seen_.resize(plants.size());
    for (std::size_t i = 0; i < plants.size(); ++i) plant_seen_[i] = culling->intersects(plants[i].box) ? 1 : 0;
    const std::size_t culled = draw_baked(mesh, groups, plant_seen_, stats);
    if (!alpha_cut) stats_.plants_culled += culled;  // once per chunk and pass pair
  }
  vao_.bind();
}

void VoxelRenderer::draw_tufts(const render::Program& program, std::span<ChunkGpu* const> chunks,
                               const glm::mat4& view_projection, const glm::dvec3& origin, render::PassStats& stats) {
  program.set("u_view_projection", view_projection);
  program.set("u_instance_base", 0u);
  for (ChunkGpu* gpu : chunks) {
    if (gpu->tuft_count == 0) continue;
    program.set("u_chunk_offset", glm::vec3(gpu->origin - origin));
    gpu->tufts.bind_base(GL_SHADER_STORAGE_BUFFER, kPlantBinding);
    glDrawArraysInstanced(GL_TRIANGLES, 0, 12, static_cast<GLsizei>(gpu->tuft_count));
    ++stats.draw_calls;
    stats.triangles += 4ull * gpu->tuft_count;
    stats.instances += gpu->tuft_count;
    stats_.tufts_drawn += gpu->tuft_count;
  }
}

void VoxelRenderer::draw_horizon(const glm::mat4& view_projection, const glm::dvec3& origin, render::PassStats& stats) {
  const auto below = static_cast<float>(lowest_block_ - origin.y);
  // Seen from below (a camera under the lowest loaded block) the ring would be a ceiling.
  if (!settings_.horizon_skirt || fade_.y <= 0.0f || below >= 0.0f) return;
  horizon_program_.set("u_view_projection", view_projection);
  // A full disc, not a ring from the view distance: under the lowest loaded block it is hidden by
  // the world everywhere, except through the one-pixel cracks where merged quads meet in
  // T-junctions (README), which then show the horizon colour instead of the void.
  horizon_program_.set("u_skirt", glm::vec3(0.0f, kSkirtOuterRadius, below));
  glDrawArrays(GL_TRIANGLES, 0, 64 * 6);
  ++stats.draw_calls;
  stats.triangles += 128;
}

void VoxelRenderer::update_view_distance(const glm::dvec3& eye) {
  fade_ = glm::vec2(0.0f);
  stats_.view_distance = 0.0f;
  if (!(settings_.view_distance > 0.0f) || chunks_.empty()) return;
  // The loaded area's xz rectangle: from inside it, its inscribed radius around the camera is the
  // farthest the world reaches in every direction.
  glm::dvec2 lo(1e300), hi(-1e300);
  lowest_block_ = 1e300;
  for (const auto& [c, gpu] : chunks_) {
    lo = glm::min(lo, glm::dvec2(gpu->origin.x, gpu->origin.z));
    hi = glm::max(hi, glm::dvec2(gpu->origin.x, gpu->origin.z) + glm::dvec2(kChunkSize));
    lowest_block_ = std::min(lowest_block_, gpu->origin.y);
  }
  double end = settings_.view_distance;
  const double inscribed = std::min({eye.x - lo.x, hi.x - eye.x, eye.z - lo.y, hi.y - eye.z});
  if (inscribed > 0.0) end = std::min(end, inscribed);
  fade_.y = static_cast<float>(end);
  fade_.x = static_cast<float>(end) * (1.0f - std::clamp(settings_.fade_share, 0.01f, 1.0f));
  stats_.view_distance = fade_.y;
}

VoxelRenderer::UboBinding VoxelRenderer::bind_fallback_block(GLuint index, const render::Buffer& fallback, bool use_host) {
  UboBinding b;
  b.index = index;
  glGetIntegeri_v(GL_UNIFORM_BUFFER_BINDING, index, &b.buffer);
  glGetInteger64i_v(GL_UNIFORM_BUFFER_START, index, &b.start);
  glGetInteger64i_v(GL_UNIFORM_BUFFER_SIZE, index, &b.size);
  if (use_host && b.buffer != 0) return b;
  fallback.bind_base(GL_UNIFORM_BUFFER, index);
  b.replaced = true;
  return b;
}

bool VoxelRenderer::shadow_lookups_needed(const UboBinding& host_shadows) {
  bool needed = true;  // a custom hook: only it knows
  if (shadow_.glsl_source.empty() || shadow_.lit_when_core_shadows_disabled) {
    // A shadow pass this frame means enabled cascades, known without touching the GPU; else a
    // render::ShadowMaps block's flag is known on the CPU too; only a host's own block is read.
    needed = settings_.receive_shadows && !host_shadows.replaced &&
             (shadow_pass_ran_ || host_shadows_enabled(host_shadows));
  }
  stats_.shadow_lookup_shaders = needed ? 1 : 0;
  return needed;
}

bool VoxelRenderer::host_shadows_enabled(const UboBinding& host_shadows) {
  // sylva_shadow_params.z of the host's block (render/lib/shadows.glsl: 0 = disabled), at the
  // offset the linker gave it in a program that samples the shadows (no copy of the layout).
  const auto buffer = static_cast<GLuint>(host_shadows.buffer);
  if (const std::optional<bool> known = render::shadow_block_enabled(buffer)) return *known;  // a ShadowMaps'
  if (shadow_enabled_offset_ < 0) return true;
  GLint64 size = host_shadows.size;
  if (size == 0) glGetNamedBufferParameteri64v(buffer, GL_BUFFER_SIZE, &size);
  const GLint64 at = host_shadows.start + shadow_enabled_offset_;
  if (at + static_cast<GLint64>(sizeof(GLint)) > host_shadows.start + size) return true;
  GLint enabled = 1;
  ++stats_.shadow_flag_reads;
  glGetNamedBufferSubData(buffer, static_cast<GLintptr>(at), sizeof(GLint), &enabled);
  return enabled != 0;
}

unsigned VoxelRenderer::frame_colour_variant(const UboBinding& host_lights, const UboBinding& host_shadows) {
  if (!colour_variant_) {
    colour_variant_ = (point_lights_shaded(host_lights) ? kPointLightLoops : 0u) |
                      (shadow_lookups_needed(host_shadows) ? kShadowLookup : 0u);
  }
  return *colour_variant_;
}

bool VoxelRenderer::point_lights_shaded(const UboBinding& host_lights) {
  const bool lit = !light_pos_.empty() || !host_lights.replaced;
  stats_.point_light_shaders = lit ? 1 : 0;
  return lit;
}

void VoxelRenderer::restore_block(const UboBinding& b) {
  if (!b.replaced) return;
  const auto buffer = static_cast<GLuint>(b.buffer);
  if (buffer != 0 && b.size > 0) {
    glBindBufferRange(GL_UNIFORM_BUFFER, b.index, buffer, static_cast<GLintptr>(b.start), static_cast<GLsizeiptr>(b.size));
  } else {
    glBindBufferBase(GL_UNIFORM_BUFFER, b.index, buffer);
  }
}

void VoxelRenderer::draw_opaque_geometry(std::span<ChunkGpu* const> chunks, const OpaquePrograms& p,
                                         const render::FrameContext* frame, const glm::mat4& vp, const glm::dvec3& eye,
                                         const render::Frustum* culling, render::PassStats& stats) {
  drawn_ = chunks;
  // Plants and tufts first, the ground after them: they stand in front of the ground they hide,
  // and llvmpipe's early depth test then skips shading the ground behind them, instead of
  // shading it and shading over it (without the pre-pass; chunks are front to back). Only
  // coplanar faces of different kinds could come out differently: none at the shipped spawn.
  const bool plants = settings_.draw_plants;
  if (plants && (settings_.plant_far_mesh || settings_.plant_near_mesh)) {
    bind_common(*p.mesh, frame);
    p.mesh->set("u_view_projection", vp);
    if (settings_.plant_near_mesh) draw_near_meshes(false, *p.mesh, eye, 0.0, culling, stats);
    if (settings_.plant_far_mesh) draw_far_meshes(*p.mesh, eye, culling, stats);
  }
  glDisable(GL_CULL_FACE);  // cut-out faces are seen from both sides (seed §2.1)
  if (plants && settings_.plant_near_mesh) {
    bind_common(*p.mesh_alpha, frame);
    p.mesh_alpha->set("u_view_projection", vp);
    draw_near_meshes(true, *p.mesh_alpha, eye, settings_.leaf_back_faces_within, culling, stats);
    glDisable(GL_CULL_FACE);
  }
  bind_common(*p.tufts, frame);
  draw_tufts(*p.tufts, chunks, vp, eye, stats);
  glEnable(GL_CULL_FACE);
  bind_common(*p.chunks, frame);
  bind_common(*p.plants, frame);
  draw_chunks(chunks, *p.chunks, *p.plants, false, vp, eye, 0.0, settings_.plant_far_beyond, culling, stats, true);
  glDisable(GL_CULL_FACE);
  bind_common(*p.chunks_alpha, frame);
  bind_common(*p.plants_alpha, frame);
  draw_chunks(chunks, *p.chunks_alpha, *p.plants_alpha, true, vp, eye, settings_.leaf_back_faces_within,
              settings_.plant_far_beyond, culling, stats, true);
}

void VoxelRenderer::draw(render::Pass pass, const render::FrameContext& frame, render::PassStats& stats) {
  if (settings_.aerial_perspective != programs_air_) {
    // Settings change per frame (the scene module copies them in): recompile on a new air
    // variant; on a compile error keep the old programs and say why.
    if (Status built = build_programs(); !built.ok()) {
      log_warn("voxel: aerial_perspective: {}", built.error().message);
      programs_air_ = settings_.aerial_perspective;
    }
  }
  if (pass == render::Pass::kShadow) {
    shadow_pass_ran_ = true;
    // Inside ShadowMaps::render (the scene's shadow pass): cast into the cascade being drawn.
    if (const render::ShadowCasterContext* c = render::active_shadow_cascade(); c != nullptr && c->camera != nullptr) {
      render::ShadowCasterContext local = *c;
      local.stats = &stats;
      draw_shadow(local);
      cast_context_ = c;
      cast_cascade_ = c->cascade;
      cast_matrix_ = c->relative_view_projection;
    }
    return;
  }
  if (pass == render::Pass::kTransparent) {
    draw_translucent(frame, stats);
    return;
  }
  if (pass != render::Pass::kOpaque) return;
  vao_.bind();  // vertex pulling: an empty VAO (the core profile needs one bound)
  // Shadows (UBO 2) and the host's point lights (UBO 3) as the host bound them, or all-zero
  // blocks (none) when it bound nothing; restored afterwards for the other drawables.
  const UboBinding shadow_block = bind_fallback_block(render::kShadowUniformBinding, no_shadows_ubo_, settings_.receive_shadows);
  const UboBinding light_block = bind_fallback_block(render::kPointLightBinding, no_point_lights_ubo_, true);
  const unsigned variant = frame_colour_variant(light_block, shadow_block);
  const GLboolean cull_was = glIsEnabled(GL_CULL_FACE);
  glEnable(GL_DEPTH_TEST);
  glEnable(GL_CULL_FACE);
  glCullFace(GL_BACK);
  glFrontFace(GL_CCW);  // the seed's "clockwise is front" is wrong for GL's default (errata)
  const glm::mat4 vp = frame.camera.view_projection();
  const glm::dvec3 eye = frame.camera.position();
  // Opaque plant cubes are convex and back-face culled: the three faces turned to the eye are
  // all that can show. Leaf cubes show their far faces through their holes, near the camera.
  const render::Frustum frustum = frame.camera.frustum();
  const render::Frustum* culling = settings_.frustum_culling ? &frustum : nullptr;
  GLint depth_func = GL_LESS;
  GLboolean depth_mask = GL_TRUE;
  if (settings_.depth_prepass) {
    // Depth first (colour writes off, the same vertex shaders, so the same depths), then colour
    // with GL_EQUAL: every pixel is shaded once instead of once per surface drawn over it
    // (llvmpipe's frame is mostly fragment shading; issue #18). The counts of the voxel stats
    // are the colour pass's; the pass's draws and triangles include both.
    glGetIntegerv(GL_DEPTH_FUNC, &depth_func);
    glGetBooleanv(GL_DEPTH_WRITEMASK, &depth_mask);
    GLboolean color_mask[4];
    glGetBooleanv(GL_COLOR_WRITEMASK, color_mask);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    const VoxelFrameStats counted = stats_;
    draw_opaque_geometry(visible_, depth_programs_, nullptr, vp, eye, culling, stats);
    stats_ = counted;
    glColorMask(color_mask[0], color_mask[1], color_mask[2], color_mask[3]);
    glDepthFunc(GL_EQUAL);
    glDepthMask(GL_FALSE);
    glEnable(GL_CULL_FACE);
  }
  // Chunks wholly nearer than the fade's start (with a block to spare for float rounding) draw
  // with the shaders without the fade, whose sky look-up llvmpipe would run for every pixel.
  unfaded_.clear();
  faded_.clear();
  for (ChunkGpu* gpu : visible_) {
    const bool near = farthest_horizontal_distance(gpu->box, eye) + 1.0 < static_cast<double>(fade_.x);
    (near || fade_.y <= 0.0f ? unfaded_ : faded_).push_back(gpu);
  }
  stats_.chunks_faded = faded_.size();
  draw_opaque_geometry(unfaded_, colour_programs(variant)->opaque_pass(), &frame, vp, eye, culling, stats);
  draw_opaque_geometry(faded_, colour_programs(variant | kDistanceFade)->opaque_pass(), &frame, vp, eye, culling, stats);
  if (settings_.depth_prepass) {
    glDepthFunc(static_cast<GLenum>(depth_func));
    glDepthMask(depth_mask);
  }
  bind_common(horizon_program_, &frame);
  draw_horizon(vp, eye, stats);
  if (cull_was) glEnable(GL_CULL_FACE);
  restore_block(light_block);
  restore_block(shadow_block);
}

namespace {

// Centre of a packed quad relative to its chunk's origin (the corners chunk.vert builds).
glm::vec3 quad_centre(const PackedQuad& p) {
  const Quad q = unpack_quad(p);
  const int axis = q.face >> 1, u = (axis + 1) % 3, v = (axis + 2) % 3;
  glm::vec3 c(static_cast<float>(q.x), static_cast<float>(q.y), static_cast<float>(q.z));
  if ((q.face & 1) == 0) c[axis] += 1.0f;
  c[u] += 0.5f * static_cast<float>(q.du);
  c[v] += 0.5f * static_cast<float>(q.dv);
  return c;
}

}  // namespace

// Back to front within the chunk: farthest quad centre first (ties keep the mesher's order, so
// the result is deterministic). Re-sorted and re-uploaded only when the eye has moved by half a
// block since the last sort; the opaque and alpha-cut ranges of the buffer are left alone.
void VoxelRenderer::sort_translucent(ChunkGpu& gpu, const glm::dvec3& eye) {
  const glm::dvec3 local = eye - gpu.origin;
  const glm::ivec3 cell(glm::floor(local * 2.0));
  if (cell == gpu.sorted_for) return;
  gpu.sorted_for = cell;
  const glm::vec3 e(local);
  std::vector<std::pair<float, PackedQuad>>& keyed = sort_keys_;
  keyed.resize(gpu.translucent.size());
  for (std::size_t i = 0; i < keyed.size(); ++i) {
    const glm::vec3 d = quad_centre(gpu.translucent[i]) - e;
    keyed[i] = {glm::dot(d, d), gpu.translucent[i]};
  }
  std::stable_sort(keyed.begin(), keyed.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  for (std::size_t i = 0; i < keyed.size(); ++i) gpu.translucent[i] = keyed[i].second;
  gpu.quads.update(std::span<const PackedQuad>(gpu.translucent),
                   static_cast<std::size_t>(gpu.opaque_quads + gpu.alpha_quads) * sizeof(PackedQuad));
  ++stats_.translucent_sorts;
}

// Translucent faces (glass, water, ice; seed §2.2): after everything opaque, blended over it,
// back to front (the seed sorted transparent objects by distance): chunks by distance and the
// faces of each chunk by their centre's distance (sort_translucent), depth tested but not
// written, back faces culled so a block's far faces do not double its colour. Texels below
// translucent_cutoff (the seed's 0.05) are discarded. They cast no shadows.
void VoxelRenderer::draw_translucent(const render::FrameContext& frame, render::PassStats& stats) {
  bool any = false;
  for (const ChunkGpu* gpu : visible_) any = any || gpu->translucent_quads > 0;
  if (!any) return;
  vao_.bind();
  const UboBinding shadow_block = bind_fallback_block(render::kShadowUniformBinding, no_shadows_ubo_, settings_.receive_shadows);
  const UboBinding light_block = bind_fallback_block(render::kPointLightBinding, no_point_lights_ubo_, true);
  const render::Program& translucent_program =
      colour_programs(frame_colour_variant(light_block, shadow_block) | kDistanceFade)->translucent;
  const render::SavedBlendState saved;
  glEnable(GL_DEPTH_TEST);
  glEnable(GL_CULL_FACE);
  glCullFace(GL_BACK);
  glFrontFace(GL_CCW);
  glEnable(GL_BLEND);
  glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ZERO, GL_ONE);
  glDepthMask(GL_FALSE);
  const glm::dvec3 eye = frame.camera.position();
  bind_common(translucent_program, &frame);
  translucent_program.use();
  translucent_program.set("u_view_projection", frame.camera.view_projection());
  // visible_ is front to back.
  for (auto it = visible_.rbegin(); it != visible_.rend(); ++it) {
    ChunkGpu* gpu = *it;
    if (gpu->translucent_quads == 0) continue;
    sort_translucent(*gpu, eye);
    translucent_program.set("u_chunk_offset", glm::vec3(gpu->origin - eye));
    translucent_program.set("u_quad_base", gpu->opaque_quads + gpu->alpha_quads);
    gpu->quads.bind_base(GL_SHADER_STORAGE_BUFFER, kQuadBinding);
    glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(gpu->translucent_quads) * 6);
    ++stats.draw_calls;
    stats.triangles += 2ull * gpu->translucent_quads;
    stats_.quads_drawn += gpu->translucent_quads;
    stats_.translucent_quads_drawn += gpu->translucent_quads;
  }
  restore_block(light_block);
  restore_block(shadow_block);
}

void VoxelRenderer::draw_depth_list(std::span<ChunkGpu* const> chunks, const glm::mat4& relative_view_projection,
                                    const glm::dvec3& origin, const render::Frustum* culling, render::PassStats& stats) {
  if (chunks.empty()) return;
  vao_.bind();
  // Both sides: a closed voxel body casts the same either way, and open geometry (alpha-cut
  // leaves, sides-only tufts, plant cubes seen edge-on) must not lose faces to culling.
  const GLboolean cull_was = glIsEnabled(GL_CULL_FACE);
  glDisable(GL_CULL_FACE);
  // Which fragment shader each kind of caster uses (seed 004 R1, ShadowPassShaders).
  const ShadowPassShaders shaders = settings_.shadow_shaders;
  render::Program& opaque_chunks = shaders == ShadowPassShaders::kAlphaTested ? depth_alpha_program_ : depth_program_;
  render::Program& opaque_plants =
      shaders == ShadowPassShaders::kAlphaTested ? plant_depth_program_ : plant_depth_opaque_program_;
  render::Program& cut_chunks = shaders == ShadowPassShaders::kEarlyZ ? depth_program_ : depth_alpha_program_;
  render::Program& cut_plants = shaders == ShadowPassShaders::kEarlyZ ? plant_depth_opaque_program_ : plant_depth_program_;
  bind_common(opaque_chunks, nullptr);
  bind_common(opaque_plants, nullptr);
  // Every face: a light's view is no eye position, and leaves cast through both their sides.
  constexpr double kAll = std::numeric_limits<double>::infinity();
  draw_chunks(chunks, opaque_chunks, opaque_plants, false, relative_view_projection, origin, kAll, kNever, culling, stats);
  bind_common(cut_chunks, nullptr);
  bind_common(cut_plants, nullptr);
  // Shadows keep the exact plants: light passing a crown's outer holes falls on its inner leaves.
  draw_chunks(chunks, cut_chunks, cut_plants, true, relative_view_projection, origin, kAll, kNever, culling, stats);
  if (cull_was) glEnable(GL_CULL_FACE);
}

void VoxelRenderer::draw_shadow(const render::ShadowCasterContext& context) {
  shadow_pass_ran_ = true;  // receiving does not depend on casting (other casters' shadows)
  if (!settings_.cast_shadows || context.camera == nullptr) return;
  render::PassStats local;
  render::PassStats& stats = context.stats != nullptr ? *context.stats : local;
  // Cull with the cascade's light frustum (stretched toward the sun by caster_reach).
  shadow_list_.clear();
  for (auto& [c, gpu] : chunks_) {
    const bool empty = gpu->opaque_quads + gpu->alpha_quads == 0 && gpu->plant_parts() == 0;
    if (empty) continue;
    if (settings_.shadow_chunk_culling && !context.light_frustum.intersects(gpu->box)) continue;
    shadow_list_.push_back(gpu.get());
  }
  std::sort(shadow_list_.begin(), shadow_list_.end(),
            [](const ChunkGpu* a, const ChunkGpu* b) { return a->coord < b->coord; });
  stats_.shadow_chunks_cast += shadow_list_.size();
  draw_depth_list(shadow_list_, context.relative_view_projection, context.camera->position(),
                  settings_.shadow_chunk_culling ? &context.light_frustum : nullptr, stats);
}

render::ShadowCaster& VoxelRenderer::shadow_caster() { return *caster_; }

void VoxelRenderer::draw_depth(const glm::mat4& relative_view_projection, const glm::dvec3& origin,
                               render::PassStats& stats) {
  if (render::active_shadow_cascade() != nullptr) shadow_pass_ran_ = true;
  if (const render::ShadowCasterContext* c = render::active_shadow_cascade();
      c != nullptr && c == cast_context_ && c->cascade == cast_cascade_ && c->relative_view_projection == cast_matrix_ &&
      relative_view_projection == cast_matrix_) {
    return;  // this cascade was cast through draw(kShadow) already
  }
  all_list_.clear();
  for (auto& [c, gpu] : chunks_) all_list_.push_back(gpu.get());
  std::sort(all_list_.begin(), all_list_.end(), [](const ChunkGpu* a, const ChunkGpu* b) { return a->coord < b->coord; });
  draw_depth_list(all_list_, relative_view_projection, origin, nullptr, stats);
}

}  // namespace sylva::voxel
