#include "material_gpu.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace sylva::terrain {
namespace {
constexpr int kDetailSize = 256;
constexpr std::uint32_t kDetailSeed = 19u;
constexpr int kBandRows = 256;  // rows per compute + upload band (bounds the work memory)
}  // namespace

render::Texture make_detail_texture() {
  // RGBA8, not half floats: llvmpipe filters 8-bit textures on its fast path (measured: the
  // frame's terrain time, see the README). Encoded as material.glsl decodes it: r, g (sd 0.4) as
  // v / 2 + 1/2, the gradient (unit RMS) as g / 8 + 1/2; clamping at +-2.5 / +-4 sigma is harmless.
  Image noise = make_detail_noise(kDetailSize, kDetailSeed);
  for (int y = 0; y < noise.height(); ++y)
    for (int x = 0; x < noise.width(); ++x)
      for (int c = 0; c < 4; ++c) {
        float& v = noise.at(x, y, c);
        v = std::clamp(c < 2 ? v * 0.5f + 0.5f : v * 0.125f + 0.5f, 0.0f, 1.0f);
      }
  render::TextureOptions options;
  options.encoding = render::TextureEncoding::kUnorm8;
  options.wrap = GL_REPEAT;
  return render::Texture::from_image(noise, options).value();
}

SampleRect update_shape_texture(const render::Texture& texture, const HeightField& field, float radius_m, int x0, int z0,
                          int x1, int z1) {
  const int grow = static_cast<int>(std::ceil(std::min(radius_m / field.spacing(), 4096.0))) + 1;
  x0 = std::max(x0 - grow, 0), z0 = std::max(z0 - grow, 0);
  x1 = std::min(x1 + grow, field.columns()), z1 = std::min(z1 + grow, field.rows());
  std::vector<float> band;
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  for (int z = z0; z < z1; z += kBandRows) {
    const int ze = std::min(z + kBandRows, z1);
    compute_terrain_shape(field, radius_m, x0, z, x1, ze, band);
    glTextureSubImage2D(texture.id(), 0, x0, z, x1 - x0, ze - z, GL_RGBA, GL_FLOAT, band.data());
  }
  return SampleRect{x0, z0, x1, z1};
}

Result<render::Texture> make_shape_texture(const HeightField& field, float radius_m) {
  GLint max_size = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
  if (field.columns() <= 0 || field.rows() <= 0 || field.columns() > max_size || field.rows() > max_size) {
    return make_error(ErrorCode::kLimit, fmt::format("terrain: a {}x{} shape texture exceeds GL_MAX_TEXTURE_SIZE {}",
                                                     field.columns(), field.rows(), max_size));
  }
  render::Texture t = render::Texture::create_2d(field.columns(), field.rows(), GL_RGBA16_SNORM, 1);
  t.set_filter(GL_LINEAR, GL_LINEAR);
  t.set_wrap(GL_CLAMP_TO_EDGE);
  update_shape_texture(t, field, radius_m, 0, 0, field.columns(), field.rows());
  return t;
}

MaterialUniforms material_uniforms(const MaterialSettings& m, const Climate& climate) {
  const MaterialLines lines = material_lines(m, climate);
  MaterialUniforms u;
  u.lines = glm::vec4(lines.snow, lines.rock, lines.tree, lines.water);
  const float rock_slope = 1.0f - std::cos(glm::radians(m.rock_slope_deg));
  u.layer = glm::vec4(m.beach_height_m, rock_slope, 1.0f / m.detail_scale_m, m.detail_strength);
  u.pole = glm::vec2(0.0f, climate.latitude_deg < 0.0f ? 1.0f : -1.0f);
  u.colors = {m.grass_color, m.meadow_color, m.dirt_color, m.scree_color, m.rock_color, m.snow_color, m.sand_color};
  return u;
}

void set_material_uniforms(const render::Program& program, const MaterialUniforms& u) {
  program.set("u_lines", u.lines);
  program.set("u_layer", u.layer);
  program.set("u_pole", u.pole);
  constexpr const char* kColorNames[7] = {"u_grass_color", "u_meadow_color", "u_dirt_color", "u_scree_color",
                                          "u_rock_color",  "u_snow_color",   "u_sand_color"};
  for (std::size_t i = 0; i < u.colors.size(); ++i) program.set(kColorNames[i], u.colors[i]);
}

void set_material_uniforms(const render::Program& program, const MaterialSettings& m, const Climate& climate) {
  set_material_uniforms(program, material_uniforms(m, climate));
}

double min_pixel_footprint_m(double min_depth_m, double fov_y_rad, double aspect, int viewport_height) {
  if (!(min_depth_m > 0.0) || viewport_height <= 0) return 0.0;
  const double ty = std::tan(0.5 * fov_y_rad), tx = ty * aspect;
  const double focal_px = 0.5 * viewport_height / ty;
  return min_depth_m / (focal_px * (1.0 + tx * tx + ty * ty));
}

int first_detail_scale(double min_depth_m, double fov_y_rad, double aspect, int viewport_height, float detail_scale_m) {
  const double footprint_m = min_pixel_footprint_m(min_depth_m, fov_y_rad, aspect, viewport_height);
  if (!(footprint_m > 0.0) || !(detail_scale_m > 0.0f)) return 0;
  // Tiles of the three scales (kScale1, kScale2 in material.glsl); a scale's fade is 0 once its
  // texel count per pixel, footprint / tile, passes 1/32.
  constexpr double kTileRatio[3] = {1.0, 5.3, 28.0};
  constexpr double kFadeEnd = 1.0 / 32.0;
  for (int k = 0; k < 3; ++k) {
    if (footprint_m / (detail_scale_m * kTileRatio[k]) < kFadeEnd) return k;
  }
  return 3;
}

}  // namespace sylva::terrain
