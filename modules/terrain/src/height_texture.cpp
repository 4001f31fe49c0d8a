#include <sylva/terrain/height_texture.hpp>

#include <fmt/format.h>

#include <algorithm>

namespace sylva::terrain {

Result<render::Texture> make_height_texture(const HeightField& field) {
  if (field.columns() <= 0 || field.rows() <= 0) {
    return make_error(ErrorCode::kInvalidArgument, "terrain: height texture of an empty field");
  }
  GLint max_size = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
  if (field.columns() > max_size || field.rows() > max_size) {
    return make_error(ErrorCode::kLimit, fmt::format("terrain: a {}x{} height field exceeds GL_MAX_TEXTURE_SIZE {}",
                                                     field.columns(), field.rows(), max_size));
  }
  render::Texture t = render::Texture::create_2d(field.columns(), field.rows(), GL_R32F, 1);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  glTextureSubImage2D(t.id(), 0, 0, 0, field.columns(), field.rows(), GL_RED, GL_FLOAT, field.samples().data());
  t.set_filter(GL_LINEAR, GL_LINEAR);
  t.set_wrap(GL_CLAMP_TO_EDGE);
  return t;
}

std::int64_t update_height_texture(const render::Texture& texture, const HeightField& field, int x0, int z0, int x1,
                                   int z1) {
  x0 = std::max(x0, 0), z0 = std::max(z0, 0);
  x1 = std::min(x1, field.columns()), z1 = std::min(z1, field.rows());
  if (x1 <= x0 || z1 <= z0) return 0;
  // The rectangle is read straight out of the field's row-major samples: the row length tells GL
  // the field's stride, so no staging copy is made.
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  glPixelStorei(GL_UNPACK_ROW_LENGTH, field.columns());
  const float* first = field.samples().data() + static_cast<std::size_t>(z0) * field.columns() + x0;
  glTextureSubImage2D(texture.id(), 0, x0, z0, x1 - x0, z1 - z0, GL_RED, GL_FLOAT, first);
  glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
  return static_cast<std::int64_t>(x1 - x0) * (z1 - z0);
}

HeightTextureInfo height_texture_info(const HeightField& field) {
  HeightTextureInfo info;
  const glm::dvec2 size(field.columns(), field.rows());
  const glm::dvec2 scale = 1.0 / (field.spacing() * size);
  info.uv_scale = glm::vec2(scale);
  info.uv_offset = glm::vec2(0.5 / size - field.origin() * scale);
  info.height_range = glm::vec2(field.min_height(), field.max_height());
  return info;
}

}  // namespace sylva::terrain
