#pragma once
// Grass density over a mesh's texture coordinates (issue 16, grass on any mesh): a greyscale or
// colour image whose channel 0 (the red of RGB(A), the grey of a greyscale file) is the density
// in [0, 1], looked up at each blade root's interpolated UV (generate_blades_on_mesh).
//
// UV convention: (0, 0) is the image's top-left corner, v grows downwards (glTF's; the OBJ loader
// flips vt). Inside [0, 1] the value is bilinear between pixel centres, clamped to the edge (a
// quad mapped 0..1 does not bleed its right column into its left edge); outside [0, 1] the UVs
// repeat (the default wrap of glTF samplers and DCC tools), each tile clamped the same way.

#include <sylva/core/image.hpp>
#include <sylva/core/result.hpp>
#include <sylva/grass/maps.hpp>

#include <glm/glm.hpp>

namespace sylva::grass {

class UvDensityMap {
 public:
  UvDensityMap() = default;
  // Channel 0 of `image`, clamped to [0, 1] (NaN counts as 0, with a warning). Errors
  // (kInvalidArgument): an empty image; the message is "grass <what>: ...".
  static Result<UvDensityMap> create(const Image& image, const char* what);

  bool empty() const { return map_.empty(); }
  int width() const { return map_.width(); }
  int height() const { return map_.height(); }
  // Density in [0, 1] at `uv` (see the header comment); 0 for non-finite UVs.
  float sample(glm::vec2 uv) const;

 private:
  ScalarMap map_;  // over the unit square: x = u, z = v
};

}  // namespace sylva::grass
