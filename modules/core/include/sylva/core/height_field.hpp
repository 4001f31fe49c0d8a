#pragma once
// HeightField: the ground every content module stands on, exchanged through core so that
// terrain, grass, trees and voxels never depend on each other (DESIGN.md §1, §2b).
//
// Samples are heights in metres on a regular grid in the world x/z plane, y up. Sample (i, j)
// (i along x in [0, columns), j along z in [0, rows)) sits at world
// (origin.x + i * spacing, origin.y + j * spacing). Owns no GL.

#include <sylva/core/image.hpp>
#include <sylva/core/result.hpp>

#include <glm/glm.hpp>

#include <vector>

namespace sylva {

enum class NonFinitePolicy {
  kReject,  // NaN/Inf samples are an error naming their count and first position
  kRepair,  // each one is replaced by the mean of its finite neighbours (0 if none), with a warning
};

struct HeightFieldImageOptions {
  double spacing = 1.0;        // metres per sample, > 0
  double height_scale = 1.0;   // metres per normalised image unit (a 16-bit 65535 reads as 1.0)
  double height_offset = 0.0;  // metres added after scaling
  glm::dvec2 origin{0.0, 0.0}; // world x/z of sample (0, 0)
  int channel = 0;             // which image channel holds the height
  NonFinitePolicy non_finite = NonFinitePolicy::kReject;
};

class HeightField {
 public:
  HeightField() = default;
  // A flat field; columns, rows >= 1 and spacing > 0 (asserted).
  HeightField(int columns, int rows, double spacing, glm::dvec2 origin = {0.0, 0.0});

  // From an image channel. Errors: empty image, bad channel, spacing <= 0, non-finite samples
  // under kReject (message names count and first sample).
  static Result<HeightField> from_image(const Image& image, const HeightFieldImageOptions& options = {});

  int columns() const { return columns_; }
  int rows() const { return rows_; }
  double spacing() const { return spacing_; }
  glm::dvec2 origin() const { return origin_; }
  // World extent in x/z: origin .. origin + (columns-1, rows-1) * spacing.
  glm::dvec2 extent() const { return {(columns_ - 1) * spacing_, (rows_ - 1) * spacing_}; }

  float sample(int i, int j) const { return heights_[index(i, j)]; }
  float& sample(int i, int j) { return heights_[index(i, j)]; }
  // Clamped to the border.
  float sample_clamped(int i, int j) const;

  // Bilinear height in metres at world (x, z); outside the field the border is extended.
  float height(double x, double z) const;
  // Unit normal (y up) from central differences of the bilinear surface at world (x, z).
  glm::vec3 normal(double x, double z) const;
  // Unit normal at sample (i, j) from central differences of the samples.
  glm::vec3 sample_normal(int i, int j) const;

  // Min and max sample height in metres (recomputed by update_range after edits).
  float min_height() const { return min_height_; }
  float max_height() const { return max_height_; }
  void update_range();

  std::vector<float>& samples() { return heights_; }
  const std::vector<float>& samples() const { return heights_; }

  // One-channel float image of the heights in metres (for saving or uploading).
  Image to_image() const;

 private:
  std::size_t index(int i, int j) const;

  int columns_ = 0;
  int rows_ = 0;
  double spacing_ = 1.0;
  glm::dvec2 origin_{0.0, 0.0};
  std::vector<float> heights_;
  float min_height_ = 0.0f;
  float max_height_ = 0.0f;
};

}  // namespace sylva
