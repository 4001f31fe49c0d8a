// Immutable-storage textures and uploads from core images (texture.hpp).
#include <sylva/render/texture.hpp>

#include <sylva/core/assert.hpp>

#include <algorithm>
#include <bit>
#include <vector>

namespace sylva::render {
namespace {

GLenum pixel_format(int channels) {
  switch (channels) {
    case 1: return GL_RED;
    case 2: return GL_RG;
    case 3: return GL_RGB;
    default: return GL_RGBA;
  }
}

// Rows bottom-up for GL (Image row 0 is the top of the picture).
std::vector<float> flipped_rows(const Image& image) {
  const std::size_t row = static_cast<std::size_t>(image.width()) * static_cast<std::size_t>(image.channels());
  std::vector<float> out(row * static_cast<std::size_t>(image.height()));
  const std::span<const float> src = image.data();
  for (int y = 0; y < image.height(); ++y) {
    const std::size_t from = static_cast<std::size_t>(image.height() - 1 - y) * row;
    std::copy_n(src.begin() + static_cast<std::ptrdiff_t>(from), row,
                out.begin() + static_cast<std::ptrdiff_t>(static_cast<std::size_t>(y) * row));
  }
  return out;
}

GLuint create_texture(GLenum target) {
  GLuint id = 0;
  glCreateTextures(target, 1, &id);
  return id;
}

// Bytes of a texture's storage: every mip level (sides halved, at least 1), layer and sample.
std::uint64_t texture_storage_bytes(int width, int height, int layers, int levels, int samples, GLenum format) {
  std::uint64_t texels = 0;
  for (int l = 0; l < levels; ++l) {
    texels += static_cast<std::uint64_t>(std::max(width >> l, 1)) * static_cast<std::uint64_t>(std::max(height >> l, 1));
  }
  return texels * static_cast<std::uint64_t>(std::max(layers, 1)) * static_cast<std::uint64_t>(std::max(samples, 1)) *
         texel_bytes(format);
}

}  // namespace

int mip_levels(int width, int height) {
  const unsigned side = static_cast<unsigned>(std::max({width, height, 1}));
  return static_cast<int>(std::bit_width(side));
}

GLenum internal_format(int channels, TextureEncoding encoding) {
  SYLVA_ASSERT(channels >= 1 && channels <= 4, "channels={} must be 1..4", channels);
  static constexpr GLenum kTable[5][4] = {
      {GL_R8, GL_RG8, GL_RGB8, GL_RGBA8},
      {GL_R8, GL_RG8, GL_SRGB8, GL_SRGB8_ALPHA8},
      {GL_R16, GL_RG16, GL_RGB16, GL_RGBA16},
      {GL_R16F, GL_RG16F, GL_RGB16F, GL_RGBA16F},
      {GL_R32F, GL_RG32F, GL_RGB32F, GL_RGBA32F},
  };
  return kTable[static_cast<int>(encoding)][channels - 1];
}

Texture Texture::create_2d(int width, int height, GLenum format, int levels) {
  SYLVA_ASSERT(width > 0 && height > 0 && levels >= 1, "size {}x{} levels {}", width, height, levels);
  Texture t;
  t.handle_ = GlHandle<TextureDeleter>(create_texture(GL_TEXTURE_2D));
  t.target_ = GL_TEXTURE_2D;
  t.format_ = format;
  t.width_ = width;
  t.height_ = height;
  t.levels_ = levels;
  glTextureStorage2D(t.id(), levels, format, width, height);
  t.memory_ = GpuMemoryRecord(GpuMemoryKind::kTexture, texture_storage_bytes(width, height, 1, levels, 1, format));
  t.set_filter(levels > 1 ? GL_LINEAR_MIPMAP_LINEAR : GL_LINEAR, GL_LINEAR);
  t.set_wrap(GL_CLAMP_TO_EDGE);
  return t;
}

Texture Texture::create_2d_multisample(int width, int height, GLenum format, int samples) {
  SYLVA_ASSERT(width > 0 && height > 0 && samples >= 2, "size {}x{} samples {}", width, height, samples);
  GLint max_samples = 1;
  glGetIntegerv(GL_MAX_SAMPLES, &max_samples);
  Texture t;
  t.handle_ = GlHandle<TextureDeleter>(create_texture(GL_TEXTURE_2D_MULTISAMPLE));
  t.target_ = GL_TEXTURE_2D_MULTISAMPLE;
  t.format_ = format;
  t.width_ = width;
  t.height_ = height;
  t.samples_ = std::min(samples, static_cast<int>(max_samples));
  glTextureStorage2DMultisample(t.id(), t.samples_, format, width, height, GL_TRUE);
  t.memory_ = GpuMemoryRecord(GpuMemoryKind::kTexture, texture_storage_bytes(width, height, 1, 1, t.samples_, format));
  return t;
}

Texture Texture::create_2d_array(int width, int height, int layers, GLenum format, int levels) {
  SYLVA_ASSERT(width > 0 && height > 0 && layers >= 1 && levels >= 1, "size {}x{}x{} levels {}", width, height,
               layers, levels);
  Texture t;
  t.handle_ = GlHandle<TextureDeleter>(create_texture(GL_TEXTURE_2D_ARRAY));
  t.target_ = GL_TEXTURE_2D_ARRAY;
  t.format_ = format;
  t.width_ = width;
  t.height_ = height;
  t.layers_ = layers;
  t.levels_ = levels;
  glTextureStorage3D(t.id(), levels, format, width, height, layers);
  t.memory_ = GpuMemoryRecord(GpuMemoryKind::kTexture, texture_storage_bytes(width, height, layers, levels, 1, format));
  t.set_filter(levels > 1 ? GL_LINEAR_MIPMAP_LINEAR : GL_LINEAR, GL_LINEAR);
  t.set_wrap(GL_CLAMP_TO_EDGE);
  return t;
}

Result<Texture> Texture::from_image(const Image& image, const TextureOptions& options) {
  return from_images(std::span<const Image>(&image, 1), options);
}

Result<Texture> Texture::from_images(std::span<const Image> layers, const TextureOptions& options) {
  if (layers.empty()) return make_error(ErrorCode::kInvalidArgument, "texture from images: no images given");
  const Image& first = layers.front();
  for (std::size_t i = 0; i < layers.size(); ++i) {
    const Image& im = layers[i];
    if (im.empty()) return make_error(ErrorCode::kInvalidArgument, fmt::format("texture layer {}: empty image", i));
    if (im.width() != first.width() || im.height() != first.height() || im.channels() != first.channels()) {
      return make_error(ErrorCode::kInvalidArgument,
                        fmt::format("texture layer {}: {}x{}x{} differs from layer 0 ({}x{}x{})", i, im.width(),
                                    im.height(), im.channels(), first.width(), first.height(), first.channels()));
    }
  }
  if (first.channels() < 1 || first.channels() > 4) {
    return make_error(ErrorCode::kUnsupported, fmt::format("texture: {} channels (1-4 supported)", first.channels()));
  }
  GLint max_size = 0;
  GLint max_layers = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
  glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &max_layers);
  if (first.width() > max_size || first.height() > max_size) {
    return make_error(ErrorCode::kLimit, fmt::format("texture {}x{} exceeds GL_MAX_TEXTURE_SIZE {}", first.width(),
                                                     first.height(), max_size));
  }
  const bool is_array = layers.size() > 1;
  if (is_array && static_cast<GLint>(layers.size()) > max_layers) {
    return make_error(ErrorCode::kLimit, fmt::format("texture array of {} layers exceeds GL_MAX_ARRAY_TEXTURE_LAYERS {}",
                                                     layers.size(), max_layers));
  }
  const GLenum format = internal_format(first.channels(), options.encoding);
  const int levels = options.mipmaps ? mip_levels(first.width(), first.height()) : 1;
  Texture t = is_array ? create_2d_array(first.width(), first.height(), static_cast<int>(layers.size()), format, levels)
                       : create_2d(first.width(), first.height(), format, levels);
  for (std::size_t i = 0; i < layers.size(); ++i) t.upload(layers[i], static_cast<int>(i));
  if (levels > 1) t.generate_mipmaps();
  t.set_filter(options.mipmaps ? options.min_filter
                               : (options.min_filter == GL_NEAREST_MIPMAP_NEAREST ||
                                          options.min_filter == GL_NEAREST_MIPMAP_LINEAR || options.min_filter == GL_NEAREST
                                      ? GL_NEAREST
                                      : GL_LINEAR),
               options.mag_filter);
  t.set_wrap(options.wrap);
  if (options.max_anisotropy > 1.0f && epoxy_gl_version() >= 46) {
    GLfloat limit = 1.0f;
    glGetFloatv(GL_MAX_TEXTURE_MAX_ANISOTROPY, &limit);
    glTextureParameterf(t.id(), GL_TEXTURE_MAX_ANISOTROPY, std::min(options.max_anisotropy, limit));
  }
  return t;
}

void Texture::bind(GLuint unit) const { glBindTextureUnit(unit, id()); }

void Texture::set_filter(GLenum min_filter, GLenum mag_filter) const {
  glTextureParameteri(id(), GL_TEXTURE_MIN_FILTER, static_cast<GLint>(min_filter));
  glTextureParameteri(id(), GL_TEXTURE_MAG_FILTER, static_cast<GLint>(mag_filter));
}

void Texture::set_wrap(GLenum wrap) const {
  glTextureParameteri(id(), GL_TEXTURE_WRAP_S, static_cast<GLint>(wrap));
  glTextureParameteri(id(), GL_TEXTURE_WRAP_T, static_cast<GLint>(wrap));
  glTextureParameteri(id(), GL_TEXTURE_WRAP_R, static_cast<GLint>(wrap));
}

void Texture::generate_mipmaps() const { glGenerateTextureMipmap(id()); }

void Texture::upload(const Image& image, int layer) const {
  SYLVA_ASSERT(image.width() == width_ && image.height() == height_, "image {}x{} into texture {}x{}", image.width(),
               image.height(), width_, height_);
  SYLVA_ASSERT(layer >= 0 && layer < layers_, "layer={} layers={}", layer, layers_);
  const std::vector<float> rows = flipped_rows(image);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  if (target_ == GL_TEXTURE_2D_ARRAY) {
    glTextureSubImage3D(id(), 0, 0, 0, layer, width_, height_, 1, pixel_format(image.channels()), GL_FLOAT,
                        rows.data());
  } else {
    glTextureSubImage2D(id(), 0, 0, 0, width_, height_, pixel_format(image.channels()), GL_FLOAT, rows.data());
  }
}

}  // namespace sylva::render
