#include "with_terrain/terrain_target.hpp"

#include "frame_finish.hpp"

#include <sylva/core/params_json.hpp>
#include <sylva/core/timer.hpp>
#include <sylva/render/buffer.hpp>
#include <sylva/render/camera.hpp>
#include <sylva/render/lighting.hpp>
#include <sylva/render/lighting_uniforms.hpp>
#include <sylva/render/queries.hpp>
#include <sylva/render/shader_library.hpp>
#include <sylva/render/sky.hpp>
#include <sylva/render/texture.hpp>
#include <sylva/render/vertex_array.hpp>
#include <sylva/terrain/chunk_tree.hpp>
#include <sylva/terrain/frame_mesh.hpp>
#include <sylva/terrain/height_source.hpp>
#include <sylva/terrain/lod_view.hpp>
#include <sylva/terrain/seams.hpp>
#include <sylva/terrain/selection.hpp>
#include <sylva/terrain/settings.hpp>
#include <sylva/terrain/vertex_position.hpp>

#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <map>
#include <mutex>

namespace sylva::render::embedded {
void register_bench_shaders();  // generated from apps/bench/shaders
}  // namespace sylva::render::embedded

namespace sylva::bench {
namespace {

struct BenchTerrainSettings {
  terrain::GeneratedFieldSettings field{.size = 1025, .rows = 0, .spacing = 4.0, .height_scale = 900.0f,
                                        .height_offset = 0.0f, .feature_size = 2400.0f,
                                        .noise = terrain::FieldNoise::kFbm,
                                        .fbm = {.octaves = 9, .persistence = 0.5f, .lacunarity = 2.0f,
                                                .frequency = 1.0f, .seed = 21, .ridge_gain = 2.0f}};
  terrain::ChunkTreeSettings tree;
  terrain::LodSettings lod;

  template <class V>
  void visit(V& v) {
    v(field, "field");
    v(tree, "tree");
    v(lod, "lod");
  }
};

struct TerrainTargetSettings {
  BenchTerrainSettings terrain;
  render::Lighting lighting;

  template <class V>
  void visit(V& v) {
    v(terrain, "terrain");
    v(lighting, "lighting");
  }
};

// A built field and tree, shared by every setting with the same field and tree settings (a tau
// sweep builds once).
struct BuiltTerrain {
  HeightField field;
  terrain::ChunkTree tree;
  double build_ms = 0.0;
};

Result<std::shared_ptr<const BuiltTerrain>> built_terrain(const BenchTerrainSettings& s) {
  static std::mutex mutex;
  static std::map<std::string, std::shared_ptr<const BuiltTerrain>> cache;
  const std::string key = params_to_json(s.field).dump() + params_to_json(s.tree).dump();
  std::lock_guard<std::mutex> lock(mutex);
  if (auto it = cache.find(key); it != cache.end()) return it->second;
  Stopwatch watch;
  auto field = terrain::generate_height_field(s.field);
  if (!field.ok()) return field.error();
  auto tree = terrain::ChunkTree::build(*field, s.tree);
  if (!tree.ok()) return tree.error();
  auto built = std::make_shared<BuiltTerrain>(BuiltTerrain{std::move(*field), std::move(*tree), watch.elapsed_ms()});
  if (cache.size() >= 2) cache.clear();
  cache.emplace(key, built);
  return std::shared_ptr<const BuiltTerrain>(built);
}

struct PathSpec {
  const char* name;
  const char* description;
};
constexpr PathSpec kPaths[] = {
    {"flight", "diagonal flight 60-120 m above the highest peak, horizon in view: distant chunks coarsen"},
    {"descent", "from 1.5 km above the field down to the ridges, looking at the centre"},
    {"grazing", "just above the peaks looking along the ground: silhouettes against the sky"},
};

class TerrainTarget final : public BenchTarget {
 public:
  std::vector<ParamDescriptor> params() override { return describe_params(settings_); }

  Status prepare(glm::ivec2 size) override {
    SYLVA_TRY(validate_params(settings_));
    size_ = size;
    auto built = built_terrain(settings_.terrain);
    if (!built.ok()) return built.error();
    built_ = *built;
    selector_ = std::make_unique<terrain::LodSelector>(built_->tree);

    render::embedded::register_render_shaders();
    render::embedded::register_bench_shaders();
    auto program = render::Program::create({"bench/terrain.vert", "bench/terrain.frag"});
    if (!program.ok()) return program.error();
    program_ = std::move(*program);
    auto sky = render::SkyRenderer::create();
    if (!sky.ok()) return sky.error();
    sky_ = std::move(*sky);
    lighting_uniforms_ = render::LightingUniforms::create();

    const HeightField& f = built_->field;
    Image normals(f.columns(), f.rows(), 3);
    for (int j = 0; j < f.rows(); ++j) {
      for (int i = 0; i < f.columns(); ++i) {
        const glm::vec3 n = f.sample_normal(i, j);
        for (int c = 0; c < 3; ++c) normals.at(i, f.rows() - 1 - j, c) = n[c];  // GL row j = sample row j
      }
    }
    auto tex = render::Texture::from_image(normals, {.encoding = render::TextureEncoding::kFloat32, .mipmaps = true,
                                                     .min_filter = GL_LINEAR_MIPMAP_LINEAR, .mag_filter = GL_LINEAR,
                                                     .wrap = GL_CLAMP_TO_EDGE});
    if (!tex.ok()) return tex.error();
    normals_ = std::move(*tex);
    vertices_ = render::Buffer::dynamic(1 << 20);
    vao_ = render::VertexArray::create();
    vao_.attribute(0, 0, 3, GL_FLOAT, 0);
    vao_.vertex_buffer(0, vertices_, sizeof(glm::vec3));
    return {};
  }

  std::vector<CameraPathInfo> camera_paths() const override {
    std::vector<CameraPathInfo> out;
    for (const PathSpec& p : kPaths) out.push_back({p.name, p.description});
    return out;
  }

  Result<CameraPose> camera_pose(const std::string& name, int frame, int frames) override {
    if (!built_) return make_error(ErrorCode::kInvalidArgument, "camera_pose() before prepare()");
    const HeightField& f = built_->field;
    const glm::dvec2 o = f.origin();
    const glm::dvec2 e = f.extent();
    const double top = f.max_height();
    auto at = [&](double fx, double dy, double fz) { return glm::dvec3(o.x + fx * e.x, top + dy, o.y + fz * e.y); };
    CameraPath path{name, "", {}};
    if (name == "flight") {
      path.keys = {{at(0.08, 120, 0.92), -45.0f, -9.0f, 60.0f},
                   {at(0.35, 80, 0.62), -50.0f, -7.0f, 60.0f},
                   {at(0.62, 60, 0.38), -40.0f, -8.0f, 60.0f},
                   {at(0.9, 100, 0.1), -45.0f, -10.0f, 60.0f}};
    } else if (name == "descent") {
      path.keys = {{at(0.5, 1500, 1.1), 0.0f, -38.0f, 60.0f},
                   {at(0.5, 600, 0.85), 0.0f, -22.0f, 60.0f},
                   {at(0.5, 40, 0.68), 0.0f, -6.0f, 60.0f}};
    } else if (name == "grazing") {
      path.keys = {{at(0.05, 15, 0.5), -90.0f, -1.0f, 50.0f},
                   {at(0.5, 10, 0.45), -80.0f, 0.0f, 50.0f},
                   {at(0.95, 15, 0.5), -100.0f, -1.0f, 50.0f}};
    } else {
      return make_error(ErrorCode::kNotFound, fmt::format("builtin:terrain has no camera path \"{}\" (flight, descent, "
                                                          "grazing)", name));
    }
    return path.frame(frame, frames);
  }

  Status render(const FrameInput& input, const render::Framebuffer& target, FrameOutput& out) override {
    Stopwatch cpu;
    render::Camera camera;
    camera.set_position(input.pose.position);
    camera.set_yaw_pitch(glm::radians(input.pose.yaw_deg), glm::radians(input.pose.pitch_deg));
    camera.perspective().fov_y = glm::radians(input.pose.fov_deg);
    camera.perspective().near_plane = 0.5f;
    camera.set_aspect(size_.x, size_.y);
    const terrain::LodSettings& lod = settings_.terrain.lod;
    const terrain::LodView view = terrain::LodView::perspective(
        camera.position(), glm::dvec3(camera.forward()), glm::dvec3(camera.up()), camera.perspective().fov_y, size_.x,
        size_.y, camera.perspective().near_plane, std::numeric_limits<double>::infinity());
    const terrain::ChunkTree& tree = built_->tree;
    const terrain::Selection& selection = selector_->select(view, lod);
    const terrain::VertexFrame frame = terrain::make_vertex_frame(tree, view, lod);
    const terrain::FrameMesh mesh = terrain::assemble_frame(tree, selection, frame, lod.crack_fix, seams_);

    // The screen-space error actually drawn: the measured delta of each drawn chunk projected from
    // the nearest point of its box (Ulrich's bound, with D - delta as in the selection).
    double max_rho = 0.0;
    for (const terrain::SelectedChunk& s : selection.chunks) {
      const terrain::Chunk& c = tree.chunk(s.index);
      if (c.error <= 0.0f) continue;
      glm::dvec3 lo, hi;
      tree.chunk_bounds(s.index, lo, hi);
      const double d = view.distance_to_box(lo, hi) - c.error;
      max_rho = std::max(max_rho, d > 1e-3 ? view.k * c.error / d : 1.0e4);
    }
    max_rho = std::min(max_rho, 1.0e4);

    const render::Lighting& lighting = settings_.lighting;
    profiler_.begin_frame();
    lighting_uniforms_.update(lighting, camera.position().y, input.time);
    lighting_uniforms_.bind();
    target.bind();
    render::apply_reversed_z_state();
    target.clear(glm::vec4(lighting.fog_color, 1.0f), 0.0f);
    profiler_.begin("opaque");
    if (!mesh.positions.empty()) {
      vertices_.upload(std::span<const glm::vec3>(mesh.positions));
      vao_.vertex_buffer(0, vertices_, sizeof(glm::vec3));
      program_.use();
      program_.set("u_view_projection", camera.view_projection());
      const glm::dvec2 o = built_->field.origin();
      program_.set("u_camera_field", glm::vec3(static_cast<float>(camera.position().x - o.x),
                                               static_cast<float>(camera.position().y),
                                               static_cast<float>(camera.position().z - o.y)));
      program_.set("u_field_size", glm::vec2(built_->field.columns(), built_->field.rows()));
      program_.set("u_spacing", static_cast<float>(built_->field.spacing()));
      program_.set("u_height_range", glm::vec2(built_->field.min_height(), built_->field.max_height()));
      program_.set("u_normals", 0);
      normals_.bind(0);
      vao_.bind();
      glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(mesh.positions.size()));
    }
    profiler_.end("opaque");
    profiler_.add_cpu_counts("opaque", render::PassStats{.triangles = mesh.triangles(),
                                                         .draw_calls = mesh.positions.empty() ? 0u : 1u,
                                                         .instances = selection.stats.chunks});
    SYLVA_TRY(finish_sky_frame(profiler_, sky_, camera, lighting, input.time, cpu, "builtin:terrain", out));
    for (std::size_t level = 0; level < selection.stats.chunks_per_level.size(); ++level) {
      out.counts.lod_instances[fmt::format("terrain.level{}", level)] = selection.stats.chunks_per_level[level];
    }
    out.metrics["terrain.max_projected_error_px"] = max_rho;
    out.metrics["terrain.selection_ms"] = selection.stats.cpu_ms;
    out.metrics["terrain.chunks"] = selection.stats.chunks;
    out.metrics["terrain.max_level_difference"] = selection.stats.max_level_difference;
    out.metrics["terrain.tree_build_ms"] = built_->build_ms;
    return {};
  }

  std::vector<std::string> modules() const override { return {"terrain"}; }

 private:
  TerrainTargetSettings settings_;
  std::shared_ptr<const BuiltTerrain> built_;
  std::unique_ptr<terrain::LodSelector> selector_;
  terrain::SeamCache seams_;
  render::Program program_;
  render::SkyRenderer sky_;
  render::LightingUniforms lighting_uniforms_;
  render::Texture normals_;
  render::Buffer vertices_;
  render::VertexArray vao_;
  render::FrameProfiler profiler_;
  glm::ivec2 size_{256, 144};
};

}  // namespace

std::unique_ptr<BenchTarget> make_terrain_target() { return std::make_unique<TerrainTarget>(); }

}  // namespace sylva::bench
