#include <sylva/vegetation/tree_renderer.hpp>

#include <sylva/core/assert.hpp>
#include <sylva/render/shadow_maps.hpp>
#include <sylva/vegetation/slice_bake.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cstddef>
#include <string>

namespace sylva::render::embedded {
void register_vegetation_shaders();
}  // namespace sylva::render::embedded

namespace sylva::vegetation {
namespace {

// Image rows top-down -> GL rows bottom-up, RGBA8 bytes.
std::vector<unsigned char> rgba8_bottom_up(const Image& img) {
  std::vector<unsigned char> out(static_cast<std::size_t>(img.width()) * static_cast<std::size_t>(img.height()) * 4u);
  std::size_t i = 0;
  for (int y = img.height() - 1; y >= 0; --y)
    for (int x = 0; x < img.width(); ++x)
      for (int c = 0; c < 4; ++c)
        out[i++] = static_cast<unsigned char>(std::lround(std::clamp(img.at(x, y, std::min(c, img.channels() - 1)), 0.0f, 1.0f) * 255.0f));
  return out;
}

Status check_leaf_maps(const LeafTextures& t) {
  const Image* maps[] = {&t.front.color, &t.front.normal, &t.front.translucency,
                         &t.back.color,  &t.back.normal,  &t.back.translucency};
  const int w = t.front.color.width();
  const int h = t.front.color.height();
  for (const Image* m : maps) {
    if (m->empty() || m->channels() != 4 || m->width() != w || m->height() != h)
      return make_error(ErrorCode::kInvalidArgument,
                        fmt::format("leaf textures: every map must be RGBA {}x{}, found {}x{}x{}", w, h, m->width(),
                                    m->height(), m->channels()));
  }
  if (w <= 0 || (w & (w - 1)) != 0 || h <= 0 || (h & (h - 1)) != 0)
    return make_error(ErrorCode::kInvalidArgument, fmt::format("leaf textures: {}x{} is not a power-of-two size", w, h));
  return ok_status();
}

// A leaf map with the texels outside the outline (alpha of `outline` = 0) set to their nearest
// texel inside (jump flooding, slice_bake.hpp), so the GL mipmaps average leaf values only: a
// distant leaf keeps its translucency (rho and the HL2 coefficients) and its normals instead of
// blending in the empty texels' zero rho and flat normals. Without it back-lit LOD0 crowns of the
// small-card presets (birch, shrub) were 25-40 % darker than their slices (crown_gl_test).
Image padded_outside_outline(const Image& img, const Image& outline) {
  const int n = img.width();
  if (img.height() != n || outline.width() != n || outline.height() != n) return img;
  const std::size_t count = static_cast<std::size_t>(n) * static_cast<std::size_t>(n);
  std::vector<std::uint8_t> covered(count);
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x)
      covered[static_cast<std::size_t>(y) * static_cast<std::size_t>(n) + static_cast<std::size_t>(x)] =
          outline.at(x, y, 3) > 0.0f ? 1 : 0;
  const std::vector<std::int32_t> source = nearest_covered(covered, n);
  Image out = img;
  for (std::size_t i = 0; i < count; ++i) {
    if (covered[i] != 0 || source[i] < 0) continue;
    const int x = static_cast<int>(i % static_cast<std::size_t>(n));
    const int y = static_cast<int>(i / static_cast<std::size_t>(n));
    for (int c = 0; c < img.channels(); ++c) out.at(x, y, c) = img.at(source[i] % n, source[i] / n, c);
  }
  return out;
}

}  // namespace

Result<TreeTextureSet> make_texture_set(SpeciesPreset preset, std::uint32_t seed, int leaf_size, int bark_size) {
  LeafTextureSettings ls = leaf_texture_settings_for(species_preset(preset).leaf_shape, seed);
  ls.size = leaf_size;
  Result<LeafTextures> leaves = generate_leaf_textures(ls);
  if (!leaves.ok()) return leaves.error();
  BarkTextureSettings bs = bark_texture_settings_for(preset, seed);
  bs.size = bark_size;
  Result<BarkTextures> bark = generate_bark_textures(bs);
  if (!bark.ok()) return bark.error();
  return TreeTextureSet{std::move(leaves).value(), std::move(bark).value(), generate_season_texture(season_palette_for(preset))};
}

Result<TreeAsset> TreeAsset::create(const TreeMesh& mesh, const TreeTextureSet& tex, const TreeAssetOptions& options) {
  SYLVA_TRY(check_leaf_maps(tex.leaves));
  TreeAsset a;
  a.branch_index_count_ = mesh.branch_indices.size();
  a.leaf_index_count_ = mesh.leaf_indices.size();
  a.branch_vertex_count_ = mesh.branch_vertices.size();
  a.leaf_vertex_count_ = mesh.leaf_vertices.size();
  a.bounds_min_ = mesh.bounds_min;
  a.bounds_max_ = mesh.bounds_max;

  // Buffers never empty (zero-size storage is an error): one dummy element where needed.
  const auto bytes = [](std::size_t n, std::size_t size) { return std::max<std::size_t>(n * size, size); };
  a.branch_vbo_ = render::Buffer::immutable(bytes(mesh.branch_vertices.size(), sizeof(BranchVertex)),
                                            mesh.branch_vertices.empty() ? nullptr : mesh.branch_vertices.data());
  a.branch_ibo_ = render::Buffer::immutable(bytes(mesh.branch_indices.size(), 4), mesh.branch_indices.empty() ? nullptr : mesh.branch_indices.data());
  a.leaf_vbo_ = render::Buffer::immutable(bytes(mesh.leaf_vertices.size(), sizeof(LeafVertex)),
                                          mesh.leaf_vertices.empty() ? nullptr : mesh.leaf_vertices.data());
  a.leaf_ibo_ = render::Buffer::immutable(bytes(mesh.leaf_indices.size(), 4), mesh.leaf_indices.empty() ? nullptr : mesh.leaf_indices.data());
  a.branches_ = render::Buffer::immutable(bytes(mesh.data.branches.size(), sizeof(BranchGpu)),
                                          mesh.data.branches.empty() ? nullptr : mesh.data.branches.data());
  a.leaves_ = render::Buffer::immutable(bytes(mesh.data.leaves.size(), sizeof(LeafGpu)),
                                        mesh.data.leaves.empty() ? nullptr : mesh.data.leaves.data());

  a.branch_vao_ = render::VertexArray::create();
  a.branch_vao_.attribute(0, 0, 3, GL_FLOAT, offsetof(BranchVertex, position));
  a.branch_vao_.attribute(1, 0, 3, GL_FLOAT, offsetof(BranchVertex, local));
  a.branch_vao_.attribute(2, 0, 3, GL_FLOAT, offsetof(BranchVertex, normal));
  a.branch_vao_.attribute(3, 0, 2, GL_FLOAT, offsetof(BranchVertex, uv));
  a.branch_vao_.attribute(4, 0, 4, GL_FLOAT, offsetof(BranchVertex, xvec));
  a.branch_vao_.attribute_int(5, 0, 1, GL_UNSIGNED_INT, offsetof(BranchVertex, branch));
  a.branch_vao_.vertex_buffer(0, a.branch_vbo_, sizeof(BranchVertex));
  a.branch_vao_.index_buffer(a.branch_ibo_);

  a.leaf_vao_ = render::VertexArray::create();
  a.leaf_vao_.attribute(0, 0, 3, GL_FLOAT, offsetof(LeafVertex, position));
  a.leaf_vao_.attribute(1, 0, 3, GL_FLOAT, offsetof(LeafVertex, normal));
  a.leaf_vao_.attribute(2, 0, 2, GL_FLOAT, offsetof(LeafVertex, corner));
  a.leaf_vao_.attribute(3, 0, 2, GL_FLOAT, offsetof(LeafVertex, uv));
  a.leaf_vao_.attribute(4, 0, 4, GL_FLOAT, offsetof(LeafVertex, xvec));
  a.leaf_vao_.attribute_int(5, 0, 1, GL_UNSIGNED_INT, offsetof(LeafVertex, branch));
  a.leaf_vao_.attribute_int(6, 0, 1, GL_UNSIGNED_INT, offsetof(LeafVertex, leaf));
  a.leaf_vao_.vertex_buffer(0, a.leaf_vbo_, sizeof(LeafVertex));
  a.leaf_vao_.index_buffer(a.leaf_ibo_);

  // Leaf colour: coverage-preserving alpha mipmaps per side, uploaded level by level.
  const int size = tex.leaves.front.color.width();
  const int levels = render::mip_levels(size, tex.leaves.front.color.height());
  a.leaf_color_ = render::Texture::create_2d_array(size, tex.leaves.front.color.height(), 2, GL_RGBA8, levels);
  const Image* sides[2] = {&tex.leaves.front.color, &tex.leaves.back.color};
  for (int layer = 0; layer < 2; ++layer) {
    const std::vector<Image> mips =
        options.preserve_alpha_coverage ? coverage_preserving_mips(*sides[layer]) : box_mips(*sides[layer]);
    for (int l = 0; l < levels && l < static_cast<int>(mips.size()); ++l) {
      const std::vector<unsigned char> px = rgba8_bottom_up(mips[static_cast<std::size_t>(l)]);
      glTextureSubImage3D(a.leaf_color_.id(), l, 0, 0, layer, mips[static_cast<std::size_t>(l)].width(),
                          mips[static_cast<std::size_t>(l)].height(), 1, GL_RGBA, GL_UNSIGNED_BYTE, px.data());
    }
  }
  a.leaf_color_.set_filter(GL_LINEAR_MIPMAP_LINEAR, GL_LINEAR);
  a.leaf_color_.set_wrap(GL_CLAMP_TO_EDGE);
  // Box-filtered alpha: the true covered share of a footprint, for alpha-to-coverage and the
  // hashed alpha test of minified leaves.
  a.leaf_coverage_ = render::Texture::create_2d_array(size, tex.leaves.front.color.height(), 2, GL_R8, levels);
  for (int layer = 0; layer < 2; ++layer) {
    const std::vector<Image> mips = box_mips(*sides[layer]);
    for (int l = 0; l < levels && l < static_cast<int>(mips.size()); ++l) {
      const Image& m = mips[static_cast<std::size_t>(l)];
      std::vector<unsigned char> px;
      px.reserve(m.pixel_count());
      for (int y = m.height() - 1; y >= 0; --y)
        for (int x = 0; x < m.width(); ++x)
          px.push_back(static_cast<unsigned char>(std::lround(std::clamp(m.at(x, y, 3), 0.0f, 1.0f) * 255.0f)));
      glTextureSubImage3D(a.leaf_coverage_.id(), l, 0, 0, layer, m.width(), m.height(), 1, GL_RED, GL_UNSIGNED_BYTE, px.data());
    }
  }
  a.leaf_coverage_.set_filter(GL_LINEAR_MIPMAP_LINEAR, GL_LINEAR);
  a.leaf_coverage_.set_wrap(GL_CLAMP_TO_EDGE);

  render::TextureOptions lin;
  lin.wrap = GL_CLAMP_TO_EDGE;
  const Image normals[2] = {padded_outside_outline(tex.leaves.front.normal, tex.leaves.front.color),
                            padded_outside_outline(tex.leaves.back.normal, tex.leaves.back.color)};
  Result<render::Texture> ln = render::Texture::from_images(normals, lin);
  if (!ln.ok()) return ln.error();
  a.leaf_normal_ = std::move(ln).value();
  const Image trans[2] = {padded_outside_outline(tex.leaves.front.translucency, tex.leaves.front.color),
                          padded_outside_outline(tex.leaves.back.translucency, tex.leaves.back.color)};
  Result<render::Texture> lt = render::Texture::from_images(trans, lin);
  if (!lt.ok()) return lt.error();
  a.leaf_translucency_ = std::move(lt).value();

  render::TextureOptions season;
  season.mipmaps = false;
  season.min_filter = GL_LINEAR;
  season.wrap = GL_REPEAT;
  Result<render::Texture> st = render::Texture::from_image(tex.season, season);
  if (!st.ok()) return st.error();
  a.season_ = std::move(st).value();

  render::TextureOptions bark;
  bark.wrap = GL_REPEAT;
  Result<render::Texture> ba = render::Texture::from_image(tex.bark.albedo, bark);
  if (!ba.ok()) return ba.error();
  a.bark_albedo_ = std::move(ba).value();
  Result<render::Texture> bn = render::Texture::from_image(tex.bark.normal, bark);
  if (!bn.ok()) return bn.error();
  a.bark_normal_ = std::move(bn).value();
  return a;
}

Result<TreeRenderer> TreeRenderer::create() {
  render::embedded::register_render_shaders();
  render::embedded::register_vegetation_shaders();
  TreeRenderer r;
  r.animation_ubo_ = render::Buffer::immutable(sizeof(AnimationGpu), nullptr, true);
  r.wind_ubo_ = render::Buffer::immutable(sizeof(WindGpuParams), nullptr, true);
  r.no_shadows_ubo_ = render::make_disabled_shadow_block();
  const AnimationGpu rest = rest_animation();
  const WindGpuParams calm{};
  r.set_frame(rest, calm);
  for (bool leaves : {false, true})
    for (bool depth : {false, true}) {
      Result<const render::Program*> p = r.program(Key{leaves, depth, 3, false});
      if (!p.ok()) return p.error();
    }
  return r;
}

void TreeRenderer::set_frame(const AnimationGpu& animation, const WindGpuParams& wind) {
  animation_ubo_.update(0, sizeof(AnimationGpu), &animation);
  wind_ubo_.update(0, sizeof(WindGpuParams), &wind);
}

Result<const render::Program*> TreeRenderer::program(const Key& key) {
  if (auto it = programs_.find(key); it != programs_.end()) return &it->second;
  render::ShaderDefines defines{{"SYLVA_TREE_ANIMATION", std::to_string(key.level)}};
  if (key.depth) defines.emplace_back("SYLVA_DEPTH_ONLY", "1");
  if (key.capture) defines.emplace_back("SYLVA_TREE_CAPTURE", "1");
  const std::string vert = key.leaves ? "vegetation/leaf.vert" : "vegetation/bark.vert";
  const std::string frag = key.leaves ? (key.depth ? "vegetation/leaf_depth.frag" : "vegetation/leaf.frag")
                                      : (key.depth ? "vegetation/depth.frag" : "vegetation/bark.frag");
  const std::string stages[2] = {vert, frag};
  Result<render::Program> p = render::Program::create(std::span<const std::string>(stages), defines);
  if (!p.ok()) return p.error();
  return &programs_.emplace(key, std::move(p).value()).first->second;
}

Status TreeRenderer::draw(render::Pass pass, const TreeAsset& asset, const render::Buffer& instances, std::uint32_t first,
                          std::uint32_t count, const TreeDrawParams& params, render::PassStats& stats) {
  return draw_impl(pass, asset, instances, first, count, params, stats, false);
}

Status TreeRenderer::draw_impl(render::Pass pass, const TreeAsset& asset, const render::Buffer& instances,
                               std::uint32_t first, std::uint32_t count, const TreeDrawParams& params,
                               render::PassStats& stats, bool capture) {
  if (pass == render::Pass::kTransparent || count == 0) return ok_status();
  const bool depth = pass == render::Pass::kShadow;
  if (!depth && !params.receive_shadows) no_shadows_ubo_.bind_base(GL_UNIFORM_BUFFER, render::kShadowUniformBinding);
  const int level = static_cast<int>(params.level);
  animation_ubo_.bind_base(GL_UNIFORM_BUFFER, kAnimationBinding);
  wind_ubo_.bind_base(GL_UNIFORM_BUFFER, kWindBinding);
  asset.branches_.bind_base(GL_SHADER_STORAGE_BUFFER, kBranchBinding);
  asset.leaves_.bind_base(GL_SHADER_STORAGE_BUFFER, kLeafBinding);
  instances.bind_base(GL_SHADER_STORAGE_BUFFER, kInstanceBinding);
  const ShadingSettings& sh = params.shading;

  GLboolean color_mask[4] = {GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE};
  glGetBooleanv(GL_COLOR_WRITEMASK, color_mask);
  if (depth) glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);

  if (params.draw_bark && asset.branch_index_count_ > 0) {
    Result<const render::Program*> p = program(Key{false, depth, level, capture});
    if (!p.ok()) {
      glColorMask(color_mask[0], color_mask[1], color_mask[2], color_mask[3]);
      return p.error();
    }
    const render::Program& prog = **p;
    prog.set("u_view_proj", params.view_proj);
    prog.set("u_instance_base", static_cast<int>(first));
    if (!depth) {
      prog.set("u_bark_specular", sh.bark_specular);
      asset.bark_albedo_.bind(4);
      asset.bark_normal_.bind(5);
    }
    prog.use();
    asset.branch_vao_.bind();
    glEnable(GL_CULL_FACE);
    glCullFace(GL_BACK);
    glDrawElementsInstanced(GL_TRIANGLES, static_cast<GLsizei>(asset.branch_index_count_), GL_UNSIGNED_INT, nullptr,
                            static_cast<GLsizei>(count));
    glDisable(GL_CULL_FACE);
    stats.draw_calls += 1;
    stats.triangles += static_cast<std::uint64_t>(asset.branch_index_count_ / 3) * count;
  }
  if (params.draw_leaves && asset.leaf_index_count_ > 0) {
    Result<const render::Program*> p = program(Key{true, depth, level, capture});
    if (!p.ok()) {
      glColorMask(color_mask[0], color_mask[1], color_mask[2], color_mask[3]);
      return p.error();
    }
    const render::Program& prog = **p;
    prog.set("u_view_proj", params.view_proj);
    prog.set("u_instance_base", static_cast<int>(first));
    prog.set("u_leaf_spread", sh.leaf_season_spread);
    prog.set("u_season_time", sh.season);
    GLint samples = 0;
    glGetIntegerv(GL_SAMPLES, &samples);
    const bool a2c = !depth && (sh.alpha_mode == AlphaMode::kAlphaToCoverage || (sh.alpha_mode == AlphaMode::kAuto && samples > 1));
    // 0 plain alpha test, 1 hashed alpha test, 2 alpha-to-coverage (leaf.frag / leaf_depth.frag).
    prog.set("u_alpha_mode", a2c ? 2 : (sh.alpha_mode == AlphaMode::kAlphaTest ? 0 : 1));
    if (!depth) prog.set("u_samples", static_cast<int>(std::max(samples, 1)));
    asset.leaf_coverage_.bind(6);
    if (!depth) {
      prog.set("u_roughness", sh.roughness);
      prog.set("u_ior", sh.refractive_index);
      prog.set("u_specular_color", sh.specular_color);
      prog.set("u_translucent_color", sh.translucent_color);
      prog.set("u_diffuse", sh.diffuse);
      prog.set("u_ambient", sh.ambient);
      asset.leaf_normal_.bind(1);
      asset.leaf_translucency_.bind(2);
    }
    asset.leaf_color_.bind(0);
    asset.season_.bind(3);
    prog.use();
    asset.leaf_vao_.bind();
    glDisable(GL_CULL_FACE);  // two-sided leaves
    // Alpha-to-coverage (a sample mask written by leaf.frag) needs multisample rasterisation on;
    // restore the caller's state after.
    const GLboolean multisample = glIsEnabled(GL_MULTISAMPLE);
    if (a2c) glEnable(GL_MULTISAMPLE);
    glDrawElementsInstanced(GL_TRIANGLES, static_cast<GLsizei>(asset.leaf_index_count_), GL_UNSIGNED_INT, nullptr,
                            static_cast<GLsizei>(count));
    if (a2c && !multisample) glDisable(GL_MULTISAMPLE);
    stats.draw_calls += 1;
    stats.triangles += static_cast<std::uint64_t>(asset.leaf_index_count_ / 3) * count;
  }
  stats.instances += count;
  glColorMask(color_mask[0], color_mask[1], color_mask[2], color_mask[3]);
  glBindVertexArray(0);
  glUseProgram(0);
  return ok_status();
}

Result<std::vector<glm::vec4>> TreeRenderer::capture(render::Pass pass, const TreeAsset& asset, const render::Buffer& instances,
                                                     std::uint32_t first, const TreeDrawParams& params, bool leaves) {
  const std::size_t vertices = leaves ? asset.leaf_vertex_count_ : asset.branch_vertex_count_;
  std::vector<glm::vec4> out(vertices * 2, glm::vec4(0.0f));
  if (vertices == 0) return out;
  const render::Buffer buffer = render::Buffer::immutable(out.size() * sizeof(glm::vec4), out.data());
  buffer.bind_base(GL_SHADER_STORAGE_BUFFER, kCaptureBinding);
  TreeDrawParams p = params;
  p.draw_bark = !leaves;
  p.draw_leaves = leaves;
  render::PassStats stats;
  SYLVA_TRY(draw_impl(pass, asset, instances, first, 1, p, stats, true));
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
  buffer.read(0, out.size() * sizeof(glm::vec4), out.data());
  return out;
}

}  // namespace sylva::vegetation
