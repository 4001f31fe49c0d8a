// The built-in "ground" module: the scene's height field drawn as a plain chunked mesh with a
// height/slope material. It is the ground of scenes that do not use the terrain module (and of
// builds without it). Chunks are independent vertex ranges of one buffer, so a painted region
// re-uploads only the chunks it touches; each chunk is frustum-culled on the CPU.

#include "modules/module_factories.hpp"

#include <sylva/core/log.hpp>
#include <sylva/render/buffer.hpp>
#include <sylva/render/shader_library.hpp>
#include <sylva/render/shadow_maps.hpp>
#include <sylva/render/vertex_array.hpp>
#include <sylva/scene/module_instance.hpp>

#include <algorithm>
#include <cstddef>

namespace sylva::render::embedded {
void register_scene_shaders();  // generated from modules/scene/shaders
}  // namespace sylva::render::embedded

namespace sylva::scene::detail {
namespace {

// The height where ground.frag starts blending to snow. It blends over +-kSnowBlend metres
// around the line, so a ground with less relief than the blend band (a flat floor) would be
// half snow everywhere: it gets none (unless snow_fraction is 0, snow everywhere).
float snow_line(float lowest, float highest, float snow_fraction) {
  constexpr float kSnowBlend = 10.0f;  // ground.frag's smoothstep half-width [m]
  constexpr float kNever = 1.0e9f;
  if (snow_fraction <= 0.0f) return -kNever;
  if (snow_fraction >= 1.0f || highest - lowest < 2.0f * kSnowBlend) return kNever;
  return lowest + snow_fraction * (highest - lowest);
}

struct GroundModuleSettings {
  HeightSourceSettings source;
  int chunk_quads = 32;        // quads per chunk side: the unit of culling and of rebuilds
  float snow_fraction = 0.8f;  // snow above this share of the height range

  template <class V>
  void visit(V& v) {
    source.visit(v);  // flat: "ground.resolution", "ground.noise.octaves", ...
    v(chunk_quads, "chunk_quads", {.min = 4, .max = 256, .help = "Quads per chunk side (culling and rebuild unit)", .rebuild = Rebuild::kGpu});
    v(snow_fraction, "snow_fraction", {.min = 0.0, .max = 1.0, .help = "Snow above this share of the height range"});
  }
};

struct GroundVertex {
  glm::vec3 position;  // relative to the field origin (x, height, z)
  glm::vec3 normal;
};

struct Chunk {
  int i0 = 0, j0 = 0, i1 = 0, j1 = 0;  // sample range, inclusive
  std::size_t first_vertex = 0;
  std::size_t first_index = 0;
  std::size_t index_count = 0;
  render::Aabb bounds;
};

class GroundDrawable final : public render::Drawable {
 public:
  static Result<std::unique_ptr<GroundDrawable>> create(const HeightField& field, int chunk_quads,
                                                        const GroundModuleSettings* settings, const DebugView* debug) {
    render::embedded::register_render_shaders();
    render::embedded::register_scene_shaders();
    auto program = render::Program::create({"scene/ground.vert", "scene/ground.frag"});
    if (!program.ok()) return program.error();
    auto g = std::unique_ptr<GroundDrawable>(new GroundDrawable());
    g->program_ = std::move(*program);
    g->field_ = &field;
    g->settings_ = settings;
    g->debug_ = debug;

    const int c = std::max(chunk_quads, 1);
    std::vector<std::uint32_t> indices;
    std::size_t vertex_count = 0;
    for (int j0 = 0; j0 + 1 < field.rows(); j0 += c) {
      for (int i0 = 0; i0 + 1 < field.columns(); i0 += c) {
        Chunk ch;
        ch.i0 = i0;
        ch.j0 = j0;
        ch.i1 = std::min(i0 + c, field.columns() - 1);
        ch.j1 = std::min(j0 + c, field.rows() - 1);
        ch.first_vertex = vertex_count;
        ch.first_index = indices.size();
        const auto w = static_cast<std::uint32_t>(ch.i1 - ch.i0 + 1);
        for (int j = 0; j < ch.j1 - ch.j0; ++j) {
          for (int i = 0; i < ch.i1 - ch.i0; ++i) {
            const auto v = static_cast<std::uint32_t>(j) * w + static_cast<std::uint32_t>(i);
            // Counter-clockwise seen from above (+y); indices are chunk-local (base vertex).
            indices.insert(indices.end(), {v, v + w, v + 1, v + 1, v + w, v + w + 1});
          }
        }
        ch.index_count = indices.size() - ch.first_index;
        vertex_count += static_cast<std::size_t>(w) * static_cast<std::size_t>(ch.j1 - ch.j0 + 1);
        g->chunks_.push_back(ch);
      }
    }
    g->vertices_ = render::Buffer::immutable(vertex_count * sizeof(GroundVertex), nullptr, true);
    g->indices_ = render::Buffer::immutable(std::span<const std::uint32_t>(indices));
    g->vao_ = render::VertexArray::create();
    g->vao_.attribute(0, 0, 3, GL_FLOAT, offsetof(GroundVertex, position));
    g->vao_.attribute(1, 0, 3, GL_FLOAT, offsetof(GroundVertex, normal));
    g->vao_.vertex_buffer(0, g->vertices_, sizeof(GroundVertex));
    g->vao_.index_buffer(g->indices_);
    for (Chunk& ch : g->chunks_) g->upload(ch);
    g->chunks_rebuilt_ = 0;  // the first upload is not a rebuild
    g->visible_.assign(g->chunks_.size(), 1);
    return g;
  }

  void update(const render::FrameContext& frame) override {
    if (debug_ && debug_->freeze_culling) return;
    const render::Frustum frustum = frame.camera.frustum();
    visible_count_ = 0;
    for (std::size_t k = 0; k < chunks_.size(); ++k) {
      visible_[k] = frustum.intersects(chunks_[k].bounds) ? 1 : 0;
      visible_count_ += visible_[k];
    }
  }

  void draw(render::Pass pass, const render::FrameContext& frame, render::PassStats& stats) override {
    if (pass == render::Pass::kShadow) {
      draw_shadow(stats);
      return;
    }
    if (pass != render::Pass::kOpaque) return;
    const float lo = field_->min_height(), hi = field_->max_height();
    program_.use();
    program_.set("u_view_projection", frame.camera.view_projection());
    program_.set("u_model", frame.camera.relative_model(glm::dvec3(field_->origin().x, 0.0, field_->origin().y)));
    program_.set("u_origin_height", 0.0f);
    program_.set("u_snow_line", snow_line(lo, hi, settings_->snow_fraction));
    vao_.bind();
    glEnable(GL_CULL_FACE);
    const bool tint = debug_ && debug_->lod_colors;
    program_.set("u_tint", glm::vec3(1.0f));
    for (std::size_t k = 0; k < chunks_.size(); ++k) {
      if (!visible_[k]) continue;
      const Chunk& ch = chunks_[k];
      if (tint) program_.set("u_tint", chunk_color(k));
      glDrawElementsBaseVertex(GL_TRIANGLES, static_cast<GLsizei>(ch.index_count), GL_UNSIGNED_INT,
                               reinterpret_cast<const void*>(ch.first_index * sizeof(std::uint32_t)),
                               static_cast<GLint>(ch.first_vertex));
      stats.draw_calls += 1;
      stats.triangles += ch.index_count / 3;
    }
    stats.instances += 1;
    glDisable(GL_CULL_FACE);
  }

  // Casts into the cascade ShadowMaps is rendering (if any): every chunk in the light's frustum.
  void draw_shadow(render::PassStats& stats) {
    const render::ShadowCasterContext* c = render::active_shadow_cascade();
    if (!c || !c->camera) return;
    if (!depth_) {
      auto program = render::Program::create({"scene/ground.vert", "scene/depth.frag"});
      if (!program.ok()) {
        log_warn("ground: no shadow casting: {}", program.error().message);
        return;
      }
      depth_ = std::move(*program);
    }
    depth_.use();
    depth_.set("u_view_projection", c->relative_view_projection);
    depth_.set("u_model", c->camera->relative_model(glm::dvec3(field_->origin().x, 0.0, field_->origin().y)));
    vao_.bind();
    for (const Chunk& ch : chunks_) {
      if (!c->light_frustum.intersects(ch.bounds)) continue;
      glDrawElementsBaseVertex(GL_TRIANGLES, static_cast<GLsizei>(ch.index_count), GL_UNSIGNED_INT,
                               reinterpret_cast<const void*>(ch.first_index * sizeof(std::uint32_t)),
                               static_cast<GLint>(ch.first_vertex));
      stats.draw_calls += 1;
      stats.triangles += ch.index_count / 3;
    }
  }

  // Re-uploads every chunk whose samples (or normals) lie in the area.
  void on_region_changed(const render::WorldRect& area) override {
    for (Chunk& ch : chunks_) {
      const glm::dvec2 a = field_->origin() + glm::dvec2(ch.i0, ch.j0) * field_->spacing();
      const glm::dvec2 b = field_->origin() + glm::dvec2(ch.i1, ch.j1) * field_->spacing();
      if (b.x < area.min.x || a.x > area.max.x || b.y < area.min.y || a.y > area.max.y) continue;
      upload(ch);
    }
  }

  std::size_t chunk_count() const { return chunks_.size(); }
  std::size_t visible_count() const { return visible_count_; }
  std::uint64_t chunks_rebuilt() const { return chunks_rebuilt_; }
  std::size_t triangle_count() const { return indices_.size() / sizeof(std::uint32_t) / 3; }
  std::vector<render::Aabb> bounds() const {
    std::vector<render::Aabb> out;
    for (const Chunk& ch : chunks_) out.push_back(ch.bounds);
    return out;
  }

 private:
  GroundDrawable() = default;

  static glm::vec3 chunk_color(std::size_t k) {
    static const glm::vec3 palette[] = {{1.6f, 0.6f, 0.6f}, {0.6f, 1.6f, 0.6f}, {0.6f, 0.6f, 1.8f},
                                        {1.6f, 1.5f, 0.5f}, {0.5f, 1.5f, 1.6f}, {1.5f, 0.6f, 1.6f}};
    return palette[k % 6];
  }

  void upload(Chunk& ch) {
    const HeightField& f = *field_;
    std::vector<GroundVertex> vertices;
    vertices.reserve(static_cast<std::size_t>(ch.i1 - ch.i0 + 1) * static_cast<std::size_t>(ch.j1 - ch.j0 + 1));
    float lo = f.sample(ch.i0, ch.j0), hi = lo;
    for (int j = ch.j0; j <= ch.j1; ++j) {
      for (int i = ch.i0; i <= ch.i1; ++i) {
        const float h = f.sample(i, j);
        lo = std::min(lo, h);
        hi = std::max(hi, h);
        vertices.push_back({glm::vec3(static_cast<float>(i * f.spacing()), h, static_cast<float>(j * f.spacing())),
                            f.sample_normal(i, j)});
      }
    }
    vertices_.update(std::span<const GroundVertex>(vertices), ch.first_vertex * sizeof(GroundVertex));
    const glm::dvec2 a = f.origin() + glm::dvec2(ch.i0, ch.j0) * f.spacing();
    const glm::dvec2 b = f.origin() + glm::dvec2(ch.i1, ch.j1) * f.spacing();
    ch.bounds = {{a.x, lo, a.y}, {b.x, hi, b.y}};
    ++chunks_rebuilt_;
  }

  render::Program program_;
  render::Program depth_;  // built on the first shadow pass
  render::Buffer vertices_;
  render::Buffer indices_;
  render::VertexArray vao_;
  std::vector<Chunk> chunks_;
  std::vector<unsigned char> visible_;
  std::size_t visible_count_ = 0;
  std::uint64_t chunks_rebuilt_ = 0;
  const HeightField* field_ = nullptr;
  const GroundModuleSettings* settings_ = nullptr;
  const DebugView* debug_ = nullptr;
};

using Settings = SettingsOf<GroundModuleSettings>;

// The plain ground draws every sample (no LOD), so its GPU buffers grow with the map's area: a
// 16384^2 map would ask for ~13 GB and leave the frame without ground. Refuse before allocating;
// the terrain module is the level-of-detail path for large maps.
constexpr std::uint64_t kMaxGroundGpuBytes = 1024ull << 20;

std::uint64_t ground_gpu_bytes(int columns, int rows) {
  const auto samples = static_cast<std::uint64_t>(columns) * static_cast<std::uint64_t>(rows);
  const auto quads = static_cast<std::uint64_t>(std::max(columns - 1, 0)) * static_cast<std::uint64_t>(std::max(rows - 1, 0));
  return samples * sizeof(GroundVertex) + quads * 6 * sizeof(std::uint32_t);
}

class GroundInstance final : public ModuleInstance {
 public:
  static Result<std::unique_ptr<ModuleInstance>> create(const ModuleBuildContext& ctx) {
    if (!ctx.ground) {
      return make_error(ErrorCode::kInvalidArgument, "ground: the scene built no ground height field for this module");
    }
    auto inst = std::unique_ptr<GroundInstance>(new GroundInstance(ctx));
    SYLVA_TRY(inst->build());
    return std::unique_ptr<ModuleInstance>(std::move(inst));
  }

  std::vector<render::Drawable*> drawables() override { return {drawable_.get()}; }

  Status rebuild(Rebuild what) override {
    if (what == Rebuild::kNone) return {};
    return build();
  }

  Status on_map_changed(const std::string& map_id, const WorldArea& area) override {
    (void)map_id;  // the ground map is the only one this module reads
    drawable_->on_region_changed({area.min, area.max});
    return {};
  }

  nlohmann::json stats() const override {
    return {{"chunks", drawable_->chunk_count()},
            {"chunks_visible", drawable_->visible_count()},
            {"chunks_rebuilt", drawable_->chunks_rebuilt()},
            {"triangles", drawable_->triangle_count()},
            {"samples", {ctx_.ground->columns(), ctx_.ground->rows()}}};
  }

  std::vector<render::Aabb> debug_bounds() const override { return drawable_->bounds(); }

 private:
  explicit GroundInstance(const ModuleBuildContext& ctx) : ModuleInstance("ground"), ctx_(ctx) {}

  const GroundModuleSettings& settings() const {
    return static_cast<const Settings&>(*ctx_.section->settings).value;
  }

  Status build() {
    const HeightField& field = *ctx_.ground;
    const std::uint64_t bytes = ground_gpu_bytes(field.columns(), field.rows());
    if (bytes > kMaxGroundGpuBytes) {
      const auto map = ctx_.section->maps.find("height");
      const std::string& raster = settings().source.elevation.file;
      const std::string& control = settings().source.control.file;
      const std::string source = map != ctx_.section->maps.end() ? "the height map " + map->second
                                 : !control.empty() ? "the control texture " + control
                                 : !raster.empty() ? "the elevation raster " + raster
                                                   : fmt::format("the generated ground (ground.resolution = {})", field.columns());
      return make_error(ErrorCode::kLimit,
                        fmt::format("ground: {} has {}x{} samples; the plain ground draws every sample and would need {} "
                                    "MiB of GPU buffers, above its limit of {} MiB. Use a terrain section (level of "
                                    "detail) for maps this large, or resample the map to at most 4097x4097",
                                    source, field.columns(), field.rows(), bytes >> 20, kMaxGroundGpuBytes >> 20));
    }
    auto d = GroundDrawable::create(*ctx_.ground, settings().chunk_quads, &settings(), ctx_.debug);
    if (!d.ok()) return make_error(d.error().code, "ground: " + d.error().message);
    drawable_ = std::move(*d);
    return {};
  }

  ModuleBuildContext ctx_;
  std::unique_ptr<GroundDrawable> drawable_;
};

}  // namespace

ModuleDescriptor ground_module() {
  ModuleDescriptor d;
  d.name = "ground";
  d.description = "plain height-field mesh (built in; the ground when the terrain module is not used)";
  d.provides_ground = true;
  d.make_settings = [] {
    return std::make_unique<Settings>(std::vector<MapSlot>{{"height", MapKind::kHeight, "Ground height in metres"}});
  };
  d.height_source = [](const ModuleSettings& s) { return static_cast<const Settings&>(s).value.source; };
  d.create = &GroundInstance::create;
  return d;
}

}  // namespace sylva::scene::detail
