// Open Inventor ASCII meshes (modules/terrain mesh_iv.cpp, the seed's cilaos.iv format for the
// general-model terrain): text -> polygon mesh -> fan triangulation -> mesh check, as the terrain
// does before building a tree. Every index must lie inside the points.
#include "support/fuzz_support.hpp"

#include <sylva/terrain/mesh.hpp>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace sylva::terrain;
  auto mesh = parse_iv(sylva::fuzz::as_text(data, size), "fuzz.iv");
  if (!mesh.ok()) {
    sylva::fuzz::require_message(mesh.error());
    return 0;
  }
  std::size_t corners = 0;
  for (std::uint32_t n : mesh->face_sizes) {
    sylva::fuzz::require(n >= 3, "a face of fewer than 3 vertices");
    corners += n;
  }
  sylva::fuzz::require(corners == mesh->face_indices.size(), "face sizes do not add up to the indices");
  const TriangleMesh triangles = triangulate(*mesh);
  for (std::uint32_t index : triangles.indices) {
    sylva::fuzz::require(index < triangles.positions.size(), "a triangle index beyond the points");
  }
  (void)check_mesh(triangles.positions, triangles.indices);
  return 0;
}
