// The "voxel" section: a procedurally generated block world (seed 004: biomes, L-system flora)
// around a centre, meshed on a worker pool and drawn by voxel::VoxelRenderer. A voxel world is
// its own ground (it does not stand on the scene's height field); it reads the scene's wind-free
// sun, sky and fog through the shared lighting block.

#include "modules/module_factories.hpp"

#include <sylva/core/log.hpp>
#include <sylva/render/shadow_maps.hpp>
#include <sylva/scene/module_instance.hpp>
#include <sylva/voxel/voxel_renderer.hpp>
#include <sylva/voxel/worker_pool.hpp>
#include <sylva/voxel/world.hpp>
#include <sylva/voxel/world_builder.hpp>
#include <sylva/voxel/worldgen.hpp>

#include <fmt/format.h>

#include <optional>

namespace sylva::scene::detail {
namespace {

struct VoxelSectionSettings {
  glm::dvec2 center{0.0, 0.0};   // world x/z the generated area is centred on [blocks = m]
  int radius_chunks = 3;         // chunks generated in each direction around the centre
  voxel::MesherKind mesher = voxel::MesherKind::kBitmask;
  int threads = 0;               // generation and meshing workers (0 = all cores)
  voxel::WorldGenSettings worldgen;
  // A scene's world fades into the sky at the edge of its generated area (view_distance caps the
  // inscribed radius around the camera; the library's default 0 means no fade).
  voxel::VoxelRenderSettings render = [] {
    voxel::VoxelRenderSettings r;
    r.view_distance = 100000.0f;
    return r;
  }();

  template <class V>
  void visit(V& v) {
    v(center, "center", {.min = -1.0e9, .max = 1.0e9, .unit = "m", .help = "Centre of the generated area (x, z)", .rebuild = Rebuild::kOffline});
    v(radius_chunks, "radius_chunks", {.min = 0, .max = 32, .help = "Chunks generated in each direction (32 blocks each)", .rebuild = Rebuild::kOffline});
    v(mesher, "mesher", {.help = "culled, greedy or bitmask", .rebuild = Rebuild::kOffline});
    v(threads, "threads", {.min = 0, .max = 256, .help = "Worker threads (0 = all cores)", .rebuild = Rebuild::kOffline});
    v(worldgen, "worldgen");
    v(render, "render");
  }
};

using Settings = SettingsOf<VoxelSectionSettings>;

// Casts the world into the cascade being rendered (VoxelRenderer::draw(kShadow) draws nothing;
// its caster entry point is draw_depth).
class VoxelShadowCaster final : public render::Drawable {
 public:
  explicit VoxelShadowCaster(voxel::VoxelRenderer*& renderer) : renderer_(renderer) {}
  void update(const render::FrameContext&) override {}
  void draw(render::Pass pass, const render::FrameContext&, render::PassStats& stats) override {
    if (pass != render::Pass::kShadow || !renderer_) return;
    const render::ShadowCasterContext* c = render::active_shadow_cascade();
    if (c && c->camera) renderer_->draw_depth(c->relative_view_projection, c->camera->position(), stats);
  }

 private:
  voxel::VoxelRenderer*& renderer_;
};

// Receiving: the renderer's shadow hook samples the scene's cascades (bound by the scene).
const char* kShadowReceiver =
    "#include \"render/lib/shadows.glsl\"\n"
    "float voxel_shadow(vec3 rel_pos, vec3 normal) { return sylva_shadow(rel_pos, normal); }\n";

class VoxelInstance final : public ModuleInstance {
 public:
  static Result<std::unique_ptr<ModuleInstance>> create(const ModuleBuildContext& ctx) {
    auto inst = std::unique_ptr<VoxelInstance>(new VoxelInstance(ctx));
    SYLVA_TRY(inst->build());
    return std::unique_ptr<ModuleInstance>(std::move(inst));
  }

  std::vector<render::Drawable*> drawables() override { return {renderer_.get(), &caster_}; }

  void sync_settings() override {
    // Per-frame render settings; texture_size (kGpu) only changes on a rebuild.
    const int texture_size = renderer_->settings().texture_size;
    renderer_->settings() = settings().render;
    renderer_->settings().texture_size = texture_size;
  }

  Status rebuild(Rebuild what) override {
    if (what == Rebuild::kNone) return {};
    return build();
  }

  Status on_map_changed(const std::string& map_id, const WorldArea& area) override {
    (void)map_id;  // a voxel world has no painted maps and does not stand on the height field
    (void)area;
    return {};
  }

  nlohmann::json stats() const override {
    const voxel::VoxelFrameStats& s = renderer_->frame_stats();
    return {{"chunks", s.chunks_total},       {"chunks_drawn", s.chunks_drawn}, {"quads_drawn", s.quads_drawn},
            {"plant_parts_drawn", s.plant_parts_drawn}, {"tufts_drawn", s.tufts_drawn},
            {"view_distance", s.view_distance}, {"point_lights", s.point_lights},
            {"shadow_chunks_cast", s.shadow_chunks_cast},
            {"generation_ms", generation_ms_}};
  }

  std::vector<render::Aabb> debug_bounds() const override {
    std::vector<render::Aabb> out;
    for (const voxel::ChunkCoord& c : world_->chunk_coords()) {
      const glm::dvec3 o(static_cast<double>(c.x) * voxel::kChunkSize, static_cast<double>(c.y) * voxel::kChunkSize,
                         static_cast<double>(c.z) * voxel::kChunkSize);
      out.push_back({o, o + glm::dvec3(voxel::kChunkSize)});
    }
    return out;
  }

 private:
  explicit VoxelInstance(const ModuleBuildContext& ctx) : ModuleInstance("voxel"), ctx_(ctx) {}

  const VoxelSectionSettings& settings() const { return static_cast<const Settings&>(*ctx_.section->settings).value; }

  Status build() {
    const VoxelSectionSettings& s = settings();
    auto generator = voxel::WorldGenerator::create(s.worldgen);
    if (!generator.ok()) return make_error(generator.error().code, "voxel: " + generator.error().message);
    auto world = std::make_unique<voxel::World>();
    voxel::WorkerPool pool(s.threads);
    std::int64_t y0 = 0, y1 = 0;
    voxel::chunk_y_range(s.worldgen, y0, y1);
    const voxel::ChunkCoord centre{static_cast<std::int64_t>(std::floor(s.center.x / voxel::kChunkSize)), 0,
                                   static_cast<std::int64_t>(std::floor(s.center.y / voxel::kChunkSize))};
    const auto coords = voxel::chunk_box(centre, s.radius_chunks, y0, y1);
    const voxel::PopulateReport report = voxel::populate(*world, **generator, coords, pool);
    for (const Error& e : report.region_errors) log_warn("voxel: {}", e.message);
    voxel::remesh_parallel(*world, pool, s.mesher);
    auto renderer = voxel::VoxelRenderer::create(*world, *generator, s.render);
    if (!renderer.ok()) return make_error(renderer.error().code, "voxel: " + renderer.error().message);
    Status receiver = (*renderer)->set_shadow_receiver({kShadowReceiver, [](GLuint) {}});
    if (!receiver.ok()) return make_error(receiver.error().code, "voxel: " + receiver.error().message);
    renderer_ = std::move(*renderer);
    renderer_ptr_ = renderer_.get();
    world_ = std::move(world);
    generator_ = *generator;
    generation_ms_ = report.milliseconds;
    return {};
  }

  ModuleBuildContext ctx_;
  std::shared_ptr<const voxel::WorldGenerator> generator_;
  std::unique_ptr<voxel::World> world_;
  std::unique_ptr<voxel::VoxelRenderer> renderer_;
  voxel::VoxelRenderer* renderer_ptr_ = nullptr;
  VoxelShadowCaster caster_{renderer_ptr_};
  double generation_ms_ = 0.0;
};

}  // namespace

ModuleDescriptor voxel_module() {
  ModuleDescriptor d;
  d.name = "voxel";
  d.description = "chunked voxel worlds with biomes and L-system flora (seed 004)";
  d.make_settings = [] { return std::make_unique<Settings>(std::vector<MapSlot>{}); };
  d.create = &VoxelInstance::create;
  return d;
}

}  // namespace sylva::scene::detail
