// The "voxel" section: a procedurally generated block world (seed 004: biomes, L-system flora)
// around a centre, meshed on a worker pool and drawn by voxel::VoxelRenderer. A voxel world is
// its own ground (it does not stand on the scene's height field); it reads the scene's wind-free
// sun, sky and fog through the shared lighting block.
//
// Its plants are data (issue #16): `flora.species_file` names a species table (JSON with .lsys
// grammars, voxel/species.hpp; relative to the scene file, "" = the shipped species). Like the
// forest's species files, a bad file does not fail the scene: a species with a bad entry is left
// out, and a file that fails as a whole (missing, not JSON, no species list) gives the shipped
// species, each with a warning naming the file and the JSON path or the grammar's
// file:line:column. A world is still a world without a user's plants, and the editor keeps the
// scene open while its user fixes the file (the scene's warnings are its messages).
//
// The block palette is data too: `blocks.palette_file` (voxel/palette_file.hpp; "" = the shipped
// data/palette.json) names blocks with render class, procedural or image textures, emission and
// specular. A palette that fails, or that lacks a block the generator lays (stone, dirt, grass,
// dry_grass, sand, snow, tall_grass, flowers), gives the standard palette with a warning; species
// whose blocks a user's palette lacks are left out with a warning.

#include "modules/module_factories.hpp"

#include <sylva/core/log.hpp>
#include <sylva/render/shadow_maps.hpp>
#include <sylva/scene/module_instance.hpp>
#include <sylva/voxel/palette_file.hpp>
#include <sylva/voxel/species.hpp>
#include <sylva/voxel/voxel_renderer.hpp>
#include <sylva/voxel/worker_pool.hpp>
#include <sylva/voxel/world.hpp>
#include <sylva/voxel/world_builder.hpp>
#include <sylva/voxel/worldgen.hpp>

#include <fmt/format.h>

#include <map>
#include <optional>

namespace sylva::scene::detail {
namespace {

struct FloraSettings {
  std::string species_file;  // "" = the shipped data/species.json

  template <class V>
  void visit(V& v) {
    v(species_file, "species_file",
      {.max = 4096.0, .help = "Species table (JSON naming .lsys grammars, see the voxel README), relative to the scene file; empty = the shipped species",
       .rebuild = Rebuild::kOffline});
  }
};

struct BlockSettings {
  std::string palette_file;  // "" = the shipped data/palette.json

  template <class V>
  void visit(V& v) {
    v(palette_file, "palette_file",
      {.max = 4096.0, .help = "Block palette (JSON: names, render class, textures from images or procedural, see the voxel README), relative to the scene file; empty = the shipped blocks",
       .rebuild = Rebuild::kOffline});
  }
};

struct VoxelSectionSettings {
  glm::dvec2 center{0.0, 0.0};   // world x/z the generated area is centred on [blocks = m]
  int radius_chunks = 3;         // chunks generated in each direction around the centre
  voxel::MesherKind mesher = voxel::MesherKind::kBitmask;
  int threads = 0;               // generation and meshing workers (0 = all cores)
  voxel::WorldGenSettings worldgen;
  FloraSettings flora;
  BlockSettings blocks;
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
    v(flora, "flora");
    v(blocks, "blocks");
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
            {"plant_triangles", s.plant_triangles}, {"plant_parts_hidden", s.plant_parts_hidden}, {"plant_far_chunks", s.plant_far_chunks},
            {"plants_culled", s.plants_culled}, {"plant_mesh_triangles", s.plant_mesh_triangles},
            {"plant_mesh_groups_skipped", s.plant_mesh_groups_skipped},
            {"view_distance", s.view_distance}, {"point_lights", s.point_lights},
            {"point_light_shaders", s.point_light_shaders}, {"shadow_lookup_shaders", s.shadow_lookup_shaders},
            {"shadow_flag_reads", s.shadow_flag_reads},
            {"shadow_chunks_cast", s.shadow_chunks_cast}, {"translucent_quads_drawn", s.translucent_quads_drawn},
            {"translucent_sorts", s.translucent_sorts},
            {"generation_ms", generation_ms_},
            {"species_table", generator_->species().source},
            {"palette_blocks", generator_->palette().size() - 1},
            {"plants_per_species", plants_per_species_},
            {"plant_blocks", plant_blocks_}};
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

  // The scene's block palette; null: the standard one (see the top of the file for the policy).
  std::shared_ptr<const voxel::BlockPalette> user_palette() const {
    const std::string& file = settings().blocks.palette_file;
    if (file.empty()) return nullptr;
    std::vector<std::string> warnings;
    auto palette = voxel::load_palette(ctx_.document->resolve(file), warnings);
    for (const std::string& w : warnings) log_warn("voxel.blocks.palette_file: {}", w);
    if (!palette.ok()) {
      log_warn("voxel.blocks.palette_file: {}; the standard palette is used", palette.error().message);
      return nullptr;
    }
    return std::make_shared<const voxel::BlockPalette>(std::move(*palette));
  }

  // The shipped species for `palette`: null (the generator's default) for the standard palette.
  static std::shared_ptr<const voxel::SpeciesTable> shipped_species(const voxel::BlockPalette& palette) {
    if (&palette == &voxel::BlockPalette::standard()) return nullptr;
    auto table = voxel::builtin_species_table(palette);
    if (!table.ok()) return nullptr;
    for (const Error& e : table->rejected) log_warn("voxel.blocks.palette_file: {}; the species is left out", e.message);
    table->rejected.clear();
    return std::make_shared<const voxel::SpeciesTable>(std::move(*table));
  }

  // The scene's species table read for `palette` (see the top of the file for the policy).
  std::shared_ptr<const voxel::SpeciesTable> species_table(const voxel::BlockPalette& palette) const {
    const std::string& file = settings().flora.species_file;
    if (file.empty()) return shipped_species(palette);
    std::vector<std::string> warnings;
    auto table = voxel::load_species_table(ctx_.document->resolve(file), palette, warnings);
    for (const std::string& w : warnings) log_warn("voxel.flora.species_file: {}", w);
    if (!table.ok()) {
      log_warn("voxel.flora.species_file: {}; the shipped species are used", table.error().message);
      return shipped_species(palette);
    }
    for (const Error& e : table->rejected) log_warn("voxel.flora.species_file: {}; the species is left out", e.message);
    return std::make_shared<const voxel::SpeciesTable>(std::move(*table));
  }

  Result<std::shared_ptr<const voxel::WorldGenerator>> make_generator(const voxel::BlockPalette& palette) const {
    const VoxelSectionSettings& s = settings();
    auto generator = voxel::WorldGenerator::create(s.worldgen, palette, species_table(palette));
    if (!generator.ok() && !s.flora.species_file.empty()) {
      // A user's grammar that fails while its variants are built (e.g. brackets nested past
      // max_depth, which the worst-case check before deriving does not bound).
      log_warn("voxel.flora.species_file: {}; the shipped species are used", generator.error().message);
      generator = voxel::WorldGenerator::create(s.worldgen, palette, shipped_species(palette));
    }
    return generator;
  }

  // Plants per species and their blocks per block name, counted from the generated world.
  void count_plants() {
    plants_per_species_ = nlohmann::json::object();
    plant_blocks_ = nlohmann::json::object();
    std::map<std::string, std::size_t> plants, blocks;
    const voxel::BlockPalette& palette = generator_->palette();
    for (const voxel::ChunkCoord& c : world_->chunk_coords()) {
      const auto* list = world_->plants(c);
      if (!list) continue;
      for (const voxel::PlantInstance& p : *list) {
        ++plants[generator_->species().species.at(p.species).name];
        const voxel::PlantVariants& variants = generator_->variants(p.species);
        const voxel::PlantModel& model = variants.at(p.variant % variants.size());
        for (int o = 0; o < voxel::kPlantOutputs; ++o) {
          const voxel::BlockId b = generator_->part_block(p.species, o);
          if (b != voxel::kAir) blocks[palette[b].name] += model.outputs[static_cast<std::size_t>(o)].size();
        }
      }
    }
    for (const auto& [name, n] : plants) plants_per_species_[name] = n;
    for (const auto& [name, n] : blocks) plant_blocks_[name] = n;
  }

  Status build() {
    const VoxelSectionSettings& s = settings();
    std::shared_ptr<const voxel::BlockPalette> palette = user_palette();
    auto generator = make_generator(palette ? *palette : voxel::BlockPalette::standard());
    if (!generator.ok() && palette) {
      log_warn("voxel.blocks.palette_file: {}; the standard palette is used", generator.error().message);
      palette = nullptr;
      generator = make_generator(voxel::BlockPalette::standard());
    }
    if (!generator.ok()) return make_error(generator.error().code, "voxel: " + generator.error().message);
    auto world = std::make_unique<voxel::World>((*generator)->palette());
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
    Status receiver = (*renderer)->set_shadow_receiver({kShadowReceiver, [](GLuint) {}, true});
    if (!receiver.ok()) return make_error(receiver.error().code, "voxel: " + receiver.error().message);
    renderer_ = std::move(*renderer);
    renderer_ptr_ = renderer_.get();
    world_ = std::move(world);
    generator_ = *generator;
    palette_ = std::move(palette);  // last: the old world, generator and renderer used the old one
    generation_ms_ = report.milliseconds;
    count_plants();
    return {};
  }

  ModuleBuildContext ctx_;
  std::shared_ptr<const voxel::BlockPalette> palette_;  // a user's palette (null: standard), outlives the rest
  std::shared_ptr<const voxel::WorldGenerator> generator_;
  std::unique_ptr<voxel::World> world_;
  std::unique_ptr<voxel::VoxelRenderer> renderer_;
  voxel::VoxelRenderer* renderer_ptr_ = nullptr;
  VoxelShadowCaster caster_{renderer_ptr_};
  double generation_ms_ = 0.0;
  nlohmann::json plants_per_species_ = nlohmann::json::object();
  nlohmann::json plant_blocks_ = nlohmann::json::object();
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
