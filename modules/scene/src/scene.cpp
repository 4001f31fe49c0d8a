#include <sylva/scene/scene.hpp>

#include "baked_edits.hpp"

#include <sylva/core/log.hpp>
#include <sylva/core/params_json.hpp>
#include <sylva/core/timer.hpp>
#include <sylva/render/buffer.hpp>
#include <sylva/render/gpu_memory.hpp>
#include <sylva/render/lighting_uniforms.hpp>
#include <sylva/render/shader_library.hpp>
#include <sylva/render/shadow_maps.hpp>
#include <sylva/render/sky.hpp>
#include <sylva/render/tone_mapping.hpp>
#include <sylva/render/vertex_array.hpp>
#include <sylva/scene/height_source.hpp>
#include <sylva/scene/module_registry.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <optional>

namespace sylva::render::embedded {
void register_scene_shaders();
}  // namespace sylva::render::embedded

namespace sylva::scene {

struct Scene::Gpu {
  render::SkyRenderer sky;
  render::LightingUniforms lighting;
  render::ShadowMaps shadows;  // the sun's cascades; bound for receivers every frame
  std::unique_ptr<render::CallbackShadowCaster> caster;  // draws every module's Pass::kShadow
  std::optional<render::ToneMapper> tone;  // built the first time tone mapping is on
  // The frame before it reaches the caller's target: multisampled (render.msaa_samples) and/or
  // RGBA16F for tone mapping; resolved, then tone-mapped or copied into the target.
  render::Framebuffer offscreen;
  GLint max_samples = -1;  // GL_MAX_SAMPLES, queried on the first multisampled frame
  render::Program lines;  // built the first time the chunk-bounds view is on
  render::Buffer line_buffer;
  render::VertexArray line_vao;
};

namespace {

struct LineVertex {
  glm::vec3 position;  // camera-relative
  glm::vec4 color;
};

glm::vec4 module_color(std::string_view module) {
  if (module == "terrain" || module == "ground") return {1.0f, 0.8f, 0.2f, 1.0f};
  if (module == "grass") return {0.3f, 1.0f, 0.3f, 1.0f};
  if (module == "vegetation") return {1.0f, 0.4f, 0.2f, 1.0f};
  return {0.3f, 0.7f, 1.0f, 1.0f};
}

std::string_view first_segment(std::string_view path) { return path.substr(0, path.find('.')); }


}  // namespace

Scene::~Scene() {
  // Modules go first: their drawables may refer to the ground and the maps.
  modules_.clear();
  if (gpu_ && gpu_->caster) gpu_->shadows.remove_caster(gpu_->caster.get());
}

Result<std::unique_ptr<Scene>> Scene::create(SceneDocument document) {
  SYLVA_TRY(document.validate());
  auto scene = std::unique_ptr<Scene>(new Scene());
  scene->document_ = std::make_unique<SceneDocument>(std::move(document));
  scene->wind_ = WindField(scene->document_->wind);
  scene->lighting_ = make_lighting(scene->document_->sun, scene->document_->environment);

  render::embedded::register_render_shaders();
  // GPU memory the scene itself holds (sky, shadow maps, targets); modules open their own scope.
  const render::GpuMemoryOwner scene_memory("scene");
  auto sky = render::SkyRenderer::create();
  if (!sky.ok()) return sky.error();
  scene->gpu_ = std::make_unique<Gpu>();
  scene->gpu_->sky = std::move(*sky);
  scene->gpu_->lighting = render::LightingUniforms::create();
  auto shadows = render::ShadowMaps::create(scene->document_->render.shadows);
  if (!shadows.ok()) return make_error(shadows.error().code, "render.shadows: " + shadows.error().message);
  scene->gpu_->shadows = std::move(*shadows);
  Scene* self = scene.get();
  scene->gpu_->caster = std::make_unique<render::CallbackShadowCaster>([self](const render::ShadowCasterContext& c) {
    // Modules draw their shadow from draw(kShadow) through render::active_shadow_cascade().
    const render::FrameContext ctx{self->camera_, self->time_, self->dt_, self->wind_, self->lighting_, self->viewport_, self->frame_};
    for (auto& m : self->modules_) {
      const render::GpuMemoryOwner memory(m->module());
      render::PassStats counts;
      for (render::Drawable* d : m->drawables()) d->draw(render::Pass::kShadow, ctx, counts);
      self->shadow_counts_[m->module()] += counts;
      if (c.stats) *c.stats += counts;
    }
  });
  scene->gpu_->shadows.add_caster(scene->gpu_->caster.get());

  SYLVA_TRY(scene->build_ground());
  SYLVA_TRY(scene->build_modules());
  return scene;
}

Status Scene::build_ground() {
  for (const ModuleSection& section : document_->modules()) {
    const ModuleDescriptor* d = find_module(section.name);
    if (!d || !d->provides_ground) continue;
    const HeightSourceSettings source = d->height_source(*section.settings);
    const std::string id = section.name + ".height";
    auto existing = maps_.find(id);
    if (existing != maps_.end() && existing->second.unsaved()) {
      // Painted and not saved: keep the painted heights, only re-place them. Heights painted over
      // an elevation raster keep the raster's spacing unless elevation.spacing overrides it.
      MapGrid& grid = existing->second.grid;
      const bool from_raster =
          existing->second.path.empty() && source.control.file.empty() && !source.elevation.file.empty();
      const double spacing = !from_raster                         ? height_spacing(source, grid.width)
                             : source.elevation.read.spacing > 0.0 ? source.elevation.read.spacing
                                                                   : grid.texel_size.x;
      // A baked terrain's ground stays where the file's chunks are (baked_ground.hpp).
      if (!baked_ground_file(*document_, section.name)) place_height_grid(grid, source, spacing);
    } else {
      std::optional<std::filesystem::path> file, elevation, control;
      std::string path;
      if (auto m = section.maps.find("height"); m != section.maps.end()) {
        path = m->second;
        file = document_->resolve(path);
      }
      if (!source.elevation.file.empty()) elevation = document_->resolve(source.elevation.file);
      if (!source.control.file.empty()) control = document_->resolve(source.control.file);
      auto grid = make_height_grid(source, file, elevation, control);
      if (!grid.ok()) {
        const char* key = file ? "maps.height" : control ? "control.file" : "elevation.file";
        return make_error(grid.error().code, fmt::format("{}.{}: {}", section.name, key, grid.error().message));
      }
      SceneMap map;
      map.module = section.name;
      map.slot = "height";
      map.kind = MapKind::kHeight;
      map.grid = std::move(*grid);
      map.path = path;
      map.file_scale = source.map_scale;
      map.file_offset = source.map_offset;
      if (existing != maps_.end()) {
        map.revision = map.saved_revision = existing->second.revision;
        existing->second = std::move(map);
      } else {
        maps_.emplace(id, std::move(map));
      }
    }
    ground_ = std::make_unique<HeightField>(height_field_from_grid(maps_.at(id).grid));
    ground_map_id_ = id;
    return {};
  }
  ground_.reset();
  ground_map_id_.clear();
  return {};
}

ModuleBuildContext Scene::context_for(const ModuleSection& section) {
  ModuleBuildContext ctx;
  ctx.section = &section;
  ctx.document = document_.get();
  ctx.ground = ground_.get();
  ctx.maps = &maps_;
  ctx.wind = &wind_;
  ctx.environment = &document_->environment;
  ctx.debug = &debug_;
  return ctx;
}

Result<std::unique_ptr<ModuleInstance>> Scene::create_module(const ModuleSection& section) {
  const ModuleDescriptor* d = find_module(section.name);
  if (!d) {
    Status s = require_module(section.name, section.name);
    return s.error();
  }
  Stopwatch watch;
  const render::GpuMemoryOwner memory(section.name);  // what the module allocates is counted as its own
  auto created = d->create(context_for(section));
  build_ms_[section.name] = watch.elapsed_ms();
  if (created.ok()) log_info("scene: built {} in {:.0f} ms", section.name, build_ms_[section.name]);
  return created;
}

namespace {

// Sections a scene opens without when they fail to build (ModuleDescriptor::left_out_on_failure;
// issue 16, "Bad input"). A left-out section has no instance; setting one of its parameters (the
// editor, --set) or reloading its files builds it again.
bool left_out_when_failing(std::string_view section) {
  const ModuleDescriptor* d = find_module(section);
  return d != nullptr && d->left_out_on_failure;
}

void warn_left_out(std::string_view section, const Error& error) {
  log_warn("{}; the {} section is left out of the scene until this is fixed", error.message, section);
}

}  // namespace

Status Scene::build_modules() {
  modules_.clear();
  for (const ModuleSection& section : document_->modules()) {
    auto inst = create_module(section);
    if (!inst.ok()) {
      if (!left_out_when_failing(section.name)) return inst.error();
      warn_left_out(section.name, inst.error());
      continue;
    }
    modules_.push_back(std::move(*inst));
  }
  return {};
}

bool Scene::left_out(std::string_view name) const {
  if (!left_out_when_failing(name) || !document_->module(name)) return false;
  for (const auto& m : modules_) {
    if (m->module() == name) return false;
  }
  return true;
}

Status Scene::build_left_out(std::string_view name) {
  const ModuleSection* section = document_->module(name);
  auto fresh = create_module(*section);
  if (!fresh.ok()) return fresh.error();
  // Back in the document's order (the draw order of equal passes).
  std::size_t at = 0;
  for (const ModuleSection& s : document_->modules()) {
    if (s.name == name) break;
    if (module(s.name)) ++at;
  }
  modules_.insert(modules_.begin() + static_cast<std::ptrdiff_t>(at), std::move(*fresh));
  log_info("scene: the {} section is built again", name);
  return {};
}

ModuleInstance* Scene::module(std::string_view name) {
  for (auto& m : modules_) {
    if (m->module() == name) return m.get();
  }
  return nullptr;
}

double Scene::ground_height(double x, double z) const { return ground_ ? ground_->height(x, z) : 0.0; }

Status Scene::rebuild_module(std::string_view name, Rebuild what) {
  const ModuleDescriptor* d = find_module(name);
  if (d && d->provides_ground) {
    // A new ground: rebuild it, then every module (they all stand on it or draw it).
    modules_.clear();
    SYLVA_TRY(build_ground());
    std::vector<std::unique_ptr<ModuleInstance>> fresh;
    for (const ModuleSection& section : document_->modules()) {
      auto inst = create_module(section);
      if (!inst.ok()) return inst.error();
      fresh.push_back(std::move(*inst));
    }
    modules_ = std::move(fresh);
    return {};
  }
  if (left_out(name)) return build_left_out(name);
  ModuleInstance* m = module(name);
  if (!m) return {};
  const render::GpuMemoryOwner memory(name);
  return m->rebuild(what);
}

Status Scene::reload_module(std::string_view name) {
  const ModuleDescriptor* d = find_module(name);
  if (d && d->provides_ground) return rebuild_module(name, Rebuild::kOffline);
  const ModuleSection* section = document_->module(name);
  if (!section) return make_error(ErrorCode::kNotFound, fmt::format("reload {}: the scene has no such section", name));
  if (left_out(name)) return build_left_out(name);
  for (auto& m : modules_) {
    if (m->module() != name) continue;
    auto fresh = create_module(*section);
    if (!fresh.ok()) return fresh.error();
    m = std::move(*fresh);
  }
  return {};
}

Status Scene::set_param(std::string_view path, std::string_view text) {
  ParamRegistry registry = document_->params();
  auto param = registry.find(path);
  if (!param.ok()) return param.error();
  const std::string before = param->get_string();
  SYLVA_TRY(param->set_string(text));
  const std::string section(first_segment(path));
  ModuleSection* ms = document_->module(section);
  auto revert = [&](const Error& error) -> Status {
    (void)param->set_string(before);
    return error;
  };
  if (ms) {
    Status check = ms->settings->check(section);
    if (!check.ok()) return revert(check.error());
    if (param->info.rebuild != Rebuild::kNone) {
      const bool was_left_out = left_out(section);
      Status rebuilt = rebuild_module(section, param->info.rebuild);
      if (!rebuilt.ok()) {
        (void)param->set_string(before);
        if (was_left_out) return rebuilt.error();  // still out, as it was
        Status restored = rebuild_module(section, param->info.rebuild);
        if (!restored.ok()) log_warn("{}: could not restore after a failed rebuild: {}", section, restored.error().message);
        return rebuilt.error();
      }
    }
  }
  return {};
}

Status Scene::replace_document(SceneDocument document) {
  SYLVA_TRY(document.validate());
  auto old = std::make_unique<SceneDocument>(std::move(*document_));
  *document_ = std::move(document);
  modules_.clear();  // they refer to the ground that is about to be replaced
  Status built = build_ground();
  if (built.ok()) built = build_modules();
  if (!built.ok()) {
    *document_ = std::move(*old);
    Status restored = build_ground();
    if (restored.ok()) restored = build_modules();
    if (!restored.ok()) log_warn("scene: could not restore the previous document: {}", restored.error().message);
    return built;
  }
  return {};
}

Result<std::string> Scene::get_param(std::string_view path) { return document_->params().get(path); }

std::vector<ParamDescriptor> Scene::describe_params() { return document_->params().describe(); }

CameraView Scene::resolve(const CameraView& view) const {
  CameraView out = view;
  if (view.height_mode == HeightMode::kAboveGround) {
    out.position.y += ground_height(view.position.x, view.position.z);
    out.height_mode = HeightMode::kAbsolute;
  }
  return out;
}

render::Camera Scene::make_camera(const CameraView& view, glm::ivec2 viewport) const {
  const CameraView v = resolve(view);
  render::Camera camera;
  camera.set_position(v.position);
  camera.set_yaw_pitch(glm::radians(v.yaw_deg), glm::radians(v.pitch_deg));
  camera.perspective().fov_y = glm::radians(v.fov_deg);
  camera.perspective().near_plane = 0.1f;
  camera.set_aspect(viewport.x, viewport.y);
  return camera;
}

Result<CameraView> Scene::camera_path_view(std::string_view name, double t) const {
  auto it = document_->camera_paths.find(std::string(name));
  if (it == document_->camera_paths.end()) {
    std::string known;
    for (const auto& [n, p] : document_->camera_paths) known += (known.empty() ? "" : ", ") + n;
    return make_error(ErrorCode::kNotFound, fmt::format("camera_paths.{}: no such camera path (the scene has: {})", name,
                                                        known.empty() ? "none" : known));
  }
  return resolve(it->second.evaluate(t));
}

CameraView Scene::view_of(const render::Camera& camera) {
  CameraView v;
  v.position = camera.position();
  v.yaw_deg = glm::degrees(camera.yaw());
  v.pitch_deg = glm::degrees(camera.pitch());
  v.fov_deg = glm::degrees(camera.perspective().fov_y);
  v.height_mode = HeightMode::kAbsolute;
  return v;
}

void Scene::update(const render::Camera& camera, double time, float dt, glm::ivec2 viewport) {
  camera_ = camera;
  time_ = time;
  dt_ = std::max(dt, 0.0f);
  viewport_ = viewport;
  ++frame_;
  wind_ = WindField(document_->wind);
  lighting_ = make_lighting(document_->sun, document_->environment);
  const render::FrameContext ctx{camera_, time_, dt_, wind_, lighting_, viewport_, frame_};
  update_ms_.clear();
  for (auto& m : modules_) {
    Stopwatch watch;
    const render::GpuMemoryOwner memory(m->module());
    m->sync_settings();
    for (render::Drawable* d : m->drawables()) d->update(ctx);
    update_ms_[m->module()] = watch.elapsed_ms();
  }
}

void Scene::draw_pass(render::Pass pass, render::FrameProfiler& profiler) {
  const render::FrameContext ctx{camera_, time_, dt_, wind_, lighting_, viewport_, frame_};
  const std::string pass_name = render::to_string(pass);
  profiler.begin(pass_name, false);
  const bool wire = debug_.wireframe && pass == render::Pass::kOpaque;
  if (wire) glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
  for (auto& m : modules_) {
    const render::GpuMemoryOwner memory(m->module());
    const std::string scope = module_scope(pass_name, m->module());
    profiler.begin(scope, !m->counts_own_primitives());
    render::PassStats counts;
    for (render::Drawable* d : m->drawables()) d->draw(pass, ctx, counts);
    profiler.end(scope);
    profiler.add_cpu_counts(scope, counts);
  }
  if (wire) glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
  profiler.end(pass_name);
}

void Scene::render(const render::Framebuffer& target, render::FrameProfiler& profiler) {
  const render::FrameContext ctx{camera_, time_, dt_, wind_, lighting_, viewport_, frame_};
  const SceneRenderSettings& rs = document_->render;
  profiler.begin_frame();

  // Shadow pass: a host hook when set, else the scene's cascaded shadow maps. One GPU scope for
  // the pass (casters run once per cascade); per-module counts are recorded without GPU time.
  const std::string shadow_pass = render::to_string(render::Pass::kShadow);
  shadow_counts_.clear();
  if (shadow_hook_) {
    profiler.begin(shadow_pass, false);
    shadow_hook_(ctx, [&](render::PassStats& total) {
      for (auto& m : modules_) {
        const render::GpuMemoryOwner memory(m->module());
        render::PassStats counts;
        for (render::Drawable* d : m->drawables()) d->draw(render::Pass::kShadow, ctx, counts);
        shadow_counts_[m->module()] += counts;
        total += counts;
      }
    });
    profiler.end(shadow_pass);
  } else if (rs.shadows.enabled) {
    gpu_->shadows.settings() = rs.shadows;
    profiler.begin(shadow_pass, false);
    render::PassStats total;
    Status s = gpu_->shadows.render(camera_, lighting_.sun_direction, &ctx, &total);
    if (!s.ok() && !shadow_warned_) {
      log_warn("scene: shadows off: {}", s.error().message);
      shadow_warned_ = true;
    }
    profiler.end(shadow_pass);
  } else {
    gpu_->shadows.settings().enabled = false;
    (void)gpu_->shadows.render(camera_, lighting_.sun_direction, &ctx, nullptr);  // uploads "disabled"
  }
  for (const auto& [module, counts] : shadow_counts_) profiler.add_cpu_counts(module_scope(shadow_pass, module), counts);

  // Colour passes into an offscreen target (multisampled, HDR for tone mapping, or both) or
  // straight into the caller's target when neither is asked for.
  const render::Framebuffer* colour = &target;
  if (rs.tone_map && !gpu_->tone) {
    auto tone = render::ToneMapper::create();
    if (tone.ok()) {
      gpu_->tone = std::move(*tone);
    } else {
      log_warn("scene: no tone mapping: {}", tone.error().message);
    }
  }
  const bool tone_map = rs.tone_map && gpu_->tone.has_value();
  int samples = rs.msaa_samples > 1 ? rs.msaa_samples : 0;
  if (samples > 1) {
    if (gpu_->max_samples < 0) glGetIntegerv(GL_MAX_SAMPLES, &gpu_->max_samples);  // once, not per frame
    const int max_samples = gpu_->max_samples;
    if (samples > max_samples) {
      if (!msaa_warned_) {
        log_warn("scene: render.msaa_samples = {} is above this GL's maximum of {} samples; using {}", samples,
                 max_samples, max_samples);
        msaa_warned_ = true;
      }
      samples = max_samples > 1 ? max_samples : 0;
    }
  }
  if (tone_map || samples > 1) {
    const GLenum format = tone_map ? GL_RGBA16F : target.desc().color_formats.front();
    const render::FramebufferDesc& have = gpu_->offscreen.desc();
    if (!gpu_->offscreen || gpu_->offscreen.size() != target.size() || have.samples != samples ||
        have.color_formats.front() != format) {
      gpu_->offscreen = {};  // free the old one first: at large sizes both would not fit
      const render::GpuMemoryOwner memory("scene");
      auto made = render::Framebuffer::create(
          {.width = target.width(), .height = target.height(), .color_formats = {format}, .samples = samples});
      if (made.ok()) {
        gpu_->offscreen = std::move(*made);
      } else if (!offscreen_warned_) {
        log_warn("scene: no offscreen target ({}), rendering without MSAA and tone mapping", made.error().message);
        offscreen_warned_ = true;
      }
    }
    if (gpu_->offscreen) colour = &gpu_->offscreen;
  }
  // Rasterise with every sample of a multisampled target whatever the caller left enabled.
  const bool multisample_was_on = glIsEnabled(GL_MULTISAMPLE);
  if (colour->multisampled()) glEnable(GL_MULTISAMPLE);
  gpu_->lighting.update(lighting_, camera_.position().y, time_);
  gpu_->lighting.bind();
  gpu_->shadows.bind();
  colour->bind();
  render::apply_reversed_z_state();
  // The sky pass covers every pixel left at depth 0, so the clear colour is never meant to be
  // seen; the horizon colour hides a gap best, magenta (debug) shows it.
  colour->clear(debug_.show_holes ? glm::vec4(1.0f, 0.0f, 1.0f, 1.0f) : glm::vec4(lighting_.fog_color, 1.0f), 0.0f);

  draw_pass(render::Pass::kOpaque, profiler);
  profiler.begin("sky");
  gpu_->sky.draw(camera_, lighting_, time_);
  profiler.end("sky");
  profiler.add_cpu_counts("sky", render::PassStats{.draw_calls = 1});
  gpu_->lighting.bind();
  draw_pass(render::Pass::kTransparent, profiler);
  if (debug_.chunk_bounds) {
    profiler.begin("debug");
    draw_debug_lines();
    profiler.end("debug");
  }
  if (colour->multisampled() && !multisample_was_on) glDisable(GL_MULTISAMPLE);
  if (colour != &target) {
    colour->resolve();  // MSAA: average the samples (before tone mapping); no-op otherwise
    if (tone_map) {
      profiler.begin("tone_map");
      target.bind();
      gpu_->tone->apply(colour->color_texture(), rs.tone);
      render::apply_reversed_z_state();
      // The tone map writes colour only: the caller's target gets the scene's depth too
      // (sylva-bench's silhouette metric reads it).
      colour->copy_depth_to(target);
      profiler.end("tone_map");
      profiler.add_cpu_counts("tone_map", render::PassStats{.draw_calls = 1});
    } else {
      glBlitNamedFramebuffer(colour->read_id(), target.id(), 0, 0, target.width(), target.height(), 0, 0, target.width(),
                             target.height(), GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT, GL_NEAREST);
      target.bind();
    }
  }
  profiler.end_frame();
}

void Scene::draw_debug_lines() {
  if (!gpu_->lines) {
    render::embedded::register_scene_shaders();
    auto program = render::Program::create({"scene/lines.vert", "scene/lines.frag"});
    if (!program.ok()) {
      log_warn("scene: chunk-bounds view unavailable: {}", program.error().message);
      debug_.chunk_bounds = false;
      return;
    }
    gpu_->lines = std::move(*program);
    gpu_->line_buffer = render::Buffer::dynamic(1 << 16, GL_STREAM_DRAW);
    gpu_->line_vao = render::VertexArray::create();
    gpu_->line_vao.attribute(0, 0, 3, GL_FLOAT, offsetof(LineVertex, position));
    gpu_->line_vao.attribute(1, 0, 4, GL_FLOAT, offsetof(LineVertex, color));
  }
  constexpr std::size_t kMaxBoxes = 50000;
  std::vector<LineVertex> vertices;
  for (auto& m : modules_) {
    const glm::vec4 color = module_color(m->module());
    const std::vector<render::Aabb> boxes = m->debug_bounds();
    for (std::size_t b = 0; b < boxes.size() && vertices.size() < kMaxBoxes * 24; ++b) {
      const glm::vec3 lo = camera_.to_relative(boxes[b].min), hi = camera_.to_relative(boxes[b].max);
      const glm::vec3 c[8] = {{lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {hi.x, lo.y, hi.z}, {lo.x, lo.y, hi.z},
                              {lo.x, hi.y, lo.z}, {hi.x, hi.y, lo.z}, {hi.x, hi.y, hi.z}, {lo.x, hi.y, hi.z}};
      static constexpr int kEdges[12][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6},
                                            {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
      for (const auto& e : kEdges) {
        vertices.push_back({c[e[0]], color});
        vertices.push_back({c[e[1]], color});
      }
    }
  }
  if (vertices.empty()) return;
  gpu_->line_buffer.upload(std::span<const LineVertex>(vertices));
  gpu_->line_vao.vertex_buffer(0, gpu_->line_buffer, sizeof(LineVertex));
  gpu_->lines.use();
  gpu_->lines.set("u_view_projection", camera_.view_projection());
  gpu_->line_vao.bind();
  glDepthMask(GL_FALSE);
  glDrawArrays(GL_LINES, 0, static_cast<GLsizei>(vertices.size()));
  glDepthMask(GL_TRUE);
}

SceneMap* Scene::map(std::string_view id) {
  auto it = maps_.find(std::string(id));
  return it == maps_.end() ? nullptr : &it->second;
}

Status Scene::map_changed(std::string_view id, const TexelRect& rect) {
  SceneMap* m = map(id);
  if (!m) return make_error(ErrorCode::kNotFound, fmt::format("map \"{}\" does not exist in this scene", id));
  const TexelRect r = rect.intersect(m->grid.bounds());
  if (r.empty()) return {};
  ++m->revision;
  const WorldArea area = changed_world_area(m->grid, r);
  if (m->id() == ground_map_id_ && ground_) {
    update_height_field(*ground_, m->grid, r);
    for (auto& mod : modules_) {
      const render::GpuMemoryOwner memory(mod->module());
      SYLVA_TRY(mod->on_map_changed(m->id(), area));
    }
    return {};
  }
  if (ModuleInstance* owner = module(m->module)) {
    const render::GpuMemoryOwner memory(m->module);
    return owner->on_map_changed(m->id(), area);
  }
  return {};
}

bool Scene::maps_unsaved() const {
  return std::any_of(maps_.begin(), maps_.end(), [](const auto& kv) { return kv.second.unsaved(); });
}

nlohmann::json Scene::module_stats() const {
  nlohmann::json j = nlohmann::json::object();
  for (const auto& m : modules_) {
    nlohmann::json info = m->stats();
    if (auto it = build_ms_.find(m->module()); it != build_ms_.end()) info["build_ms"] = it->second;
    j[m->module()] = std::move(info);
  }
  return j;
}

}  // namespace sylva::scene
