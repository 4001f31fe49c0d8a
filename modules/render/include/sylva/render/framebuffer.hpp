#pragma once
// Render targets: a framebuffer object with colour attachments and a 32-bit float depth
// attachment (reversed-Z needs float depth, camera.hpp), optionally multisampled with a
// resolve into single-sample textures that can be read back or sampled.
//
// Failure: create() returns kGl naming the incompleteness status or a GL error (out of memory)
// raised while allocating, and kLimit when the size exceeds GL_MAX_FRAMEBUFFER_WIDTH/HEIGHT,
// samples exceed GL_MAX_SAMPLES, or the target would take more than kMaxFramebufferBytes
// (checked before anything is allocated).

#include <sylva/core/result.hpp>
#include <sylva/render/gl_handle.hpp>
#include <sylva/render/texture.hpp>

#include <epoxy/gl.h>
#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace sylva::render {

struct FramebufferDeleter {
  void operator()(GLuint id) const { glDeleteFramebuffers(1, &id); }
};

struct FramebufferDesc {
  int width = 256;   // pixels, >= 1
  int height = 144;
  std::vector<GLenum> color_formats{GL_RGBA8};  // may be empty (depth-only, shadow maps)
  GLenum depth_format = GL_DEPTH_COMPONENT32F;  // GL_NONE for no depth
  int samples = 0;   // 0 or 1: single-sampled; >= 2: MSAA with resolve targets
};

// Largest render target create() allocates (all attachments, samples and resolve targets).
inline constexpr std::uint64_t kMaxFramebufferBytes = 4ull << 30;

class Framebuffer {
 public:
  Framebuffer() = default;
  static Result<Framebuffer> create(const FramebufferDesc& desc);
  // GPU bytes a target of `desc` takes (attachments x samples, plus resolve targets).
  static std::uint64_t estimated_bytes(const FramebufferDesc& desc);

  GLuint id() const { return fbo_.get(); }
  int width() const { return desc_.width; }
  int height() const { return desc_.height; }
  glm::ivec2 size() const { return {desc_.width, desc_.height}; }
  int samples() const { return desc_.samples; }
  bool multisampled() const { return desc_.samples > 1; }
  const FramebufferDesc& desc() const { return desc_; }
  explicit operator bool() const { return static_cast<bool>(fbo_); }

  // Binds as GL_FRAMEBUFFER and sets the viewport to the full size.
  void bind() const;
  static void bind_default(int width, int height);

  // Clears every colour attachment to `color` and depth to `depth` (0 = far with reversed-Z),
  // whole: whatever write masks and scissor the caller left (restored afterwards).
  void clear(const glm::vec4& color, float depth = 0.0f) const;

  // MSAA: blits colour (and depth) into the resolve textures. No-op for single-sampled targets.
  void resolve() const;

  // Copies this target's depth (the resolved one when multisampled: call resolve() first) into
  // `to`'s, pixel for pixel. Nothing when either has no depth, or their sizes or depth formats
  // differ (a blit cannot convert them).
  void copy_depth_to(const Framebuffer& to) const;

  // The single-sample texture holding attachment i (the resolve target for MSAA).
  const Texture& color_texture(int i = 0) const;
  const Texture& depth_texture() const;
  // The FBO to read single-sampled pixels from (the resolve FBO for MSAA).
  GLuint read_id() const;

 private:
  FramebufferDesc desc_;
  GlHandle<FramebufferDeleter> fbo_;
  GlHandle<FramebufferDeleter> resolve_fbo_;
  std::vector<Texture> color_;          // attachments of fbo_
  Texture depth_;
  std::vector<Texture> resolve_color_;  // MSAA only
  Texture resolve_depth_;
};

}  // namespace sylva::render
