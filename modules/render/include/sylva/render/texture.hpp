#pragma once
// Textures with immutable storage (glTextureStorage*), DSA style: 2D, 2D array and depth.
// Uploads from sylva::Image (core): an Image's row 0 is the top of the picture, GL's row 0 is
// the bottom, so uploads flip rows; a texture coordinate v = 0 therefore samples the image's
// bottom row, as in every GL convention. Formats follow the image's channel count:
// 1 -> R, 2 -> RG, 3 -> RGB, 4 -> RGBA; `srgb` picks SRGB8(_ALPHA8) for colour textures.

#include <sylva/core/image.hpp>
#include <sylva/core/result.hpp>
#include <sylva/render/gl_handle.hpp>
#include <sylva/render/gpu_memory.hpp>

#include <epoxy/gl.h>

#include <span>

namespace sylva::render {

struct TextureDeleter {
  void operator()(GLuint id) const { glDeleteTextures(1, &id); }
};

enum class TextureEncoding {
  kUnorm8,   // RGBA8 etc., linear
  kSrgb8,    // SRGB8 / SRGB8_ALPHA8 (1-2 channel images fall back to unorm8)
  kUnorm16,  // R16 ... RGBA16, e.g. 16-bit height maps without quantisation
  kFloat16,
  kFloat32,
};

struct TextureOptions {
  TextureEncoding encoding = TextureEncoding::kUnorm8;
  bool mipmaps = true;           // full chain, generated with glGenerateTextureMipmap
  GLenum min_filter = GL_LINEAR_MIPMAP_LINEAR;  // GL_LINEAR when mipmaps is false
  GLenum mag_filter = GL_LINEAR;
  GLenum wrap = GL_REPEAT;
  float max_anisotropy = 1.0f;   // > 1 uses GL_TEXTURE_MAX_ANISOTROPY when available
};

// Levels of a full mip chain for a w x h texture: floor(log2(max(w, h))) + 1.
int mip_levels(int width, int height);

// Internal format for `channels` (1..4) in `encoding`.
GLenum internal_format(int channels, TextureEncoding encoding);

class Texture {
 public:
  Texture() = default;

  // Empty 2D storage (levels >= 1), e.g. render targets: GL_RGBA8, GL_DEPTH_COMPONENT32F.
  static Texture create_2d(int width, int height, GLenum internal_format, int levels = 1);
  // Multisampled 2D storage (samples >= 2, clamped to GL_MAX_SAMPLES).
  static Texture create_2d_multisample(int width, int height, GLenum internal_format, int samples);
  // Empty 2D array storage with `layers` layers.
  static Texture create_2d_array(int width, int height, int layers, GLenum internal_format, int levels = 1);

  // From images. Errors: empty image, mismatched sizes/channels between layers (kInvalidArgument
  // naming the layer), size beyond GL_MAX_TEXTURE_SIZE / GL_MAX_ARRAY_TEXTURE_LAYERS (kLimit).
  static Result<Texture> from_image(const Image& image, const TextureOptions& options = {});
  static Result<Texture> from_images(std::span<const Image> layers, const TextureOptions& options = {});

  GLuint id() const { return handle_.get(); }
  GLenum target() const { return target_; }
  GLenum format() const { return format_; }
  int width() const { return width_; }
  int height() const { return height_; }
  int layers() const { return layers_; }
  int levels() const { return levels_; }
  int samples() const { return samples_; }
  explicit operator bool() const { return static_cast<bool>(handle_); }
  // Bytes of its storage (every level, layer and sample) as tracked (gpu_memory.hpp), and the
  // kind it is counted as: a texture until a framebuffer attaches it as a render target.
  std::uint64_t storage_bytes() const { return memory_.bytes(); }
  void set_memory_kind(GpuMemoryKind kind) { memory_.set_kind(kind); }

  void bind(GLuint unit) const;
  void set_filter(GLenum min_filter, GLenum mag_filter) const;
  void set_wrap(GLenum wrap) const;
  void generate_mipmaps() const;

  // Uploads one image into `layer` (0 for 2D) at level 0; size/channels must match (asserted).
  void upload(const Image& image, int layer = 0) const;

 private:
  GlHandle<TextureDeleter> handle_;
  GpuMemoryRecord memory_;
  GLenum target_ = GL_TEXTURE_2D;
  GLenum format_ = GL_RGBA8;
  int width_ = 0;
  int height_ = 0;
  int layers_ = 1;
  int levels_ = 1;
  int samples_ = 0;
};

}  // namespace sylva::render
