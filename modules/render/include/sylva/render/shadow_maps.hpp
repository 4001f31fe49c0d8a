#pragma once
// The sun's cascaded shadow maps on the GPU (seed 004 §3.6, extraction §4.7; seed 000 §4.7):
// one GL_DEPTH_COMPONENT32F 2D array texture (one layer per cascade), a depth-only FBO per
// layer, the casters every module registers, and the SylvaShadows uniform block receivers read
// through "render/lib/shadows.glsl" (`float sylva_shadow(vec3 rel_pos, vec3 normal)`, 1 = lit).
//
// Binding points (fixed, so no per-program plumbing; lighting uses UBO binding 0):
//   kShadowUniformBinding = 2   std140 block SylvaShadows (matrices, splits, bias, counts)
//   kShadowTextureUnit    = 15  sampler2DArrayShadow sylva_shadow_map (compare GL_GEQUAL)
// Cascade count and resolution change at run time: the texture is reallocated, shaders are
// never recompiled (arrays are sized kMaxShadowCascades = 8; the seed had to recompile, §4.8).
//
// Depth convention: reversed like the camera (shadow_cascades.hpp): cleared to 0, drawn with
// GL_GREATER, 1 = nearest to the sun. During render() GL_DEPTH_CLAMP is on so casters between
// the sun and the cascade volume still occlude.
//
// A caster (terrain, trees, grass, voxels) draws its geometry, deformed exactly as in its colour
// pass, with ShadowCasterContext::relative_view_projection applied to CAMERA-RELATIVE positions
// (world - context.camera.position()) and writes only depth (colour writes are off; there is no
// colour attachment). It may cull against context.light_frustum and must not change the FBO.

#include <sylva/core/result.hpp>
#include <sylva/render/buffer.hpp>
#include <sylva/render/camera.hpp>
#include <sylva/render/framebuffer.hpp>
#include <sylva/render/frustum.hpp>
#include <sylva/render/queries.hpp>
#include <sylva/render/sampler.hpp>
#include <sylva/render/shadow_cascades.hpp>
#include <sylva/render/texture.hpp>

#include <functional>
#include <optional>
#include <span>
#include <vector>

namespace sylva::render {

inline constexpr GLuint kShadowUniformBinding = 2;

// A SylvaShadows block with shadows disabled (sylva_shadow returns 1), sized from the same std140
// mirror ShadowMaps uploads: for receivers drawn where no host bound shadow maps.
Buffer make_disabled_shadow_block();
inline constexpr GLuint kShadowTextureUnit = 15;

struct FrameContext;

// What a caster gets for one cascade.
struct ShadowCasterContext {
  int cascade = 0;                         // 0 .. cascade_count - 1 (0 = nearest the camera)
  glm::mat4 relative_view_projection{1.0f};  // camera-relative position -> shadow clip space
  Frustum light_frustum;                   // of that matrix, for CPU culling (world boxes)
  const Camera* camera = nullptr;          // positions are relative to camera->position()
  const FrameContext* frame = nullptr;     // may be null (tests); time/wind for animation
  glm::vec3 light_direction{0.0f, 1.0f, 0.0f};  // unit, toward the sun
  float texel_size = 0.0f;                 // world metres per shadow texel in this cascade
  PassStats* stats = nullptr;              // add draw calls / triangles here (never null in render())
};

class ShadowCaster {
 public:
  virtual ~ShadowCaster() = default;
  // Called once per cascade with that cascade's depth layer bound and cleared.
  virtual void draw_shadow(const ShadowCasterContext& context) = 0;
};

// A caster from a callback (for modules that would rather not derive from ShadowCaster).
class CallbackShadowCaster final : public ShadowCaster {
 public:
  explicit CallbackShadowCaster(std::function<void(const ShadowCasterContext&)> fn) : fn_(std::move(fn)) {}
  void draw_shadow(const ShadowCasterContext& context) override { if (fn_) fn_(context); }

 private:
  std::function<void(const ShadowCasterContext&)> fn_;
};

// The cascade being drawn while ShadowMaps::render() runs its casters, else null. This lets a
// Drawable draw its shadow from draw(Pass::kShadow, ...) (the scene's shadow hook) without a
// new parameter: `if (auto* c = render::active_shadow_cascade()) draw_depth(c->relative_view_projection)`.
// GL is used from one thread, so this is a plain global of the rendering thread.
const ShadowCasterContext* active_shadow_cascade();

// Whether the shadow block in `buffer` says "enabled", known on the CPU: the flag of the last
// upload into it by a live ShadowMaps (render() with shadows on: true; disabled or failed: false).
// std::nullopt for any other buffer (a host's own block, make_disabled_shadow_block's): a receiver
// that must know reads it back, which on hardware drivers waits for the GPU.
std::optional<bool> shadow_block_enabled(GLuint buffer);

namespace detail {
// A ShadowMaps' uniform buffer, registered for shadow_block_enabled with its last upload's flag
// and unregistered when destroyed or overwritten by a move (a deleted GL name may be reused).
class ShadowBlockBuffer {
 public:
  ShadowBlockBuffer() = default;
  explicit ShadowBlockBuffer(Buffer buffer) : buffer_(std::move(buffer)) {}
  ShadowBlockBuffer(ShadowBlockBuffer&&) noexcept = default;  // the name moves with its entry
  ShadowBlockBuffer& operator=(ShadowBlockBuffer&& other) noexcept;
  ShadowBlockBuffer(const ShadowBlockBuffer&) = delete;
  ShadowBlockBuffer& operator=(const ShadowBlockBuffer&) = delete;
  ~ShadowBlockBuffer();

  void upload(const void* block, std::size_t bytes, bool enabled);
  const Buffer& buffer() const { return buffer_; }

 private:
  Buffer buffer_;
};
}  // namespace detail

class ShadowMaps {
 public:
  // Needs a current GL 4.5 context. Errors: kLimit when the resolution exceeds
  // GL_MAX_TEXTURE_SIZE, kGl when a layer FBO is incomplete.
  static Result<ShadowMaps> create(const ShadowSettings& settings = {});
  ShadowMaps() = default;

  ShadowSettings& settings() { return settings_; }
  const ShadowSettings& settings() const { return settings_; }

  // Casters are not owned; a registered caster must outlive its registration. Registering twice
  // is a no-op; unregistering an unknown caster is a no-op.
  void add_caster(ShadowCaster* caster);
  void remove_caster(ShadowCaster* caster);
  std::size_t caster_count() const { return casters_.size(); }

  // Fits the cascades to `camera` and the sun (unit vector toward it), (re)allocates storage if
  // settings().cascade_count or resolution changed (kLimit/kGl as in create, the old maps stay),
  // draws every registered caster into every cascade and uploads the uniform block. Leaves the
  // FBO 0 bound with depth clamp off; the caller binds its own target afterwards.
  // `frame` is handed to casters (may be null); per-cascade counts are added to `stats`.
  Status render(const Camera& camera, const glm::vec3& toward_sun, const FrameContext* frame = nullptr,
                PassStats* stats = nullptr);

  // Binds the block (kShadowUniformBinding), the depth array and its comparison sampler
  // (kShadowTextureUnit) for receivers. Harmless before the first render (shadows disabled).
  void bind() const;

  const ShadowCascades& cascades() const { return cascades_; }
  const Texture& depth_array() const { return depth_; }
  int allocated_layers() const { return depth_.layers(); }
  int resolution() const { return depth_.width(); }

 private:
  Status allocate(int layers, int resolution);
  void upload_uniforms(bool enabled);

  ShadowSettings settings_;
  ShadowCascades cascades_;
  Texture depth_;
  std::vector<GlHandle<FramebufferDeleter>> layer_fbos_;
  Sampler compare_sampler_;
  detail::ShadowBlockBuffer uniforms_;
  std::vector<ShadowCaster*> casters_;
};

}  // namespace sylva::render
