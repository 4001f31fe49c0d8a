// Wavefront OBJ meshes (modules/terrain mesh.cpp, the general-model terrain's input): text ->
// polygon mesh -> fan triangulation -> mesh check, as the terrain does before building a tree.
#include "support/fuzz_support.hpp"

#include <sylva/terrain/mesh.hpp>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace sylva::terrain;
  auto mesh = parse_obj(sylva::fuzz::as_text(data, size), "fuzz.obj");
  if (!mesh.ok()) {
    sylva::fuzz::require_message(mesh.error());
    return 0;
  }
  const TriangleMesh triangles = triangulate(*mesh);
  for (std::uint32_t index : triangles.indices) {
    sylva::fuzz::require(index < triangles.positions.size(), "a triangle index beyond the vertices");
  }
  (void)check_mesh(triangles.positions, triangles.indices);
  return 0;
}
