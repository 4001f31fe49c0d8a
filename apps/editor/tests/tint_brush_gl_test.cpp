// The colour brush on the grass tint (issue 16): the tint is three unit maps (grass.tint_r/g/b);
// a stroke on the colour map "grass.tint" paints all three towards brush.color with the brush
// falloff, as ONE undo step. Driven through the editor's script commands in process
// (`brush color=1,0,0 ...`, `stroke grass.tint X,Z`), checked on the three maps, on the
// rendered grass (redder in the patch, not a pixel changed outside), on undo/redo (bit-exact) and on a
// save and reload (the 16-bit PNG maps within their quantisation). And the other grass file of
// issue 16 the editor follows: grass.mesh.density_file (density over a mesh's UVs) is watched
// like every `*_file` setting, and rewriting it while the scene runs regrows the blades.
#include "editor_session.hpp"
#include "script_runner.hpp"
#include "source_watcher.hpp"

#include <sylva/core/atomic_file.hpp>
#include <sylva/core/image.hpp>
#include <sylva/render/readback.hpp>
#include <sylva/render/testing.hpp>
#include <sylva/scene/module_registry.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <sstream>
#include <unistd.h>

namespace fs = std::filesystem;
using namespace sylva;
using namespace sylva::editor;

namespace {

using TintBrushGl = render::GlTest;

constexpr glm::ivec2 kViewport(128, 96);

// Flat ground, a 16 x 16 m meadow of wide blades (so that they cover the view from above) with
// 32 x 32 texel maps, seen straight down from 12 m.
const char* kMeadow = R"({
  "sun": {"follow_clock": false, "azimuth_deg": 200.0, "elevation_deg": 60.0, "fog_density": 0.0},
  "wind": {"strength": 0.0, "gust_amplitude": 0.0},
  "ground": {"size": 32.0, "resolution": 33, "generator": "flat"},
  "grass": {"area_min": [-8.0, -8.0], "area_max": [8.0, 8.0], "map_resolution": 32, "far_field": false,
            "field": {"density": 120.0, "tile_size": 4.0}, "blade": {"height_min": 0.3, "height_max": 0.5, "width_min": 0.06, "width_max": 0.08},
            "render": {"simulate": false}},
  "render": {"shadows": {"enabled": false}, "msaa_samples": 1}
})";

using Tint = std::array<std::vector<float>, 3>;

Tint tint_maps(EditorSession& s) {
  Tint t;
  for (int c = 0; c < 3; ++c) t[c] = s.scene().map(std::string("grass.tint_") + "rgb"[c])->grid.values;
  return t;
}

bool bit_equal(const Tint& a, const Tint& b) {
  for (int c = 0; c < 3; ++c) {
    if (a[c].size() != b[c].size() || std::memcmp(a[c].data(), b[c].data(), a[c].size() * sizeof(float)) != 0) return false;
  }
  return true;
}

// The viewport after two frames.
Image frame(EditorSession& s) {
  for (int i = 0; i < 2; ++i) EXPECT_TRUE(s.render_frame(1.0 / 30.0).ok());
  return render::read_color(s.framebuffer()).value();
}

// Pixels of [x0, x1) x [y0, y1) whose red minus green rose by more than 0.05 from `a` to `b`
// (blades turned redder), and pixels that changed at all.
glm::ivec2 redder_and_changed(const Image& a, const Image& b, int x0, int x1, int y0, int y1) {
  glm::ivec2 n(0);
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) {
      n.x += (b.at(x, y, 0) - b.at(x, y, 1)) - (a.at(x, y, 0) - a.at(x, y, 1)) > 0.05f ? 1 : 0;
      n.y += a.at(x, y, 0) != b.at(x, y, 0) || a.at(x, y, 1) != b.at(x, y, 1) || a.at(x, y, 2) != b.at(x, y, 2) ? 1 : 0;
    }
  return n;
}

Status run(EditorSession& s, const std::string& text, const fs::path& dir) {
  auto commands = parse_script(text, "tint.txt");
  if (!commands.ok()) return commands.error();
  std::ostringstream out;
  auto r = run_script(s, *commands, "tint.txt", dir, out);
  return r.ok() ? Status{} : Status(r.error());
}

}  // namespace

TEST_F(TintBrushGl, ColourStrokePaintsTheThreeTintMapsAsOneUndoStep) {
  if (!scene::find_module("grass") || !scene::find_module("ground")) GTEST_SKIP() << "needs the grass and ground modules";
  const fs::path dir = fs::temp_directory_path() / ("sylva_editor_tint_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  ASSERT_TRUE(write_file_atomic(dir / "meadow.json", kMeadow).ok());
  auto session = EditorSession::create(kViewport);
  ASSERT_TRUE(session.ok()) << session.error().message;
  EditorSession& s = **session;
  ASSERT_TRUE(s.load(dir / "meadow.json").ok());
  EXPECT_EQ(s.color_map_ids(), std::vector<std::string>{"grass.tint"});
  s.set_camera({{0.0, 12.0, 0.0}, 0.0f, -89.9f, 60.0f, scene::HeightMode::kAbsolute});
  const Tint before = tint_maps(s);
  const Image image0 = frame(s);

  ASSERT_TRUE(run(s, "brush op=paint radius=3 strength=1 falloff=constant color=1,0.25,0\nstroke grass.tint 0,0\n", dir).ok());
  EXPECT_EQ(s.history().position(), 1u) << "one undo step for the three maps";
  ASSERT_EQ(s.history().next_undo()->edits.size(), 3u);
  const Tint after = tint_maps(s);
  const scene::MapGrid& grid = s.scene().map("grass.tint_r")->grid;
  int inside = 0, outside = 0;
  for (int j = 0; j < grid.height; ++j)
    for (int i = 0; i < grid.width; ++i) {
      const std::size_t k = static_cast<std::size_t>(j) * grid.width + i;
      const double d = glm::length(grid.world(i, j));
      const glm::vec3 v(after[0][k], after[1][k], after[2][k]);
      if (d < 2.9) {
        ++inside;
        EXPECT_EQ(v, glm::vec3(1.0f, 0.25f, 0.0f)) << i << "," << j;
      } else if (d > 3.1) {
        ++outside;
        EXPECT_EQ(v, glm::vec3(1.0f)) << i << "," << j;
      }
    }
  EXPECT_GT(inside, 100);
  EXPECT_GT(outside, 600);

  // Centre: within 1.5 m of the stroke (radius 3 m); corner: beyond 6 m from it.
  const Image image1 = frame(s);
  const glm::ivec2 centre = redder_and_changed(image0, image1, 54, 74, 38, 58);
  const glm::ivec2 corner = redder_and_changed(image0, image1, 0, 16, 0, 16);
  std::printf("pixels redder / changed: centre %d / %d of 400, corner %d / %d of 256\n", centre.x, centre.y, corner.x,
              corner.y);
  EXPECT_GT(centre.x, 60) << "the patch's blades turn redder";
  EXPECT_EQ(corner.y, 0) << "outside the patch nothing changes";

  ASSERT_TRUE(s.undo().ok());
  EXPECT_TRUE(bit_equal(tint_maps(s), before));
  EXPECT_FALSE(s.unsaved());
  ASSERT_TRUE(s.redo().ok());
  EXPECT_TRUE(bit_equal(tint_maps(s), after));

  ASSERT_TRUE(run(s, "save saved.json\n", dir).ok());
  ASSERT_TRUE(s.load(dir / "saved.json").ok());
  const Tint reloaded = tint_maps(s);
  for (int c = 0; c < 3; ++c) {
    ASSERT_EQ(reloaded[c].size(), after[c].size());
    float worst = 0.0f;
    for (std::size_t k = 0; k < after[c].size(); ++k) worst = std::max(worst, std::abs(reloaded[c][k] - after[c][k]));
    EXPECT_LE(worst, 0.5f / 65535.0f + 1e-7f) << "channel " << c << " (16-bit PNG)";
  }
  fs::remove_all(dir);
}

TEST_F(TintBrushGl, RewritingTheMeshUvDensityFileRegrowsTheBlades) {
  if (!scene::find_module("grass") || !scene::find_module("model_terrain")) GTEST_SKIP() << "needs grass and terrain";
  const fs::path dir = fs::temp_directory_path() / ("sylva_editor_uv_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  // A 4 x 4 m quad with UVs 0..1 and a density image black on its left half.
  ASSERT_TRUE(write_file_atomic(dir / "quad.obj", "v -2 0 -2\nv 2 0 -2\nv 2 0 2\nv -2 0 2\n"
                                                  "vt 0 1\nvt 1 1\nvt 1 0\nvt 0 0\nf 1/1 4/4 3/3 2/2\n").ok());
  auto density = [&](bool left_black) {
    Image image(32, 32, 1);
    for (int j = 0; j < 32; ++j)
      for (int i = 0; i < 32; ++i) image.at(i, j) = left_black && i < 16 ? 0.0f : 1.0f;
    return write_image(dir / "moss.png", image, PixelFormat::kU8);
  };
  ASSERT_TRUE(density(true).ok());
  ASSERT_TRUE(write_file_atomic(dir / "rock.json", R"({"grass": {"surface": "mesh", "far_field": false,
      "mesh": {"file": "quad.obj", "density_source": "uv_map", "density_file": "moss.png"},
      "field": {"density": 100.0}, "render": {"simulate": false}}})").ok());
  auto session = EditorSession::create({64, 36});
  ASSERT_TRUE(session.ok()) << session.error().message;
  EditorSession& s = **session;
  ASSERT_TRUE(s.load(dir / "rock.json").ok());
  const auto sources = scene_sources(s.scene().document());
  EXPECT_NE(std::find(sources.begin(), sources.end(),
                      WatchedSource{"grass.mesh.density_file", fs::weakly_canonical(dir / "moss.png")}),
            sources.end());
  const auto half = s.scene().module_stats()["grass"]["blades"].get<std::uint64_t>();
  ASSERT_TRUE(density(false).ok());
  fs::last_write_time(dir / "moss.png", fs::last_write_time(dir / "moss.png") + std::chrono::seconds(2));
  s.poll_sources(true);
  const auto full = s.scene().module_stats()["grass"]["blades"].get<std::uint64_t>();
  std::printf("blades: %llu with the left half black, %llu after rewriting moss.png white\n",
              static_cast<unsigned long long>(half), static_cast<unsigned long long>(full));
  EXPECT_NEAR(static_cast<double>(half), 800.0, 80.0);
  EXPECT_NEAR(static_cast<double>(full), 1600.0, 80.0);
  ASSERT_FALSE(s.messages().empty());
  EXPECT_NE(s.messages().back().find("grass.mesh.density_file"), std::string::npos) << s.messages().back();
  fs::remove_all(dir);
}
