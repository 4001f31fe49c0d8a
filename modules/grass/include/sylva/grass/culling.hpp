#pragma once
// Per-blade culling and LOD formulas (CPU reference; shaders/cull.comp evaluates the same
// expressions and the GL tests compare the two).
//
// Order of tests for one blade (the first that fails names the reason):
//  1. density   rank >= density_scale                       (quality knob; seed 001 eq. 4.1 reads
//               a random r1 against the map, here the map already set the count, see generator.hpp)
//  2. distance  rank >= keep(d) * density_scale, d = |root - camera|, where
//               keep(d) = 1 before thinning_start, falls linearly to thinning_min_keep at
//               near_distance, and is 0 beyond (seed 001 eq. 4.3: start 0 and min_keep 0 give
//               exactly 1 - d/d_max). Ranks are low-discrepancy within a tile, so the survivors
//               stay evenly spread, and each blade has a fixed fade distance: no flicker.
//  3. frustum   the blade's bounding sphere (hull of v0, v1, v2 plus half its drawn width) is
//               outside one of the four side planes or behind the camera. Conservative: it
//               never removes a visible pixel.
//  4. orientation  |dot(view dir, width dir)| > orientation_threshold AND the edge-on width
//               w * sqrt(1 - dot^2) projects to fewer than orientation_max_px pixels; the second
//               clause (ours) keeps near blades whose sliver is still visible. Default threshold
//               0.97 (14 degrees from edge-on), not Jahrmann & Wimmer 2017's 0.9 (26 degrees):
//               with uniformly random orientations a threshold c removes a share
//               acos(c) / (pi/2) of the blades but only 1 - c of their projected area (the
//               integral of sin), so 0.97 culls 16 % of the in-view blades for 3 % of their
//               coverage, 0.9 culls 29 % for 10 %. Measured at 256x144 (grass_field_gl_test
//               CullingKeepsTheImage, 2026-11-22): 0.9 -> 35.3 dB PSNR against the unculled
//               picture, 0.95 -> 41.1, 0.97 -> 44.2, 0.98 -> 47.5, 0.99 -> 57.1 dB.
// A survivor whose rank is within 0.1 of keep is narrowed linearly to zero width (blade.tesc),
// so a blade fades out over a distance band instead of popping.
// Survivors are widened by 1 / keep (blend width_compensation, at most 4x) so that thinning
// keeps the covered area, which is what the eye integrates at a distance.
//
// Tessellation: segments = clamp(ceil(projected blade height [px] / pixels_per_segment), 1,
// max_tess_level), i.e. seed 001 eq. 2.3 driven by screen size instead of linear distance.
// With cull.distance_tess_law (off by default) the seed's own law: segments =
// clamp(ceil(max_tess_level (1 - d / near_distance)), 1, max_tess_level), d = root distance
// (eq. 2.3 with s = max_tess_level, d_max = near_distance; its level 0 beyond d_max is the
// culling at near_distance). It ignores resolution and field of view, so a blade gets as many
// segments in a 256 px picture as in a 4K one.
// cull.tess_spacing (seed 001 pitfall "LOD popping"): with the default `equal` the level above is
// ceil-ed and the segment count jumps by one where it crosses an integer; with
// `fractional_even` / `fractional_odd` the level is passed without the ceil (the same clamps)
// and the tessellator morphs the new pair of segments in from zero length (tessellation_level,
// spacing_segments). A jittered blade (blade.hpp drawn_control) is culled and tessellated with
// its drawn control point.

#include <sylva/grass/blade.hpp>
#include <sylva/grass/generator.hpp>
#include <sylva/grass/settings.hpp>

#include <glm/glm.hpp>

#include <cstdint>

namespace sylva::grass {

// What the cull stage sees of the camera, in BladeSet-local coordinates.
struct CullView {
  glm::vec4 planes[4];          // left, right, bottom, top; inside: dot(p, n) + w >= 0, |n| = 1
  glm::vec3 camera{0.0f};       // camera position
  glm::vec3 forward{0.0f, 0.0f, -1.0f};  // unit view direction
  float pixels_per_radian = 1.0f;        // viewport_height / (2 tan(fov_y / 2))
};

// From a BladeSet-local view-projection matrix (any depth convention: only the side planes are
// taken from it) and the camera in the same frame.
CullView make_cull_view(const glm::mat4& view_projection, const glm::vec3& camera, const glm::vec3& forward,
                        float viewport_height_px, float fov_y_radians);

enum class CullResult : std::uint8_t { kVisible = 0, kDensity, kDistance, kFrustum, kOrientation };
const char* to_string(CullResult result);

// keep(d) of step 2 (without density_scale), in [0, 1].
float distance_keep(float distance, const CullSettings& settings);
// Width multiplier for a blade that survived with keep fraction `keep` (> 0).
float width_scale(float keep, const CullSettings& settings);

CullResult cull_blade(const Blade& blade, const CullView& view, const CullSettings& settings);

// Level along the blade handed to the tessellator (blade.tesc), in [1, max(max_tess_level, 1)]:
// an integer (ceil) for TessSpacing::kEqual, continuous in the distance for the fractional modes.
float tessellation_level(const Blade& blade, const CullView& view, const CullSettings& settings);

// Segments the tessellator makes of an edge of `level` (GL 4.5 §11.2.2, GL_MAX_TESS_GEN_LEVEL
// 64): equal ceil(clamp(level, 1, 64)); fractional_even the even integer at or above
// clamp(level, 2, 64); fractional_odd the odd integer at or above clamp(level, 1, 63).
int spacing_segments(float level, TessSpacing spacing);

// Segments along the blade for the tessellator, >= 1: int(tessellation_level) for kEqual (the
// level is an integer unless max_tess_level is not), spacing_segments of it otherwise.
int tessellation_segments(const Blade& blade, const CullView& view, const CullSettings& settings);

// Most blades (patches) one draw call may hold: kTessVerticesPerDraw / (2 (L + 1)) with
// L = min(ceil(max_tess_level), 64), since a blade of n segments tessellates to 2 (n + 1)
// vertices. Why: Mesa llvmpipe (22.3, the CI's GL) joins vertices of unrelated blades into long
// streaks once one draw's tessellated output passes 65,536 vertices (measured on the default
// scene at 960x540: 4,096 blades of <= 8 segments per draw streak in about one run of two,
// 1,024 blades of <= 64 segments streak every run, 256 never). GrassField therefore splits each
// chunk's blade draw into indirect sub-draws of this size (grass/draw_batches.comp writes them
// from the cull count); kTessVerticesPerDraw is half the failing count, as margin. Result >= 1.
inline constexpr std::uint32_t kTessVerticesPerDraw = 32768;
// With a fractional spacing L is spacing_segments(max_tess_level, spacing) (an odd max level
// gives one more segment under fractional_even).
std::uint32_t blades_per_draw(float max_tess_level, TessSpacing spacing = TessSpacing::kEqual);

// Tile-level test (CPU, before any blade is looked at): the tile's box intersects the frustum
// and its nearest point is closer than near_distance.
bool tile_visible(const GrassTile& tile, const CullView& view, const CullSettings& settings);

// Tallies of one pass, by reason.
struct CullCounts {
  std::uint64_t considered = 0;
  std::uint64_t visible = 0;
  std::uint64_t density = 0;
  std::uint64_t distance = 0;
  std::uint64_t frustum = 0;
  std::uint64_t orientation = 0;
  std::uint64_t segments = 0;  // sum of tessellation segments of the visible blades
  void add(CullResult r);
};

// cull_blade over every blade of the visible tiles (tiles failing tile_visible count as frustum
// or distance culls for all their blades).
CullCounts cull_blade_set(const BladeSet& set, const CullView& view, const CullSettings& settings);

}  // namespace sylva::grass
