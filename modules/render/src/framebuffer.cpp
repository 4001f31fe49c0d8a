// Render targets with float depth and optional MSAA resolve (framebuffer.hpp).
#include <sylva/render/framebuffer.hpp>

#include <sylva/core/assert.hpp>
#include <sylva/render/gl_debug.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <array>

namespace sylva::render {
namespace {

// Clears and blits write every pixel of a target only with the write masks open and the
// scissor test off: both obey the scissor test (GL 4.5 §17.4.3, §18.3.1), clears obey the
// masks, and NVIDIA's driver honours the depth and colour masks in blits too (Mesa does not).
// Opens them for one operation and restores what the caller had.
class OpenWrites {
 public:
  OpenWrites() {
    glGetBooleanv(GL_DEPTH_WRITEMASK, &depth_mask_);
    glGetBooleanv(GL_COLOR_WRITEMASK, color_mask_);
    scissor_ = glIsEnabled(GL_SCISSOR_TEST);
    glDepthMask(GL_TRUE);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDisable(GL_SCISSOR_TEST);
  }
  ~OpenWrites() {
    glDepthMask(depth_mask_);
    glColorMask(color_mask_[0], color_mask_[1], color_mask_[2], color_mask_[3]);
    if (scissor_) glEnable(GL_SCISSOR_TEST);
  }
  OpenWrites(const OpenWrites&) = delete;
  OpenWrites& operator=(const OpenWrites&) = delete;

 private:
  GLboolean depth_mask_ = GL_TRUE;
  GLboolean color_mask_[4] = {GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE};
  GLboolean scissor_ = GL_FALSE;
};

const char* status_name(GLenum status) {
  switch (status) {
    case GL_FRAMEBUFFER_UNDEFINED: return "GL_FRAMEBUFFER_UNDEFINED";
    case GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT: return "GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT";
    case GL_FRAMEBUFFER_INCOMPLETE_MISSING_ATTACHMENT: return "GL_FRAMEBUFFER_INCOMPLETE_MISSING_ATTACHMENT";
    case GL_FRAMEBUFFER_INCOMPLETE_DRAW_BUFFER: return "GL_FRAMEBUFFER_INCOMPLETE_DRAW_BUFFER";
    case GL_FRAMEBUFFER_INCOMPLETE_READ_BUFFER: return "GL_FRAMEBUFFER_INCOMPLETE_READ_BUFFER";
    case GL_FRAMEBUFFER_UNSUPPORTED: return "GL_FRAMEBUFFER_UNSUPPORTED";
    case GL_FRAMEBUFFER_INCOMPLETE_MULTISAMPLE: return "GL_FRAMEBUFFER_INCOMPLETE_MULTISAMPLE";
    case GL_FRAMEBUFFER_INCOMPLETE_LAYER_TARGETS: return "GL_FRAMEBUFFER_INCOMPLETE_LAYER_TARGETS";
    default: return "unknown framebuffer status";
  }
}

GLuint create_fbo() {
  GLuint id = 0;
  glCreateFramebuffers(1, &id);
  return id;
}

// Attaches colour textures and depth, sets draw buffers and checks completeness.
Status attach(GLuint fbo, const std::vector<Texture>& color, const Texture& depth, const char* what) {
  std::vector<GLenum> draw_buffers;
  for (std::size_t i = 0; i < color.size(); ++i) {
    const GLenum attachment = GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(i);
    glNamedFramebufferTexture(fbo, attachment, color[i].id(), 0);
    draw_buffers.push_back(attachment);
  }
  if (depth) glNamedFramebufferTexture(fbo, GL_DEPTH_ATTACHMENT, depth.id(), 0);
  if (draw_buffers.empty()) {
    glNamedFramebufferDrawBuffer(fbo, GL_NONE);
    glNamedFramebufferReadBuffer(fbo, GL_NONE);
  } else {
    glNamedFramebufferDrawBuffers(fbo, static_cast<GLsizei>(draw_buffers.size()), draw_buffers.data());
    glNamedFramebufferReadBuffer(fbo, GL_COLOR_ATTACHMENT0);
  }
  const GLenum status = glCheckNamedFramebufferStatus(fbo, GL_FRAMEBUFFER);
  if (status != GL_FRAMEBUFFER_COMPLETE) {
    return make_error(ErrorCode::kGl, fmt::format("{} framebuffer incomplete: {}", what, status_name(status)));
  }
  return ok_status();
}

}  // namespace

std::uint64_t Framebuffer::estimated_bytes(const FramebufferDesc& desc) {
  std::uint64_t per_pixel = desc.depth_format != GL_NONE ? texel_bytes(desc.depth_format) : 0;
  for (GLenum format : desc.color_formats) per_pixel += texel_bytes(format);
  const std::uint64_t samples = static_cast<std::uint64_t>(std::max(desc.samples, 1));
  const std::uint64_t resolve = desc.samples > 1 ? per_pixel : 0;
  return static_cast<std::uint64_t>(std::max(desc.width, 0)) * static_cast<std::uint64_t>(std::max(desc.height, 0)) *
         (per_pixel * samples + resolve);
}

Result<Framebuffer> Framebuffer::create(const FramebufferDesc& desc) {
  GLint max_w = 0;
  GLint max_h = 0;
  GLint max_samples = 0;
  GLint max_attachments = 0;
  glGetIntegerv(GL_MAX_FRAMEBUFFER_WIDTH, &max_w);
  glGetIntegerv(GL_MAX_FRAMEBUFFER_HEIGHT, &max_h);
  glGetIntegerv(GL_MAX_SAMPLES, &max_samples);
  glGetIntegerv(GL_MAX_COLOR_ATTACHMENTS, &max_attachments);
  if (desc.width < 1 || desc.height < 1) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("framebuffer size {}x{} must be at least 1x1", desc.width, desc.height));
  }
  if (desc.width > max_w || desc.height > max_h) {
    return make_error(ErrorCode::kLimit, fmt::format("framebuffer {}x{} exceeds the GL limit {}x{}", desc.width,
                                                     desc.height, max_w, max_h));
  }
  if (desc.samples < 0 || desc.samples > max_samples) {
    return make_error(ErrorCode::kLimit, fmt::format("framebuffer samples={} outside 0..{}", desc.samples, max_samples));
  }
  if (static_cast<GLint>(desc.color_formats.size()) > max_attachments) {
    return make_error(ErrorCode::kLimit, fmt::format("{} colour attachments exceed GL_MAX_COLOR_ATTACHMENTS {}",
                                                     desc.color_formats.size(), max_attachments));
  }
  const std::uint64_t bytes = estimated_bytes(desc);
  if (bytes > kMaxFramebufferBytes) {
    return make_error(ErrorCode::kLimit,
                      fmt::format("render target {}x{} ({} samples) would take {} MiB of GPU memory, above the limit of "
                                  "{} MiB; use a smaller size",
                                  desc.width, desc.height, std::max(desc.samples, 1), bytes >> 20,
                                  kMaxFramebufferBytes >> 20));
  }
  const std::size_t mark = gl_error_mark();
  Framebuffer fb;
  fb.desc_ = desc;
  fb.fbo_ = GlHandle<FramebufferDeleter>(create_fbo());
  const bool msaa = desc.samples > 1;
  for (GLenum format : desc.color_formats) {
    fb.color_.push_back(msaa ? Texture::create_2d_multisample(desc.width, desc.height, format, desc.samples)
                             : Texture::create_2d(desc.width, desc.height, format));
  }
  if (desc.depth_format != GL_NONE) {
    fb.depth_ = msaa ? Texture::create_2d_multisample(desc.width, desc.height, desc.depth_format, desc.samples)
                     : Texture::create_2d(desc.width, desc.height, desc.depth_format);
  }
  SYLVA_TRY(attach(fb.fbo_.get(), fb.color_, fb.depth_, msaa ? "MSAA" : "single-sample"));
  if (msaa) {
    fb.resolve_fbo_ = GlHandle<FramebufferDeleter>(create_fbo());
    for (GLenum format : desc.color_formats) {
      fb.resolve_color_.push_back(Texture::create_2d(desc.width, desc.height, format));
    }
    if (desc.depth_format != GL_NONE) fb.resolve_depth_ = Texture::create_2d(desc.width, desc.height, desc.depth_format);
    SYLVA_TRY(attach(fb.resolve_fbo_.get(), fb.resolve_color_, fb.resolve_depth_, "MSAA resolve"));
  }
  for (Texture* t : {&fb.depth_, &fb.resolve_depth_}) {
    if (*t) t->set_memory_kind(GpuMemoryKind::kRenderTarget);
  }
  for (auto* list : {&fb.color_, &fb.resolve_color_}) {
    for (Texture& t : *list) t.set_memory_kind(GpuMemoryKind::kRenderTarget);
  }
  // Storage is allocated by the calls above; an implementation out of memory says so only
  // through a GL error, which must not turn into a black picture later.
  SYLVA_TRY(check_frame_gl_errors(mark, fmt::format("the allocation of a {}x{} render target", desc.width, desc.height)));
  return fb;
}

void Framebuffer::bind() const {
  glBindFramebuffer(GL_FRAMEBUFFER, id());
  glViewport(0, 0, desc_.width, desc_.height);
}

void Framebuffer::bind_default(int width, int height) {
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glViewport(0, 0, width, height);
}

void Framebuffer::clear(const glm::vec4& color, float depth) const {
  const OpenWrites open;
  for (std::size_t i = 0; i < color_.size(); ++i) {
    glClearNamedFramebufferfv(id(), GL_COLOR, static_cast<GLint>(i), &color.x);
  }
  if (depth_) glClearNamedFramebufferfv(id(), GL_DEPTH, 0, &depth);
}

void Framebuffer::resolve() const {
  if (!multisampled()) return;
  const GLint w = desc_.width;
  const GLint h = desc_.height;
  // With the masks open (OpenWrites): a pass that had left depth writes off made every resolved
  // depth the allocation's garbage on NVIDIA, while Mesa copied.
  const OpenWrites open;
  for (std::size_t i = 0; i < color_.size(); ++i) {
    const GLenum attachment = GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(i);
    glNamedFramebufferReadBuffer(id(), attachment);
    glNamedFramebufferDrawBuffer(resolve_fbo_.get(), attachment);
    glBlitNamedFramebuffer(id(), resolve_fbo_.get(), 0, 0, w, h, 0, 0, w, h, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  }
  if (depth_) {
    glBlitNamedFramebuffer(id(), resolve_fbo_.get(), 0, 0, w, h, 0, 0, w, h, GL_DEPTH_BUFFER_BIT, GL_NEAREST);
  }
  if (!color_.empty()) {
    // Runs every frame: the draw-buffer list lives on the stack (create() refused more than
    // GL_MAX_COLOR_ATTACHMENTS, 8 on Mesa and the GPUs seen; the array has room for 32).
    std::array<GLenum, 32> draw_buffers{};
    const std::size_t n = std::min(color_.size(), draw_buffers.size());
    for (std::size_t i = 0; i < n; ++i) draw_buffers[i] = GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(i);
    glNamedFramebufferReadBuffer(id(), GL_COLOR_ATTACHMENT0);
    glNamedFramebufferDrawBuffers(resolve_fbo_.get(), static_cast<GLsizei>(n), draw_buffers.data());
  }
}

void Framebuffer::copy_depth_to(const Framebuffer& to) const {
  if (!depth_ || !to.depth_ || desc_.depth_format != to.desc_.depth_format || size() != to.size()) return;
  const OpenWrites open;
  glBlitNamedFramebuffer(read_id(), to.id(), 0, 0, width(), height(), 0, 0, width(), height(), GL_DEPTH_BUFFER_BIT,
                         GL_NEAREST);
}

const Texture& Framebuffer::color_texture(int i) const {
  const std::vector<Texture>& list = multisampled() ? resolve_color_ : color_;
  SYLVA_ASSERT(i >= 0 && i < static_cast<int>(list.size()), "colour attachment {} of {}", i, list.size());
  return list[static_cast<std::size_t>(i)];
}

const Texture& Framebuffer::depth_texture() const { return multisampled() ? resolve_depth_ : depth_; }

GLuint Framebuffer::read_id() const { return multisampled() ? resolve_fbo_.get() : fbo_.get(); }

}  // namespace sylva::render

