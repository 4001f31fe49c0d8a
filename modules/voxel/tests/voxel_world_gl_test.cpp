// The streamed voxel world: chunks load around the camera, unload behind it, edits survive an
// unload through the region files, and a frame renders.

#include <sylva/render/testing.hpp>
#include <sylva/voxel/voxel_world.hpp>

#include <gtest/gtest.h>

#include <filesystem>

#include "support/voxel_gl_scene.hpp"

namespace sylva::voxel {
namespace {

using VoxelWorldGl = render::GlTest;

TEST_F(VoxelWorldGl, StreamsAroundTheCameraAndKeepsEdits) {
  const auto dir = std::filesystem::temp_directory_path() / ("sylva_voxel_stream_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  VoxelWorldSettings s;
  s.generation.seed = 21;
  s.generation.variants_per_species = 3;
  s.view_radius = 1;
  s.chunks_per_update = 1000;
  s.threads = 2;
  s.region_folder = dir.string();
  auto vw = VoxelWorld::create(s);
  ASSERT_TRUE(vw.ok()) << vw.error().message;
  VoxelWorld& w = **vw;
  std::int64_t y0, y1;
  chunk_y_range(s.generation, y0, y1);
  const auto layers = static_cast<std::size_t>(y1 - y0 + 1);
  w.stream_around({5.0, 30.0, 5.0});
  EXPECT_EQ(w.world().chunk_count(), 9 * layers);
  EXPECT_TRUE(w.world().dirty_chunks().empty()) << "everything loaded is meshed";
  // Edit: a glowstone pillar at the origin.
  const BlockId glow = w.world().palette().id("glowstone");
  for (int y = 0; y < 40; ++y) ASSERT_TRUE(w.world().set({3, y, 3}, glow) || w.world().get({3, y, 3}) == glow);
  // Walk 20 chunks away: the origin chunks are unloaded (and saved), new ones generated.
  w.stream_around({20.0 * kChunkSize, 30.0, 5.0});
  EXPECT_GT(w.unloaded_last_update(), 0u);
  EXPECT_EQ(w.world().get({3, 10, 3}), kAir) << "unloaded";
  EXPECT_EQ(w.world().chunk_count(), 9 * layers);
  // Come back: the edit is read back from the region file, not regenerated.
  w.stream_around({5.0, 30.0, 5.0});
  EXPECT_GT(w.last_populate().loaded, 0u);
  EXPECT_EQ(w.world().get({3, 10, 3}), glow);
  // A frame renders.
  auto scene = testing::VoxelGlScene::create(160, 90);
  scene.camera.set_position({-20.0, 50.0, -20.0});
  scene.camera.look_at({16.0, 20.0, 16.0});
  render::apply_reversed_z_state();
  scene.target.bind();
  scene.target.clear(scene.clear_color, 0.0f);
  scene.lighting_ubo.update(scene.lighting, scene.camera.position().y, 0.0);
  scene.lighting_ubo.bind();
  const render::FrameContext frame{scene.camera, 0.0, 0.016f, scene.wind, scene.lighting, scene.target.size(), 1};
  w.update(frame);
  render::PassStats stats;
  w.draw(render::Pass::kOpaque, frame, stats);
  EXPECT_GT(stats.triangles, 0u);
  EXPECT_TRUE(w.save().ok());
  std::filesystem::remove_all(dir);
}

TEST_F(VoxelWorldGl, BadSettingsNameTheParameter) {
  VoxelWorldSettings s;
  s.view_radius = 0;
  auto w = VoxelWorld::create(s);
  ASSERT_FALSE(w.ok());
  EXPECT_NE(w.error().message.find("voxel.view_radius"), std::string::npos);
}

}  // namespace
}  // namespace sylva::voxel
