#include <sylva/terrain/renderer.hpp>

#include <sylva/core/log.hpp>
#include <sylva/core/timer.hpp>
#include <sylva/render/shadow_maps.hpp>
#include <sylva/terrain/frame_mesh.hpp>
#include <sylva/terrain/height_texture.hpp>

#include "far_material.hpp"
#include "material_gpu.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace sylva::render::embedded {
void register_terrain_shaders();  // generated from modules/terrain/shaders (cmake/embed_shaders.cmake)
}  // namespace sylva::render::embedded

namespace sylva::terrain {

namespace {
constexpr GLuint kAttrGrid = 0, kAttrHeight = 1, kAttrSkirt = 2, kAttrCentre = 3;

// The colour-pass program of one debug view, with or without received shadows, with the air
// per pixel, per vertex or off, fetching the detail scales from first_scale on (terrain.frag,
// chunk.vert, material.glsl).
// vertex_sky: per_vertex air with the sky radiance per vertex as well (SYLVA_TERRAIN_AIR 3).
// baked: the material read from the baked far material (SYLVA_TERRAIN_BAKED, first_scale 3).
Result<render::Program> make_shaded_program(bool shadows, DebugView view, AerialPerspective air, int first_scale = 0,
                                            bool vertex_sky = false, bool baked = false) {
  return render::Program::create({"terrain/chunk.vert", "terrain/terrain.frag"},
                                 {{"SYLVA_TERRAIN_SHADOWS", shadows ? "1" : "0"},
                                  {"SYLVA_TERRAIN_VIEW", std::to_string(static_cast<int>(view))},
                                  {"SYLVA_TERRAIN_AIR", vertex_sky ? "3" : std::to_string(static_cast<int>(air))},
                                  {"SYLVA_TERRAIN_FIRST_SCALE", std::to_string(first_scale)},
                                  {"SYLVA_TERRAIN_BAKED", baked ? "1" : "0"}});
}

bool uses_material(DebugView view) { return view == DebugView::kShaded || view == DebugView::kMaterials; }

// shaded_coarse_ for a view: the variants without the finer detail scales (empty where the view
// has no material). Errors: the first variant that does not compile.
Status make_coarse_programs(bool shadows, DebugView view, AerialPerspective air, render::Program (&coarse)[4]) {
  for (int k = 0; k < 4; ++k) {
    coarse[k] = {};
    if (!uses_material(view) || (k == 3 && air != AerialPerspective::kPerVertex)) continue;
    auto p = make_shaded_program(shadows, view, air, std::min(k + 1, 3), k == 3);
    if (!p.ok()) return p.error();
    coarse[k] = std::move(p).value();
  }
  return {};
}

// shaded_baked_: [0] like shaded_coarse_[2], [1] like shaded_coarse_[3], reading the baked far
// material; empty unless far_material is baked and the view is the shaded one (the materials
// view shows the layer weights, which the bake does not keep).
Status make_baked_programs(bool shadows, DebugView view, AerialPerspective air, FarMaterial far,
                           render::Program (&baked)[2]) {
  for (int k = 0; k < 2; ++k) {
    baked[k] = {};
    if (far != FarMaterial::kBaked || view != DebugView::kShaded || (k == 1 && air != AerialPerspective::kPerVertex)) {
      continue;
    }
    auto p = make_shaded_program(shadows, view, air, 3, k == 1, true);
    if (!p.ok()) return p.error();
    baked[k] = std::move(p).value();
  }
  return {};
}

// A far chunk takes the baked material where one field sample spans at most this many pixels at
// its nearest corner (README "vs CDLOD": the measured picture against the computed material).
constexpr double kBakedMaxTexelPx = 4.0;
}  // namespace

LodView TerrainRenderer::view_for(const render::Camera& camera, glm::ivec2 viewport) {
  const render::PerspectiveParams& p = camera.perspective();
  const int w = std::max(viewport.x, 1), h = std::max(viewport.y, 1);
  const double far_m = (p.far_plane > p.near_plane && std::isfinite(p.far_plane)) ? p.far_plane
                                                                                   : std::numeric_limits<double>::infinity();
  return LodView::perspective(camera.position(), glm::dvec3(camera.forward()), glm::dvec3(camera.up()), p.fov_y, w, h,
                              p.near_plane, far_m);
}

Result<std::unique_ptr<TerrainRenderer>> TerrainRenderer::create(std::shared_ptr<const ChunkTree> tree,
                                                                 const HeightField* field,
                                                                 const TerrainRenderSettings& settings) {
  if (!tree || !tree->has_meshes()) {
    return make_error(ErrorCode::kInvalidArgument,
                      "terrain: the renderer needs a chunk tree built with keep_meshes (or a ChunkStreamer)");
  }
  std::unique_ptr<TerrainRenderer> r(new TerrainRenderer());
  r->settings_ = settings;
  r->tree_ = std::move(tree);
  r->meshes_ = tree_meshes(*r->tree_);
  SYLVA_TRY(r->init(field));
  return r;
}

Result<std::unique_ptr<TerrainRenderer>> TerrainRenderer::create(std::unique_ptr<ChunkStreamer> streamer,
                                                                 const HeightField* field,
                                                                 const TerrainRenderSettings& settings) {
  if (!streamer) return make_error(ErrorCode::kInvalidArgument, "terrain: null chunk streamer");
  std::unique_ptr<TerrainRenderer> r(new TerrainRenderer());
  r->settings_ = settings;
  // The streamer's tree lives as long as the streamer, which the renderer owns.
  r->tree_ = std::shared_ptr<const ChunkTree>(std::shared_ptr<const ChunkTree>{}, &streamer->tree());
  r->streamer_ = std::move(streamer);
  r->meshes_ = r->streamer_->meshes();
  SYLVA_TRY(r->init(field));
  return r;
}

TerrainRenderer::~TerrainRenderer() = default;

Result<RegionRebuild> TerrainRenderer::apply_height_edit(const HeightField& field, int x0, int z0, int x1, int z1) {
  if (streamer_) return apply_streamed_edit(field, x0, z0, x1, z1);
  // Copy-on-write: the chunk meshes are copied (a few MB at 257^2, milliseconds), the expensive
  // triangulation runs only for the chunks the edit reaches.
  auto tree = std::make_shared<ChunkTree>(*tree_);
  auto changed = tree->rebuild_region(field, x0, z0, x1, z1);
  if (!changed.ok()) return changed.error();
  tree_ = std::move(tree);
  meshes_ = tree_meshes(*tree_);
  selector_ = std::make_unique<LodSelector>(*tree_);
  shadow_selector_ = std::make_unique<LodSelector>(*tree_);
  selection_ = &empty_selection_;
  shadow_selection_ = &empty_selection_;
  std::vector<std::uint32_t> dirty = changed->rebuilt;
  dirty.insert(dirty.end(), changed->updated.begin(), changed->updated.end());
  for (std::uint32_t i : dirty) {
    auto it = gpu_.find(i);
    if (it == gpu_.end()) continue;
    gpu_bytes_ -= it->second.bytes;
    gpu_.erase(it);
  }
  seams_.invalidate(dirty);
  update_height_textures(field, x0, z0, x1, z1);
  return changed;
}

// A streamed terrain (streaming.hpp apply_height_edit): rebuilt chunks replace the file's in the
// streamer; morph data may change in any chunk (a raised root bound), so every GPU mesh and seam
// is dropped and re-made from the streamer's meshes as they are drawn.
Result<RegionRebuild> TerrainRenderer::apply_streamed_edit(const HeightField& field, int x0, int z0, int x1, int z1) {
  auto changed = streamer_->apply_height_edit(field, x0, z0, x1, z1);
  if (!changed.ok()) return changed.error();
  tree_ = std::shared_ptr<const ChunkTree>(std::shared_ptr<const ChunkTree>{}, &streamer_->tree());
  meshes_ = streamer_->meshes();
  selector_ = std::make_unique<LodSelector>(*tree_);
  shadow_selector_ = std::make_unique<LodSelector>(*tree_);
  selection_ = &empty_selection_;
  shadow_selection_ = &empty_selection_;
  gpu_.clear();
  gpu_bytes_ = 0;
  seams_ = SeamCache();
  update_height_textures(field, x0, z0, x1, z1);
  return changed;
}

void TerrainRenderer::update_height_textures(const HeightField& field, int x0, int z0, int x1, int z1) {
  if (has_heights_ && heights_.width() == field.columns() && heights_.height() == field.rows()) {
    height_texels_uploaded_ += update_height_texture(heights_, field, x0, z0, x1, z1);
  } else if (has_heights_) {
    auto heights = make_height_texture(field);
    if (heights.ok()) {
      heights_ = std::move(heights).value();
      height_texels_uploaded_ += static_cast<std::int64_t>(field.columns()) * field.rows();
    } else {
      log_warn("{}; normals come from the triangles", heights.error().message);
      has_heights_ = false;
      shape_ = {};
    }
  }
  if (!shape_) {
    far_bake_.reset();
    return;
  }
  const SampleRect changed = update_shape_texture(shape_, field, shape_radius_m_, x0, z0, x1, z1);
  // A field of another size gets a new bake on the next draw; else only the changed samples.
  if (far_bake_ && (far_bake_->texture().width() != field.columns() || far_bake_->texture().height() != field.rows())) {
    far_bake_.reset();
  }
  if (far_bake_) far_bake_->mark_dirty(changed);
}

Status TerrainRenderer::init(const HeightField* field) {
  SYLVA_TRY(validate_params(settings_, "terrain"));
  render::embedded::register_terrain_shaders();
  render::embedded::register_render_shaders();
  shaded_with_shadows_ = false;  // until a frame's shadow pass runs (draw)
  shaded_view_ = settings_.debug_view;
  shaded_air_ = settings_.aerial_perspective;
  shaded_far_ = settings_.far_material;
  auto shaded = make_shaded_program(shaded_with_shadows_, shaded_view_, shaded_air_);
  if (!shaded.ok()) return shaded.error();
  shaded_ = std::move(shaded).value();
  SYLVA_TRY(make_coarse_programs(shaded_with_shadows_, shaded_view_, shaded_air_, shaded_coarse_));
  SYLVA_TRY(make_baked_programs(shaded_with_shadows_, shaded_view_, shaded_air_, shaded_far_, shaded_baked_));
  auto depth = render::Program::create({"terrain/chunk.vert", "terrain/depth.frag"});
  if (!depth.ok()) return depth.error();
  depth_ = std::move(depth).value();
  auto bounds = render::Program::create({"terrain/bounds.vert", "terrain/bounds.frag"});
  if (!bounds.ok()) return bounds.error();
  bounds_ = std::move(bounds).value();

  detail_ = make_detail_texture();
  if (field != nullptr && field->columns() > 0 && field->rows() > 0) {
    auto heights = make_height_texture(*field);
    if (heights.ok()) {
      heights_ = std::move(heights).value();
      has_heights_ = true;
      field_spacing_m_ = static_cast<float>(field->spacing());
      shape_radius_m_ = settings_.material.curvature_radius_m;
      shape_ = std::move(make_shape_texture(*field, shape_radius_m_)).value();  // same size: fits too
    } else {
      log_warn("{}; normals come from the triangles", heights.error().message);
    }
  }

  batch_vao_ = render::VertexArray::create();
  batch_vao_.attribute_int(kAttrGrid, 0, 2, GL_UNSIGNED_INT, offsetof(BatchVertex, gx));
  batch_vao_.attribute(kAttrHeight, 0, 3, GL_FLOAT, offsetof(BatchVertex, height));
  batch_vao_.attribute(kAttrSkirt, 0, 1, GL_FLOAT, offsetof(BatchVertex, skirt));
  batch_buffer_ = render::Buffer::dynamic(64 * sizeof(BatchVertex), GL_STREAM_DRAW);
  shadow_batch_buffer_ = render::Buffer::dynamic(64 * sizeof(BatchVertex), GL_STREAM_DRAW);
  batch_vao_.vertex_buffer(0, batch_buffer_, sizeof(BatchVertex));
  bounds_vao_ = render::VertexArray::create();
  bounds_vao_.attribute(0, 0, 3, GL_FLOAT, 0);
  bounds_buffer_ = render::Buffer::dynamic(64 * sizeof(glm::vec3), GL_STREAM_DRAW);
  bounds_vao_.vertex_buffer(0, bounds_buffer_, sizeof(glm::vec3));

  selector_ = std::make_unique<LodSelector>(*tree_);
  shadow_selector_ = std::make_unique<LodSelector>(*tree_);
  selection_ = &empty_selection_;
  shadow_selection_ = &empty_selection_;
  return {};
}

TerrainRenderer::GpuMesh* TerrainRenderer::gpu_mesh(std::uint32_t chunk) {
  auto it = gpu_.find(chunk);
  if (it != gpu_.end()) {
    it->second.last_used = frame_number_;
    return &it->second;
  }
  const ChunkMesh* m = meshes_(chunk);
  if (m == nullptr || m->indices.empty()) return nullptr;
  GpuMesh g;
  static_assert(sizeof(ChunkVertex) == 24, "ChunkVertex layout is uploaded as is");
  g.vertices = render::Buffer::immutable(std::span<const ChunkVertex>(m->vertices));
  g.indices = render::Buffer::immutable(std::span<const std::uint32_t>(m->indices));
  g.vao = render::VertexArray::create();
  g.vao.attribute_int(kAttrGrid, 0, 2, GL_UNSIGNED_INT, offsetof(ChunkVertex, gx));
  g.vao.attribute(kAttrHeight, 0, 3, GL_FLOAT, offsetof(ChunkVertex, height));
  g.vao.attribute(kAttrCentre, 0, 1, GL_UNSIGNED_BYTE, offsetof(ChunkVertex, centre));
  g.vao.vertex_buffer(0, g.vertices, sizeof(ChunkVertex));
  g.vao.index_buffer(g.indices);
  g.index_count = static_cast<std::uint32_t>(m->indices.size());
  g.bytes = g.vertices.size() + g.indices.size();
  g.last_used = frame_number_;
  gpu_bytes_ += g.bytes;
  ++stats_.uploads;
  // LRU eviction of meshes not drawn this frame.
  const std::size_t budget = static_cast<std::size_t>(settings_.gpu_cache_mb * 1048576.0);
  if (gpu_bytes_ > budget) {
    std::vector<std::pair<std::uint64_t, std::uint32_t>> old;
    for (const auto& [id, mesh] : gpu_)
      if (mesh.last_used < frame_number_) old.emplace_back(mesh.last_used, id);
    std::sort(old.begin(), old.end());
    for (const auto& [used, id] : old) {
      if (gpu_bytes_ <= budget) break;
      gpu_bytes_ -= gpu_.at(id).bytes;
      gpu_.erase(id);
    }
  }
  return &gpu_.emplace(chunk, std::move(g)).first->second;
}

void TerrainRenderer::assemble_batch(const Selection& selection, std::vector<BatchVertex>& batch) {
  // Seam or skirt batch: vertex = grid point, height / morph target / morph error, skirt depth.
  batch.clear();
  auto push = [&](const ChunkVertex& v, float skirt) {
    batch.push_back(BatchVertex{v.gx, v.gz, v.height, v.morph_target, v.morph_error, skirt});
  };
  for (const SelectedChunk& s : selection.chunks) {
    const ChunkMesh* m = meshes_(s.index);
    if (m == nullptr) continue;
    for (int e = 0; e < 4; ++e) {
      const Edge edge = static_cast<Edge>(e);
      if (settings_.lod.crack_fix == CrackFix::kSeams) {
        const std::uint32_t coarse = s.coarser_neighbour[static_cast<std::size_t>(e)];
        if (coarse == kNoChunk || meshes_(coarse) == nullptr) continue;
        const Seam& seam = seams_.get(*tree_, meshes_, s.index, edge, coarse);
        const std::uint32_t n = static_cast<std::uint32_t>(m->vertices.size());
        for (std::uint32_t i : seam.indices) push(i < n ? m->vertices[i] : seam.extra_vertices[i - n], 0.0f);
        if (&selection == selection_) stats_.seam_triangles += seam.indices.size() / 3;
      } else if (settings_.lod.crack_fix == CrackFix::kSkirts) {
        const float depth = skirt_depth(*tree_, s, edge);
        const auto& ev = m->edges[static_cast<std::size_t>(e)];
        const bool increasing = (edge == kWest || edge == kNorth);
        for (std::size_t i = 0; i + 1 < ev.size(); ++i) {
          const ChunkVertex& a = m->vertices[increasing ? ev[i] : ev[ev.size() - 1 - i]];
          const ChunkVertex& b = m->vertices[increasing ? ev[i + 1] : ev[ev.size() - 2 - i]];
          push(b, 0.0f), push(a, 0.0f), push(a, depth);
          push(b, 0.0f), push(a, depth), push(b, depth);
          if (&selection == selection_) stats_.skirt_triangles += 2;
        }
      }
    }
  }
}

void TerrainRenderer::update(const render::FrameContext& frame) {
  Stopwatch watch;
  ++frame_number_;
  stats_ = TerrainFrameStats{};
  if (streamer_) streamer_->update();
  const LodView view = view_for(frame.camera, frame.viewport);
  Residency residency;
  if (streamer_) residency = streamer_->residency();
  selection_ = &selector_->select(view, settings_.lod, streamer_ ? &residency : nullptr);
  stats_.selection = selection_->stats;
  if (streamer_) streamer_->count_misses(selection_->stats.substituted);
  frame_ = make_vertex_frame(*tree_, view, settings_.lod);

  assemble_batch(*selection_, batch_);
  batch_uploaded_ = false;
  // Shadow casters: the same LOD decisions without the camera frustum, so hills behind or beside
  // the camera still cast into view; each cascade culls them with its own light frustum. Where
  // both selections hold a chunk it is the same chunk, so self-shadowing matches the drawn surface.
  if (settings_.cast_shadows) {
    LodSettings unculled = settings_.lod;
    unculled.frustum_cull = false;
    shadow_selection_ = &shadow_selector_->select(view, unculled, streamer_ ? &residency : nullptr);
    assemble_batch(*shadow_selection_, shadow_batch_);
    shadow_batch_uploaded_ = false;
  } else {
    shadow_selection_ = &empty_selection_;
    shadow_batch_.clear();
  }
  bounds_lines_.clear();
  if (settings_.chunk_bounds) {
    for (const SelectedChunk& s : selection_->chunks) {
      glm::dvec3 lo, hi;
      tree_->chunk_bounds(s.index, lo, hi);
      const glm::vec3 a(lo - view.position), b(hi - view.position);
      const glm::vec3 c[8] = {{a.x, a.y, a.z}, {b.x, a.y, a.z}, {b.x, a.y, b.z}, {a.x, a.y, b.z},
                              {a.x, b.y, a.z}, {b.x, b.y, a.z}, {b.x, b.y, b.z}, {a.x, b.y, b.z}};
      const int edges[12][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6}, {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
      for (const auto& e : edges) {
        bounds_lines_.push_back(c[e[0]]);
        bounds_lines_.push_back(c[e[1]]);
      }
    }
  }
  stats_.update_ms = watch.elapsed_ms();
  stats_.gpu_bytes = gpu_bytes_;
}

bool TerrainRenderer::beyond_shadow_maps(const glm::dvec3& lo, const glm::dvec3& hi) const {
  if (shadow_pass_frame_ != frame_number_ || shadow_cascades_.empty()) return false;
  for (const CascadeFootprint& f : shadow_cascades_) {
    const glm::dvec3 a = lo - f.origin, b = hi - f.origin;
    bool outside = false;
    for (const glm::vec4& plane : f.sides) {
      // The box corner farthest along the plane's inward normal.
      const glm::dvec3 n(plane);
      const glm::dvec3 corner(n.x > 0.0 ? b.x : a.x, n.y > 0.0 ? b.y : a.y, n.z > 0.0 ? b.z : a.z);
      if (glm::dot(n, corner) + double(plane.w) < -f.margin_m) {
        outside = true;
        break;
      }
    }
    if (!outside) return false;
  }
  return true;
}

std::int64_t TerrainRenderer::far_material_texels_baked() const {
  return far_bake_ ? far_bake_->texels_baked() : 0;
}

bool TerrainRenderer::bake_far_material() {
  if (!far_bake_ && !far_bake_failed_) {
    auto bake = FarMaterialBake::create(shape_.width(), shape_.height());
    if (bake.ok()) {
      far_bake_ = std::make_unique<FarMaterialBake>(std::move(bake).value());
    } else {
      log_warn("terrain: far_material baked: {}; far chunks compute their material", bake.error().message);
      far_bake_failed_ = true;
    }
  }
  if (!far_bake_) return false;
  far_bake_->refresh(heights_, shape_, material_uniforms(settings_.material, climate_));
  return true;
}

void TerrainRenderer::set_frame_uniforms(const render::Program& program, const glm::mat4& view_projection) const {
  program.set("u_origin", frame_.origin);
  program.set("u_camera", frame_.camera);
  program.set("u_spacing", frame_.spacing);
  program.set("u_k_over_tau", frame_.k_over_tau);
  program.set("u_morph_start", frame_.morph_start);
  program.set("u_morph", frame_.morph ? 1 : 0);
  program.set("u_view_projection", view_projection);
  program.set("u_field_size", glm::ivec2(tree_->field_columns(), tree_->field_rows()));
}

void TerrainRenderer::draw_geometry(const render::Program& program, const glm::mat4& view_projection,
                                    bool debug_levels, render::PassStats& stats, bool shadow,
                                    const render::Frustum* cull,
                                    const std::vector<const render::Program*>* chunk_programs) {
  const Selection& selection = shadow ? *shadow_selection_ : *selection_;
  const std::vector<BatchVertex>& batch = shadow ? shadow_batch_ : batch_;
  render::Buffer& buffer = shadow ? shadow_batch_buffer_ : batch_buffer_;
  bool& uploaded = shadow ? shadow_batch_uploaded_ : batch_uploaded_;
  program.use();
  set_frame_uniforms(program, view_projection);
  glVertexAttrib1f(kAttrSkirt, 0.0f);   // bodies have no skirt attribute array
  glVertexAttrib1f(kAttrCentre, 0.0f);  // seams and skirts hold edge points only, never centres
  // chunk.vert clips the padding beyond a field that does not fill the root grid.
  const auto padded_intervals = static_cast<int>(tree_->root_intervals());
  const bool padded = tree_->field_columns() - 1 < padded_intervals || tree_->field_rows() - 1 < padded_intervals;
  if (padded) {
    glEnable(GL_CLIP_DISTANCE0);
    glEnable(GL_CLIP_DISTANCE1);
  }
  // Chunk bodies face up (counter-clockwise from above, chunk_tree.hpp), so a body triangle seen
  // from behind lies behind the ground in front of it: culled in the colour pass, half of a
  // grazing view's triangles never reach the rasteriser. The shadow pass keeps both faces (the
  // sun may see the field from below its horizon line), and seam fans are vertical (drawn after).
  // Skirts only hang down from the edges: a crack between two chunks is then closed partly by
  // the far body's back face seen through it, so with skirts the bodies keep both faces
  // (SkirtsAlsoLeaveNoCracksOnTheCliffField: 613 background pixels with the bodies culled).
  const bool cull_backs = !shadow && settings_.lod.crack_fix != CrackFix::kSkirts;
  GLint front_face = GL_CCW, cull_mode = GL_BACK;
  if (cull_backs) {
    glGetIntegerv(GL_FRONT_FACE, &front_face);
    glGetIntegerv(GL_CULL_FACE_MODE, &cull_mode);
    glFrontFace(GL_CCW);
    glCullFace(GL_BACK);
    glEnable(GL_CULL_FACE);
  }
  const render::Program* current = &program;
  for (std::size_t i = 0; i < selection.chunks.size(); ++i) {
    const SelectedChunk& s = selection.chunks[i];
    if (cull != nullptr) {
      render::Aabb box;
      tree_->chunk_bounds(s.index, box.min, box.max);
      if (!cull->intersects(box)) continue;
    }
    GpuMesh* g = gpu_mesh(s.index);
    if (g == nullptr) continue;
    if (chunk_programs != nullptr && (*chunk_programs)[i] != current) {
      current = (*chunk_programs)[i];
      current->use();
    }
    if (debug_levels) program.set("u_level", tree_->chunk(s.index).key.level);
    g->vao.bind();
    glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(g->index_count), GL_UNSIGNED_INT, nullptr);
    stats.triangles += g->index_count / 3;
    ++stats.draw_calls;
  }
  if (cull_backs) {
    glDisable(GL_CULL_FACE);
    glFrontFace(static_cast<GLenum>(front_face));
    glCullFace(static_cast<GLenum>(cull_mode));
  }
  if (current != &program) program.use();
  if (!batch.empty()) {
    // Uploaded once per frame (the shadow batch is drawn once per cascade).
    if (!uploaded) {
      buffer.upload(std::span<const BatchVertex>(batch));
      uploaded = true;
    }
    batch_vao_.vertex_buffer(0, buffer, sizeof(BatchVertex));
    if (debug_levels) program.set("u_level", 7);
    batch_vao_.bind();
    glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(batch.size()));
    stats.triangles += batch.size() / 3;
    ++stats.draw_calls;
  }
  glBindVertexArray(0);
  if (padded) {
    glDisable(GL_CLIP_DISTANCE0);
    glDisable(GL_CLIP_DISTANCE1);
  }
}

void TerrainRenderer::draw(render::Pass pass, const render::FrameContext& frame, render::PassStats& stats) {
  if (pass == render::Pass::kTransparent) return;
  const GLboolean cull = glIsEnabled(GL_CULL_FACE);
  glDisable(GL_CULL_FACE);  // seam fans are vertical and may face either way
  if (pass == render::Pass::kShadow) {
    const render::ShadowCasterContext* cascade = render::active_shadow_cascade();
    if (cascade != nullptr) {
      if (shadow_pass_frame_ != frame_number_) shadow_cascades_.clear();
      shadow_pass_frame_ = frame_number_;
      // Margin: the normal offset (at most normal_offset 8 x (pcf_radius 3 + 1) texels,
      // ShadowSettings' limits) plus the bilinear PCF reach (pcf_radius + 1 texels).
      CascadeFootprint f;
      for (int i = 0; i < 4; ++i) f.sides[static_cast<std::size_t>(i)] = cascade->light_frustum.planes()[static_cast<std::size_t>(i)];
      f.origin = cascade->light_frustum.origin();
      f.margin_m = 40.0 * cascade->texel_size;
      shadow_cascades_.push_back(f);
    }
    if (settings_.cast_shadows && cascade != nullptr) {
      draw_geometry(depth_, cascade->relative_view_projection, false, stats, true, &cascade->light_frustum);
    }
  } else {
    // Shadows are received (compiled in) only on frames whose shadow pass ran: with the host's
    // shadows off, sylva_shadow returns 1 for every pixel, but llvmpipe would still run its
    // cascade loop and PCF taps under an all-off mask (README "vs CDLOD": 52 ms of 178 per race
    // frame, same picture byte for byte).
    const bool receive = settings_.receive_shadows && shadow_pass_frame_ == frame_number_;
    if (receive != shaded_with_shadows_ || settings_.debug_view != shaded_view_ ||
        settings_.aerial_perspective != shaded_air_ || settings_.far_material != shaded_far_) {
      const AerialPerspective air = settings_.aerial_perspective;
      const FarMaterial far = settings_.far_material;
      auto p = make_shaded_program(receive, settings_.debug_view, air);
      Status coarse = p.ok() ? make_coarse_programs(receive, settings_.debug_view, air, shaded_coarse_) : Status{};
      if (coarse.ok() && p.ok()) coarse = make_baked_programs(receive, settings_.debug_view, air, far, shaded_baked_);
      for (int k = 0; k < 2 && coarse.ok() && p.ok(); ++k) {
        unshadowed_far_[k] = {};
        if (!receive || !uses_material(settings_.debug_view) || (k == 1 && air != AerialPerspective::kPerVertex)) continue;
        auto u = make_shaded_program(false, settings_.debug_view, air, 3, k == 1);
        if (u.ok()) {
          unshadowed_far_[k] = std::move(u).value();
        } else {
          coarse = u.error();
        }
      }
      if (p.ok() && !coarse.ok()) p = coarse.error();
      if (p.ok()) {
        shaded_ = std::move(p).value();
        shaded_with_shadows_ = receive;
        shaded_view_ = settings_.debug_view;
        shaded_air_ = air;
        shaded_far_ = far;
      } else {
        log_warn("terrain: {}", p.error().message);
      }
    }
    const glm::mat4 vp = frame.camera.view_projection();
    // Each view's program has only the uniforms its view reads (the others are compiled out).
    const DebugView view = shaded_view_;
    const bool coarse = uses_material(view) && static_cast<bool>(shaded_coarse_[0]);
    // The baked far material: made on first use, refreshed where the field or material changed.
    const bool baked = coarse && shaded_baked_[0] && shape_ && bake_far_material();
    const int programs = coarse ? 9 : 1;
    for (int k = 0; k < programs; ++k) {
      const render::Program& p = k == 0   ? shaded_
                                 : k <= 4 ? shaded_coarse_[k - 1]
                                 : k <= 6 ? shaded_baked_[k - 5]
                                          : unshadowed_far_[k - 7];
      if (!p) continue;
      p.use();
      if (view == DebugView::kFlat) {
        p.set("u_flat_color", glm::vec4(0.6f, 0.6f, 0.6f, 1.0f));
      } else {
        p.set("u_has_shape", shape_ ? 1 : 0);
        // The baked variants read the material from the bake (its uniforms are compiled out).
        if (uses_material(view) && (k < 5 || k > 6)) set_material_uniforms(p, settings_.material, climate_);
      }
      if (k > 0) set_frame_uniforms(p, vp);
    }
    detail_.bind(1);
    if (shape_) shape_.bind(2);
    if (baked) far_bake_->texture().bind(3);
    const bool levels = view == DebugView::kLodColors;
    std::vector<const render::Program*>& chunk_programs = chunk_programs_;  // no allocation per frame
    chunk_programs.clear();
    if (coarse) {
      // Per chunk, the variant without the detail scales that have faded out on all of it: the
      // nearest corner of its box in view depth bounds its pixels' footprints (first_detail_scale).
      const glm::dvec3 eye = frame.camera.position(), forward(frame.camera.forward());
      const render::PerspectiveParams& lens = frame.camera.perspective();
      chunk_programs.reserve(selection_->chunks.size());
      stats_.far_baked_chunks = 0;
      stats_.beyond_shadow_chunks = 0;
      for (const SelectedChunk& s : selection_->chunks) {
        glm::dvec3 lo, hi;
        tree_->chunk_bounds(s.index, lo, hi);
        double depth = std::numeric_limits<double>::infinity();
        for (int c = 0; c < 8; ++c) {
          const glm::dvec3 corner((c & 1) ? hi.x : lo.x, (c & 2) ? hi.y : lo.y, (c & 4) ? hi.z : lo.z);
          depth = std::min(depth, glm::dot(corner - eye, forward));
        }
        const int k = first_detail_scale(depth, lens.fov_y, lens.aspect, frame.viewport.y, settings_.material.detail_scale_m);
        // Wholly below the camera (every view ray points down), a chunk without detail takes the
        // sky radiance per vertex too: below the horizon it varies smoothly with the direction,
        // unlike across it (the sky table's rows go with sqrt(dir.y)).
        const bool vertex_sky = k == 3 && shaded_coarse_[3] && hi.y < eye.y;
        // A field sample spans at most spacing / footprint pixels anywhere on the chunk.
        const bool far = baked && k == 3 &&
                         field_spacing_m_ <= kBakedMaxTexelPx * min_pixel_footprint_m(depth, lens.fov_y, lens.aspect,
                                                                                      frame.viewport.y);
        if (far) {
          chunk_programs.push_back(&shaded_baked_[vertex_sky ? 1 : 0]);
          ++stats_.far_baked_chunks;
        } else if (k == 3 && unshadowed_far_[vertex_sky ? 1 : 0] && beyond_shadow_maps(lo, hi)) {
          chunk_programs.push_back(&unshadowed_far_[vertex_sky ? 1 : 0]);
          ++stats_.beyond_shadow_chunks;
        } else {
          chunk_programs.push_back(k == 0 ? &shaded_ : &shaded_coarse_[vertex_sky ? 3 : k - 1]);
        }
      }
    }
    draw_geometry(shaded_, vp, levels, stats, false, nullptr, coarse ? &chunk_programs : nullptr);
    if (settings_.wireframe && !flat_) {
      auto p = make_shaded_program(false, DebugView::kFlat, AerialPerspective::kOff);
      if (p.ok()) {
        flat_ = std::move(p).value();
      } else {
        log_warn("terrain: wireframe: {}", p.error().message);
      }
    }
    if (settings_.wireframe && flat_) {
      render::PassStats lines;
      flat_.use();
      flat_.set("u_flat_color", glm::vec4(0.05f, 0.05f, 0.05f, 1.0f));
      glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
      GLint depth_func = GL_GREATER;
      glGetIntegerv(GL_DEPTH_FUNC, &depth_func);
      glDepthFunc(depth_func == GL_GREATER ? GL_GEQUAL : GL_LEQUAL);
      draw_geometry(flat_, vp, false, lines, false, nullptr);
      glDepthFunc(static_cast<GLenum>(depth_func));
      glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
      stats.draw_calls += lines.draw_calls;
    }
    if (settings_.chunk_bounds && !bounds_lines_.empty()) {
      bounds_.use();
      bounds_.set("u_view_projection", vp);
      bounds_.set("u_flat_color", glm::vec4(1.0f, 0.85f, 0.1f, 1.0f));
      bounds_buffer_.upload(std::span<const glm::vec3>(bounds_lines_));
      bounds_vao_.vertex_buffer(0, bounds_buffer_, sizeof(glm::vec3));
      bounds_vao_.bind();
      glDrawArrays(GL_LINES, 0, static_cast<GLsizei>(bounds_lines_.size()));
      glBindVertexArray(0);
      ++stats.draw_calls;
    }
  }
  if (cull) glEnable(GL_CULL_FACE);
  stats_.gpu_bytes = gpu_bytes_;
}

}  // namespace sylva::terrain
