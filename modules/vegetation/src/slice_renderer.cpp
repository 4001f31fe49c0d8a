#include <sylva/vegetation/slice_renderer.hpp>

#include <sylva/core/rng.hpp>
#include <sylva/render/shadow_maps.hpp>

#include "tree_asset_access.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace sylva::render::embedded {
void register_vegetation_shaders();
}  // namespace sylva::render::embedded

namespace sylva::vegetation {
namespace {

// std140 block SylvaSliceSet of shaders/lib/slices.glsl.
struct SliceSetGpu {
  glm::vec4 center_radius;
  glm::vec4 extent;
  glm::vec4 fade_range;
  glm::vec4 leaf_scroll;
  glm::vec4 misc;
};
static_assert(sizeof(SliceSetGpu) == 80);

constexpr int kDisplacementSize = 64;

// A smooth tileable 2-channel field in [0, 1]: a few random plane waves with integer frequencies
// (periodic over the texture), so scrolling it never shows a seam (eq. 3.40's T_def).
std::vector<unsigned char> displacement_field() {
  constexpr double kTwoPi = 6.283185307179586;
  std::vector<unsigned char> px(static_cast<std::size_t>(kDisplacementSize * kDisplacementSize * 2));
  Pcg32 rng(0x5eed1eafu);
  struct Wave {
    int fx, fy;
    double phase, amp;
  };
  std::array<std::array<Wave, 6>, 2> waves{};
  for (auto& channel : waves)
    for (Wave& w : channel) {
      w.fx = static_cast<int>(rng.next_u32() % 7u) - 3;
      w.fy = static_cast<int>(rng.next_u32() % 7u) - 3;
      if (w.fx == 0 && w.fy == 0) w.fx = 1;
      w.phase = kTwoPi * rng.next_double();
      w.amp = 0.5 + 0.5 * rng.next_double();
    }
  for (int c = 0; c < 2; ++c) {
    double norm = 0.0;
    for (const Wave& w : waves[static_cast<std::size_t>(c)]) norm += w.amp;
    for (int y = 0; y < kDisplacementSize; ++y)
      for (int x = 0; x < kDisplacementSize; ++x) {
        double v = 0.0;
        for (const Wave& w : waves[static_cast<std::size_t>(c)])
          v += w.amp * std::sin(kTwoPi * (w.fx * x + w.fy * y) / kDisplacementSize + w.phase);
        const double u = 0.5 + 0.5 * v / norm;
        px[static_cast<std::size_t>((y * kDisplacementSize + x) * 2 + c)] =
            static_cast<unsigned char>(std::lround(std::clamp(u, 0.0, 1.0) * 255.0));
      }
  }
  return px;
}

}  // namespace

Result<SliceAsset> SliceAsset::create(const BakedTree& baked, float leaf_transmittance) {
  SliceAsset a;
  a.leaf_transmittance_ = std::clamp(leaf_transmittance, 0.0f, 1.0f);
  for (int lod = 0; lod < 2; ++lod) {
    const BakedLod& b = baked.lod[static_cast<std::size_t>(lod)];
    const SliceImages& im = b.images;
    const int res = im.resolution;
    if (res < 1 || im.count != b.layout.count() || im.color.size() != im.texels() * 4 || im.normal.size() != im.texels() * 4 ||
        im.depth.size() != im.texels() || im.branch.size() != im.texels() * 4)
      return make_error(ErrorCode::kInvalidArgument, fmt::format("slice asset: LOD{} images are inconsistent", lod + 1));
    Level& l = a.lods_[static_cast<std::size_t>(lod)];
    l.layout = b.layout;
    l.resolution = res;
    const int levels = render::mip_levels(res, res);
    l.color = render::Texture::create_2d_array(res, res, im.count, GL_RGBA8, levels);
    l.normal = render::Texture::create_2d_array(res, res, im.count, GL_RGBA8, levels);
    l.depth = render::Texture::create_2d_array(res, res, im.count, GL_R32F, 1);
    l.branch = render::Texture::create_2d_array(res, res, im.count, GL_RGBA32F, 1);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTextureSubImage3D(l.color.id(), 0, 0, 0, 0, res, res, im.count, GL_RGBA, GL_UNSIGNED_BYTE, im.color.data());
    glTextureSubImage3D(l.normal.id(), 0, 0, 0, 0, res, res, im.count, GL_RGBA, GL_UNSIGNED_BYTE, im.normal.data());
    glTextureSubImage3D(l.depth.id(), 0, 0, 0, 0, res, res, im.count, GL_RED, GL_FLOAT, im.depth.data());
    glTextureSubImage3D(l.branch.id(), 0, 0, 0, 0, res, res, im.count, GL_RGBA, GL_FLOAT, im.branch.data());
    l.color.generate_mipmaps();
    l.normal.generate_mipmaps();
    l.color.set_filter(GL_LINEAR_MIPMAP_LINEAR, GL_LINEAR);
    l.normal.set_filter(GL_LINEAR_MIPMAP_LINEAR, GL_LINEAR);
    l.depth.set_filter(GL_NEAREST, GL_NEAREST);
    l.branch.set_filter(GL_NEAREST, GL_NEAREST);
    for (const render::Texture* t : {&l.color, &l.normal, &l.depth, &l.branch}) t->set_wrap(GL_CLAMP_TO_EDGE);
    l.block = render::Buffer::immutable(sizeof(SliceSetGpu), nullptr, true);
  }
  return a;
}

Result<SliceRenderer> SliceRenderer::create() {
  render::embedded::register_render_shaders();
  render::embedded::register_vegetation_shaders();
  SliceRenderer r;
  r.animation_ubo_ = render::Buffer::immutable(sizeof(AnimationGpu), nullptr, true);
  r.wind_ubo_ = render::Buffer::immutable(sizeof(WindGpuParams), nullptr, true);
  r.no_shadows_ubo_ = render::make_disabled_shadow_block();
  r.empty_vao_ = render::VertexArray::create();
  r.leaf_displacement_ = render::Texture::create_2d(kDisplacementSize, kDisplacementSize, GL_RG8, 1);
  const std::vector<unsigned char> field = displacement_field();
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTextureSubImage2D(r.leaf_displacement_.id(), 0, 0, 0, kDisplacementSize, kDisplacementSize, GL_RG, GL_UNSIGNED_BYTE, field.data());
  r.leaf_displacement_.set_filter(GL_LINEAR, GL_LINEAR);
  r.leaf_displacement_.set_wrap(GL_REPEAT);
  r.set_frame(rest_animation(), WindGpuParams{}, 0.0, LodSettings{});
  for (bool depth : {false, true}) {
    Result<const render::Program*> p = r.program(Key{depth, 3});
    if (!p.ok()) return p.error();
  }
  return r;
}

void SliceRenderer::set_frame(const AnimationGpu& animation, const WindGpuParams& wind, double time, const LodSettings& lod) {
  animation_ubo_.update(0, sizeof(AnimationGpu), &animation);
  wind_ubo_.update(0, sizeof(WindGpuParams), &wind);
  lod_ = lod;
  // Scroll offsets in texture units, wrapped in double so they stay exact at any time (the field
  // repeats every unit). Two directions and speeds (eq. 3.40's d1, d2), scaled by the leaf
  // flutter frequency of the LOD0 leaves.
  const double t = std::isfinite(time) ? time : 0.0;
  const double f = static_cast<double>(animation.leaf2.x) * 0.08;
  const auto wrap = [](double v) { return static_cast<float>(v - std::floor(v)); };
  leaf_scroll_ = glm::vec4(wrap(t * f * 0.83), wrap(t * f * 0.31), wrap(-t * f * 0.47), wrap(t * f * 0.71));
}

Result<const render::Program*> SliceRenderer::program(const Key& key) {
  if (auto it = programs_.find(key); it != programs_.end()) return &it->second;
  const render::ShaderDefines defines{{"SYLVA_TREE_ANIMATION", std::to_string(key.level)}};
  const std::string stages[2] = {"vegetation/slice.vert", key.depth ? "vegetation/slice_depth.frag" : "vegetation/slice.frag"};
  Result<render::Program> p = render::Program::create(std::span<const std::string>(stages), defines);
  if (!p.ok()) return p.error();
  return &programs_.emplace(key, std::move(p).value()).first->second;
}

Status SliceRenderer::draw(render::Pass pass, const TreeAsset& tree, const SliceAsset& slices, int lod,
                           const render::Buffer& instances, std::uint32_t first, std::uint32_t count,
                           const SliceDrawParams& params, render::PassStats& stats) {
  if (pass == render::Pass::kTransparent || count == 0) return ok_status();
  if (lod != 1 && lod != 2)
    return make_error(ErrorCode::kInvalidArgument, fmt::format("slice renderer: level {} is not 1 or 2", lod));
  const bool depth = pass == render::Pass::kShadow;
  Result<const render::Program*> p = program(Key{depth, static_cast<int>(params.level)});
  if (!p.ok()) return p.error();
  const render::Program& prog = **p;
  const SliceAsset::Level& l = slices.lods_[static_cast<std::size_t>(lod - 1)];

  SliceSetGpu block{};
  const SliceLayout& s = l.layout;
  block.center_radius = glm::vec4(s.center, s.radius);
  block.extent = glm::vec4(s.half_height, s.margin, static_cast<float>(s.directions), static_cast<float>(s.layers));
  // Direction weights rise over |cos| in [cos(spacing), 1]: a view along a normal shows only that
  // direction, a view between two shows both, half each (slice.vert).
  const float spacing = std::cos(3.14159265f / static_cast<float>(s.directions));
  block.fade_range = glm::vec4(spacing, 1.0f, static_cast<float>(l.resolution), lod_.leaf_displacement);
  block.leaf_scroll = leaf_scroll_;
  const float scale = std::max(lod_.leaf_displacement_scale, 1.0e-3f);
  block.misc = glm::vec4(1.0f / scale, lod_.color_noise, lod_.shadow_depth_offset ? 1.0f : 0.0f, 0.25f * scale);
  l.block.update(0, sizeof(SliceSetGpu), &block);

  if (!depth && !params.receive_shadows) no_shadows_ubo_.bind_base(GL_UNIFORM_BUFFER, render::kShadowUniformBinding);
  animation_ubo_.bind_base(GL_UNIFORM_BUFFER, kAnimationBinding);
  wind_ubo_.bind_base(GL_UNIFORM_BUFFER, kWindBinding);
  l.block.bind_base(GL_UNIFORM_BUFFER, kSliceSetBinding);
  TreeAssetAccess::branches(tree).bind_base(GL_SHADER_STORAGE_BUFFER, kBranchBinding);
  TreeAssetAccess::leaves(tree).bind_base(GL_SHADER_STORAGE_BUFFER, kLeafBinding);
  instances.bind_base(GL_SHADER_STORAGE_BUFFER, kInstanceBinding);
  TreeAssetAccess::season(tree).bind(3);
  l.color.bind(8);
  l.normal.bind(9);
  l.depth.bind(10);
  l.branch.bind(11);
  leaf_displacement_.bind(12);

  const ShadingSettings& sh = params.shading;
  prog.set("u_view_proj", params.view_proj);
  prog.set("u_instance_base", static_cast<int>(first));
  prog.set("u_view_direction", params.view_direction);
  GLint viewport[4] = {0, 0, 1, 1};
  glGetIntegerv(GL_VIEWPORT, viewport);
  prog.set("u_viewport", glm::vec2(static_cast<float>(viewport[2]), static_cast<float>(viewport[3])));
  prog.set("u_season_time", sh.season);
  prog.set("u_leaf_spread", sh.leaf_season_spread);
  GLint samples = 0;
  glGetIntegerv(GL_SAMPLES, &samples);
  const bool a2c = !depth && (sh.alpha_mode == AlphaMode::kAlphaToCoverage || (sh.alpha_mode == AlphaMode::kAuto && samples > 1));
  GLboolean color_mask[4] = {GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE};
  glGetBooleanv(GL_COLOR_WRITEMASK, color_mask);
  if (!depth) {
    prog.set("u_alpha_mode", a2c ? 2 : (sh.alpha_mode == AlphaMode::kAlphaTest ? 0 : 1));
    prog.set("u_samples", static_cast<int>(std::max(samples, 1)));
    prog.set("u_roughness", sh.roughness);
    prog.set("u_ior", sh.refractive_index);
    prog.set("u_specular_color", sh.specular_color);
    prog.set("u_translucent_color", sh.translucent_color);
    prog.set("u_leaf_transmittance", slices.leaf_transmittance_);
    prog.set("u_diffuse", sh.diffuse);
    prog.set("u_ambient", sh.ambient);
  } else {
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  }
  prog.use();
  empty_vao_.bind();  // core profile draws need a bound VAO; this one has no attributes
  glDisable(GL_CULL_FACE);  // slices are seen from both sides
  const GLboolean multisample = glIsEnabled(GL_MULTISAMPLE);
  if (a2c) glEnable(GL_MULTISAMPLE);
  glDrawArraysInstanced(GL_TRIANGLES, 0, 6 * s.count(), static_cast<GLsizei>(count));
  if (a2c && !multisample) glDisable(GL_MULTISAMPLE);
  glColorMask(color_mask[0], color_mask[1], color_mask[2], color_mask[3]);
  glBindVertexArray(0);
  glUseProgram(0);
  stats.draw_calls += 1;
  stats.instances += count;
  stats.triangles += static_cast<std::uint64_t>(2 * s.count()) * count;
  return ok_status();
}

}  // namespace sylva::vegetation
