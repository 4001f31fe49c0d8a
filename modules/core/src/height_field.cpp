#include <sylva/core/height_field.hpp>

#include <sylva/core/assert.hpp>
#include <sylva/core/log.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace sylva {

HeightField::HeightField(int columns, int rows, double spacing, glm::dvec2 origin)
    : columns_(columns), rows_(rows), spacing_(spacing), origin_(origin) {
  SYLVA_ASSERT(columns >= 1 && rows >= 1 && spacing > 0.0, "columns={} rows={} spacing={}", columns, rows, spacing);
  heights_.assign(static_cast<std::size_t>(columns) * static_cast<std::size_t>(rows), 0.0f);
}

namespace {

// Replaces each non-finite sample by the mean of its finite 8-neighbours; repeats so holes
// larger than one sample fill from their rim inwards. Returns the count repaired.
std::size_t repair_non_finite(HeightField& field) {
  std::size_t repaired = 0;
  bool any_left = true;
  for (int pass = 0; any_left && pass < std::max(field.columns(), field.rows()); ++pass) {
    any_left = false;
    HeightField before = field;
    for (int j = 0; j < field.rows(); ++j) {
      for (int i = 0; i < field.columns(); ++i) {
        if (std::isfinite(before.sample(i, j))) continue;
        double sum = 0.0;
        int count = 0;
        for (int dj = -1; dj <= 1; ++dj) {
          for (int di = -1; di <= 1; ++di) {
            const int x = i + di, z = j + dj;
            if (x < 0 || z < 0 || x >= field.columns() || z >= field.rows()) continue;
            const float h = before.sample(x, z);
            if (std::isfinite(h)) {
              sum += h;
              ++count;
            }
          }
        }
        if (count > 0) {
          field.sample(i, j) = static_cast<float>(sum / count);
          ++repaired;
        } else {
          any_left = true;
        }
      }
    }
  }
  // A field with no finite sample at all becomes flat at 0.
  for (float& h : field.samples()) {
    if (!std::isfinite(h)) {
      h = 0.0f;
      ++repaired;
    }
  }
  return repaired;
}

}  // namespace

Result<HeightField> HeightField::from_image(const Image& image, const HeightFieldImageOptions& options) {
  if (image.empty()) return make_error(ErrorCode::kInvalidArgument, "height field: the image is empty");
  if (options.channel < 0 || options.channel >= image.channels()) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("height field: channel {} requested from a {}-channel image", options.channel,
                                  image.channels()));
  }
  if (!(options.spacing > 0.0) || !std::isfinite(options.spacing)) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("height field: spacing must be a finite value > 0 m, got {}", options.spacing));
  }
  if (!std::isfinite(options.height_scale) || !std::isfinite(options.height_offset)) {
    return make_error(ErrorCode::kInvalidArgument, "height field: height_scale and height_offset must be finite");
  }
  HeightField field(image.width(), image.height(), options.spacing, options.origin);
  NonFiniteReport bad;
  for (int j = 0; j < field.rows(); ++j) {
    for (int i = 0; i < field.columns(); ++i) {
      const float v = image.at(i, j, options.channel);
      const double h = static_cast<double>(v) * options.height_scale + options.height_offset;
      // A finite sample can still leave float range once scaled (3e38 x 100 m): that is as
      // unusable as NaN/Inf (found by the image_map fuzz target).
      if (!std::isfinite(v) || !(std::abs(h) <= static_cast<double>(std::numeric_limits<float>::max()))) {
        if (bad.count == 0) {
          bad.first_x = i;
          bad.first_y = j;
        }
        ++bad.count;
        field.sample(i, j) = std::numeric_limits<float>::quiet_NaN();
      } else {
        field.sample(i, j) = static_cast<float>(h);
      }
    }
  }
  if (bad.count > 0) {
    if (options.non_finite == NonFinitePolicy::kReject) {
      return make_error(ErrorCode::kInvalidArgument,
                        fmt::format("height field: {} NaN/Inf samples (or beyond float range once scaled), the "
                                    "first at ({}, {}); use the repair option to fill them from their neighbours",
                                    bad.count, bad.first_x, bad.first_y));
    }
    const std::size_t repaired = repair_non_finite(field);
    log_warn("height field: repaired {} NaN/Inf samples (first at ({}, {}))", repaired, bad.first_x, bad.first_y);
  }
  field.update_range();
  return field;
}

std::size_t HeightField::index(int i, int j) const {
  SYLVA_ASSERT(i >= 0 && i < columns_ && j >= 0 && j < rows_, "sample ({}, {}) outside {}x{}", i, j, columns_,
               rows_);
  return static_cast<std::size_t>(j) * static_cast<std::size_t>(columns_) + static_cast<std::size_t>(i);
}

float HeightField::sample_clamped(int i, int j) const {
  return sample(std::clamp(i, 0, columns_ - 1), std::clamp(j, 0, rows_ - 1));
}

float HeightField::height(double x, double z) const {
  SYLVA_ASSERT(!heights_.empty(), "height() on an empty field");
  // Work in sample units relative to the origin, in double, so far-from-origin fields keep
  // their precision.
  const double u = std::clamp((x - origin_.x) / spacing_, 0.0, static_cast<double>(columns_ - 1));
  const double v = std::clamp((z - origin_.y) / spacing_, 0.0, static_cast<double>(rows_ - 1));
  if (!std::isfinite(u) || !std::isfinite(v)) return sample(0, 0);
  const int i0 = std::min(static_cast<int>(u), std::max(columns_ - 2, 0));
  const int j0 = std::min(static_cast<int>(v), std::max(rows_ - 2, 0));
  const double fu = u - i0, fv = v - j0;
  const double h00 = sample_clamped(i0, j0), h10 = sample_clamped(i0 + 1, j0);
  const double h01 = sample_clamped(i0, j0 + 1), h11 = sample_clamped(i0 + 1, j0 + 1);
  const double a = h00 + (h10 - h00) * fu;
  const double b = h01 + (h11 - h01) * fu;
  return static_cast<float>(a + (b - a) * fv);
}

glm::vec3 HeightField::normal(double x, double z) const {
  const double d = spacing_ * 0.5;
  const double dhdx = (static_cast<double>(height(x + d, z)) - height(x - d, z)) / (2.0 * d);
  const double dhdz = (static_cast<double>(height(x, z + d)) - height(x, z - d)) / (2.0 * d);
  return glm::normalize(glm::vec3(static_cast<float>(-dhdx), 1.0f, static_cast<float>(-dhdz)));
}

glm::vec3 HeightField::sample_normal(int i, int j) const {
  // One-sided differences at the border, central inside; a 1-sample axis is flat.
  const int il = std::max(i - 1, 0), ir = std::min(i + 1, columns_ - 1);
  const int jl = std::max(j - 1, 0), jr = std::min(j + 1, rows_ - 1);
  const double dx = ir > il ? (static_cast<double>(sample(ir, j)) - sample(il, j)) / ((ir - il) * spacing_) : 0.0;
  const double dz = jr > jl ? (static_cast<double>(sample(i, jr)) - sample(i, jl)) / ((jr - jl) * spacing_) : 0.0;
  return glm::normalize(glm::vec3(static_cast<float>(-dx), 1.0f, static_cast<float>(-dz)));
}

void HeightField::update_range() {
  if (heights_.empty()) return;
  const auto [lo, hi] = std::minmax_element(heights_.begin(), heights_.end());
  min_height_ = *lo;
  max_height_ = *hi;
}

Image HeightField::to_image() const {
  Image image(columns_, rows_, 1, PixelFormat::kF32);
  std::copy(heights_.begin(), heights_.end(), image.data().begin());
  return image;
}

}  // namespace sylva
