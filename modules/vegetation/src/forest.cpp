#include <sylva/vegetation/forest.hpp>

#include <sylva/core/assert.hpp>
#include <sylva/core/log.hpp>
#include <sylva/core/wind.hpp>
#include <sylva/render/frustum.hpp>
#include <sylva/render/shadow_maps.hpp>

#include <fmt/format.h>

#include <chrono>
#include <cmath>

namespace sylva::vegetation {

struct Forest::Impl {
  struct Species {
    TreeModel model;
    TreeMesh mesh;
    TreeAsset asset;
    std::vector<TreeInstance> instances;
    std::vector<std::uint32_t> visible;
    render::Buffer gpu;                   // visible records, in draw order
    render::Buffer depth_gpu;             // records culled for the last draw_depth()
    glm::vec3 sphere_center{0.0f};        // object space
    float sphere_radius = 0.0f;
  };
  ForestSettings settings;
  TreeRenderer renderer;
  std::vector<Species> species;
  ForestStats stats;
  glm::dvec3 origin{0.0};
  double time = 0.0;
  WindField wind;  // the last update's wind (copied: the frame's reference may not outlive it)
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
  Forest f;
  f.impl_->settings = settings;
  f.impl_->renderer = std::move(r).value();
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
  s.gpu = render::Buffer::dynamic(sizeof(InstanceGpu));
  s.depth_gpu = render::Buffer::dynamic(sizeof(InstanceGpu));
  impl_->species.push_back(std::move(s));
  impl_->stats.species.emplace_back();
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
  return ok_status();
}

std::size_t Forest::species_count() const { return impl_->species.size(); }
const TreeModel& Forest::model(int species) const { return impl_->at(species).model; }
const TreeMesh& Forest::mesh(int species) const { return impl_->at(species).mesh; }
const TreeAsset& Forest::asset(int species) const { return impl_->at(species).asset; }
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
  m.wind = frame.wind;
  // Season: wrapped in double so a long-running animation keeps full precision.
  const double season = static_cast<double>(st.shading.season) + static_cast<double>(st.season_speed) * time;
  m.season = static_cast<float>(season - std::floor(season));
  m.renderer.set_frame(make_animation_gpu(st.animation, time), frame.wind.frame(time, m.origin).gpu);
  const render::Frustum frustum = frame.camera.frustum();
  const double max_d2 = static_cast<double>(st.max_distance) * static_cast<double>(st.max_distance);
  m.stats.instances = 0;
  m.stats.visible = 0;
  for (std::size_t si = 0; si < m.species.size(); ++si) {
    Impl::Species& s = m.species[si];
    s.visible.clear();
    std::vector<InstanceGpu> upload;
    for (std::size_t i = 0; i < s.instances.size(); ++i) {
      const TreeInstance& t = s.instances[i];
      const render::Sphere sphere = Impl::sphere(s, t, st.cull_margin);
      const glm::dvec3 d = sphere.center - m.origin;
      const double reach = std::max(0.0, std::sqrt(glm::dot(d, d)) - sphere.radius);
      const bool near_enough = reach * reach <= max_d2;
      if (!near_enough) continue;
      if (st.frustum_culling && !frustum.intersects(sphere)) continue;
      s.visible.push_back(static_cast<std::uint32_t>(i));
      upload.push_back(make_instance_gpu(t, m.origin, frame.wind, time, st.animation));
    }
    if (!upload.empty()) s.gpu.upload(std::span<const InstanceGpu>(upload));
    m.stats.species[si] = {s.instances.size(), s.visible.size()};
    m.stats.instances += s.instances.size();
    m.stats.visible += s.visible.size();
  }
  m.updated = true;
  m.stats.update_cpu_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

void Forest::draw(render::Pass pass, const render::FrameContext& frame, render::PassStats& stats) {
  Impl& m = *impl_;
  if (!m.updated) return;
  if (pass == render::Pass::kShadow) {
    // Inside ShadowMaps::render (the scene's shadow hook): draw into the cascade being rendered.
    if (const render::ShadowCasterContext* c = render::active_shadow_cascade()) {
      const Status st = draw_depth(c->relative_view_projection, c->light_frustum, stats);
      if (!st.ok() && !m.reported_error) {
        log_error("forest: {}", st.error().message);
        m.reported_error = true;
      }
    }
    return;
  }
  if (pass != render::Pass::kOpaque) return;
  const TreeDrawParams params = m.params(frame.camera.view_projection());
  for (Impl::Species& s : m.species) {
    if (s.visible.empty()) continue;
    // The default programs are built in create(); other animation levels compile on first use. A
    // failure there is reported once and the species is skipped rather than crashing the frame.
    const Status st = m.renderer.draw(pass, s.asset, s.gpu, 0, static_cast<std::uint32_t>(s.visible.size()), params, stats);
    if (!st.ok() && !m.reported_error) {
      log_error("forest: {}", st.error().message);
      m.reported_error = true;
    }
  }
}

Status Forest::draw_depth(const glm::mat4& relative_view_proj, render::PassStats& stats) {
  return draw_depth(relative_view_proj, render::Frustum::from_matrix(relative_view_proj, impl_->origin), stats);
}

Status Forest::draw_depth(const glm::mat4& relative_view_proj, const render::Frustum& frustum, render::PassStats& stats) {
  Impl& m = *impl_;
  if (!m.updated) return ok_status();
  const TreeDrawParams params = m.params(relative_view_proj);
  for (Impl::Species& s : m.species) {
    std::vector<InstanceGpu> upload;
    for (std::size_t i = 0; i < s.instances.size(); ++i)
      if (frustum.intersects(Impl::sphere(s, s.instances[i], m.settings.cull_margin)))
        upload.push_back(make_instance_gpu(s.instances[i], m.origin, m.wind, m.time, m.settings.animation));
    if (upload.empty()) continue;
    s.depth_gpu.upload(std::span<const InstanceGpu>(upload));
    SYLVA_TRY(m.renderer.draw(render::Pass::kShadow, s.asset, s.depth_gpu, 0, static_cast<std::uint32_t>(upload.size()), params, stats));
  }
  return ok_status();
}

}  // namespace sylva::vegetation
