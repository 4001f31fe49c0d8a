#include <sylva/terrain/model_renderer.hpp>

#include <sylva/core/log.hpp>
#include <sylva/core/timer.hpp>
#include <sylva/render/frustum.hpp>
#include <sylva/render/shadow_maps.hpp>
#include <sylva/terrain/renderer.hpp>

#include "material_gpu.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace sylva::render::embedded {
void register_terrain_shaders();  // generated from modules/terrain/shaders (cmake/embed_shaders.cmake)
}  // namespace sylva::render::embedded

namespace sylva::terrain {

namespace {
constexpr GLuint kAttrPosition = 0, kAttrNormal = 1;

struct ModelVertex {
  glm::vec3 position;  // relative to the model origin
  glm::vec3 normal;
};

// LOD debug tint per level (the height-field terrain's palette, terrain.frag lod_color).
glm::vec3 level_color(int level) {
  static const glm::vec3 palette[8] = {{0.9f, 0.2f, 0.2f}, {0.95f, 0.6f, 0.1f}, {0.9f, 0.9f, 0.2f},
                                       {0.3f, 0.85f, 0.3f}, {0.2f, 0.8f, 0.85f}, {0.25f, 0.4f, 0.95f},
                                       {0.65f, 0.35f, 0.9f}, {0.9f, 0.9f, 0.9f}};
  return palette[level % 8];
}
}  // namespace

std::vector<glm::vec3> ModelRenderer::vertex_normals(const ModelTree& tree) {
  const std::vector<glm::vec3>& p = tree.positions();
  std::vector<glm::dvec3> sum(p.size(), glm::dvec3(0.0));
  const int leaf = tree.levels() - 1;
  const std::uint32_t side = 1u << leaf;
  for (std::uint32_t z = 0; z < side; ++z) {
    for (std::uint32_t x = 0; x < side; ++x) {
      const Segment& s = tree.segment(tree.index(leaf, x, z));
      for (std::size_t t = 0; t + 2 < s.indices.size(); t += 3) {
        const std::uint32_t a = s.indices[t], b = s.indices[t + 1], c = s.indices[t + 2];
        // The cross product's length is twice the area: area weighting for free.
        const glm::dvec3 n = glm::cross(glm::dvec3(p[b]) - glm::dvec3(p[a]), glm::dvec3(p[c]) - glm::dvec3(p[a]));
        sum[a] += n, sum[b] += n, sum[c] += n;
      }
    }
  }
  std::vector<glm::vec3> out(p.size(), glm::vec3(0.0f, 1.0f, 0.0f));
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double l = glm::length(sum[i]);
    if (l > 0.0) out[i] = glm::vec3(sum[i] / l);
  }
  return out;
}

double ModelRenderer::projected_error(const ModelTree& tree, std::uint32_t segment, const LodView& view) {
  const Segment& s = tree.segment(segment);
  if (s.key.level + 1 >= tree.levels() || s.error_bound <= 0.0f) return 0.0;
  const double delta = s.error_bound;
  const double d = view.distance_to_box(glm::dvec3(s.lo), glm::dvec3(s.hi)) - delta;
  if (d <= 0.0) return std::numeric_limits<double>::infinity();
  return view.k * delta / d;
}

Result<std::unique_ptr<ModelRenderer>> ModelRenderer::create(std::shared_ptr<const ModelTree> tree,
                                                             const ModelRenderSettings& settings) {
  if (!tree) return make_error(ErrorCode::kInvalidArgument, "terrain.model: the renderer needs a model tree");
  std::unique_ptr<ModelRenderer> r(new ModelRenderer());
  r->settings_ = settings;
  r->tree_ = std::move(tree);
  SYLVA_TRY(r->init());
  return r;
}

ModelRenderer::~ModelRenderer() = default;

Result<render::Program> ModelRenderer::shaded_program(bool shadows) const {
  return render::Program::create({"terrain/model.vert", "terrain/model.frag"},
                                 {{"SYLVA_TERRAIN_SHADOWS", shadows ? "1" : "0"}});
}

Status ModelRenderer::init() {
  SYLVA_TRY(validate_params(settings_, "terrain.model"));
  render::embedded::register_terrain_shaders();
  render::embedded::register_render_shaders();
  shaded_with_shadows_ = settings_.receive_shadows;
  auto shaded = shaded_program(shaded_with_shadows_);
  if (!shaded.ok()) return shaded.error();
  shaded_ = std::move(shaded).value();
  auto depth = render::Program::create({"terrain/model.vert", "terrain/model_depth.frag"});
  if (!depth.ok()) return depth.error();
  depth_ = std::move(depth).value();
  detail_ = make_detail_texture();

  const ModelTree& tree = *tree_;
  origin_ = glm::dvec3(tree.root_origin().x, 0.0, tree.root_origin().y);
  const std::vector<glm::vec3> normals = vertex_normals(tree);
  std::vector<ModelVertex> vertices(tree.positions().size());
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    vertices[i] = {glm::vec3(glm::dvec3(tree.positions()[i]) - origin_), normals[i]};
  }
  std::vector<std::uint32_t> indices;
  first_index_.assign(tree.segment_count(), 0);
  for (std::uint32_t i = 0; i < tree.segment_count(); ++i) {
    first_index_[i] = static_cast<std::uint32_t>(indices.size());
    const Segment& s = tree.segment(i);
    indices.insert(indices.end(), s.indices.begin(), s.indices.end());
  }
  if (indices.empty()) return make_error(ErrorCode::kInvalidArgument, "terrain.model: the model tree has no triangles");
  vertices_ = render::Buffer::immutable(std::span<const ModelVertex>(vertices));
  indices_ = render::Buffer::immutable(std::span<const std::uint32_t>(indices));
  vao_ = render::VertexArray::create();
  vao_.attribute(kAttrPosition, 0, 3, GL_FLOAT, offsetof(ModelVertex, position));
  vao_.attribute(kAttrNormal, 0, 3, GL_FLOAT, offsetof(ModelVertex, normal));
  vao_.vertex_buffer(0, vertices_, sizeof(ModelVertex));
  vao_.index_buffer(indices_);
  return {};
}

void ModelRenderer::update(const render::FrameContext& frame) {
  Stopwatch watch;
  stats_ = ModelFrameStats{};
  const LodView view = TerrainRenderer::view_for(frame.camera, frame.viewport);
  const LodSettings lod = settings_.lod.lod();
  // Casters: the camera's LOD decisions without its frustum (as the height-field terrain), so
  // relief beside or behind the camera still shadows the view; each cascade culls by its box.
  // Both come from one traversal.
  shadow_selection_ = ModelSelection{};
  selection_ = select_segments(*tree_, view, lod, settings_.cast_shadows ? &shadow_selection_ : nullptr);
  stats_.selections = 1;
  stats_.segments = static_cast<std::uint32_t>(selection_.segments.size());
  stats_.culled = selection_.culled;
  stats_.triangles = selection_.triangles;
  stats_.segments_per_level.assign(static_cast<std::size_t>(tree_->levels()), 0);
  for (std::uint32_t i : selection_.segments) {
    ++stats_.segments_per_level[static_cast<std::size_t>(tree_->segment(i).key.level)];
    stats_.max_projected_error_px = std::max(stats_.max_projected_error_px, projected_error(*tree_, i, view));
  }
  stats_.select_ms = watch.elapsed_ms();
  stats_.gpu_bytes = vertices_.size() + indices_.size();
}

void ModelRenderer::draw_segments(const render::Program& program, const ModelSelection& selection, bool tint,
                                  render::PassStats& stats, const render::Frustum* cull) {
  vao_.bind();
  for (std::uint32_t i : selection.segments) {
    const Segment& s = tree_->segment(i);
    if (s.indices.empty()) continue;
    if (cull != nullptr && !cull->intersects(render::Aabb{glm::dvec3(s.lo), glm::dvec3(s.hi)})) continue;
    if (tint) program.set("u_flat_color", glm::vec4(level_color(s.key.level), 1.0f));
    glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(s.indices.size()), GL_UNSIGNED_INT,
                   reinterpret_cast<const void*>(static_cast<std::size_t>(first_index_[i]) * sizeof(std::uint32_t)));
    stats.triangles += s.triangle_count();
    ++stats.draw_calls;
  }
  glBindVertexArray(0);
}

void ModelRenderer::draw(render::Pass pass, const render::FrameContext& frame, render::PassStats& stats) {
  if (pass == render::Pass::kTransparent) return;
  const GLboolean cull = glIsEnabled(GL_CULL_FACE);
  glDisable(GL_CULL_FACE);  // overhangs and arches are seen from both sides
  if (pass == render::Pass::kShadow) {
    const render::ShadowCasterContext* cascade = render::active_shadow_cascade();
    if (settings_.cast_shadows && cascade != nullptr && cascade->camera != nullptr) {
      depth_.use();
      depth_.set("u_view_projection", cascade->relative_view_projection);
      depth_.set("u_model", cascade->camera->relative_model(origin_));
      draw_segments(depth_, shadow_selection_, false, stats, &cascade->light_frustum);
    }
  } else {
    if (settings_.receive_shadows != shaded_with_shadows_) {
      auto p = shaded_program(settings_.receive_shadows);
      if (p.ok()) {
        shaded_ = std::move(p).value();
        shaded_with_shadows_ = settings_.receive_shadows;
      } else {
        log_warn("terrain.model: {}", p.error().message);
      }
    }
    shaded_.use();
    shaded_.set("u_view_projection", frame.camera.view_projection());
    shaded_.set("u_model", frame.camera.relative_model(origin_));
    shaded_.set("u_origin", glm::vec3(origin_));
    shaded_.set("u_debug_view", static_cast<int>(settings_.debug_view));
    shaded_.set("u_flat_color", glm::vec4(settings_.flat_color, 1.0f));
    set_material_uniforms(shaded_, settings_.material, climate_);
    detail_.bind(1);
    draw_segments(shaded_, selection_, settings_.debug_view == ModelDebugView::kLodColors, stats, nullptr);
    if (settings_.wireframe) {
      render::PassStats lines;
      shaded_.set("u_debug_view", 2);
      shaded_.set("u_flat_color", glm::vec4(0.05f, 0.05f, 0.05f, 1.0f));
      glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
      GLint depth_func = GL_GREATER;
      glGetIntegerv(GL_DEPTH_FUNC, &depth_func);
      glDepthFunc(depth_func == GL_GREATER ? GL_GEQUAL : GL_LEQUAL);
      draw_segments(shaded_, selection_, false, lines, nullptr);
      glDepthFunc(static_cast<GLenum>(depth_func));
      glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
      stats.draw_calls += lines.draw_calls;
    }
  }
  if (cull) glEnable(GL_CULL_FACE);
}

}  // namespace sylva::terrain
