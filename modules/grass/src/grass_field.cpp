#include <sylva/grass/grass_field.hpp>

#include "shadow_binding.hpp"

#include <sylva/core/assert.hpp>
#include <sylva/core/log.hpp>
#include <sylva/grass/field_color.hpp>
#include <sylva/render/frame_context.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <utility>

namespace sylva::render::embedded {
void register_grass_shaders();
}  // namespace sylva::render::embedded

namespace sylva::grass {

namespace {

// Layout of the Command block of cull.comp (std430, 12 uints).
struct CommandBlock {  // GRASS_COMMAND_MEMBERS of shaders/blade.glsl
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

// DrawArraysIndirectCommand, as draw_batches.comp writes it.
struct DrawCommand {
  std::uint32_t count, instance_count, first, base_instance;
};
static_assert(sizeof(DrawCommand) == 16);

constexpr GLuint kBladesBinding = 0;
constexpr GLuint kVisibleBinding = 1;
constexpr GLuint kJobsBinding = 2;
constexpr GLuint kCommandBinding = 3;
constexpr GLuint kSpheresBinding = 4;
constexpr GLuint kBatchesBinding = 6;
constexpr GLuint kWindUboBinding = 1;

// The blade colour and depth programs for one cull.tess_spacing: the spacing is a layout
// qualifier of blade.tese, so each spacing is its own program (GRASS_TESS_SPACING; none for
// equal, so the default program is the one without defines).
Result<std::pair<render::Program, render::Program>> blade_programs(TessSpacing spacing) {
  render::ShaderDefines defines;
  if (spacing != TessSpacing::kEqual) defines.emplace_back("GRASS_TESS_SPACING", spacing == TessSpacing::kFractionalEven ? "1" : "2");
  auto draw = render::Program::create({"grass/blade.vert", "grass/blade.tesc", "grass/blade.tese", "grass/blade.frag"}, defines);
  if (!draw) return draw.error();
  auto depth = render::Program::create({"grass/blade.vert", "grass/blade.tesc", "grass/blade.tese", "grass/blade_depth.frag"}, defines);
  if (!depth) return depth.error();
  return std::pair<render::Program, render::Program>(std::move(*draw), std::move(*depth));
}

}  // namespace

Result<GrassField> GrassField::create(BladeSet blades, const GrassRenderSettings& settings,
                                     std::size_t max_blades_per_buffer) {
  render::embedded::register_render_shaders();  // render/lib/*.glsl (wind, lighting, fog, shadows)
  render::embedded::register_grass_shaders();
  GrassField f;
  f.settings_ = settings;
  f.max_blades_per_buffer_ = max_blades_per_buffer;
  auto physics = render::Program::create({"grass/physics.comp"});
  if (!physics) return physics.error();
  auto cull = render::Program::create({"grass/cull.comp"});
  if (!cull) return cull.error();
  auto blade = blade_programs(settings.cull.tess_spacing);
  if (!blade) return blade.error();
  auto batch = render::Program::create({"grass/draw_batches.comp"});
  if (!batch) return batch.error();
  f.physics_ = std::move(*physics);
  f.cull_ = std::move(*cull);
  f.draw_ = std::move(blade->first);
  f.depth_ = std::move(blade->second);
  f.blade_spacing_ = settings.cull.tess_spacing;
  f.batch_ = std::move(*batch);
  f.spheres_ = render::Buffer::immutable(kMaxColliders * sizeof(glm::vec4), nullptr, true);
  f.wind_ = render::Buffer::immutable(sizeof(WindGpuParams), nullptr, true);
  f.vao_ = render::VertexArray::create();
  f.sim_query_ = render::PassQuery::create(false);
  f.cull_query_ = render::PassQuery::create(false);
  f.draw_query_ = render::PassQuery::create(true);
  SYLVA_TRY(f.set_blades(blades));
  return f;
}

Status GrassField::set_blades(const BladeSet& blades) {
  GLint64 max_block = 0;
  glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &max_block);
  std::size_t per_chunk = max_block > 0 ? static_cast<std::size_t>(max_block) / sizeof(Blade) : kMaxBlades;
  if (max_blades_per_buffer_ > 0) per_chunk = std::min(per_chunk, max_blades_per_buffer_);
  per_chunk = std::max<std::size_t>(per_chunk, 1);

  // Tiles in blade order; they must not overlap and must lie inside the blade array.
  std::vector<std::uint32_t> order(blades.tiles.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<std::uint32_t>(i);
  std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return blades.tiles[a].first < blades.tiles[b].first; });
  std::uint64_t end_of_previous = 0;
  for (const std::uint32_t i : order) {
    const GrassTile& t = blades.tiles[i];
    const std::uint64_t end = std::uint64_t{t.first} + t.count;
    if (t.count > 0 && (t.first < end_of_previous || end > blades.blades.size())) {
      return make_error(ErrorCode::kInvalidArgument,
                        fmt::format("grass: tile {} holds blades [{}, {}) which overlap another tile or lie outside the "
                                    "{} blades of the set", i, t.first, end, blades.blades.size()));
    }
    if (t.count > per_chunk) {
      return make_error(ErrorCode::kLimit,
                        fmt::format("grass: tile {} holds {} blades, more than one storage buffer takes ({} blades, "
                                    "GL_MAX_SHADER_STORAGE_BLOCK_SIZE {} MB); lower grass.field.density or tile_size",
                                    i, t.count, per_chunk, max_block >> 20));
    }
    if (t.count > 0) end_of_previous = end;
  }

  origin_ = blades.origin;
  blade_count_ = blades.blades.size();
  max_height_ = blades.max_height;
  tile_sim_time_.assign(blades.tiles.size(), -1.0);
  tile_chunk_.assign(blades.tiles.size(), 0);
  chunks_.clear();

  // Chunks: greedy runs of whole tiles in blade order (blades between tiles ride along).
  struct Range {
    std::uint64_t first, end;
  };
  std::vector<Range> ranges;
  for (const std::uint32_t i : order) {
    const GrassTile& t = blades.tiles[i];
    if (t.count == 0) continue;
    if (ranges.empty() || std::uint64_t{t.first} + t.count - ranges.back().first > per_chunk) {
      ranges.push_back({t.first, std::uint64_t{t.first} + t.count});
    } else {
      ranges.back().end = std::uint64_t{t.first} + t.count;
    }
    tile_chunk_[i] = static_cast<std::uint32_t>(ranges.size() - 1);
  }
  if (ranges.empty()) ranges.push_back({0, 0});
  for (const Range& r : ranges) {
    Chunk c;
    c.first_blade = static_cast<std::uint32_t>(r.first);
    c.blade_count = static_cast<std::uint32_t>(r.end - r.first);
    const Blade dummy{};
    const std::span<const Blade> data = c.blade_count > 0
                                            ? std::span<const Blade>(blades.blades.data() + r.first, c.blade_count)
                                            : std::span<const Blade>(&dummy, 1);  // GL wants non-empty buffers
    c.blades = render::Buffer::immutable(data, true);
    const std::size_t list_bytes = std::max<std::size_t>(c.blade_count, 1) * sizeof(std::uint32_t);
    for (PassLists* pass : {&c.colour, &c.shadow}) {
      pass->visible = render::Buffer::immutable(list_bytes, nullptr, true);  // sort_visible_lists
      pass->command = render::Buffer::immutable(sizeof(CommandBlock), nullptr, true);
      pass->jobs = render::Buffer::dynamic(sizeof(TileJob));
    }
    chunks_.push_back(std::move(c));
  }
  allocate_draw_batches();
  tiles_ = blades.tiles;
  return {};
}

void GrassField::set_colliders(std::span<const glm::dvec3> centers, std::span<const float> radii) {
  SYLVA_ASSERT(centers.size() == radii.size(), "centers={} radii={}", centers.size(), radii.size());
  colliders_.clear();
  for (std::size_t i = 0; i < centers.size() && i + 1 < kMaxColliders; ++i) {
    colliders_.emplace_back(glm::vec3(centers[i] - origin_), radii[i]);
  }
  if (centers.size() + 1 > kMaxColliders) {
    log_warn("grass: {} colliders given, only the first {} are used", centers.size(), kMaxColliders - 1);
  }
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
  p.set("u_tess", glm::vec4(c.max_tess_level, c.pixels_per_segment, c.distance_tess_law ? 1.0f : 0.0f,
                            static_cast<float>(c.tess_spacing)));
}

void GrassField::update(const render::Camera& camera, glm::ivec2 viewport, double time, float dt, const WindField& wind) {
  ++frame_;
  time_ = time;
  shadow_stats_ = {};
  const CullSettings& cs = settings_.cull;
  // Cull view in blade-set local coordinates: VP * translate(origin - camera).
  const glm::mat4 vp_local = camera.view_projection() * camera.relative_model(origin_);
  camera_local_ = glm::vec3(camera.position() - origin_);
  const float height_px = static_cast<float>(std::max(viewport.y, 1));
  view_ = make_cull_view(vp_local, camera_local_, camera.forward(), height_px, camera.perspective().fov_y);
  ppr_ = view_.pixels_per_radian;
  if (cs.tess_spacing != blade_spacing_) {
    // cull.tess_spacing changed since the programs were built (settings are read every frame).
    auto blade = blade_programs(cs.tess_spacing);
    if (blade) {
      draw_ = std::move(blade->first);
      depth_ = std::move(blade->second);
    } else {
      log_warn("grass.render.cull.tess_spacing: {}; keeping the previous spacing", blade.error().message);
    }
    blade_spacing_ = cs.tess_spacing;  // one attempt per change
  }

  // Tiles: frustum + near_distance on the CPU.
  for (Chunk& c : chunks_) c.colour.job_list.clear();
  blades_in_culled_tiles_ = 0;
  job_count_ = 0;
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
    Chunk& c = chunks_[tile_chunk_[i]];
    c.colour.job_list.push_back({t.first - c.first_blade, t.count, tile_dt, settings_.simulate ? 1u : 0u});
    ++job_count_;
  }

  reset_pass(&Chunk::colour);
  if (job_count_ == 0) return;
  spheres_.bind_base(GL_SHADER_STORAGE_BUFFER, kSpheresBinding);

  if (settings_.simulate) {
    const WindFrame wf = wind.frame(sane_time ? time : 0.0, origin_);
    wind_.update(0, sizeof(WindGpuParams), &wf.gpu);
    wind_.bind_base(GL_UNIFORM_BUFFER, kWindUboBinding);
    const PhysicsSettings& ps = settings_.physics;
    physics_.set("u_physics", glm::vec4(ps.gravity, ps.front_gravity, ps.wind_response, ps.collision_recovery));
    physics_.set("u_substep", glm::vec2(ps.max_substep, static_cast<float>(ps.max_substeps)));
    std::vector<glm::vec4> spheres = colliders_;
    if (ps.camera_collider_radius > 0.0f) {
      spheres.emplace_back(glm::vec3(camera.position() - origin_) + ps.camera_collider_offset, ps.camera_collider_radius);
    }
    if (!spheres.empty()) spheres_.update(std::span<const glm::vec4>(spheres));
    physics_.set("u_sphere_count", static_cast<int>(spheres.size()));
    physics_.set("u_wind_offset", glm::vec3(0.0f));
    const Seed001WindSettings& sw = ps.seed001_wind;
    physics_.set("u_seed001_on", sw.enabled ? 1 : 0);
    physics_.set("u_seed001_wind", glm::vec4(sw.k1, sw.k2, sw.k3, sw.strength));
    physics_.set("u_seed001_time", seed001_wind_time(sane_time ? time : 0.0));
    sim_query_.begin(frame_);
    physics_.use();
    for (const Chunk& c : chunks_) {
      if (c.colour.job_list.empty()) continue;
      c.blades.bind_base(GL_SHADER_STORAGE_BUFFER, kBladesBinding);
      c.colour.jobs.bind_base(GL_SHADER_STORAGE_BUFFER, kJobsBinding);
      glDispatchCompute(static_cast<GLuint>(c.colour.job_list.size()), 1, 1);
    }
    sim_query_.end();
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  }

  set_cull_uniforms(cull_, view_);
  cull_.set("u_planes", std::span<const glm::vec4>(view_.planes));
  cull_.set("u_forward", view_.forward);
  cull_.set("u_orientation", glm::vec2(cs.orientation_threshold, cs.orientation_max_px));
  cull_query_.begin(frame_);
  cull_chunks(&Chunk::colour);
  cull_query_.end();
}

void GrassField::reset_pass(PassLists Chunk::*lists) {
  for (Chunk& c : chunks_) {
    PassLists& pass = c.*lists;
    CommandBlock reset{};
    reset.instance_count = 1;
    reset.capacity = c.blade_count;
    pass.command.update(0, sizeof(reset), &reset);
    pass.batch_count = 0;
    if (!pass.job_list.empty()) pass.jobs.upload(std::span<const TileJob>(pass.job_list));
  }
}

void GrassField::cull_chunks(PassLists Chunk::*lists) {
  cull_.use();
  for (const Chunk& c : chunks_) {
    const PassLists& pass = c.*lists;
    if (pass.job_list.empty()) continue;
    c.blades.bind_base(GL_SHADER_STORAGE_BUFFER, kBladesBinding);
    pass.visible.bind_base(GL_SHADER_STORAGE_BUFFER, kVisibleBinding);
    pass.jobs.bind_base(GL_SHADER_STORAGE_BUFFER, kJobsBinding);
    pass.command.bind_base(GL_SHADER_STORAGE_BUFFER, kCommandBinding);
    glDispatchCompute(static_cast<GLuint>(pass.job_list.size()), 1, 1);
  }
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  if (sorted_draw_order_) sort_visible_lists(lists);
  // Sub-draws of at most blades_per_sub_draw() blades each (culling.hpp, blades_per_draw).
  const std::uint32_t per_draw = blades_per_sub_draw();
  batch_.use();
  batch_.set("u_batch", per_draw);
  for (Chunk& c : chunks_) {
    PassLists& pass = c.*lists;
    if (pass.job_list.empty()) continue;
    pass.batch_count = (std::max<std::uint32_t>(c.blade_count, 1) + per_draw - 1) / per_draw;
    batch_.set("u_batch_count", pass.batch_count);
    pass.command.bind_base(GL_SHADER_STORAGE_BUFFER, kCommandBinding);
    pass.batches.bind_base(GL_SHADER_STORAGE_BUFFER, kBatchesBinding);
    glDispatchCompute(1, 1, 1);
  }
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
}

void GrassField::sort_visible_lists(PassLists Chunk::*lists) {
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  std::vector<std::uint32_t> indices;
  for (Chunk& c : chunks_) {
    PassLists& pass = c.*lists;
    if (pass.job_list.empty()) continue;
    CommandBlock block{};
    pass.command.read(0, sizeof(block), &block);
    indices.resize(std::min(block.draw_count, block.capacity));
    if (indices.size() < 2) continue;
    pass.visible.read(0, indices.size() * sizeof(std::uint32_t), indices.data());
    std::sort(indices.begin(), indices.end());
    pass.visible.update(0, indices.size() * sizeof(std::uint32_t), indices.data());
  }
}

void GrassField::draw_chunks(PassLists Chunk::*lists, render::PassStats* stats) const {
  for (const Chunk& c : chunks_) {
    const PassLists& pass = c.*lists;
    if (pass.batch_count == 0) continue;
    c.blades.bind_base(GL_SHADER_STORAGE_BUFFER, kBladesBinding);
    pass.visible.bind_base(GL_SHADER_STORAGE_BUFFER, kVisibleBinding);
    pass.batches.bind(GL_DRAW_INDIRECT_BUFFER);
    glMultiDrawArraysIndirect(GL_PATCHES, nullptr, static_cast<GLsizei>(pass.batch_count), 0);
    if (stats) stats->draw_calls += 1;
  }
}

void GrassField::set_blades_per_draw(std::uint32_t blades) {
  blades_per_draw_override_ = blades;
  allocate_draw_batches();
}

std::uint32_t GrassField::blades_per_sub_draw() const {
  return blades_per_draw_override_ > 0 ? blades_per_draw_override_
                                       : blades_per_draw(settings_.cull.max_tess_level, settings_.cull.tess_spacing);
}

void GrassField::allocate_draw_batches() {
  // Room for the most sub-draws any max_tess_level (at most 64 segments) or the override asks for.
  const std::uint32_t smallest = blades_per_draw_override_ > 0 ? blades_per_draw_override_ : blades_per_draw(64.0f);
  for (Chunk& c : chunks_) {
    const std::size_t commands = (std::max<std::size_t>(c.blade_count, 1) + smallest - 1) / smallest;
    for (PassLists* pass : {&c.colour, &c.shadow}) {
      pass->batches = render::Buffer::immutable(commands * sizeof(DrawCommand), nullptr);
      pass->batch_count = 0;
    }
  }
}

void GrassField::draw(render::Pass pass, const render::FrameContext& frame, render::PassStats& stats) {
  if (pass == render::Pass::kOpaque) {
    draw_blades(frame.camera, &stats);
  } else if (pass == render::Pass::kShadow) {
    if (const render::ShadowCasterContext* cascade = render::active_shadow_cascade()) draw_shadow(*cascade, &stats);
  }
}

void GrassField::set_blade_uniforms(const render::Program& p, const glm::mat4& relative_view_projection,
                                    const render::Camera& camera) const {
  p.set("u_view_proj", relative_view_projection);
  p.set("u_origin_rel", glm::vec3(origin_ - camera.position()));
  p.set("u_shape", static_cast<int>(settings_.shape));
  set_cull_uniforms(p, view_);
}

void GrassField::draw_blades(const render::Camera& camera, render::PassStats* stats) {
  if (job_count_ == 0) return;
  set_blade_uniforms(draw_, camera.view_projection(), camera);
  draw_.set("u_base_color", settings_.base_color);
  draw_.set("u_tip_color", settings_.tip_color);
  const ShadingSettings& sh = settings_.shading;
  draw_.set("u_shading", glm::vec4(sh.translucency, sh.ambient, sh.root_occlusion, sh.specular));
  draw_.set("u_receive_shadows", sh.receive_shadows && detail::shadow_block_bound() ? 1 : 0);
  draw_.set("u_color_motion", color_motion_uniform(sh.color_motion, sh.color_motion_hz, time_));

  vao_.bind();
  draw_.use();
  glPatchParameteri(GL_PATCH_VERTICES, 1);
  draw_query_.begin(frame_);
  draw_chunks(&Chunk::colour, stats);
  draw_query_.end();
  glBindVertexArray(0);
}

void GrassField::draw_shadow(const render::ShadowCasterContext& cascade, render::PassStats* stats) {
  if (!settings_.cast_shadows || cascade.cascade >= settings_.shadow_cascades || cascade.camera == nullptr) return;
  if (frame_ == 0) return;  // no update() yet: no camera to thin and tessellate for
  const render::Camera& camera = *cascade.camera;
  // The light frustum's side planes in blade-set local coordinates (the cascade is an
  // orthographic box; its depth range is unbounded by GL_DEPTH_CLAMP, so only the sides cull).
  const glm::mat4 vp_local = cascade.relative_view_projection * camera.relative_model(origin_);
  CullView light = make_cull_view(vp_local, camera_local_, camera.forward(), 1.0f, 1.0f);
  CullSettings cs = settings_.cull;
  cs.frustum = true;
  // Tile reach only; the blades keep the colour pass's thinning (cull uniforms below).
  CullSettings reach = cs;
  reach.near_distance = std::min(cs.near_distance, settings_.shadow_distance);
  std::size_t jobs = 0;
  for (Chunk& c : chunks_) c.shadow.job_list.clear();
  for (std::size_t i = 0; i < tiles_.size(); ++i) {
    const GrassTile& t = tiles_[i];
    if (t.count == 0 || !tile_visible(t, light, reach)) continue;
    Chunk& c = chunks_[tile_chunk_[i]];
    c.shadow.job_list.push_back({t.first - c.first_blade, t.count, 0.0f, 0u});
    shadow_stats_.considered += t.count;
    ++jobs;
  }
  ++shadow_stats_.cascades;
  if (jobs == 0) return;

  // Cull against the light frustum: same density and distance thinning (camera distance, as in
  // the colour pass), no orientation test, no behind-the-camera test (forward = 0).
  set_cull_uniforms(cull_, view_);
  cull_.set("u_planes", std::span<const glm::vec4>(light.planes));
  cull_.set("u_forward", glm::vec3(0.0f));
  cull_.set("u_cull", glm::vec4(cs.density_scale, cs.width_compensation, 1.0f, 0.0f));
  reset_pass(&Chunk::shadow);
  cull_chunks(&Chunk::shadow);

  set_blade_uniforms(depth_, cascade.relative_view_projection, camera);
  vao_.bind();
  depth_.use();
  glPatchParameteri(GL_PATCH_VERTICES, 1);
  draw_chunks(&Chunk::shadow, stats);
  glBindVertexArray(0);
}

std::vector<Blade> GrassField::read_blades() const {
  std::vector<Blade> out(blade_count_);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  for (const Chunk& c : chunks_) {
    if (c.blade_count > 0) c.blades.read(0, std::size_t{c.blade_count} * sizeof(Blade), out.data() + c.first_blade);
  }
  return out;
}

GrassFrameStats GrassField::read_frame_stats() const {
  GrassFrameStats s;
  s.blades_total = blade_count_;
  s.tiles_total = tiles_.size();
  s.tiles_visible = job_count_;
  s.blades_in_culled_tiles = blades_in_culled_tiles_;
  s.chunks = chunks_.size();
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  for (const Chunk& ch : chunks_) {
    CommandBlock c{};
    ch.colour.command.read(0, sizeof(c), &c);
    s.counts.considered += c.considered;
    s.counts.visible += std::min<std::uint64_t>(c.draw_count, c.capacity);
    s.counts.density += c.culled_density;
    s.counts.distance += c.culled_distance;
    s.counts.frustum += c.culled_frustum;
    s.counts.orientation += c.culled_orientation;
    s.counts.segments += c.segments;
    s.overflow += c.overflow;
  }
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
