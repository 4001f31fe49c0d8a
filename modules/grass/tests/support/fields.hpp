#pragma once
// Shared fixtures for the grass tests: small fields, maps and meshes with known answers.

#include <sylva/core/height_field.hpp>
#include <sylva/core/image.hpp>
#include <sylva/grass/generator.hpp>
#include <sylva/grass/maps.hpp>

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace sylva::grass::testing {

// A density image with a smooth gradient, a dense disc and an empty strip (w x h pixels).
Image make_density_image(int w, int h);

// A gently rolling height field covering [lo, hi] in x and z, 1 m spacing.
HeightField make_ground(double lo, double hi);

// A UV sphere of `radius` centred at `center` (positions relative to it), outward normals.
struct SphereMesh {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;
  std::vector<std::uint32_t> indices;
  GroundMesh view() const { return {positions, normals, indices, {}}; }
  double area() const;  // sum of triangle areas
};
SphereMesh make_sphere(float radius, int rings, int segments, const glm::vec3& center = glm::vec3(0.0f));

}  // namespace sylva::grass::testing
