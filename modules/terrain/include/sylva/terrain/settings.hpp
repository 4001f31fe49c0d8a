#pragma once
// Settings of the height-field chunk tree (built offline) and of the per-frame LOD selection.
// Each struct lists its fields once through visit() (DESIGN.md §2), which drives JSON, --set,
// the editor and sylva-bench sweeps.

#include <sylva/core/params.hpp>

#include <array>
#include <cstdint>
#include <string>

namespace sylva::terrain {

// How a level's grid is triangulated (seed 002 §3.3 "Tessellation modes", -hq 0/1/2, beside
// Sylva's RTIN). The hq modes keep every sample of the level's grid (no flat reduction):
//   kRtin: right-triangulated irregular network reduced where flat (default; README "Meshes").
//   kHq0:  method A, 2 triangles per grid square, always the same diagonal ((x0,z0)-(x1,z1)).
//   kHq1:  method B, 2 triangles per square, the diagonal chosen from the corner heights: the one
//          whose two ends differ less (the seed's rule is not given; this is the extraction's
//          [Inference]). The levels' triangulations are then not nested (a fully morphed vertex
//          can still pop by the difference of the two diagonals).
//   kHq2:  method C, 4 triangles per square around a centre vertex whose height is the mean of
//          the 4 corners (twice the triangles, ~2x the vertices). Leaf centres lie half a sample
//          off the grid (ChunkVertex::centre).
// Measured triangles and errors follow from the meshes in every mode; the chunk file, the bake
// and the tree cache hold RTIN trees only (the hq modes are built in memory, for comparison).
enum class Tessellation : std::uint8_t { kRtin, kHq0, kHq1, kHq2 };
constexpr std::array<EnumName<Tessellation>, 4> enum_names(Tessellation) {
  return {{{Tessellation::kRtin, "rtin"}, {Tessellation::kHq0, "hq0"}, {Tessellation::kHq1, "hq1"},
           {Tessellation::kHq2, "hq2"}}};
}

// Offline build of the chunk quadtree (seed 002 §2.2, Ulrich 2002). Changing any of these
// means rebuilding the tree (Rebuild::kOffline).
struct ChunkTreeSettings {
  // Vertices per side of a chunk at its own level (the seed's -dimension): 2^k + 1 in [3, 257].
  // Every level has the same dimension; the sample spacing doubles per coarser level.
  int leaf_dimension = 33;
  // Flat-ground reduction: a vertex is dropped from a level's mesh when removing it changes the
  // surface by at most flat_tolerance * (that level's sample spacing in metres). 0 keeps every
  // vertex of the level's grid. The leaf level always uses 0 (exact leaves: nothing finer can
  // take over when the camera comes close). The resulting error is measured, never assumed.
  float flat_tolerance = 0.02f;
  // The error bound of a parent is raised to at least child_bound / (1 - max_morph_fraction), so
  // a morph over up to this share of a LOD range keeps the screen-space bound (README, "Morphing").
  // The default 0.5 makes every parent's bound at least twice its children's (Ulrich's "a child
  // halves the error"); that also keeps a coarser level's vertices from morphing while finer
  // chunks are drawn, which is what makes switches pop-free (measured: +0.2 % triangles on fBm).
  // LodSettings::morph_fraction above this relaxes the bound (Selection::bound_certified).
  float max_morph_fraction = 0.5f;
  // Worker threads for the build; 0 = all hardware threads.
  int threads = 0;
  // Keep the chunk meshes in memory. false keeps only the per-chunk metadata (error, bounds,
  // triangle counts), enough for selection statistics on fields too big to hold as meshes.
  bool keep_meshes = true;
  // Reorder each chunk's triangles and vertices for the post-transform cache (meshoptimizer).
  bool optimize_vertex_cache = true;
  // Refuse to build when the error grid would need more bytes than this (a clear kLimit error
  // instead of running the machine out of memory).
  double max_build_bytes = 3.0e9;
  // Mesh of each level (above): rtin (default) or the seed's hq0/hq1/hq2 full grids.
  Tessellation tessellation = Tessellation::kRtin;

  template <class V>
  void visit(V& v) {
    v(leaf_dimension, "leaf_dimension", {.min = 3, .max = 257, .help = "Vertices per chunk side, 2^k+1",
      .rebuild = Rebuild::kOffline});
    v(flat_tolerance, "flat_tolerance", {.min = 0.0, .max = 10.0, .unit = "m/m",
      .help = "Allowed vertical change per metre of level spacing when dropping flat vertices",
      .rebuild = Rebuild::kOffline});
    v(max_morph_fraction, "max_morph_fraction", {.min = 0.0, .max = 0.9,
      .help = "Largest morph fraction for which the pixel-error bound is certified", .rebuild = Rebuild::kOffline});
    v(threads, "threads", {.min = 0, .max = 256, .help = "Build threads (0 = all cores)"});
    v(keep_meshes, "keep_meshes", {.help = "Keep chunk meshes (false: statistics only)", .rebuild = Rebuild::kOffline});
    v(optimize_vertex_cache, "optimize_vertex_cache", {.help = "meshoptimizer vertex-cache order",
      .rebuild = Rebuild::kOffline});
    v(max_build_bytes, "max_build_bytes", {.min = 1e6, .max = 1e12, .unit = "B",
      .help = "Memory cap of the build's error grid", .log_scale = true});
    v(tessellation, "tessellation", {.help = "rtin (reduced where flat) or the seed's full grids hq0, hq1, hq2",
      .rebuild = Rebuild::kOffline});
  }
};

// The chunk-tree cache (tree_cache.hpp): where a built tree is kept so the next launch of the same
// field with the same ChunkTreeSettings reopens it instead of rebuilding (issue 15).
struct TreeCacheSettings {
  // "auto" = <temp>/sylva-terrain-cache, "" = no cache, else a folder (relative to the scene file).
  std::string directory = "auto";
  // Fields with fewer samples are built, not cached: below about 1414^2 a build takes about a second
  // on 2 cores and the file (~65 B per sample) would cost more disk than the launch time it
  // saves (README, "Tree cache"). 0 caches every field.
  int min_samples = 2'000'000;
  // Cache files kept in the folder; the least recently used beyond this are deleted after a write
  // (a 4097^2 tree is ~1.1 GB, and every tree-setting change in the editor makes a new one).
  int max_files = 4;

  template <class V>
  void visit(V& v) {
    v(directory, "directory", {.min = 0, .max = 4096,
      .help = "Chunk-tree cache folder (auto = temp folder, empty = no cache)"});
    v(min_samples, "min_samples", {.min = 0, .max = 1'000'000'000,
      .help = "Smallest field (samples) whose tree is cached"});
    v(max_files, "max_files", {.min = 1, .max = 1000, .help = "Cached trees kept (least recently used deleted)"});
  }
};

// Which test decides that a chunk is detailed enough.
enum class LodCriterion : std::uint8_t {
  // Ulrich 2002: rho = K * delta / D <= tau, K = viewport_width / (2 tan(fov_x / 2)), D = distance
  // from the camera to the nearest point of the chunk's bounding box, delta = measured error.
  kScreenSpaceError,
  // Seed 002 §2.3: chunk_error * lod_distance / d <= 1, chunk_error = the chunk's sample spacing,
  // d = distance to the chunk centre. Kept for comparison; it does not bound the pixel error.
  kSeedDistance,
  // No LOD: every leaf (the full-resolution mesh) is drawn, the "unoptimised rendering" baseline
  // of seed 002 Tab. 3.1. Frustum culling still follows LodSettings::frustum_cull.
  kBruteForce,
};
constexpr std::array<EnumName<LodCriterion>, 3> enum_names(LodCriterion) {
  return {{{LodCriterion::kScreenSpaceError, "screen_space_error"}, {LodCriterion::kSeedDistance, "seed_distance"},
           {LodCriterion::kBruteForce, "brute_force"}}};
}

// How chunks of different LOD are joined.
enum class CrackFix : std::uint8_t {
  kSeams,   // zero-width seam fans built by the finer side: bit-identical shared edges (default)
  kSkirts,  // vertical skirts hanging below every chunk edge, depth from the chunks' errors
  kNone,    // nothing: for demonstrating the cracks
};
constexpr std::array<EnumName<CrackFix>, 3> enum_names(CrackFix) {
  return {{{CrackFix::kSeams, "seams"}, {CrackFix::kSkirts, "skirts"}, {CrackFix::kNone, "none"}}};
}

// Per-frame selection (Rebuild::kNone: read every frame).
struct LodSettings {
  float max_pixel_error = 1.0f;  // tau [px]
  // Share of a chunk's LOD range over which its new vertices move to the parent surface
  // (CDLOD-style). 0 = no morphing (LOD switches pop).
  float morph_fraction = 0.25f;
  LodCriterion criterion = LodCriterion::kScreenSpaceError;
  float lod_distance = 100.0f;   // the seed's -distance (only for kSeedDistance)
  CrackFix crack_fix = CrackFix::kSeams;
  bool frustum_cull = true;

  template <class V>
  void visit(V& v) {
    v(max_pixel_error, "max_pixel_error", {.min = 0.05, .max = 64.0, .unit = "px",
      .help = "Largest allowed projected height error (tau)", .log_scale = true});
    v(morph_fraction, "morph_fraction", {.min = 0.0, .max = 1.0,
      .help = "Share of a LOD range used to morph towards the parent"});
    v(criterion, "criterion", {.help = "screen_space_error (Ulrich), seed_distance (seed 002) or brute_force (no LOD)"});
    v(lod_distance, "lod_distance", {.min = 0.01, .max = 1e6, .unit = "m",
      .help = "Seed criterion: distance per metre of sample spacing", .log_scale = true});
    v(crack_fix, "crack_fix", {.help = "seams, skirts or none"});
    v(frustum_cull, "frustum_cull", {.help = "Skip chunks outside the view frustum"});
  }
};

}  // namespace sylva::terrain
