#include <sylva/vegetation/forest.hpp>

#include <sylva/core/assert.hpp>
#include <sylva/core/log.hpp>
#include <sylva/core/wind.hpp>
#include <sylva/render/frustum.hpp>
#include <sylva/render/shadow_maps.hpp>

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <optional>

namespace sylva::vegetation {

struct Forest::Impl {
  struct Species {
    TreeModel model;
    TreeMesh mesh;
    TreeAsset asset;
    std::optional<BakedTree> baked;       // CPU copy of the slices (tests, stats)
    std::optional<SliceAsset> slices;
    std::vector<TreeInstance> instances;
    std::vector<std::uint32_t> visible;
    std::array<render::Buffer, kLodLevels> gpu;        // queued records per LOD, in draw order
    std::array<std::uint32_t, kLodLevels> queued{};
    std::array<render::Buffer, kLodLevels> depth_gpu;  // records of the last draw_depth()
    std::vector<render::Sphere> spheres;  // world bounding spheres (cull margin included)
    std::vector<float> heights;           // world heights [m] (screen-size criterion)
    float spheres_margin = -1.0f;         // cull_margin the spheres were computed with
    LodState lod_state;                   // effective distance and LOD coordinate per instance
    LodQueues queues;
    glm::vec3 sphere_center{0.0f};        // object space
    float sphere_radius = 0.0f;
    SpeciesTuning tuning;
  };
  ForestSettings settings;
  TreeRenderer renderer;
  SliceRenderer slice_renderer;
  std::vector<Species> species;
  ForestStats stats;
  glm::dvec3 origin{0.0};
  double time = 0.0;
  WindFrame wind_frame;  // the last update's wind split at the camera (WindField::frame)
  float season = 0.0f;
  bool updated = false;
  bool reported_error = false;

  Species& at(int i) {
    SYLVA_ASSERT(i >= 0 && i < static_cast<int>(species.size()), "species {} of {}", i, species.size());
    return species[static_cast<std::size_t>(i)];
  }
  const Species& at(int i) const {
    SYLVA_ASSERT(i >= 0 && i < static_cast<int>(species.size()), "species {} of {}", i, species.size());
    return species[static_cast<std::size_t>(i)];
  }

  // World bounding sphere of an instance (double precision).
  static render::Sphere sphere(const Species& s, const TreeInstance& t, float margin) {
    const glm::vec3 c = s.sphere_center * t.scale;
    const double cs = std::cos(static_cast<double>(t.yaw));
    const double sn = std::sin(static_cast<double>(t.yaw));
    const glm::dvec3 rotated(cs * c.x + sn * c.z, c.y, -sn * c.x + cs * c.z);
    return {t.position + rotated, static_cast<double>(s.sphere_radius * t.scale * (1.0f + margin))};
  }

  void ensure_spheres(Species& s) {
    const float margin = settings.cull_margin;
    if (s.spheres_margin == margin && s.spheres.size() == s.instances.size()) return;
    s.spheres.resize(s.instances.size());
    s.heights.resize(s.instances.size());
    const float h = s.mesh.bounds_max.y - s.mesh.bounds_min.y;
    for (std::size_t i = 0; i < s.instances.size(); ++i) {
      s.spheres[i] = sphere(s, s.instances[i], margin);
      s.heights[i] = h * s.instances[i].scale;
    }
    s.spheres_margin = margin;
  }

  SliceDrawParams slice_params(const glm::mat4& view_proj) const {
    SliceDrawParams p;
    p.view_proj = view_proj;
    p.shading = settings.shading;
    p.shading.season = season;
    p.level = settings.animation_level;
    p.receive_shadows = settings.receive_shadows;
    return p;
  }

  // The instance record for the last update's camera and wind. The wind comes from the per-frame
  // split at the camera (WindField::evaluate(frame, local): float work per tree, no double noise
  // setup), the same in the colour and the shadow passes.
  InstanceGpu record(const TreeInstance& t, const Species& s) const {
    const glm::vec3 local(t.position - origin);
    return make_instance_gpu(t, origin, WindField::evaluate(wind_frame, local) * (settings.animation.wind_scale * s.tuning.wind_scale));
  }

  void report(const Status& st) {
    if (!st.ok() && !reported_error) {
      log_error("forest: {}", st.error().message);
      reported_error = true;
    }
  }

  TreeDrawParams params(const glm::mat4& view_proj) const {
    TreeDrawParams p;
    p.view_proj = view_proj;
    p.shading = settings.shading;
    p.shading.season = season;
    p.level = settings.animation_level;
    p.receive_shadows = settings.receive_shadows;
    return p;
  }
};

Forest::Forest() : impl_(std::make_unique<Impl>()) {}
Forest::Forest(Forest&&) noexcept = default;
Forest& Forest::operator=(Forest&&) noexcept = default;
Forest::~Forest() = default;

Result<Forest> Forest::create(const ForestSettings& settings) {
  SYLVA_TRY(validate_params(settings, "forest"));
  Result<TreeRenderer> r = TreeRenderer::create();
  if (!r.ok()) return r.error();
  Result<SliceRenderer> sr = SliceRenderer::create();
  if (!sr.ok()) return sr.error();
  Forest f;
  f.impl_->settings = settings;
  f.impl_->renderer = std::move(r).value();
  f.impl_->slice_renderer = std::move(sr).value();
  return f;
}

Result<int> Forest::add_species(const TreeModel& model, const TreeTextureSet& textures, const MeshSettings& mesh_settings,
                                const TreeAssetOptions& options) {
  if (Status s = validate(model); !s.ok()) return s.error();
  SYLVA_TRY(validate_params(mesh_settings, "forest.mesh"));
  Impl::Species s;
  s.model = model;
  s.mesh = build_tree_mesh(model, mesh_settings);
  Result<TreeAsset> asset = TreeAsset::create(s.mesh, textures, options);
  if (!asset.ok()) return asset.error();
  s.asset = std::move(asset).value();
  s.sphere_center = 0.5f * (s.mesh.bounds_min + s.mesh.bounds_max);
  s.sphere_radius = 0.5f * glm::length(s.mesh.bounds_max - s.mesh.bounds_min);
  for (int k = 0; k < kLodLevels; ++k) {
    s.gpu[static_cast<std::size_t>(k)] = render::Buffer::dynamic(sizeof(InstanceGpu));
    s.depth_gpu[static_cast<std::size_t>(k)] = render::Buffer::dynamic(sizeof(InstanceGpu));
  }
  ForestStats::Species st;
  const LodSettings& lod = impl_->settings.lod;
  if (lod.enabled) {
    // Bake the image-based levels at load time (or load them from the cache).
    Result<BakedTree> baked = bake_or_load_slices(s.asset, s.mesh, textures, lod.slice_resolution, lod.slice_margin,
                                                  resolve_cache_directory(lod.cache_directory));
    if (!baked.ok()) return baked.error();
    Result<SliceAsset> slices = SliceAsset::create(*baked, mean_leaf_transmittance(textures.leaves));
    if (!slices.ok()) return slices.error();
    st.bake_ms = baked->bake_ms;
    st.bake_from_cache = baked->from_cache;
    s.baked = std::move(baked).value();
    s.slices = std::move(slices).value();
  }
  impl_->species.push_back(std::move(s));
  impl_->stats.species.push_back(st);
  return static_cast<int>(impl_->species.size()) - 1;
}

Result<int> Forest::add_preset(SpeciesPreset preset, std::uint32_t seed, int texture_size) {
  Result<TreeModel> model = generate_tree(species_preset(preset, seed));
  if (!model.ok()) return model.error();
  Result<TreeTextureSet> tex = make_texture_set(preset, seed, texture_size, texture_size);
  if (!tex.ok()) return tex.error();
  return add_species(*model, *tex);
}

Status Forest::set_instances(int species, std::vector<TreeInstance> instances) {
  if (species < 0 || species >= static_cast<int>(impl_->species.size()))
    return make_error(ErrorCode::kInvalidArgument, fmt::format("forest: species {} does not exist ({} added)", species,
                                                               impl_->species.size()));
  for (std::size_t i = 0; i < instances.size(); ++i) {
    const TreeInstance& t = instances[i];
    if (!(t.scale > 0.0f) || !std::isfinite(t.scale) || !std::isfinite(t.position.x) || !std::isfinite(t.position.y) ||
        !std::isfinite(t.position.z) || !std::isfinite(t.yaw))
      return make_error(ErrorCode::kInvalidArgument,
                        fmt::format("forest: instance {} of species {} has a non-finite position/yaw or scale {} <= 0", i,
                                    species, t.scale));
  }
  Impl::Species& s = impl_->at(species);
  s.instances = std::move(instances);
  s.visible.clear();
  s.lod_state = {};  // new instances start at their target LOD
  s.spheres_margin = -1.0f;
  return ok_status();
}

Status Forest::set_species_tuning(int species, const SpeciesTuning& tuning) {
  if (species < 0 || species >= static_cast<int>(impl_->species.size()))
    return make_error(ErrorCode::kInvalidArgument, fmt::format("forest: species {} does not exist ({} added)", species,
                                                               impl_->species.size()));
  const float values[] = {tuning.v1, tuning.v2, tuning.s1, tuning.s2};
  for (float v : values) {
    if (!std::isfinite(v)) return make_error(ErrorCode::kInvalidArgument, fmt::format("forest: species {}: non-finite LOD threshold", species));
  }
  if (!(tuning.wind_scale >= 0.0f && tuning.wind_scale <= 100.0f))
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("forest: species {}: wind_scale {} is outside [0, 100]", species, tuning.wind_scale));
  impl_->at(species).tuning = tuning;
  return ok_status();
}

const SpeciesTuning& Forest::species_tuning(int species) const { return impl_->at(species).tuning; }

std::size_t Forest::species_count() const { return impl_->species.size(); }
const TreeModel& Forest::model(int species) const { return impl_->at(species).model; }
const TreeMesh& Forest::mesh(int species) const { return impl_->at(species).mesh; }
const TreeAsset& Forest::asset(int species) const { return impl_->at(species).asset; }
const SliceAsset* Forest::slices(int species) const {
  const auto& s = impl_->at(species).slices;
  return s ? &*s : nullptr;
}
const BakedTree* Forest::baked(int species) const {
  const auto& b = impl_->at(species).baked;
  return b ? &*b : nullptr;
}
const std::vector<float>& Forest::lod_state(int species) const { return impl_->at(species).lod_state.level; }
const std::vector<TreeInstance>& Forest::instances(int species) const { return impl_->at(species).instances; }
const std::vector<std::uint32_t>& Forest::visible(int species) const { return impl_->at(species).visible; }
ForestSettings& Forest::settings() { return impl_->settings; }
const ForestSettings& Forest::settings() const { return impl_->settings; }
float Forest::current_season() const { return impl_->season; }
const ForestStats& Forest::stats() const { return impl_->stats; }

void Forest::update(const render::FrameContext& frame) {
  const auto start = std::chrono::steady_clock::now();
  Impl& m = *impl_;
  const ForestSettings& st = m.settings;
  const double time = std::isfinite(frame.time) ? frame.time : 0.0;
  m.origin = frame.camera.position();
  m.time = time;
  // Season: wrapped in double so a long-running animation keeps full precision.
  const double season = static_cast<double>(st.shading.season) + static_cast<double>(st.season_speed) * time;
  m.season = static_cast<float>(season - std::floor(season));
  const AnimationGpu anim = make_animation_gpu(st.animation, time);
  m.wind_frame = frame.wind.frame(time, m.origin);
  const WindGpuParams wind_gpu = m.wind_frame.gpu;
  m.renderer.set_frame(anim, wind_gpu);
  m.slice_renderer.set_frame(anim, wind_gpu, time, st.lod);
  const render::Frustum frustum = frame.camera.frustum();
  LodView view;
  view.camera = m.origin;
  view.frustum = st.frustum_culling ? &frustum : nullptr;
  const int vh = frame.viewport.y > 0 ? frame.viewport.y : 720;
  view.pixels_per_radian = static_cast<double>(vh) / (2.0 * std::tan(0.5 * static_cast<double>(frame.camera.perspective().fov_y)));
  view.max_distance = static_cast<double>(st.max_distance);
  m.stats.instances = 0;
  m.stats.visible = 0;
  m.stats.lod = {};
  m.stats.transitions = 0;
  double select_ms = 0.0;
  std::vector<InstanceGpu> upload;
  std::vector<std::uint8_t> seen;
  for (std::size_t si = 0; si < m.species.size(); ++si) {
    Impl::Species& s = m.species[si];
    m.ensure_spheres(s);
    LodSettings lod = st.lod;
    lod.enabled = lod.enabled && s.slices.has_value();
    if (s.tuning.v1 >= 0.0f) lod.v1 = s.tuning.v1;
    if (s.tuning.v2 >= 0.0f) lod.v2 = s.tuning.v2;
    if (s.tuning.s1 >= 0.0f) lod.s1 = s.tuning.s1;
    if (s.tuning.s2 >= 0.0f) lod.s2 = s.tuning.s2;
    const auto t0 = std::chrono::steady_clock::now();
    select_lods(lod, view, s.spheres, s.heights, s.lod_state, s.queues);
    select_ms += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    s.visible.clear();
    seen.assign(s.instances.size(), 0);
    ForestStats::Species& ss = m.stats.species[si];
    for (int k = 0; k < kLodLevels; ++k) {
      const std::vector<LodQueueEntry>& q = s.queues.level[static_cast<std::size_t>(k)];
      ss.lod[static_cast<std::size_t>(k)] = q.size();
      m.stats.lod[static_cast<std::size_t>(k)] += q.size();
      if (!st.lod.draws_level(k)) {  // selected and counted, not drawn (LodSettings::draw_lod*)
        s.queued[static_cast<std::size_t>(k)] = 0;
        continue;
      }
      upload.clear();
      upload.reserve(q.size());
      for (const LodQueueEntry& e : q) {
        InstanceGpu g = m.record(s.instances[e.instance], s);
        g.lod = glm::vec4(e.fade, e.instance < s.lod_state.level.size() ? s.lod_state.level[e.instance] : 0.0f, 0.0f, 0.0f);
        upload.push_back(g);
        if (seen[e.instance] == 0) {
          seen[e.instance] = 1;
          s.visible.push_back(e.instance);
        }
      }
      if (!upload.empty()) s.gpu[static_cast<std::size_t>(k)].upload(std::span<const InstanceGpu>(upload));
      s.queued[static_cast<std::size_t>(k)] = static_cast<std::uint32_t>(q.size());
    }
    ss.instances = s.instances.size();
    ss.visible = s.visible.size();
    m.stats.instances += s.instances.size();
    m.stats.visible += s.visible.size();
    m.stats.transitions += s.queues.transitions;
  }
  m.updated = true;
  m.stats.select_cpu_ms = select_ms;
  m.stats.update_cpu_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

void Forest::draw(render::Pass pass, const render::FrameContext& frame, render::PassStats& stats) {
  Impl& m = *impl_;
  if (!m.updated) return;
  if (pass == render::Pass::kShadow) {
    // Inside ShadowMaps::render (the scene's shadow hook): draw into the cascade being rendered.
    if (const render::ShadowCasterContext* c = render::active_shadow_cascade())
      m.report(draw_depth(c->relative_view_projection, c->light_frustum, stats));
    return;
  }
  if (pass != render::Pass::kOpaque) return;
  const TreeDrawParams params = m.params(frame.camera.view_projection());
  const SliceDrawParams sparams = m.slice_params(frame.camera.view_projection());
  // Near to far: LOD0 queues first, then the slices (early depth rejection behind near trees).
  for (Impl::Species& s : m.species) {
    // The default programs are built in create(); other animation levels compile on first use. A
    // failure there is reported once and the species is skipped rather than crashing the frame.
    if (s.queued[0] > 0) m.report(m.renderer.draw(pass, s.asset, s.gpu[0], 0, s.queued[0], params, stats));
  }
  for (int k = 1; k < kLodLevels; ++k)
    for (Impl::Species& s : m.species)
      if (s.slices && s.queued[static_cast<std::size_t>(k)] > 0)
        m.report(m.slice_renderer.draw(pass, s.asset, *s.slices, k, s.gpu[static_cast<std::size_t>(k)], 0,
                                       s.queued[static_cast<std::size_t>(k)], sparams, stats));
}

Status Forest::draw_depth(const glm::mat4& relative_view_proj, render::PassStats& stats) {
  return draw_depth(relative_view_proj, render::Frustum::from_matrix(relative_view_proj, impl_->origin), stats);
}

Status Forest::draw_depth(const glm::mat4& relative_view_proj, const render::Frustum& frustum, render::PassStats& stats) {
  Impl& m = *impl_;
  if (!m.updated) return ok_status();
  const TreeDrawParams params = m.params(relative_view_proj);
  SliceDrawParams sparams = m.slice_params(relative_view_proj);
  // A directional light's orthographic matrix: slices fade by the light direction (the null space
  // of the matrix's x and y rows), not by the direction to the camera.
  const glm::vec4 row3(relative_view_proj[0][3], relative_view_proj[1][3], relative_view_proj[2][3], relative_view_proj[3][3]);
  if (row3 == glm::vec4(0.0f, 0.0f, 0.0f, 1.0f)) {
    const glm::vec3 rx(relative_view_proj[0][0], relative_view_proj[1][0], relative_view_proj[2][0]);
    const glm::vec3 ry(relative_view_proj[0][1], relative_view_proj[1][1], relative_view_proj[2][1]);
    const glm::vec3 d = glm::cross(rx, ry);
    if (glm::dot(d, d) > 0.0f) sparams.view_direction = glm::vec4(glm::normalize(d), 1.0f);
  }
  std::array<std::vector<InstanceGpu>, kLodLevels> upload;
  for (Impl::Species& s : m.species) {
    m.ensure_spheres(s);
    for (auto& u : upload) u.clear();
    const bool lod = m.settings.lod.enabled && s.slices.has_value();
    for (std::size_t i = 0; i < s.instances.size(); ++i) {
      if (!frustum.intersects(s.spheres[i])) continue;
      // The LOD of the last update (trees beyond max_distance were never selected: LOD2).
      float l = 0.0f;
      if (lod) l = i < s.lod_state.level.size() && !std::isnan(s.lod_state.level[i]) ? s.lod_state.level[i] : 2.0f;
      const LodDraws draws = lod_draws(l, m.settings.lod.transition, m.settings.lod.transition_shift);
      const InstanceGpu g = m.record(s.instances[i], s);
      for (int k = 0; k < draws.count; ++k) {
        InstanceGpu r = g;
        r.lod = glm::vec4(draws.draw[static_cast<std::size_t>(k)].fade, l, 0.0f, 0.0f);
        upload[static_cast<std::size_t>(draws.draw[static_cast<std::size_t>(k)].level)].push_back(r);
      }
    }
    for (int k = 0; k < kLodLevels; ++k) {
      const std::vector<InstanceGpu>& u = upload[static_cast<std::size_t>(k)];
      if (u.empty() || !m.settings.lod.draws_level(k)) continue;
      render::Buffer& buf = s.depth_gpu[static_cast<std::size_t>(k)];
      buf.upload(std::span<const InstanceGpu>(u));
      const auto n = static_cast<std::uint32_t>(u.size());
      if (k == 0) {
        SYLVA_TRY(m.renderer.draw(render::Pass::kShadow, s.asset, buf, 0, n, params, stats));
      } else {
        SYLVA_TRY(m.slice_renderer.draw(render::Pass::kShadow, s.asset, *s.slices, k, buf, 0, n, sparams, stats));
      }
    }
  }
  return ok_status();
}

}  // namespace sylva::vegetation
