// Leaf shading and seasons on the GPU (seed 000 §3.2, §4.6): two-sided leaves with their own
// textures, Cook-Torrance specular, translucency only when the sun is behind the leaf, season
// colours as the season texture specifies, budding and leaf fall by discard, per-instance offsets
// and colour variation.
#include <sylva/vegetation/tree_renderer.hpp>

#include <sylva/core/image_metrics.hpp>
#include <sylva/render/testing.hpp>

#include "support/gl_scene.hpp"
#include "support/models.hpp"

#include <gtest/gtest.h>

#include <cstdio>

namespace sylva::vegetation {
namespace {

using LeafShadingGl = render::GlTest;

using testing::single_leaf;

struct Stats {
  glm::dvec3 mean{0.0};
  std::size_t pixels = 0;
};

// Mean colour of the pixels that differ from the clear colour.
Stats leaf_pixels(const Image& img, const glm::vec4& clear) {
  Stats s;
  for (int y = 0; y < img.height(); ++y)
    for (int x = 0; x < img.width(); ++x) {
      const glm::vec3 c(img.at(x, y, 0), img.at(x, y, 1), img.at(x, y, 2));
      if (glm::length(c - glm::vec3(clear)) < 1e-3f) continue;
      s.mean += glm::dvec3(c);
      ++s.pixels;
    }
  if (s.pixels > 0) s.mean /= static_cast<double>(s.pixels);
  return s;
}

class LeafScene {
 public:
  explicit LeafScene(const TreeModel& model, SpeciesPreset textures, int size = 64)
      : renderer_(TreeRenderer::create().value()),
        tree_(testing::upload_tree(build_tree_mesh(model), textures)),
        scene_(testing::GlScene::create(size, size)) {
    scene_.clear_color = {0.0f, 0.0f, 0.0f, 1.0f};
    scene_.lighting.ambient = glm::vec3(0.0f);
    scene_.lighting.ground_color = glm::vec3(0.0f);
    scene_.lighting.sun_color = glm::vec3(1.0f);
    scene_.lighting.sun_intensity = 1.0f;
    params_.draw_bark = false;
    params_.shading.alpha_mode = AlphaMode::kAlphaTest;
  }

  // Camera at `eye` looking at `target`; the sun towards `sun`. Instances relative to the camera.
  Image render(const glm::dvec3& eye, const glm::dvec3& target, const glm::vec3& sun, std::vector<TreeInstance> instances = {TreeInstance{}}) {
    scene_.camera.set_position(eye);
    scene_.camera.look_at(target);
    scene_.lighting.sun_direction = glm::normalize(sun);
    renderer_.set_frame(rest_animation(), WindGpuParams{});
    std::vector<InstanceGpu> gpu;
    for (const TreeInstance& t : instances) gpu.push_back(make_instance_gpu(t, eye, glm::vec3(0.0f)));
    testing::set_instances(tree_, gpu);
    scene_.begin();
    params_.view_proj = scene_.camera.view_projection();
    render::PassStats stats;
    EXPECT_TRUE(renderer_.draw(render::Pass::kOpaque, tree_.asset, tree_.instances, 0, static_cast<std::uint32_t>(gpu.size()), params_, stats).ok());
    return scene_.read();
  }

  TreeDrawParams& params() { return params_; }
  const testing::GlScene& scene() const { return scene_; }

 private:
  TreeRenderer renderer_;
  testing::TreeOnGpu tree_;
  testing::GlScene scene_;
  TreeDrawParams params_;
};

const glm::dvec3 kCentre(0.0, 1.2, 0.0);
const glm::dvec3 kFrontEye(0.0, 1.2, 2.6);
const glm::dvec3 kBackEye(0.0, 1.2, -2.6);
const glm::vec4 kBlack(0.0f, 0.0f, 0.0f, 1.0f);

TEST_F(LeafShadingGl, BothSidesAreDrawnWithTheirOwnTextures) {
  LeafScene s(single_leaf(), SpeciesPreset::kBroadleaf);
  s.params().shading.specular_color = glm::vec3(0.0f);
  const Image front = s.render(kFrontEye, kCentre, glm::vec3(0.0f, 0.0f, 1.0f));
  const Image back = s.render(kBackEye, kCentre, glm::vec3(0.0f, 0.0f, -1.0f));
  testing::save_png(front, "leaf_front");
  testing::save_png(back, "leaf_back");
  const Stats f = leaf_pixels(front, kBlack);
  const Stats b = leaf_pixels(back, kBlack);
  ASSERT_GT(f.pixels, 250u);
  EXPECT_NEAR(static_cast<double>(b.pixels), static_cast<double>(f.pixels), 0.05 * static_cast<double>(f.pixels));  // same outline
  // The lower side is paler (back_lightness): brighter under the same light.
  const double lf = f.mean.r + f.mean.g + f.mean.b;
  const double lb = b.mean.r + b.mean.g + b.mean.b;
  EXPECT_GT(lb, lf * 1.1) << "front " << lf << " back " << lb;
}

TEST_F(LeafShadingGl, TranslucencyOnlyWhenTheSunIsBehind) {
  LeafScene s(single_leaf(), SpeciesPreset::kBroadleaf);
  s.params().shading.specular_color = glm::vec3(0.0f);
  const glm::vec3 behind(0.0f, 0.3f, -1.0f);   // sun behind the leaf, seen from the front
  const glm::vec3 in_front(0.0f, 0.3f, 1.0f);
  const Stats lit_through = leaf_pixels(s.render(kFrontEye, kCentre, behind), kBlack);
  testing::save_png(s.render(kFrontEye, kCentre, behind), "leaf_backlit");
  s.params().shading.translucent_color = glm::vec3(0.0f);
  const Stats no_translucency = leaf_pixels(s.render(kFrontEye, kCentre, behind), kBlack);
  const Stats front_lit_without = leaf_pixels(s.render(kFrontEye, kCentre, in_front), kBlack);
  s.params().shading.translucent_color = ShadingSettings{}.translucent_color;
  const Stats front_lit_with = leaf_pixels(s.render(kFrontEye, kCentre, in_front), kBlack);
  const auto sum = [](const Stats& x) { return x.mean.r + x.mean.g + x.mean.b; };
  std::printf("backlit %.3f (no translucency %.3f); front-lit %.3f / %.3f\n", sum(lit_through), sum(no_translucency),
              sum(front_lit_with), sum(front_lit_without));
  EXPECT_GT(sum(lit_through), 0.05);
  EXPECT_LT(sum(no_translucency), 0.01 * 3.0);  // no ambient, no diffuse from behind: black (but drawn)
  EXPECT_NEAR(sum(front_lit_with), sum(front_lit_without), 1e-3);  // translucency plays no part
  // Light through a leaf is yellow-green (translucent colour and the seasonal green).
  EXPECT_GT(lit_through.mean.g, lit_through.mean.b);
}

TEST_F(LeafShadingGl, SpecularHighlightAtTheMirrorDirection) {
  LeafScene s(single_leaf(), SpeciesPreset::kBroadleaf);
  const Stats with = leaf_pixels(s.render(kFrontEye, kCentre, glm::vec3(0.0f, 0.0f, 1.0f)), kBlack);
  s.params().shading.specular_color = glm::vec3(0.0f);
  const Stats without = leaf_pixels(s.render(kFrontEye, kCentre, glm::vec3(0.0f, 0.0f, 1.0f)), kBlack);
  EXPECT_GT(with.mean.g, without.mean.g + 0.01);
}

TEST_F(LeafShadingGl, SeasonColoursFollowTheSeasonTexture) {
  LeafScene s(single_leaf(), SpeciesPreset::kBroadleaf);
  s.params().shading.specular_color = glm::vec3(0.0f);
  s.params().shading.leaf_season_spread = 0.0f;
  const Result<TreeTextureSet> tex = make_texture_set(SpeciesPreset::kBroadleaf, 1, 64, 64);
  ASSERT_TRUE(tex.ok());
  // Mean colour deviation c_v of the upper side.
  glm::dvec3 cv(0.0);
  double weight = 0.0;
  const Image& col = tex->leaves.front.color;
  for (int y = 0; y < col.height(); ++y)
    for (int x = 0; x < col.width(); ++x) {
      const double a = col.at(x, y, 3) >= 0.5f ? 1.0 : 0.0;
      cv += a * (glm::dvec3(col.at(x, y, 0), col.at(x, y, 1), col.at(x, y, 2)) - 0.5);
      weight += a;
    }
  cv /= weight;
  for (float season : {0.45f, 0.55f, 0.75f, 0.78f, 0.81f}) {
    s.params().shading.season = season;
    const Image img = s.render(kFrontEye, kCentre, glm::vec3(0.0f, 0.0f, 1.0f));
    const Stats st = leaf_pixels(img, kBlack);
    ASSERT_GT(st.pixels, 100u) << "season " << season;
    const glm::dvec3 expected = cv + glm::dvec3(glm::vec3(sample_season(tex->season, season)));
    const glm::dvec3 chroma = st.mean / (st.mean.r + st.mean.g + st.mean.b);
    const glm::dvec3 chroma_expected = expected / (expected.r + expected.g + expected.b);
    std::printf("season %.2f: rendered chromaticity (%.3f %.3f %.3f), expected (%.3f %.3f %.3f)\n", static_cast<double>(season),
                chroma.r, chroma.g, chroma.b, chroma_expected.r, chroma_expected.g, chroma_expected.b);
    EXPECT_LT(glm::length(chroma - chroma_expected), 0.04) << "season " << season;
    testing::save_png(img, fmt::format("season_{:.2f}", static_cast<double>(season)));
  }
  // Winter: no leaves at all.
  s.params().shading.season = 0.05f;
  EXPECT_EQ(leaf_pixels(s.render(kFrontEye, kCentre, glm::vec3(0.0f, 0.0f, 1.0f)), kBlack).pixels, 0u);
}

TEST_F(LeafShadingGl, BuddingAndLeafFallAreGradualAndVaryPerInstance) {
  const TreeMesh& mesh = testing::preset_mesh(SpeciesPreset::kShrub);
  LeafScene s(testing::preset_tree(SpeciesPreset::kShrub), SpeciesPreset::kShrub, 96);
  const glm::vec3 c = 0.5f * (mesh.bounds_min + mesh.bounds_max);
  const glm::dvec3 eye(c.x, c.y + 0.5f, c.z + 4.5f);
  const glm::vec3 sun(0.2f, 0.5f, 1.0f);
  // Spring: leaves appear one by one over leaf_season_spread (0.2 of the year): presence crosses
  // 0.5 at about 0.29 in the texture, so leaf n opens at season 0.29 - 0.2 n.
  std::vector<std::size_t> counts;
  for (float season = 0.04f; season <= 0.345f; season += 0.01f) {
    s.params().shading.season = season;
    counts.push_back(leaf_pixels(s.render(eye, glm::dvec3(c), sun), kBlack).pixels);
  }
  const std::size_t full = counts.back();
  ASSERT_GT(full, 250u);
  EXPECT_LT(counts.front(), full / 20);
  std::size_t largest_step = 0;
  for (std::size_t i = 1; i < counts.size(); ++i) {
    EXPECT_GE(counts[i] + full / 50, counts[i - 1]) << "step " << i;  // (nearly) monotonic growth
    largest_step = std::max(largest_step, counts[i] > counts[i - 1] ? counts[i] - counts[i - 1] : 0u);
  }
  EXPECT_LT(largest_step, full / 5);  // no pop: at most a fifth of the crown per 1/100 year
  // Autumn: leaves fall gradually too (presence crosses 0.5 at about 0.855, leaf n falls at
  // 0.855 - 0.2 n).
  s.params().shading.season = 0.62f;
  const std::size_t before_fall = leaf_pixels(s.render(eye, glm::dvec3(c), sun), kBlack).pixels;
  s.params().shading.season = 0.76f;
  const std::size_t mid_fall = leaf_pixels(s.render(eye, glm::dvec3(c), sun), kBlack).pixels;
  s.params().shading.season = 0.87f;
  const std::size_t after_fall = leaf_pixels(s.render(eye, glm::dvec3(c), sun), kBlack).pixels;
  EXPECT_GT(before_fall, mid_fall + full / 10);
  EXPECT_GT(mid_fall, after_fall + full / 10);
  EXPECT_EQ(after_fall, 0u);
  // Per-instance season offsets: an instance ahead in the year has more leaves in spring.
  s.params().shading.season = 0.19f;
  TreeInstance early;
  early.season_offset = 0.05f;
  TreeInstance late;
  late.season_offset = -0.05f;
  const std::size_t n_early = leaf_pixels(s.render(eye, glm::dvec3(c), sun, {early}), kBlack).pixels;
  const std::size_t n_late = leaf_pixels(s.render(eye, glm::dvec3(c), sun, {late}), kBlack).pixels;
  EXPECT_GT(n_early, n_late + full / 10);
  // Per-instance colour variation shifts the colour.
  s.params().shading.season = 0.55f;
  TreeInstance redder;
  redder.color_variation = {0.08f, 0.0f, 0.0f};
  const Stats plain = leaf_pixels(s.render(eye, glm::dvec3(c), sun), kBlack);
  const Stats varied = leaf_pixels(s.render(eye, glm::dvec3(c), sun, {redder}), kBlack);
  EXPECT_GT(varied.mean.r / varied.mean.g, 1.2 * plain.mean.r / plain.mean.g);
}

}  // namespace
}  // namespace sylva::vegetation
