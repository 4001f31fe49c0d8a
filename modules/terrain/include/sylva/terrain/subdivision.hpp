#pragma once
// Refinement of a coarse control cage into the high-resolution general-model terrain with
// OpenSubdiv 3.5 (uniform refinement, optionally projected to the limit surface).

#include <sylva/core/params.hpp>
#include <sylva/core/result.hpp>
#include <sylva/terrain/mesh.hpp>

#include <array>
#include <cstdint>

namespace sylva::terrain {

enum class SubdivisionScheme : std::uint8_t { kCatmullClark, kLoop };
constexpr std::array<EnumName<SubdivisionScheme>, 2> enum_names(SubdivisionScheme) {
  return {{{SubdivisionScheme::kCatmullClark, "catmull_clark"}, {SubdivisionScheme::kLoop, "loop"}}};
}

struct SubdivisionSettings {
  SubdivisionScheme scheme = SubdivisionScheme::kCatmullClark;
  int level = 3;              // uniform refinement level N (each level: x4 faces)
  bool limit_surface = true;  // move the finest vertices onto the limit surface

  template <class V>
  void visit(V& v) {
    v(scheme, "scheme", {.help = "catmull_clark (any polygons) or loop (triangles only)", .rebuild = Rebuild::kOffline});
    v(level, "level", {.min = 0, .max = 8, .help = "Uniform refinement level", .rebuild = Rebuild::kOffline});
    v(limit_surface, "limit_surface", {.help = "Project the result onto the limit surface", .rebuild = Rebuild::kOffline});
  }
};

// Errors: invalid settings, Loop on a cage with non-triangular faces, a topology OpenSubdiv
// rejects (non-manifold cage), or a result above 64 M faces (kLimit).
Result<PolygonMesh> subdivide(const PolygonMesh& cage, const SubdivisionSettings& settings);

}  // namespace sylva::terrain
