#include <sylva/terrain/height_texture.hpp>

#include <fmt/format.h>

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
