#pragma once
// Helpers shared by the terrain tests: test fields, camera poses, and the watertightness check.

#include <sylva/core/height_field.hpp>
#include <sylva/terrain/chunk_tree.hpp>
#include <sylva/terrain/frame_mesh.hpp>
#include <sylva/terrain/lod_view.hpp>
#include <sylva/terrain/selection.hpp>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <functional>
#include <random>
#include <string>
#include <vector>

namespace sylva::terrain::testing {

// Bit-exact equality of two arrays, empty ones included: memcmp must not be given the null
// data() of an empty vector (undefined behaviour, reported by UBSan).
template <class T>
bool same_bytes(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

// A path in the temporary folder that belongs to this process ("sylva_terrain_<pid>_<name>"):
// ctest runs every test case as its own process, two at a time, and suites may run side by
// side, so a fixed name is written, damaged or removed by another test while this one reads it.
std::filesystem::path unique_temp(const std::string& name);

HeightField make_field(int columns, int rows, double spacing, const std::function<float(int, int)>& height,
                       glm::dvec2 origin = {0.0, 0.0});
// fBm hills in [0, amplitude] metres.
HeightField fbm_field(int columns, int rows, double spacing, float amplitude, std::uint32_t seed,
                      glm::dvec2 origin = {0.0, 0.0});
// Terraces with vertical cliffs of cliff_height metres plus fBm detail.
HeightField cliff_field(int columns, int rows, double spacing, float cliff_height, std::uint32_t seed);

// A camera above (or, with below_ground, under) the terrain looking in a random direction.
struct PoseOptions {
  double min_altitude = 2.0, max_altitude = 400.0;  // above the ground under the camera [m]
  double min_fov_deg = 30.0, max_fov_deg = 90.0;
  double min_pitch_deg = -80.0, max_pitch_deg = 10.0;
  int width = 256, height = 144;
  bool below_ground = false;
};
LodView random_view(std::mt19937& rng, const ChunkTree& tree, const HeightField& field, const PoseOptions& options);
LodView look_at_view(const glm::dvec3& eye, const glm::dvec3& target, double fov_deg, int width = 256, int height = 144);

// Directed-edge balance of a frame: every edge between two drawn chunks must be used once in each
// direction with bit-identical end points. Returns the number of offending edges and describes
// the first few in `report`.
struct WatertightResult {
  std::size_t edges = 0;          // distinct undirected edges
  std::size_t boundary_edges = 0; // unbalanced edges on the outline of the drawn region (allowed)
  std::size_t crack_edges = 0;    // unbalanced edges between drawn chunks or inside a chunk
  std::string report;
};
WatertightResult check_watertight(const ChunkTree& tree, const LodSelector& selector, const VertexFrame& frame,
                                  const FrameMesh& mesh);

}  // namespace sylva::terrain::testing

#include <sylva/terrain/error_measure.hpp>

namespace sylva::terrain::testing {
inline ProjectedError projected_error(const HeightField& field, const VertexFrame& frame, const FrameMesh& mesh, double k) {
  return measure_projected_error(field, frame, mesh, k);
}
}  // namespace sylva::terrain::testing

#include <sylva/terrain/mesh.hpp>

namespace sylva::terrain::testing {
// An n x n quad grid over [0, size]^2 with heights h(x, z), as a polygon (quad) mesh.
PolygonMesh grid_cage(int n, double size, const std::function<float(double, double)>& h);
// A terrain with overhangs: a grid whose high parts lean sideways (x += lean * y), so several
// surface points share one ground position.
PolygonMesh overhang_cage(int n, double size, float lean);
}  // namespace sylva::terrain::testing
