// The curated suites (--suite), as scenes run through modules/scene. Each suite says what
// "maximum quality" means for its module, sweeps the settings that trade image error for time,
// and flies a camera path that shows what the settings change.
#include "suites.hpp"
#include "with_scene/scene_target.hpp"
#include "with_scene/shipped_files.hpp"
#include "with_scene/stream_suite.hpp"

#include <sylva/scene/module_registry.hpp>

#include <fmt/format.h>

#include <filesystem>
#include <system_error>

namespace sylva::bench {
namespace {

Error unavailable(const std::string& suite, const std::string& module) {
  return make_error(ErrorCode::kUnsupported,
                    fmt::format("module not available: the {} suite needs the {} module in modules/scene, and this "
                                "build's scene registry has no \"{}\" section (the module is built out or not yet "
                                "integrated into the scene)",
                                suite, module, module));
}

// Terrain: the scene's ground drawn by modules/terrain (chunk tree, screen-space-error or seed
// distance selection, seams/skirts, morphing, shadows: exactly what the player draws). A 4 km
// field of 900 m relief, flown over diagonally 70-130 m above the ground with the horizon in
// view, so near chunks are fine, far chunks coarse and silhouettes of distant ridges show.
constexpr const char* kTerrainScene = R"json({
  "sylva_scene": 1,
  "name": "bench: terrain flight",
  "camera": {"position": [-1720.0, 120.0, 1720.0], "height_mode": "above_ground", "yaw_deg": -45.0, "pitch_deg": -9.0, "fov_deg": 60.0},
  "sun": {"azimuth_deg": 200.0, "elevation_deg": 35.0, "fog_density": 0.0002},
  "terrain": {"size": 4096.0, "resolution": 1025, "height": 900.0, "generator": "fbm",
              "noise": {"octaves": 9, "persistence": 0.5, "frequency": 0.0004, "seed": 21},
              "tree": {"leaf_dimension": 33},
              "render": {"lod": {"max_pixel_error": 1.0, "morph_fraction": 0.25, "crack_fix": "seams"}}},
  "camera_paths": {
    "flight": {"interpolation": "catmull_rom", "keys": [
      {"time_s": 0.0, "position": [-1720.0, 130.0, 1720.0], "height_mode": "above_ground", "yaw_deg": -45.0, "pitch_deg": -9.0},
      {"time_s": 4.0, "position": [-614.0, 100.0, 1044.0], "height_mode": "above_ground", "yaw_deg": -50.0, "pitch_deg": -7.0},
      {"time_s": 8.0, "position": [500.0, 80.0, -491.0], "height_mode": "above_ground", "yaw_deg": -40.0, "pitch_deg": -8.0},
      {"time_s": 12.0, "position": [1638.0, 110.0, -1638.0], "height_mode": "above_ground", "yaw_deg": -45.0, "pitch_deg": -10.0}]}
  }
})json";

}  // namespace

// The terrain suite's scene, also flown by --suite stream (stream_suite.hpp).
std::string terrain_suite_scene() { return kTerrainScene; }

namespace {

Result<SuiteSpec> terrain_suite() {
  if (scene::find_module("terrain") == nullptr) return unavailable("terrain", "terrain");
  SuiteSpec s;
  s.name = "terrain";
  s.module = "terrain";
  RunSpec& r = s.run;
  r.factory = scene_text_factory(kTerrainScene, "<bench terrain suite>");
  r.scene = "terrain suite scene (modules/scene terrain section: 4 km fBm field, 1025 x 1025 samples, 900 m relief, "
            "33-vertex chunks)";
  r.suite = "terrain";
  r.description =
      "Terrain chunked LOD as the scene draws it: the screen-space error bound tau (Ulrich 2002, "
      "terrain.render.lod.max_pixel_error) against the seed's distance criterion (terrain.render.lod.lod_distance), "
      "seams against skirts and no crack fix, and tau without morphing (the seed's criterion never morphs), each "
      "against the tree refined to tau = 0.05 px. The table's max geometric error is the largest projected error of "
      "the drawn chunks (K delta / (D - delta) with each chunk's measured delta, from the scene's terrain renderer), "
      "the number tau certifies and the seed's criterion does not.";
  const std::string lod = "terrain.render.lod.";
  r.sweep_groups = {
      {{lod + "criterion", {"screen_space_error"}}, {lod + "max_pixel_error", {"0.5", "1", "2", "4", "8"}}},
      {{lod + "criterion", {"seed_distance"}}, {lod + "lod_distance", {"10", "20", "40", "80", "160"}}},
      {{lod + "max_pixel_error", {"2"}}, {lod + "crack_fix", {"skirts", "none"}}},
      // The seed's criterion never morphs; these separate what morphing costs in per-frame image
      // error (it buys the absence of pops, which a per-frame metric cannot see).
      {{lod + "morph_fraction", {"0"}}, {lod + "max_pixel_error", {"1", "2", "4"}}},
  };
  r.reference = {{lod + "criterion", "screen_space_error"}, {lod + "max_pixel_error", "0.05"}};
  r.reference_note = "screen-space criterion with tau = 0.05 px (practically the full-resolution field where it is "
                     "on screen)";
  r.camera_path = "flight";
  r.frames = 12;
  r.size = {256, 144};
  return s;
}

// Grass: blades near, billboard clumps in the middle, a ground layer far (seeds 001/003). The
// walk looks across a 100 m meadow so every band is on screen; its heights are above the ground
// (with absolute heights the 6 m hills put the camera under the ground in part of the walk).
constexpr const char* kGrassScene = R"json({
  "sylva_scene": 1,
  "name": "bench: grass meadow",
  "camera": {"position": [0.0, 1.7, 45.0], "height_mode": "above_ground", "yaw_deg": 0.0, "pitch_deg": -6.0, "fov_deg": 60.0},
  "sun": {"azimuth_deg": 210.0, "elevation_deg": 32.0, "fog_density": 0.0015},
  "wind": {"direction_deg": 30.0, "strength": 4.0, "gust_amplitude": 3.0, "seed": 5},
  "ground": {"size": 400.0, "resolution": 129, "height": 6.0, "snow_fraction": 1.0,
             "noise": {"octaves": 4, "persistence": 0.45, "frequency": 0.004, "seed": 3}},
  "grass": {"area_min": [-50.0, -50.0], "area_max": [50.0, 50.0], "field": {"density": 40.0, "seed": 9}},
  "camera_paths": {
    "walk": {"interpolation": "catmull_rom", "keys": [
      {"time_s": 0.0, "position": [0.0, 1.7, 45.0], "height_mode": "above_ground", "yaw_deg": 0.0, "pitch_deg": -6.0},
      {"time_s": 4.0, "position": [-6.0, 1.8, 25.0], "height_mode": "above_ground", "yaw_deg": 15.0, "pitch_deg": -8.0},
      {"time_s": 8.0, "position": [-2.0, 4.0, 5.0], "height_mode": "above_ground", "yaw_deg": -20.0, "pitch_deg": -18.0},
      {"time_s": 12.0, "position": [10.0, 2.0, -15.0], "height_mode": "above_ground", "yaw_deg": -60.0, "pitch_deg": -5.0}]}
  }
})json";

Result<SuiteSpec> grass_suite() {
  if (scene::find_module("grass") == nullptr) return unavailable("grass", "grass");
  SuiteSpec s;
  s.name = "grass";
  s.module = "grass";
  RunSpec& r = s.run;
  r.factory = scene_text_factory(kGrassScene, "<bench grass suite>");
  r.scene = "grass suite meadow (100 m x 100 m, 40 blades/m^2, gentle fBm ground)";
  r.suite = "grass";
  r.description =
      "Grass LOD: where the tessellated blades end (cull.near_distance; billboard clumps and the ground layer take "
      "over), the tessellation scale (cull.pixels_per_segment: projected pixels per blade segment), distance "
      "thinning, and the clumps of the far field, each against a reference with blades over the whole meadow, no "
      "thinning and the finest tessellation. The first two groups keep everything else at reference quality, so "
      "they converge to the reference; the last two show what thinning and clumps cost and buy.";
  const std::vector<SweepAxis> fine = {{"grass.render.cull.distance_thinning", {"false"}},
                                       {"grass.render.cull.max_tess_level", {"16"}}};
  auto group = [&](std::vector<SweepAxis> extra, bool fine_tessellation) {
    std::vector<SweepAxis> g = {fine[0]};
    if (fine_tessellation) g.push_back(fine[1]);
    for (SweepAxis& a : extra) g.push_back(std::move(a));
    return g;
  };
  r.sweep_groups = {
      group({{"grass.render.cull.pixels_per_segment", {"2"}},
             {"grass.render.cull.near_distance", {"8", "15", "25", "40", "70"}}},
            true),
      group({{"grass.render.cull.near_distance", {"150"}},
             {"grass.render.cull.pixels_per_segment", {"4", "8", "16", "32"}}},
            true),
      {{"grass.render.cull.distance_thinning", {"true"}}, {"grass.render.cull.near_distance", {"25", "50"}}},
      {{"grass.far.clumps", {"false"}}, {"grass.render.cull.near_distance", {"25"}}},
  };
  r.reference = {{"grass.render.cull.near_distance", "150"},
                 {"grass.render.cull.distance_thinning", "false"},
                 {"grass.render.cull.pixels_per_segment", "2"},
                 {"grass.render.cull.max_tess_level", "16"}};
  // 2 px per segment, not the range's 0.5: below about 2 px the near blades vanish in the walk's
  // fourth frame (grass module issue, see apps/bench/README.md "Findings").
  r.reference_note = "blades everywhere (near_distance 150 m covers the meadow), no thinning, 2 px per segment, "
                     "up to 16 segments";
  r.camera_path = "walk";
  r.frames = 8;
  r.size = {256, 144};
  return s;
}

// Trees: a forest on rolling hills, approached from outside so trees are seen from 150 m down
// to a few metres (where the LOD thresholds and the mesh detail matter).
constexpr const char* kTreesScene = R"json({
  "sylva_scene": 1,
  "name": "bench: forest approach",
  "camera": {"position": [0.0, 12.0, 110.0], "height_mode": "above_ground", "yaw_deg": 0.0, "pitch_deg": -5.0, "fov_deg": 60.0},
  "sun": {"azimuth_deg": 150.0, "elevation_deg": 40.0, "fog_density": 0.002},
  "environment": {"season": 0.3},
  "wind": {"direction_deg": 10.0, "strength": 6.0, "gust_amplitude": 4.0, "seed": 2},
  "ground": {"size": 1024.0, "resolution": 129, "height": 25.0, "generator": "fbm",
             "noise": {"octaves": 5, "frequency": 0.002, "seed": 3}, "snow_fraction": 1.0},
  "vegetation": {"area_min": [-50.0, -50.0], "area_max": [50.0, 50.0], "trees_per_hectare": 40.0, "min_spacing": 6.0,
                 "species": "broadleaf", "seed": 4},
  "camera_paths": {
    "approach": {"interpolation": "catmull_rom", "keys": [
      {"time_s": 0.0, "position": [0.0, 12.0, 110.0], "height_mode": "above_ground", "pitch_deg": -5.0},
      {"time_s": 6.0, "position": [-10.0, 6.0, 45.0], "height_mode": "above_ground", "yaw_deg": 10.0, "pitch_deg": -2.0},
      {"time_s": 12.0, "position": [5.0, 2.5, 5.0], "height_mode": "above_ground", "yaw_deg": 30.0, "pitch_deg": 8.0}]}
  }
})json";

Result<SuiteSpec> trees_suite() {
  if (scene::find_module("vegetation") == nullptr) return unavailable("trees", "vegetation");
  SuiteSpec s;
  s.name = "trees";
  s.module = "vegetation";
  RunSpec& r = s.run;
  r.factory = scene_text_factory(kTreesScene, "<bench trees suite>");
  r.scene = "trees suite forest (100 m x 100 m, 40 broadleaf trees per hectare, fBm hills)";
  r.suite = "trees";
  r.description =
      "Tree LOD (seed 000): the image-based levels' thresholds, v1 (LOD0 geometry to LOD1 slices) with v2 far out, "
      "and v2 (LOD1 to the LOD2 billboard) with v1 near, the screen-size criterion's s1, the drawing distance "
      "(max_distance), the animation level (the seed's table 5.5: static, trunk, branches, leaves) and the bark mesh "
      "detail (ring spacing), against every tree drawn as full geometry (image-based levels off) at the finest mesh "
      "with full animation. The table counts instances per LOD level (vegetation.lod0/1/2; a tree in a transition "
      "band counts in both levels).";
  const std::string f = "vegetation.forest.";
  r.sweep_groups = {
      {{f + "lod.v2", {"200"}}, {f + "lod.v1", {"10", "25", "45", "80"}}},
      {{f + "lod.v1", {"20"}}, {f + "lod.v2", {"30", "60", "110"}}},
      {{f + "lod.criterion", {"screen_size"}}, {f + "lod.s1", {"40", "70", "140"}}},
      // Full geometry everywhere, as in the reference, so these groups measure only their own setting.
      {{f + "lod.enabled", {"false"}}, {f + "max_distance", {"25", "50", "100"}}},
      {{f + "lod.enabled", {"false"}}, {f + "animation_level", {"static", "trunk", "branches"}}},
      {{f + "lod.enabled", {"false"}}, {"vegetation.mesh.ring_spacing", {"0.5", "1", "2", "4"}}},
  };
  r.reference = {{f + "lod.enabled", "false"},
                 {f + "max_distance", "2000"},
                 {f + "animation_level", "leaves"},
                 {"vegetation.mesh.ring_spacing", "0.25"}};
  r.reference_note = "every tree drawn as full geometry (image-based LOD off, max_distance 2 km), full animation, "
                     "bark rings every 0.25 m";
  r.camera_path = "approach";
  r.frames = 8;
  r.size = {256, 144};
  return s;
}

// Voxels: a generated world seen from above and then at eye level; the meshers must give the
// same picture (any difference is a bug), at different quad counts and times.
constexpr const char* kVoxelScene = R"json({
  "sylva_scene": 1,
  "name": "bench: voxel world",
  "camera": {"position": [-50.0, 75.0, -50.0], "yaw_deg": -135.0, "pitch_deg": -30.0, "fov_deg": 60.0},
  "sun": {"azimuth_deg": 140.0, "elevation_deg": 40.0, "fog_density": 0.004},
  "voxel": {"center": [16.0, 16.0], "radius_chunks": 2, "threads": 2, "worldgen": {"seed": 3, "variants_per_species": 2}},
  "camera_paths": {
    "flyover": {"interpolation": "catmull_rom", "keys": [
      {"time_s": 0.0, "position": [-50.0, 75.0, -50.0], "yaw_deg": -135.0, "pitch_deg": -30.0},
      {"time_s": 5.0, "position": [0.0, 60.0, -30.0], "yaw_deg": -170.0, "pitch_deg": -25.0},
      {"time_s": 10.0, "position": [40.0, 50.0, 10.0], "yaw_deg": 150.0, "pitch_deg": -15.0}]}
  }
})json";

Result<SuiteSpec> voxel_suite() {
  if (scene::find_module("voxel") == nullptr) return unavailable("voxel", "voxel");
  SuiteSpec s;
  s.name = "voxel";
  s.module = "voxel";
  RunSpec& r = s.run;
  r.factory = scene_text_factory(kVoxelScene, "<bench voxel suite>");
  r.scene = "voxel suite world (5 x 5 chunk columns, seed 3)";
  r.suite = "voxel";
  r.description =
      "Voxel mesher choice (hidden-face culling, greedy, bitmask greedy): the same visible surface from fewer "
      "quads, so the image error must stay at zero while the cost drops; and the view radius in chunks against the "
      "full world; and far plants as shells from 0 blocks or never (issue 18; default 96; the module's "
      "plant_triangles and plant_far_chunks stats); and the depth pre-pass, off by default (issue 18: each "
      "vertex twice against each pixel shaded once).";
  r.sweep_groups = {
      {{"voxel.mesher", {"culled", "greedy", "bitmask"}}},
      {{"voxel.radius_chunks", {"0", "1"}}},
      {{"voxel.render.plant_far_beyond", {"0", "1000000"}}},
      {{"voxel.render.depth_prepass", {"true"}}},
  };
  r.reference = {{"voxel.mesher", "culled"}, {"voxel.radius_chunks", "2"}};
  r.reference_note = "hidden-face culling only (one quad per visible block face) over the whole 5 x 5 chunk world";
  r.camera_path = "flyover";
  r.frames = 8;
  r.size = {256, 144};
  return s;
}

// The general model (seed 002 §4): the shipped scenes/model_terrain.obj (a 400 m sheet of hills
// with an overhanging cliff, 32768 triangles) in the model tree, flown around so the cliff is
// seen near and far. The shipped scenes folder is found from the working directory or above the
// executable (the bench runs from the source or build tree).
constexpr const char* kModelScene = R"json({
  "sylva_scene": 1,
  "name": "bench: general-model terrain",
  "camera": {"position": [-190.0, 40.0, -190.0], "yaw_deg": -135.0, "pitch_deg": -8.0, "fov_deg": 60.0},
  "sun": {"azimuth_deg": 90.0, "elevation_deg": 30.0, "fog_density": 0.0008},
  "render": {"shadows": {"max_distance": 700.0}},
  "ground": {"size": 4000.0, "resolution": 33, "generator": "flat"},
  "model_terrain": {"file": "model_terrain.obj", "offset": [0.0, -0.5, 0.0],
                    "tree": {"levels": 5, "reducer": "qem"}, "render": {"lod": {"max_pixel_error": 1.0}}},
  "camera_paths": {
    "orbit": {"interpolation": "catmull_rom", "keys": [
      {"time_s": 0.0, "position": [-260.0, 60.0, -260.0], "yaw_deg": -135.0, "pitch_deg": -10.0},
      {"time_s": 4.0, "position": [-150.0, 30.0, -40.0], "yaw_deg": -100.0, "pitch_deg": -6.0},
      {"time_s": 8.0, "position": [-120.0, 45.0, 120.0], "yaw_deg": -50.0, "pitch_deg": -12.0},
      {"time_s": 12.0, "position": [40.0, 90.0, 200.0], "yaw_deg": 10.0, "pitch_deg": -25.0}]}
  }
})json";

// The folder holding model_terrain.obj (shipped_files.hpp).
Result<std::filesystem::path> shipped_scenes_dir() {
  auto obj = find_shipped_file("scenes/model_terrain.obj", "the model suite");
  if (!obj.ok()) return obj.error();
  return obj->parent_path();
}

Result<SuiteSpec> model_suite() {
  if (scene::find_module("model_terrain") == nullptr) return unavailable("model", "model_terrain");
  auto scenes = shipped_scenes_dir();
  if (!scenes.ok()) return scenes.error();
  SuiteSpec s;
  s.name = "model";
  s.module = "model_terrain";
  RunSpec& r = s.run;
  r.factory = scene_text_factory(kModelScene, "<bench model suite>", *scenes);
  r.scene = "model suite: scenes/model_terrain.obj (400 m sheet with an overhanging cliff, 32768 triangles) in the "
            "model tree (QEM, locked borders)";
  r.suite = "model";
  r.description =
      "General-model terrain (seed 002 §4): the screen-space error bound tau "
      "(model_terrain.render.lod.max_pixel_error) on a 5-level tree, the tree height (model_terrain.tree.levels, the "
      "seed's -level) at tau = 1 px, and the seed's shortest-edge reducer against QEM, each against the "
      "full-resolution mesh (a one-level tree: every frame draws all 32768 triangles). The module's metrics carry "
      "the tree's build time (model_terrain.tree_build_ms) and the largest projected error of the drawn segments.";
  const std::string m = "model_terrain.";
  r.sweep_groups = {
      {{m + "tree.levels", {"5"}}, {m + "render.lod.max_pixel_error", {"0.5", "1", "2", "4", "8"}}},
      {{m + "render.lod.max_pixel_error", {"1"}}, {m + "tree.levels", {"2", "3", "4", "6"}}},
      {{m + "tree.reducer", {"shortest_edge"}}, {m + "render.lod.max_pixel_error", {"1", "4"}}},
  };
  r.reference = {{m + "tree.levels", "1"}};
  r.reference_note = "the full-resolution mesh: a one-level model tree draws the file's 32768 triangles";
  r.camera_path = "orbit";
  r.frames = 8;
  r.size = {256, 144};
  return s;
}

}  // namespace

Result<SuiteSpec> make_scene_suite(const std::string& name) {
  if (name == "terrain") return terrain_suite();
  if (name == "grass") return grass_suite();
  if (name == "trees") return trees_suite();
  if (name == "voxel") return voxel_suite();
  if (name == "model") return model_suite();
  return make_error(ErrorCode::kUnsupported,
                    fmt::format("module not available: the {} module is in the scene registry but the bench has no "
                                "curated sweep for it yet", name));
}

}  // namespace sylva::bench
