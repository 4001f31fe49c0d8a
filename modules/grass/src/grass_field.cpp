#include <sylva/grass/grass_field.hpp>

#include <sylva/core/assert.hpp>
#include <sylva/core/log.hpp>
#include <sylva/render/frame_context.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstring>

namespace sylva::render::embedded {
void register_grass_shaders();
}  // namespace sylva::render::embedded

namespace sylva::grass {

namespace {

// Layout of the Command block of cull.comp (std430, 12 uints).
struct CommandBlock {
  std::uint32_t draw_count;
  std::uint32_t instance_count;
  std::uint32_t first_vertex;
  std::uint32_t base_instance;
  std::uint32_t considered;
  std::uint32_t culled_density;
  std::uint32_t culled_distance;
  std::uint32_t culled_frustum;
  std::uint32_t culled_orientation;
  std::uint32_t segments;
  std::uint32_t capacity;
  std::uint32_t overflow;
};
static_assert(sizeof(CommandBlock) == 48);

constexpr GLuint kBladesBinding = 0;
constexpr GLuint kVisibleBinding = 1;
constexpr GLuint kJobsBinding = 2;
constexpr GLuint kCommandBinding = 3;
constexpr GLuint kSpheresBinding = 4;
constexpr GLuint kWindUboBinding = 1;

}  // namespace

Result<GrassField> GrassField::create(BladeSet blades, const GrassRenderSettings& settings) {
  render::embedded::register_render_shaders();  // render/lib/*.glsl (wind, lighting, fog)
  render::embedded::register_grass_shaders();
  GLint64 max_block = 0;
  glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &max_block);
  const std::size_t bytes = std::max<std::size_t>(blades.blades.size(), 1) * sizeof(Blade);
  if (max_block > 0 && bytes > static_cast<std::size_t>(max_block)) {
    return make_error(ErrorCode::kLimit,
                      fmt::format("grass: {} blades need {} MB of storage buffer, the GL limit is {} MB "
                                  "(GL_MAX_SHADER_STORAGE_BLOCK_SIZE); lower grass.field.density or split the field",
                                  blades.blades.size(), bytes >> 20, max_block >> 20));
  }

  GrassField f;
  f.settings_ = settings;
  f.origin_ = blades.origin;
  f.tiles_ = std::move(blades.tiles);
  f.tile_sim_time_.assign(f.tiles_.size(), -1.0);
  f.blade_count_ = blades.blades.size();
  f.max_height_ = blades.max_height;

  auto physics = render::Program::create({"grass/physics.comp"});
  if (!physics) return physics.error();
  auto cull = render::Program::create({"grass/cull.comp"});
  if (!cull) return cull.error();
  auto draw = render::Program::create({"grass/blade.vert", "grass/blade.tesc", "grass/blade.tese", "grass/blade.frag"});
  if (!draw) return draw.error();
  f.physics_ = std::move(*physics);
  f.cull_ = std::move(*cull);
  f.draw_ = std::move(*draw);

  if (blades.blades.empty()) blades.blades.push_back(Blade{});  // GL wants non-empty buffers
  f.blades_ = render::Buffer::immutable(std::span<const Blade>(blades.blades), true);
  f.visible_ = render::Buffer::immutable(std::max<std::size_t>(f.blade_count_, 1) * sizeof(std::uint32_t), nullptr);
  f.jobs_ = render::Buffer::dynamic(std::max<std::size_t>(f.tiles_.size(), 1) * sizeof(TileJob));
  f.command_ = render::Buffer::immutable(sizeof(CommandBlock), nullptr, true);
  f.spheres_ = render::Buffer::immutable(kMaxColliders * sizeof(glm::vec4), nullptr, true);
  f.wind_ = render::Buffer::immutable(sizeof(WindGpuParams), nullptr, true);
  f.vao_ = render::VertexArray::create();
  f.sim_query_ = render::PassQuery::create(false);
  f.cull_query_ = render::PassQuery::create(false);
  f.draw_query_ = render::PassQuery::create(true);
  {
    // Blades go to the GPU; free the CPU copy now rather than at the end of the caller's scope.
    std::vector<Blade> drop;
    drop.swap(blades.blades);
  }
  return f;
}

void GrassField::set_colliders(std::span<const glm::dvec3> centers, std::span<const float> radii) {
  SYLVA_ASSERT(centers.size() == radii.size(), "centers={} radii={}", centers.size(), radii.size());
  std::vector<glm::vec4> local;
  for (std::size_t i = 0; i < centers.size() && i < kMaxColliders; ++i) {
    local.emplace_back(glm::vec3(centers[i] - origin_), radii[i]);
  }
  if (centers.size() > kMaxColliders) log_warn("grass: {} colliders given, only the first {} are used", centers.size(), kMaxColliders);
  sphere_count_ = static_cast<int>(local.size());
  if (!local.empty()) spheres_.update(std::span<const glm::vec4>(local));
}

void GrassField::update(const render::FrameContext& frame) {
  update(frame.camera, frame.viewport, frame.time, frame.dt, frame.wind);
}

void GrassField::set_cull_uniforms(const render::Program& p, const CullView& view) const {
  const CullSettings& c = settings_.cull;
  p.set("u_camera", view.camera);
  p.set("u_ppr", view.pixels_per_radian);
  p.set("u_thinning", glm::vec4(c.thinning_start, c.near_distance, c.thinning_min_keep, c.distance_thinning ? 1.0f : 0.0f));
  p.set("u_cull", glm::vec4(c.density_scale, c.width_compensation, c.frustum ? 1.0f : 0.0f, c.orientation ? 1.0f : 0.0f));
  p.set("u_tess", glm::vec2(c.max_tess_level, c.pixels_per_segment));
}

void GrassField::update(const render::Camera& camera, glm::ivec2 viewport, double time, float dt, const WindField& wind) {
  ++frame_;
  const CullSettings& cs = settings_.cull;
  // Cull view in blade-set local coordinates: VP * translate(origin - camera).
  const glm::mat4 vp_local = camera.view_projection() * camera.relative_model(origin_);
  camera_local_ = glm::vec3(camera.position() - origin_);
  const float height_px = static_cast<float>(std::max(viewport.y, 1));
  view_ = make_cull_view(vp_local, camera_local_, camera.forward(), height_px, camera.perspective().fov_y);
  ppr_ = view_.pixels_per_radian;

  // Tiles: frustum + near_distance on the CPU.
  std::vector<TileJob> jobs;
  jobs.reserve(tiles_.size());
  blades_in_culled_tiles_ = 0;
  const bool sane_time = std::isfinite(time);
  for (std::size_t i = 0; i < tiles_.size(); ++i) {
    const GrassTile& t = tiles_[i];
    if (t.count == 0) continue;
    if (!tile_visible(t, view_, cs)) {
      blades_in_culled_tiles_ += t.count;
      continue;
    }
    float tile_dt = dt;
    if (sane_time) {
      // A tile that was out of view catches up in one (stable) step.
      if (tile_sim_time_[i] >= 0.0 && time >= tile_sim_time_[i]) tile_dt = static_cast<float>(time - tile_sim_time_[i]);
      tile_sim_time_[i] = time;
    }
    jobs.push_back({t.first, t.count, tile_dt, settings_.simulate ? 1u : 0u});
  }
  job_count_ = jobs.size();

  CommandBlock reset{};
  reset.instance_count = 1;
  reset.capacity = static_cast<std::uint32_t>(blade_count_);
  command_.update(0, sizeof(reset), &reset);
  if (jobs.empty()) return;
  jobs_.upload(std::span<const TileJob>(jobs));

  blades_.bind_base(GL_SHADER_STORAGE_BUFFER, kBladesBinding);
  visible_.bind_base(GL_SHADER_STORAGE_BUFFER, kVisibleBinding);
  jobs_.bind_base(GL_SHADER_STORAGE_BUFFER, kJobsBinding);
  command_.bind_base(GL_SHADER_STORAGE_BUFFER, kCommandBinding);
  spheres_.bind_base(GL_SHADER_STORAGE_BUFFER, kSpheresBinding);

  if (settings_.simulate) {
    const WindFrame wf = wind.frame(sane_time ? time : 0.0, origin_);
    wind_.update(0, sizeof(WindGpuParams), &wf.gpu);
    wind_.bind_base(GL_UNIFORM_BUFFER, kWindUboBinding);
    const PhysicsSettings& ps = settings_.physics;
    physics_.set("u_physics", glm::vec4(ps.gravity, ps.front_gravity, ps.wind_response, ps.collision_recovery));
    physics_.set("u_substep", glm::vec2(ps.max_substep, static_cast<float>(ps.max_substeps)));
    physics_.set("u_sphere_count", sphere_count_);
    physics_.set("u_wind_offset", glm::vec3(0.0f));
    sim_query_.begin(frame_);
    physics_.use();
    glDispatchCompute(static_cast<GLuint>(jobs.size()), 1, 1);
    sim_query_.end();
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  }

  set_cull_uniforms(cull_, view_);
  for (int i = 0; i < 4; ++i) cull_.set(fmt::format("u_planes[{}]", i), view_.planes[i]);
  cull_.set("u_forward", view_.forward);
  cull_.set("u_orientation", glm::vec2(cs.orientation_threshold, cs.orientation_max_px));
  cull_query_.begin(frame_);
  cull_.use();
  glDispatchCompute(static_cast<GLuint>(jobs.size()), 1, 1);
  cull_query_.end();
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
}

void GrassField::draw(render::Pass pass, const render::FrameContext& frame, render::PassStats& stats) {
  if (pass != render::Pass::kOpaque) return;
  draw_blades(frame.camera, &stats);
}

void GrassField::draw_blades(const render::Camera& camera, render::PassStats* stats) {
  if (job_count_ == 0) return;
  draw_.set("u_view_proj", camera.view_projection());
  draw_.set("u_origin_rel", glm::vec3(origin_ - camera.position()));
  draw_.set("u_shape", static_cast<int>(settings_.shape));
  draw_.set("u_base_color", settings_.base_color);
  draw_.set("u_tip_color", settings_.tip_color);
  const ShadingSettings& sh = settings_.shading;
  draw_.set("u_shading", glm::vec4(sh.translucency, sh.ambient, sh.root_occlusion, sh.specular));
  set_cull_uniforms(draw_, view_);

  blades_.bind_base(GL_SHADER_STORAGE_BUFFER, kBladesBinding);
  visible_.bind_base(GL_SHADER_STORAGE_BUFFER, kVisibleBinding);
  command_.bind(GL_DRAW_INDIRECT_BUFFER);
  vao_.bind();
  draw_.use();
  glPatchParameteri(GL_PATCH_VERTICES, 1);
  draw_query_.begin(frame_);
  glDrawArraysIndirect(GL_PATCHES, nullptr);
  draw_query_.end();
  glBindVertexArray(0);
  if (stats) stats->draw_calls += 1;
}

std::vector<Blade> GrassField::read_blades() const {
  std::vector<Blade> out(blade_count_);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  if (!out.empty()) blades_.read(0, out.size() * sizeof(Blade), out.data());
  return out;
}

GrassFrameStats GrassField::read_frame_stats() const {
  GrassFrameStats s;
  s.blades_total = blade_count_;
  s.tiles_total = tiles_.size();
  s.tiles_visible = job_count_;
  s.blades_in_culled_tiles = blades_in_culled_tiles_;
  CommandBlock c{};
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  command_.read(0, sizeof(c), &c);
  s.counts.considered = c.considered;
  s.counts.visible = std::min<std::uint64_t>(c.draw_count, c.capacity);
  s.counts.density = c.culled_density;
  s.counts.distance = c.culled_distance;
  s.counts.frustum = c.culled_frustum;
  s.counts.orientation = c.culled_orientation;
  s.counts.segments = c.segments;
  s.overflow = c.overflow;
  return s;
}

std::optional<GrassField::GpuTimes> GrassField::gpu_times(bool wait) {
  auto d = wait ? draw_query_.wait_all() : draw_query_.poll();
  if (!d) return std::nullopt;
  GpuTimes t;
  t.draw_ms = d->gpu_ms;
  t.primitives = d->primitives;
  if (auto c = wait ? cull_query_.wait_all() : cull_query_.poll()) t.cull_ms = c->gpu_ms;
  if (auto p = wait ? sim_query_.wait_all() : sim_query_.poll()) t.simulate_ms = p->gpu_ms;
  return t;
}

}  // namespace sylva::grass
