// The terrain suite (--suite terrain): Ulrich's screen-space error bound tau against the seed's
// distance criterion on one error-against-time plot, plus the crack fixes, on the built-in
// terrain target (the module's real chunk tree, selection, morphing and seams).
#include "suites.hpp"
#include "with_terrain/terrain_target.hpp"

namespace sylva::bench {

Result<SuiteSpec> make_terrain_suite() {
  SuiteSpec s;
  s.name = "terrain";
  s.module = "terrain";
  RunSpec& r = s.run;
  r.factory = []() -> Result<std::unique_ptr<BenchTarget>> { return make_terrain_target(); };
  r.scene = "builtin:terrain (1025 x 1025 fBm field, 4 m spacing, 900 m relief, 33-vertex chunks)";
  r.suite = "terrain";
  r.description =
      "Terrain chunked LOD: the screen-space error bound tau (Ulrich 2002, terrain.lod.max_pixel_error) against the "
      "seed's distance criterion (terrain.lod.lod_distance), and seams against skirts and no crack fix, each against "
      "the tree refined to tau = 0.05 px, and tau without morphing (the seed's criterion never morphs). The table's max "
      "geometric error is the largest projected error of the "
      "drawn chunks (K delta / (D - delta) with the measured delta), the number tau certifies and the seed's "
      "criterion does not.";
  r.sweep_groups = {
      {{"terrain.lod.criterion", {"screen_space_error"}},
       {"terrain.lod.max_pixel_error", {"0.5", "1", "2", "4", "8"}}},
      {{"terrain.lod.criterion", {"seed_distance"}}, {"terrain.lod.lod_distance", {"10", "20", "40", "80", "160"}}},
      {{"terrain.lod.max_pixel_error", {"2"}}, {"terrain.lod.crack_fix", {"skirts", "none"}}},
      // The seed's criterion never morphs; these separate what morphing costs in per-frame
      // image error (it buys the absence of pops, which a per-frame metric cannot see).
      {{"terrain.lod.morph_fraction", {"0"}}, {"terrain.lod.max_pixel_error", {"1", "2", "4"}}},
  };
  r.reference = {{"terrain.lod.criterion", "screen_space_error"}, {"terrain.lod.max_pixel_error", "0.05"}};
  r.reference_note = "screen-space criterion with tau = 0.05 px (practically the full-resolution field where it is "
                     "on screen)";
  r.camera_path = "flight";
  r.frames = 12;
  r.size = {256, 144};
  return s;
}

}  // namespace sylva::bench
