// Procedural leaf, bark and season textures (seed 000 §3.2, §4.3.2, §4.6), coverage-preserving
// alpha mipmaps, and their save/load round trip through core images. The images are written to
// the test's working directory for a person to look at.
#include <sylva/vegetation/textures.hpp>

#include <sylva/core/image.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

namespace sylva::vegetation {
namespace {

std::filesystem::path out_dir() {
  const std::filesystem::path p = std::filesystem::current_path() / "vegetation_out" / "textures";
  std::filesystem::create_directories(p);
  return p;
}

glm::vec3 decode(const Image& img, int x, int y) {
  return glm::vec3(img.at(x, y, 0), img.at(x, y, 1), img.at(x, y, 2)) * 2.0f - 1.0f;
}

TEST(Textures, LeafShapesHaveTheirOutline) {
  for (LeafShape shape : {LeafShape::kOvate, LeafShape::kElliptic, LeafShape::kBirch, LeafShape::kNeedles}) {
    LeafTextureSettings s = leaf_texture_settings_for(shape);
    s.size = 128;
    Result<LeafTextures> t = generate_leaf_textures(s);
    ASSERT_TRUE(t.ok()) << t.error().describe();
    const double cover = alpha_coverage(t->front.color);
    std::printf("leaf %d: coverage %.3f\n", static_cast<int>(shape), cover);
    EXPECT_GT(cover, shape == LeafShape::kNeedles ? 0.08 : 0.3);
    EXPECT_LT(cover, 0.8);
    // Corners are empty, the blade centre is leaf; front and back share the outline.
    EXPECT_EQ(t->front.color.at(0, 0, 3), 0.0f);
    EXPECT_EQ(t->front.color.at(127, 127, 3), 0.0f);
    EXPECT_EQ(t->front.color.at(64, 48, 3), 1.0f);
    EXPECT_EQ(t->front.color.data().size(), t->back.color.data().size());
    for (int y = 0; y < 128; ++y)
      for (int x = 0; x < 128; ++x) ASSERT_EQ(t->front.color.at(x, y, 3), t->back.color.at(x, y, 3));
    ASSERT_TRUE(save_leaf_textures(out_dir(), fmt::format("leaf{}", static_cast<int>(shape)), *t).ok());
  }
}

TEST(Textures, VenationNormalsAndThickness) {
  LeafTextureSettings s = leaf_texture_settings_for(LeafShape::kOvate);
  s.cluster = 1;  // one leaf filling the card: its venation, untilted
  s.size = 128;
  Result<LeafTextures> t = generate_leaf_textures(s);
  ASSERT_TRUE(t.ok());
  double tilt_vein = 0.0;
  double tilt_lamina = 0.0;
  int n_vein = 0;
  int n_lamina = 0;
  for (int y = 0; y < 128; ++y) {
    for (int x = 0; x < 128; ++x) {
      if (t->front.color.at(x, y, 3) < 1.0f) continue;
      const glm::vec3 n = decode(t->front.normal, x, y);
      ASSERT_NEAR(glm::length(n), 1.0f, 1e-4f);
      ASSERT_GT(n.z, 0.0f);
      const float thick = t->front.normal.at(x, y, 3);
      const double tilt = std::hypot(n.x, n.y);
      if (thick > 0.45f) {
        tilt_vein += tilt;
        ++n_vein;
      } else if (thick < 0.27f) {
        tilt_lamina += tilt;
        ++n_lamina;
      }
    }
  }
  ASSERT_GT(n_vein, 20);
  ASSERT_GT(n_lamina, 1000);
  // The relief lives on the veins (their flanks tilt the normal), the lamina is nearly flat.
  EXPECT_GT(tilt_vein / n_vein, 3.0 * tilt_lamina / n_lamina);
}

TEST(Textures, TranslucencyIsTheHl2ProjectionOfTheTransport) {
  LeafTextureSettings s = leaf_texture_settings_for(LeafShape::kElliptic);
  s.cluster = 1;  // a flat single lamina: the cosine lobe exactly
  s.size = 128;
  s.veins = 0;
  s.vein_depth = 0.0f;
  Result<LeafTextures> t = generate_leaf_textures(s);
  ASSERT_TRUE(t.ok());
  // A texel in the flat lamina with flat neighbours: transport = cosine lobe attenuated by
  // exp(-k d), whose HL2 coordinates are all sqrt(2 pi) / 3 exp(-k d) (eq. 3.31 with f = L.z).
  const int x = 40;
  const int y = 64;
  ASSERT_EQ(t->front.color.at(x, y, 3), 1.0f);
  const float d = t->front.normal.at(x, y, 3);
  const float expected = std::sqrt(2.0f * 3.14159265f) / 3.0f * std::exp(-s.thickness_absorption * d);
  const glm::vec3 h = decode(t->front.translucency, x, y);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(h[c], expected, 0.03f);
  // Reconstruction: light straight through gives exp(-k d); grazing light gives less.
  const float rho = 1.0f;
  EXPECT_NEAR(hl2_reconstruct(h, rho, {0.0f, 0.0f, 1.0f}), std::exp(-s.thickness_absorption * d), 0.04f);
  EXPECT_LT(hl2_reconstruct(h, rho, glm::normalize(glm::vec3(1.0f, 0.0f, 0.2f))),
            0.5f * hl2_reconstruct(h, rho, {0.0f, 0.0f, 1.0f}));
  EXPECT_EQ(hl2_reconstruct(h, rho, {0.0f, 0.0f, -1.0f}), 0.0f);
  // HL2 basis: orthonormal-ish lobes that sum to sqrt(3) along the normal (eq. 3.29).
  const auto H = hl2_basis();
  for (const glm::vec3& b : H) EXPECT_NEAR(glm::length(b), 1.0f, 1e-6f);
  EXPECT_NEAR((H[0] + H[1] + H[2]).z, std::sqrt(3.0f), 1e-5f);
}

TEST(Textures, VeinsTransmitLessThanTheLamina) {
  LeafTextureSettings s = leaf_texture_settings_for(LeafShape::kOvate);
  s.size = 128;
  Result<LeafTextures> t = generate_leaf_textures(s);
  ASSERT_TRUE(t.ok());
  const glm::vec3 L(0.0f, 0.0f, 1.0f);
  double vein = 0.0, lamina = 0.0;
  int nv = 0, nl = 0;
  for (int y = 0; y < 128; ++y)
    for (int x = 0; x < 128; ++x) {
      if (t->front.color.at(x, y, 3) < 1.0f) continue;
      const float d = t->front.normal.at(x, y, 3);
      const float tr = hl2_reconstruct(decode(t->front.translucency, x, y), t->front.translucency.at(x, y, 3), L);
      if (d > 0.6f) { vein += tr; ++nv; }
      if (d < 0.27f) { lamina += tr; ++nl; }
    }
  ASSERT_GT(nv, 10);
  EXPECT_LT(vein / nv, 0.8 * lamina / nl);
}

TEST(Textures, SeasonTextureFollowsTheYear) {
  const Image tex = generate_season_texture(SeasonPalette::kDeciduous);
  ASSERT_EQ(tex.width(), 1);
  ASSERT_EQ(tex.height(), 64);
  ASSERT_TRUE(write_image(out_dir() / "season_deciduous.png", tex, PixelFormat::kU8).ok());
  const glm::vec4 winter = sample_season(tex, 0.05f);
  const glm::vec4 summer = sample_season(tex, 0.55f);
  const glm::vec4 autumn = sample_season(tex, 0.78f);
  EXPECT_LT(winter.a, 0.5f);  // no leaves
  EXPECT_GT(summer.a, 0.99f);
  EXPECT_GT(summer.g, 1.8f * summer.r);
  EXPECT_GT(summer.g, 2.0f * summer.b);
  EXPECT_GT(autumn.a, 0.99f);
  EXPECT_GT(autumn.r, 1.5f * autumn.g);  // red-orange
  // Budding: presence crosses 0.5 once in spring, and once more at leaf fall.
  int crossings = 0;
  for (int i = 0; i < 1000; ++i) {
    const float a0 = sample_season(tex, static_cast<float>(i) / 1000.0f).a;
    const float a1 = sample_season(tex, static_cast<float>(i + 1) / 1000.0f).a;
    crossings += (a0 < 0.5f) != (a1 < 0.5f) ? 1 : 0;
  }
  EXPECT_EQ(crossings, 2);
  // Wraps: the year repeats.
  EXPECT_LT(glm::length(sample_season(tex, 0.3f) - sample_season(tex, 1.3f)), 1e-5f);
  EXPECT_LT(glm::length(sample_season(tex, -0.7f) - sample_season(tex, 0.3f)), 1e-5f);
  // Evergreens keep their needles all year.
  const Image ever = generate_season_texture(SeasonPalette::kEvergreen);
  for (int i = 0; i < 100; ++i) EXPECT_GT(sample_season(ever, static_cast<float>(i) / 100.0f).a, 0.99f);
}

TEST(Textures, CoveragePreservingMipsKeepTheLeavesBoxMipsLoseThem) {
  // Needle sprays: thin features that box filtering dissolves first.
  LeafTextureSettings s = leaf_texture_settings_for(LeafShape::kNeedles);
  s.size = 256;
  Result<LeafTextures> t = generate_leaf_textures(s);
  ASSERT_TRUE(t.ok());
  const double c0 = alpha_coverage(t->front.color);
  const std::vector<Image> keep = coverage_preserving_mips(t->front.color);
  const std::vector<Image> box = box_mips(t->front.color);
  ASSERT_EQ(keep.size(), 9u);
  ASSERT_TRUE(write_image(out_dir() / "needles_box_mip3.png", box[3], PixelFormat::kU8).ok());
  ASSERT_TRUE(write_image(out_dir() / "needles_preserving_mip3.png", keep[3], PixelFormat::kU8).ok());
  double worst_keep = 0.0;
  double worst_box = 0.0;
  for (std::size_t l = 1; l < keep.size(); ++l) {
    if (keep[l].width() < 8) break;
    worst_keep = std::max(worst_keep, std::fabs(alpha_coverage(keep[l]) - c0));
    worst_box = std::max(worst_box, std::fabs(alpha_coverage(box[l]) - c0));
    std::printf("mip %zu (%dx%d): coverage box %.3f, preserving %.3f (level 0: %.3f)\n", l, keep[l].width(),
                keep[l].height(), alpha_coverage(box[l]), alpha_coverage(keep[l]), c0);
  }
  EXPECT_LT(worst_keep, 0.01);
  EXPECT_GT(worst_box, 0.05);  // the failure the seed observed (§5: leaves vanish at distance)
}

TEST(Textures, BarkTilesSeamlessly) {
  for (SpeciesPreset p : {SpeciesPreset::kBroadleaf, SpeciesPreset::kBirch}) {
    BarkTextureSettings s = bark_texture_settings_for(p);
    s.size = 128;
    Result<BarkTextures> b = generate_bark_textures(s);
    ASSERT_TRUE(b.ok()) << b.error().describe();
    // The wrap-around column (row) step is no outlier among the column (row) steps inside the
    // image: at most the 90th percentile of the inner steps times 1.5.
    const Image& a = b->albedo;
    const int n = a.width();
    std::vector<double> cols(static_cast<std::size_t>(n), 0.0);
    std::vector<double> rows(static_cast<std::size_t>(n), 0.0);
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x)
        for (int c = 0; c < 3; ++c) {
          cols[static_cast<std::size_t>(x)] += std::fabs(a.at((x + 1) % n, y, c) - a.at(x, y, c));
          rows[static_cast<std::size_t>(y)] += std::fabs(a.at(x, (y + 1) % n, c) - a.at(x, y, c));
        }
    for (std::vector<double>* steps : {&cols, &rows}) {
      const double seam = steps->back();
      std::vector<double> inner(steps->begin(), steps->end() - 1);
      std::sort(inner.begin(), inner.end());
      const double p90 = inner[inner.size() * 9 / 10];
      EXPECT_LT(seam, 1.5 * p90) << "seam step " << seam << ", 90th percentile of inner steps " << p90;
    }
    ASSERT_TRUE(save_bark_textures(out_dir(), fmt::format("bark{}", static_cast<int>(p)), *b).ok());
  }
}

TEST(Textures, SaveLoadRoundTripAndErrors) {
  LeafTextureSettings s = leaf_texture_settings_for(LeafShape::kOvate, 5);
  s.size = 64;
  Result<LeafTextures> t = generate_leaf_textures(s);
  ASSERT_TRUE(t.ok());
  const std::filesystem::path dir = out_dir() / "roundtrip";
  std::filesystem::create_directories(dir);
  ASSERT_TRUE(save_leaf_textures(dir, "oak", *t).ok());
  Result<LeafTextures> back = load_leaf_textures(dir, "oak");
  ASSERT_TRUE(back.ok()) << back.error().describe();
  float worst = 0.0f;
  for (std::size_t i = 0; i < t->front.translucency.data().size(); ++i)
    worst = std::max(worst, std::fabs(back->front.translucency.data()[i] - t->front.translucency.data()[i]));
  EXPECT_LE(worst, 0.5f / 255.0f + 1e-6f);
  // Saving what was loaded gives the same files' values exactly (8-bit round trip).
  ASSERT_TRUE(save_leaf_textures(dir, "oak2", *back).ok());
  Result<LeafTextures> again = load_leaf_textures(dir, "oak2");
  ASSERT_TRUE(again.ok());
  EXPECT_EQ(again->back.normal.data()[1234], back->back.normal.data()[1234]);
  // Missing file: the error names it.
  std::filesystem::remove(dir / "oak_back_normal.png");
  Result<LeafTextures> missing = load_leaf_textures(dir, "oak");
  ASSERT_FALSE(missing.ok());
  EXPECT_NE(missing.error().message.find("oak_back_normal.png"), std::string::npos) << missing.error().message;
  // A map of another size: the error names it.
  ASSERT_TRUE(write_image(dir / "oak_back_normal.png", Image(32, 32, 4, PixelFormat::kU8), PixelFormat::kU8).ok());
  Result<LeafTextures> wrong = load_leaf_textures(dir, "oak");
  ASSERT_FALSE(wrong.ok());
  EXPECT_NE(wrong.error().message.find("oak_back_normal.png: size 32x32"), std::string::npos) << wrong.error().message;
  // Bad settings name the parameter.
  s.size = 100;
  Result<LeafTextures> bad = generate_leaf_textures(s);
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().message.find("leaf_texture.size"), std::string::npos);
}

TEST(Textures, Deterministic) {
  LeafTextureSettings s = leaf_texture_settings_for(LeafShape::kBirch, 9);
  s.size = 64;
  Result<LeafTextures> a = generate_leaf_textures(s);
  Result<LeafTextures> b = generate_leaf_textures(s);
  ASSERT_TRUE(a.ok() && b.ok());
  for (std::size_t i = 0; i < a->front.color.data().size(); ++i) ASSERT_EQ(a->front.color.data()[i], b->front.color.data()[i]);
}

}  // namespace
}  // namespace sylva::vegetation
