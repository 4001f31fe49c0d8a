#pragma once
// Painted control maps of a grass field: density (blade count), height (blade height scale) and
// tint (colour multiplier), each a sylva::Image laid over a world rectangle in x/z.
//
// Conventions (shared with the editor's brushes and seed 001 §3.3):
//  - Image x runs along world +x and image y (rows from the top of the picture) along world +z,
//    the same orientation as sylva::HeightField::from_image, so a density map painted over a
//    terrain's height map lines up with it. Each pixel covers an equal cell of the rectangle;
//    values are sampled bilinearly between pixel centres, clamped to the edge inside the rectangle.
//  - Outside the rectangle the density is 0 (no grass) and height/tint are their defaults.
//  - Density and height are in [0, 1] (values outside are clamped, NaN counts as 0 with a
//    warning when the maps are built). Tint is linear RGB, 1 = no change.
//  - A missing map means "1 everywhere" (density, height) or "white" (tint).
//
// Seed 001's single control texture (R density, G blade height, B terrain height, with B
// inverted: dark = high) is accepted by from_control_texture(); its terrain channel becomes a
// sylva::HeightField through control_texture_terrain().

#include <sylva/core/height_field.hpp>
#include <sylva/core/image.hpp>
#include <sylva/core/result.hpp>

#include <glm/glm.hpp>

#include <optional>

namespace sylva::grass {

// An axis-aligned world rectangle in the x/z plane [m].
struct Rect {
  glm::dvec2 min{0.0, 0.0};
  glm::dvec2 max{0.0, 0.0};
  glm::dvec2 size() const { return max - min; }
  bool empty() const { return !(max.x > min.x && max.y > min.y); }
  Rect intersect(const Rect& o) const { return {glm::max(min, o.min), glm::min(max, o.max)}; }
};

// One scalar map over a world rectangle, with an exact integral of its bilinear interpolant.
class ScalarMap {
 public:
  ScalarMap() = default;
  // Channel `channel` of `image` over `rect`. Errors: empty image, channel out of range, empty
  // rect; the message names `what` (e.g. "density map").
  static Result<ScalarMap> create(const Image& image, int channel, const Rect& rect, const char* what);

  bool empty() const { return width_ == 0; }
  float value(int i, int j) const { return texel(i, j); }
  const Rect& rect() const { return rect_; }
  int width() const { return width_; }
  int height() const { return height_; }

  // Bilinear value at world (x, z); `outside` when the point is not inside rect().
  float sample(double x, double z, float outside) const;
  // Exact integral over `area` (clipped to rect()) of the bilinear interpolant [value * m^2].
  double integral(const Rect& area) const;

 private:
  float texel(int i, int j) const { return values_[static_cast<std::size_t>(j) * static_cast<std::size_t>(width_) + static_cast<std::size_t>(i)]; }
  // Integrals of the 1D tent functions of texels lo..hi over [a, b] along one axis.
  void tent_weights(double a, double b, double origin, double texel_size, int count, int& first,
                    std::vector<double>& w) const;

  Rect rect_;
  int width_ = 0;
  int height_ = 0;
  std::vector<float> values_;  // row j = picture row from the top; clamped to [0, 1] or finite
};

class GrassMaps {
 public:
  GrassMaps() = default;

  // Any map may be absent (nullptr). Each image is laid over `rect`. Tint must have >= 3
  // channels. Errors name the map and what is wrong with it.
  static Result<GrassMaps> from_images(const Rect& rect, const Image* density, const Image* height,
                                       const Image* tint);
  // Seed 001's control texture: R = density, G = blade height, B = terrain height (ignored
  // here; see control_texture_terrain). Needs >= 3 channels.
  static Result<GrassMaps> from_control_texture(const Image& control, const Rect& rect);

  // Maps that cover `rect` with density 1, height 1, tint white (a uniform meadow).
  static GrassMaps uniform(const Rect& rect);

  const Rect& rect() const { return rect_; }
  float density(double x, double z) const;       // [0, 1]
  float height_scale(double x, double z) const;  // [0, 1]
  glm::vec3 tint(double x, double z) const;      // linear RGB
  // Exact integral of density over `area` [m^2 of full density].
  double density_integral(const Rect& area) const;
  // World size of one density-map pixel [m]; the whole rectangle when there is no density map.
  glm::dvec2 density_texel() const;
  bool has_density_map() const { return density_.has_value(); }
  // The density map as a one-channel float image (row 0 at rect().min.y, like the input);
  // a 1 x 1 white image when there is no map.
  Image density_image() const;
  bool has_tint_map() const { return tint_[0].has_value(); }
  // The tint map as a three-channel float image (same layout as density_image()); 1 x 1 white
  // when there is no map. The far field's ground layer multiplies its colour by it.
  Image tint_image() const;

 private:
  Rect rect_;
  std::optional<ScalarMap> density_;
  std::optional<ScalarMap> height_;
  std::optional<ScalarMap> tint_[3];
};

// Seed 001 §3.2/§3.3: terrain height = mix(0, max_terrain_height, 1 - B) over `rect`, one height
// sample per texel centre. Errors: fewer than 3 channels, empty rect, non-square texels.
Result<HeightField> control_texture_terrain(const Image& control, const Rect& rect, double max_terrain_height);

}  // namespace sylva::grass
