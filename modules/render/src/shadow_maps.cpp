// Cascaded shadow maps on the GPU; see shadow_maps.hpp.
#include <sylva/core/log.hpp>
#include <sylva/render/frame_context.hpp>
#include <sylva/render/shadow_maps.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cstring>
#include <unordered_map>

namespace sylva::render {
namespace {

// std140 mirror of SylvaShadows in shaders/lib/shadows.glsl (keep in sync; sizes asserted).
// Per-cascade scalars are packed four to a vec4 (std140 would pad a float[8] to 16 bytes each).
constexpr int kCascadeVec4s = (kMaxShadowCascades + 3) / 4;
struct ShadowBlock {
  glm::mat4 matrix[kMaxShadowCascades];  // camera-relative -> (u, v, depth)
  glm::vec4 split_far[kCascadeVec4s];    // far view depth of each cascade [m]
  glm::vec4 texel[kCascadeVec4s];        // world texel size per cascade [m]
  glm::vec4 bias_scale[kCascadeVec4s];   // per-cascade bias factor
  glm::vec4 view_forward;                // xyz camera forward, w blend fraction
  glm::vec4 light_direction;             // xyz toward the sun
  glm::vec4 bias;                        // x slope bias, y min bias, z normal offset [texels]
  glm::ivec4 params;                     // x count, y pcf radius, z enabled, w resolution
};
static_assert(sizeof(ShadowBlock) == kMaxShadowCascades * 64 + (3 * kCascadeVec4s + 4) * 16,
              "std140 layout of SylvaShadows");

const ShadowCasterContext* g_active_cascade = nullptr;

// shadow_block_enabled's registry: GL buffer name -> the last upload's flag. GL is used from one
// thread (as g_active_cascade), so a plain global of the rendering thread; never destroyed, so a
// ShadowMaps destroyed during static destruction still finds it.
std::unordered_map<GLuint, bool>& shadow_blocks() {
  static auto* blocks = new std::unordered_map<GLuint, bool>();
  return *blocks;
}

}  // namespace

std::optional<bool> shadow_block_enabled(GLuint buffer) {
  const auto it = shadow_blocks().find(buffer);
  if (it == shadow_blocks().end()) return std::nullopt;
  return it->second;
}

namespace detail {

ShadowBlockBuffer& ShadowBlockBuffer::operator=(ShadowBlockBuffer&& other) noexcept {
  if (this != &other) {
    shadow_blocks().erase(buffer_.id());
    buffer_ = std::move(other.buffer_);
  }
  return *this;
}

ShadowBlockBuffer::~ShadowBlockBuffer() { shadow_blocks().erase(buffer_.id()); }

void ShadowBlockBuffer::upload(const void* block, std::size_t bytes, bool enabled) {
  buffer_.update(0, bytes, block);
  shadow_blocks()[buffer_.id()] = enabled;
}

}  // namespace detail

Buffer make_disabled_shadow_block() {
  const ShadowBlock disabled{};  // params.z = 0: disabled
  return Buffer::immutable(sizeof(disabled), &disabled);
}

const ShadowCasterContext* active_shadow_cascade() { return g_active_cascade; }

Result<ShadowMaps> ShadowMaps::create(const ShadowSettings& settings) {
  ShadowMaps maps;
  maps.settings_ = settings;
  SamplerDesc desc;
  desc.min_filter = GL_LINEAR;  // 2x2 bilinear comparison per tap
  desc.mag_filter = GL_LINEAR;
  desc.wrap_s = desc.wrap_t = desc.wrap_r = GL_CLAMP_TO_BORDER;
  desc.depth_compare = true;
  desc.compare_func = GL_GEQUAL;  // reversed depth: lit when receiver depth >= stored depth
  // Border depth 0 = "farthest": everything outside a map compares lit (seed §3.1).
  maps.compare_sampler_ = Sampler::create(desc);
  maps.uniforms_ = detail::ShadowBlockBuffer(Buffer::immutable(sizeof(ShadowBlock), nullptr, true));
  const int count = std::clamp(settings.cascade_count, 1, kMaxShadowCascades);
  SYLVA_TRY(maps.allocate(count, settings.resolution));
  maps.upload_uniforms(false);
  return maps;
}

Status ShadowMaps::allocate(int layers, int resolution) {
  GLint max_size = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
  if (resolution < 1 || resolution > max_size || resolution > 8192) {
    return make_error(ErrorCode::kLimit, fmt::format("shadow.resolution = {} is outside 1..{} (GL_MAX_TEXTURE_SIZE {})",
                                                     resolution, std::min(max_size, 8192), max_size));
  }
  Texture depth = Texture::create_2d_array(resolution, resolution, layers, GL_DEPTH_COMPONENT32F);
  depth.set_memory_kind(GpuMemoryKind::kRenderTarget);
  std::vector<GlHandle<FramebufferDeleter>> fbos;
  for (int i = 0; i < layers; ++i) {
    GLuint fbo = 0;
    glCreateFramebuffers(1, &fbo);
    fbos.emplace_back(fbo);
    glNamedFramebufferTextureLayer(fbo, GL_DEPTH_ATTACHMENT, depth.id(), 0, i);
    glNamedFramebufferDrawBuffer(fbo, GL_NONE);
    glNamedFramebufferReadBuffer(fbo, GL_NONE);
    const GLenum status = glCheckNamedFramebufferStatus(fbo, GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE) {
      return make_error(ErrorCode::kGl, fmt::format("shadow map layer {} framebuffer incomplete (0x{:x})", i, status));
    }
  }
  depth_ = std::move(depth);
  layer_fbos_ = std::move(fbos);
  return ok_status();
}

void ShadowMaps::add_caster(ShadowCaster* caster) {
  if (caster == nullptr) return;
  if (std::find(casters_.begin(), casters_.end(), caster) == casters_.end()) casters_.push_back(caster);
}

void ShadowMaps::remove_caster(ShadowCaster* caster) {
  casters_.erase(std::remove(casters_.begin(), casters_.end(), caster), casters_.end());
}

Status ShadowMaps::render(const Camera& camera, const glm::vec3& toward_sun, const FrameContext* frame, PassStats* stats) {
  if (!settings_.enabled) {
    upload_uniforms(false);
    return ok_status();
  }
  const int count = std::clamp(settings_.cascade_count, 1, kMaxShadowCascades);
  if (count != depth_.layers() || settings_.resolution != depth_.width()) {
    const Status st = allocate(count, settings_.resolution);
    if (!st.ok()) {
      upload_uniforms(false);
      return st;
    }
  }
  cascades_ = compute_shadow_cascades(camera, toward_sun, settings_);

  PassStats local;
  PassStats& out = stats != nullptr ? *stats : local;
  GLboolean color_mask[4];
  glGetBooleanv(GL_COLOR_WRITEMASK, color_mask);
  glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  glEnable(GL_DEPTH_CLAMP);
  glEnable(GL_DEPTH_TEST);
  glDepthMask(GL_TRUE);
  glDepthFunc(GL_GREATER);
  glViewport(0, 0, depth_.width(), depth_.width());
  for (int i = 0; i < count; ++i) {
    const ShadowCascade& c = cascades_.cascades[static_cast<std::size_t>(i)];
    glBindFramebuffer(GL_FRAMEBUFFER, layer_fbos_[static_cast<std::size_t>(i)].get());
    const float zero = 0.0f;
    glClearNamedFramebufferfv(layer_fbos_[static_cast<std::size_t>(i)].get(), GL_DEPTH, 0, &zero);
    ShadowCasterContext ctx;
    ctx.cascade = i;
    ctx.relative_view_projection = c.relative_view_projection;
    ctx.light_frustum = Frustum::from_matrix(c.relative_cull, camera.position());
    ctx.camera = &camera;
    ctx.frame = frame;
    ctx.light_direction = cascades_.light_direction;
    ctx.texel_size = c.texel_size;
    ctx.stats = &out;
    g_active_cascade = &ctx;
    for (ShadowCaster* caster : casters_) caster->draw_shadow(ctx);
    g_active_cascade = nullptr;
  }
  glDisable(GL_DEPTH_CLAMP);
  glColorMask(color_mask[0], color_mask[1], color_mask[2], color_mask[3]);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  upload_uniforms(true);
  return ok_status();
}

void ShadowMaps::upload_uniforms(bool enabled) {
  ShadowBlock b{};
  const int count = enabled ? cascades_.count : 0;
  for (int i = 0; i < kMaxShadowCascades; ++i) {
    const ShadowCascade& c = cascades_.cascades[static_cast<std::size_t>(i)];
    b.matrix[i] = i < count ? c.relative_texture : glm::mat4(1.0f);
    b.split_far[i / 4][i % 4] = i < count ? c.far_depth : 0.0f;
    b.texel[i / 4][i % 4] = i < count ? c.texel_size : 0.0f;
    b.bias_scale[i / 4][i % 4] = i < count ? c.bias_scale : 1.0f;
  }
  b.view_forward = glm::vec4(cascades_.view_forward, std::clamp(settings_.blend_fraction, 0.0f, 0.5f));
  b.light_direction = glm::vec4(cascades_.light_direction, 0.0f);
  b.bias = glm::vec4(std::max(settings_.slope_bias, 0.0f), std::max(settings_.min_bias, 0.0f),
                     std::max(settings_.normal_offset, 0.0f), 0.0f);
  b.params = glm::ivec4(count, std::clamp(settings_.pcf_radius, 0, 3), enabled && count > 0 ? 1 : 0, depth_.width());
  uniforms_.upload(&b, sizeof(b), b.params.z != 0);
}

void ShadowMaps::bind() const {
  uniforms_.buffer().bind_base(GL_UNIFORM_BUFFER, kShadowUniformBinding);
  if (depth_) {
    glBindTextureUnit(kShadowTextureUnit, depth_.id());
    compare_sampler_.bind(kShadowTextureUnit);
  }
}

}  // namespace sylva::render
