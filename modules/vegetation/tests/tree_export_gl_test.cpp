// Tree export of the impostor slices (issue #16; seed 000 §2.6, Fig. 3.16): the baked LOD1 (3 x 3)
// and LOD2 (2 x 1) layers written as PNG pairs with a manifest another engine can rebuild the
// impostor from. Checks the manifest against the bake's layout (layer order direction * layers +
// layer, planes, rectangle sizes) and every image against the baked bytes (rows flipped to
// top-first, coverage and normals kept exactly).
#include <sylva/vegetation/tree_export.hpp>

#include <sylva/core/atomic_file.hpp>
#include <sylva/core/image.hpp>
#include <sylva/render/testing.hpp>

#include "support/temp_path.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>

namespace sylva::vegetation {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using TreeExportGl = render::GlTest;

TEST_F(TreeExportGl, SlicesAreWrittenAsLayersWithAManifest) {
  Result<ExportTree> tree = export_tree_from_preset(SpeciesPreset::kShrub, 2, 32);
  ASSERT_TRUE(tree.ok()) << tree.error().message;
  const TreeExportOptions options;
  Result<BakedTree> baked = bake_export_slices(*tree, options, 32, 0.12f);
  ASSERT_TRUE(baked.ok()) << baked.error().message;
  const fs::path dir = testing::unique_temp("export_slices");
  fs::remove_all(dir);
  Result<TreeExportReport> r = export_tree(*tree, dir, options, &*baked);
  ASSERT_TRUE(r.ok()) << r.error().message;
  EXPECT_EQ(r->slice_layers, 11);

  const fs::path sd = dir / "shrub_2_slices";
  Result<std::string> text = read_file(sd / "slices.json");
  ASSERT_TRUE(text.ok());
  const json m = json::parse(*text);
  EXPECT_EQ(m["format"], "sylva-tree-slices");
  ASSERT_EQ(m["levels"].size(), 2u);
  std::size_t covered_total = 0;
  for (std::size_t level = 0; level < 2; ++level) {
    const json& lj = m["levels"][level];
    const BakedLod& lod = baked->lod[level];
    EXPECT_EQ(lj["level"], level + 1);
    EXPECT_EQ(lj["directions"], level == 0 ? 3 : 2);
    EXPECT_EQ(lj["layers"], level == 0 ? 3 : 1);
    EXPECT_EQ(lj["resolution"], 32);
    EXPECT_EQ(lj["radius"].get<float>(), lod.layout.radius);
    ASSERT_EQ(lj["slices"].size(), static_cast<std::size_t>(lod.layout.count()));
    for (std::size_t s = 0; s < lj["slices"].size(); ++s) {
      const json& sj = lj["slices"][s];
      const int j = sj["direction"], i = sj["index_in_direction"];
      EXPECT_EQ(sj["layer"].get<int>(), j * lod.layout.layers + i);
      EXPECT_EQ(sj["layer"].get<std::size_t>(), s);
      const glm::vec3 n(sj["normal"][0].get<float>(), sj["normal"][1].get<float>(), sj["normal"][2].get<float>());
      EXPECT_LT(glm::length(n - lod.layout.normal(j)), 1e-6f);
      const glm::vec3 p(sj["plane_point"][0].get<float>(), sj["plane_point"][1].get<float>(), sj["plane_point"][2].get<float>());
      EXPECT_NEAR(glm::dot(p - lod.layout.center, n), lod.layout.layer_offset(i), 1e-5f);
      EXPECT_EQ(sj["width"].get<float>(), 2.0f * lod.layout.radius);
      EXPECT_EQ(sj["height"].get<float>(), 2.0f * lod.layout.half_height);

      Result<Image> color = read_image(sd / sj["color"].get<std::string>());
      Result<Image> normal = read_image(sd / sj["normal_map"].get<std::string>());
      ASSERT_TRUE(color.ok() && normal.ok()) << sj.dump();
      ASSERT_EQ(color->width(), 32);
      ASSERT_EQ(color->channels(), 4);
      ASSERT_EQ(normal->channels(), 4);
      std::size_t covered = 0, baked_covered = 0, normal_diff = 0;
      for (int row = 0; row < 32; ++row)
        for (int x = 0; x < 32; ++x) {
          const std::size_t t = ((s * 32 + static_cast<std::size_t>(row)) * 32 + static_cast<std::size_t>(x)) * 4;
          const int y = 31 - row;  // baked rows are bottom-up
          covered += color->at(x, y, 3) > 0.5f ? 1 : 0;
          baked_covered += lod.images.color[t + 3] > 127 ? 1 : 0;
          for (int c = 0; c < 4; ++c)
            normal_diff += std::lround(normal->at(x, y, c) * 255.0f) != lod.images.normal[t + static_cast<std::size_t>(c)] ? 1 : 0;
        }
      EXPECT_EQ(covered, baked_covered) << sj["color"];
      EXPECT_EQ(normal_diff, 0u) << sj["normal_map"];
      EXPECT_GT(covered, 0u) << sj["color"];
      covered_total += covered;
    }
  }
  std::printf("slices: %d layers, %zu covered texels of %d\n", r->slice_layers, covered_total, 11 * 32 * 32);
  // The glTF is written beside them.
  EXPECT_TRUE(fs::exists(dir / "shrub_2.gltf"));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace sylva::vegetation
