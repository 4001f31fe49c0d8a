#pragma once
// The general-model chunk tree (seed 002 §4): an arbitrary triangle mesh (overhangs, arches),
// split into a quadtree of segments over the x/z ground plane by triangle centroid (§4.1, half-open
// cells so every triangle belongs to exactly one segment per level), with the segment's border
// vertices found by the seed's three-case rule (§4.2) and locked, then each non-leaf segment
// reduced from the original triangles (§4.4: "extract from the original landscape, then reduce").
//
// Crack-free by construction: locked border vertices keep their exact original positions and the
// reducers never remove a border edge, so the outline of every segment is the same polyline of
// original vertices at every level and any combination of segment levels closes (no run-time
// seams, as in the seed). The error of a segment is the measured Hausdorff distance between its
// reduced and its original triangles (both directions, the larger); error_bound is made monotone
// up the tree. Selection uses the screen-space rule of selection.hpp.

#include <sylva/core/params.hpp>
#include <sylva/core/result.hpp>
#include <sylva/terrain/chunk_tree.hpp>
#include <sylva/terrain/lod_view.hpp>
#include <sylva/terrain/mesh.hpp>
#include <sylva/terrain/settings.hpp>

#include <array>
#include <cstdint>
#include <vector>

namespace sylva::terrain {

enum class Reducer : std::uint8_t { kQem, kShortestEdge };
constexpr std::array<EnumName<Reducer>, 2> enum_names(Reducer) {
  return {{{Reducer::kQem, "qem"}, {Reducer::kShortestEdge, "shortest_edge"}}};
}

struct ModelTreeSettings {
  int levels = 5;                // quadtree height (the seed's -level; recommended 5)
  // Share of a segment's original triangles kept per level above the leaves: 0.25 keeps about
  // the same triangle count in every segment (each level covers 4x the area).
  float keep_per_level = 0.25f;
  // The seed's -reduce (§4.3, Tab. 4.6-4.11): the share of a segment's triangles one reduction
  // pass removes, with one pass per level above the leaves (a segment d levels above them gets d
  // passes, each reducing the previous pass's result). 0 = off: keep_per_level decides.
  float reduce_per_pass = 0.0f;
  Reducer reducer = Reducer::kQem;
  bool lock_mesh_boundary = true;  // also lock the open outline of the whole model
  int threads = 0;
  bool optimize_vertex_cache = true;

  template <class V>
  void visit(V& v) {
    v(levels, "levels", {.min = 1, .max = 12, .help = "Quadtree height (seed -level)", .rebuild = Rebuild::kOffline});
    v(keep_per_level, "keep_per_level", {.min = 0.01, .max = 1.0,
      .help = "Triangle share kept per coarser level", .rebuild = Rebuild::kOffline});
    v(reduce_per_pass, "reduce_per_pass", {.min = 0.0, .max = 0.99,
      .help = "Seed -reduce: share removed per pass, one pass per level (0 = use keep_per_level)",
      .rebuild = Rebuild::kOffline});
    v(reducer, "reducer", {.help = "qem (default) or shortest_edge (the seed's)", .rebuild = Rebuild::kOffline});
    v(lock_mesh_boundary, "lock_mesh_boundary", {.help = "Keep the model's open outline", .rebuild = Rebuild::kOffline});
    v(threads, "threads", {.min = 0, .max = 256, .help = "Build threads (0 = all cores)"});
    v(optimize_vertex_cache, "optimize_vertex_cache", {.help = "meshoptimizer vertex-cache order",
      .rebuild = Rebuild::kOffline});
  }
};

struct Segment {
  ChunkKey key;
  bool present = false;                 // holds at least one original triangle
  std::vector<std::uint32_t> indices;   // reduced triangles, indexing ModelTree::positions()
  std::uint32_t original_triangles = 0;
  std::uint32_t locked_vertices = 0;
  float error = 0.0f;                   // measured Hausdorff distance [m]
  float error_bound = 0.0f;             // monotone [m]
  glm::vec3 lo{0.0f}, hi{0.0f};         // bounds of the reduced triangles
  std::uint32_t triangle_count() const { return static_cast<std::uint32_t>(indices.size() / 3); }
};

struct ModelLevelReport {
  int level = 0;
  std::uint32_t segments = 0;
  std::uint64_t original_triangles = 0;
  std::uint64_t triangles = 0;
  float max_error = 0.0f;
  double reduce_ms = 0.0;   // summed over segments (CPU time, all threads)
  double measure_ms = 0.0;
};

struct ModelBuildReport {
  double total_ms = 0.0;
  int threads = 1;
  std::vector<ModelLevelReport> levels;
  std::size_t holes = 0, degenerate = 0, non_manifold = 0, flipped = 0;  // checks over all segments
};

class ModelTree {
 public:
  // Errors: invalid settings (names the parameter), an empty mesh or indices out of range,
  // non-finite positions, cancellation.
  static Result<ModelTree> build(const TriangleMesh& mesh, const ModelTreeSettings& settings,
                                 const BuildControl& control = {});

  int levels() const { return levels_; }
  const std::vector<glm::vec3>& positions() const { return positions_; }
  std::size_t segment_count() const { return segments_.size(); }
  const Segment& segment(std::uint32_t i) const { return segments_[i]; }
  std::uint32_t index(int level, std::uint32_t x, std::uint32_t z) const;
  std::array<std::uint32_t, 4> child_indices(std::uint32_t i) const;
  // Square ground-plane cell of the root: x/z origin and side [m].
  glm::dvec2 root_origin() const { return root_origin_; }
  double root_size() const { return root_size_; }
  const ModelBuildReport& report() const { return report_; }
  const ModelTreeSettings& settings() const { return settings_; }

 private:
  ModelTreeSettings settings_;
  int levels_ = 1;
  glm::dvec2 root_origin_{0.0};
  double root_size_ = 1.0;
  std::vector<glm::vec3> positions_;
  std::vector<std::uint32_t> level_offset_;
  std::vector<Segment> segments_;
  ModelBuildReport report_;
};

struct ModelSelection {
  std::vector<std::uint32_t> segments;
  std::uint64_t triangles = 0;
  std::uint32_t culled = 0;
  double cpu_ms = 0.0;
};

// Screen-space selection (rho = K * delta / (D - delta) <= tau, frustum culling); the seed's
// distance criterion is not offered here because the seed's general model used SoLOD ranges it
// does not give.
// With `unculled` (not null), the same traversal also fills it with what settings without
// frustum_cull would select (the shadow casters: the camera's LOD decisions, no frustum), so one
// selection serves both; `unculled` is overwritten.
ModelSelection select_segments(const ModelTree& tree, const LodView& view, const LodSettings& settings,
                               ModelSelection* unculled = nullptr);

}  // namespace sylva::terrain
