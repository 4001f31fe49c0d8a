#pragma once
// The sky dome's mesh (SkyRenderer, shaders/sky.vert): a closed polyhedron of unit directions
// around the camera, in a frame whose x axis points at the sun's azimuth (y up). Its rings and
// spokes follow where the sky's table look-up changes fast, so interpolating the table per
// vertex matches the per-pixel look-up: the rings lie on the table's rows (sin elevation =
// (r / 15)^2, densest at the horizon) cut into kRowSteps, and at most kMaxRingStepRad apart
// elsewhere (kNadirRingStepRad in the nadir's azimuth fade); a ring sits exactly on the horizon
// (no triangle straddles the kink there); the spokes are kSpokes even azimuths, among them the table's
// columns (0, 60, 90, 120, 180 degrees from the sun); half as far apart near the nadir. Poles: one vertex at the zenith and one
// at the nadir, so every direction hits a triangle (no holes at any pitch or field of view).
// The first nadir_cap_indices indices are the cap within 30 degrees of the nadir (the table's
// azimuth fade, SkyTable::kNadirFade), which the renderer shades per pixel.

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace sylva::render {

struct SkyDomeMesh {
  static constexpr int kSpokes = 72;  // 5 degrees: a multiple of the columns' 30 degrees
  static constexpr int kRowSteps = 4;
  static constexpr float kMaxRingStepRad = 0.035f;  // 2 degrees
  // Within 30 degrees of the nadir, where the azimuth fades out (smoothstep: curved at 30).
  static constexpr float kNadirRingStepRad = 0.0175f;

  std::vector<glm::vec3> directions;  // unit, sun frame
  std::vector<std::uint32_t> indices;  // triangles, both poles closed
  std::size_t nadir_cap_indices = 0;
};

// Builds the mesh (a few thousand triangles; once per SkyRenderer).
SkyDomeMesh build_sky_dome();

// The elevations (radians, ascending, -pi/2 and pi/2 excluded: the poles) of the mesh's rings.
std::vector<float> sky_dome_ring_elevations();

}  // namespace sylva::render
