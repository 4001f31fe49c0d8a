#include <sylva/grass/maps.hpp>

#include <sylva/core/log.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace sylva::grass {

namespace {

// Primitive of the unit tent max(0, 1 - |t|): T(s) = int_{-inf}^{s}.
double tent_primitive(double s) {
  if (s <= -1.0) return 0.0;
  if (s <= 0.0) return 0.5 * (s + 1.0) * (s + 1.0);
  if (s <= 1.0) return 1.0 - 0.5 * (1.0 - s) * (1.0 - s);
  return 1.0;
}

// Integral over [a, b] (texel-centre units, centres at integers) of the clamped-to-edge basis
// function of texel i among `count`: a tent, extended flat to -inf for the first texel and to
// +inf for the last (that is what clamp-to-edge bilinear interpolation amounts to).
double basis_integral(int i, int count, double a, double b) {
  if (b <= a) return 0.0;
  if (count == 1) return b - a;
  double total = 0.0;
  const double di = static_cast<double>(i);
  // Flat extension on the left of texel 0 (s < 0) and the right of the last (s > count - 1).
  if (i == 0) {
    total += std::max(0.0, std::min(b, 0.0) - a);
    a = std::max(a, 0.0);
  }
  if (i == count - 1) {
    total += std::max(0.0, b - std::max(a, di));
    b = std::min(b, di);
  }
  if (b > a) total += tent_primitive(b - di) - tent_primitive(a - di);
  return total;
}

}  // namespace

Result<ScalarMap> ScalarMap::create(const Image& image, int channel, const Rect& rect, const char* what) {
  if (image.empty()) return make_error(ErrorCode::kInvalidArgument, fmt::format("grass {}: the image is empty", what));
  if (channel < 0 || channel >= image.channels()) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("grass {}: channel {} requested from a {}-channel image", what, channel,
                                  image.channels()));
  }
  if (rect.empty() || !std::isfinite(rect.min.x) || !std::isfinite(rect.min.y) || !std::isfinite(rect.max.x) ||
      !std::isfinite(rect.max.y)) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("grass {}: the world rectangle ({}, {})..({}, {}) is empty or not finite", what,
                                  rect.min.x, rect.min.y, rect.max.x, rect.max.y));
  }
  ScalarMap map;
  map.rect_ = rect;
  map.width_ = image.width();
  map.height_ = image.height();
  map.values_.resize(image.pixel_count());
  std::size_t non_finite = 0;
  for (int j = 0; j < map.height_; ++j) {
    for (int i = 0; i < map.width_; ++i) {
      float v = image.at(i, j, channel);
      if (!std::isfinite(v)) {
        ++non_finite;
        v = 0.0f;
      }
      map.values_[static_cast<std::size_t>(j) * static_cast<std::size_t>(map.width_) + static_cast<std::size_t>(i)] =
          std::clamp(v, 0.0f, 1.0f);
    }
  }
  if (non_finite > 0) log_warn("grass {}: {} NaN/Inf values read as 0", what, non_finite);
  return map;
}

float ScalarMap::sample(double x, double z, float outside) const {
  if (!(x >= rect_.min.x && x <= rect_.max.x && z >= rect_.min.y && z <= rect_.max.y)) return outside;
  const glm::dvec2 size = rect_.size();
  const double u = std::clamp((x - rect_.min.x) / size.x * width_ - 0.5, 0.0, static_cast<double>(width_ - 1));
  const double v = std::clamp((z - rect_.min.y) / size.y * height_ - 0.5, 0.0, static_cast<double>(height_ - 1));
  const int i0 = std::min(static_cast<int>(u), std::max(width_ - 2, 0));
  const int j0 = std::min(static_cast<int>(v), std::max(height_ - 2, 0));
  const int i1 = std::min(i0 + 1, width_ - 1);
  const int j1 = std::min(j0 + 1, height_ - 1);
  const double fu = u - i0, fv = v - j0;
  const double a = texel(i0, j0) + (texel(i1, j0) - texel(i0, j0)) * fu;
  const double b = texel(i0, j1) + (texel(i1, j1) - texel(i0, j1)) * fu;
  return static_cast<float>(a + (b - a) * fv);
}

void ScalarMap::tent_weights(double a, double b, double origin, double texel_size, int count, int& first,
                             std::vector<double>& w) const {
  // To texel-centre units.
  const double sa = (a - origin) / texel_size - 0.5;
  const double sb = (b - origin) / texel_size - 0.5;
  first = std::clamp(static_cast<int>(std::floor(sa)) - 1, 0, count - 1);
  const int last = std::clamp(static_cast<int>(std::ceil(sb)) + 1, 0, count - 1);
  w.assign(static_cast<std::size_t>(last - first + 1), 0.0);
  for (int i = first; i <= last; ++i) w[static_cast<std::size_t>(i - first)] = basis_integral(i, count, sa, sb) * texel_size;
}

double ScalarMap::integral(const Rect& area) const {
  const Rect clip = area.intersect(rect_);
  if (clip.empty() || empty()) return 0.0;
  const glm::dvec2 cell = rect_.size() / glm::dvec2(width_, height_);
  int fx = 0, fz = 0;
  std::vector<double> wx, wz;
  tent_weights(clip.min.x, clip.max.x, rect_.min.x, cell.x, width_, fx, wx);
  tent_weights(clip.min.y, clip.max.y, rect_.min.y, cell.y, height_, fz, wz);
  double sum = 0.0;
  for (std::size_t jj = 0; jj < wz.size(); ++jj) {
    if (wz[jj] == 0.0) continue;
    double row = 0.0;
    for (std::size_t ii = 0; ii < wx.size(); ++ii) row += wx[ii] * texel(fx + static_cast<int>(ii), fz + static_cast<int>(jj));
    sum += row * wz[jj];
  }
  return sum;
}

Result<GrassMaps> GrassMaps::from_images(const Rect& rect, const Image* density, const Image* height,
                                         const Image* tint) {
  if (rect.empty()) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("grass maps: the world rectangle ({}, {})..({}, {}) is empty", rect.min.x,
                                  rect.min.y, rect.max.x, rect.max.y));
  }
  GrassMaps maps;
  maps.rect_ = rect;
  if (density) {
    auto m = ScalarMap::create(*density, 0, rect, "density map");
    if (!m) return m.error();
    maps.density_ = std::move(*m);
  }
  if (height) {
    auto m = ScalarMap::create(*height, 0, rect, "height map");
    if (!m) return m.error();
    maps.height_ = std::move(*m);
  }
  if (tint) {
    if (tint->channels() < 3) {
      return make_error(ErrorCode::kInvalidArgument,
                        fmt::format("grass tint map: needs 3 channels (RGB), the image has {}", tint->channels()));
    }
    for (int c = 0; c < 3; ++c) {
      auto m = ScalarMap::create(*tint, c, rect, "tint map");
      if (!m) return m.error();
      maps.tint_[c] = std::move(*m);
    }
  }
  return maps;
}

Result<GrassMaps> GrassMaps::from_control_texture(const Image& control, const Rect& rect) {
  if (control.channels() < 3) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("grass control texture: needs 3 channels (R density, G height, B terrain), "
                                  "the image has {}",
                                  control.channels()));
  }
  GrassMaps maps;
  maps.rect_ = rect;
  auto d = ScalarMap::create(control, 0, rect, "control texture (R density)");
  if (!d) return d.error();
  auto h = ScalarMap::create(control, 1, rect, "control texture (G height)");
  if (!h) return h.error();
  maps.density_ = std::move(*d);
  maps.height_ = std::move(*h);
  return maps;
}

GrassMaps GrassMaps::uniform(const Rect& rect) {
  GrassMaps maps;
  maps.rect_ = rect;
  return maps;
}

namespace {
bool inside(const Rect& r, double x, double z) { return x >= r.min.x && x <= r.max.x && z >= r.min.y && z <= r.max.y; }
}  // namespace

float GrassMaps::density(double x, double z) const {
  if (!inside(rect_, x, z)) return 0.0f;
  return density_ ? density_->sample(x, z, 0.0f) : 1.0f;
}

float GrassMaps::height_scale(double x, double z) const { return height_ ? height_->sample(x, z, 1.0f) : 1.0f; }

glm::vec3 GrassMaps::tint(double x, double z) const {
  if (!tint_[0]) return glm::vec3(1.0f);
  return {tint_[0]->sample(x, z, 1.0f), tint_[1]->sample(x, z, 1.0f), tint_[2]->sample(x, z, 1.0f)};
}

double GrassMaps::density_integral(const Rect& area) const {
  if (density_) return density_->integral(area);
  const Rect clip = area.intersect(rect_);
  return clip.empty() ? 0.0 : clip.size().x * clip.size().y;
}

namespace {

// The texels of `channels` (all of one size) as one float image; 1 x 1 white without maps.
Image maps_image(const std::optional<ScalarMap>* channels, int count) {
  if (!channels[0]) {
    Image one(1, 1, count);
    for (int c = 0; c < count; ++c) one.at(0, 0, c) = 1.0f;
    return one;
  }
  Image img(channels[0]->width(), channels[0]->height(), count);
  for (int j = 0; j < img.height(); ++j)
    for (int i = 0; i < img.width(); ++i)
      for (int c = 0; c < count; ++c) img.at(i, j, c) = channels[c]->value(i, j);
  return img;
}

}  // namespace

Image GrassMaps::density_image() const { return maps_image(&density_, 1); }

Image GrassMaps::tint_image() const { return maps_image(tint_, 3); }

glm::dvec2 GrassMaps::density_texel() const {
  if (!density_) return rect_.size();
  return rect_.size() / glm::dvec2(density_->width(), density_->height());
}

Result<HeightField> control_texture_terrain(const Image& control, const Rect& rect, double max_terrain_height) {
  if (control.channels() < 3) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("grass control texture: the terrain height is channel B, the image has {} channels",
                                  control.channels()));
  }
  if (control.empty() || rect.empty()) {
    return make_error(ErrorCode::kInvalidArgument, "grass control texture: empty image or world rectangle");
  }
  if (!std::isfinite(max_terrain_height)) {
    return make_error(ErrorCode::kInvalidArgument, "grass control texture: max_terrain_height must be finite");
  }
  const glm::dvec2 texel = rect.size() / glm::dvec2(control.width(), control.height());
  if (std::abs(texel.x - texel.y) > 1e-6 * std::max(texel.x, texel.y)) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("grass control texture: texels must be square for a height field, got {} x {} m",
                                  texel.x, texel.y));
  }
  // Samples at pixel centres, so grass density and terrain refer to the same points.
  HeightField field(control.width(), control.height(), texel.x, rect.min + 0.5 * texel);
  for (int j = 0; j < control.height(); ++j) {
    for (int i = 0; i < control.width(); ++i) {
      float b = control.at(i, j, 2);
      if (!std::isfinite(b)) b = 1.0f;
      field.sample(i, j) = static_cast<float>(max_terrain_height * (1.0 - std::clamp(static_cast<double>(b), 0.0, 1.0)));
    }
  }
  field.update_range();
  return field;
}

}  // namespace sylva::grass
