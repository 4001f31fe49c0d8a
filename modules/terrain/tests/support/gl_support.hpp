#pragma once
// GL test support for the terrain: an off-screen target with the frame's lighting bound, a
// brute-force full-resolution reference renderer of a height field (for silhouettes), and the
// exact full-resolution surface height (the leaf RTIN triangulation) for error measurements.
// Only the *_gl_test executables call these (they need a current context).

#include <sylva/core/height_field.hpp>
#include <sylva/core/image.hpp>
#include <sylva/core/wind.hpp>
#include <sylva/render/buffer.hpp>
#include <sylva/render/camera.hpp>
#include <sylva/render/framebuffer.hpp>
#include <sylva/render/lighting.hpp>
#include <sylva/render/lighting_uniforms.hpp>
#include <sylva/render/readback.hpp>
#include <sylva/render/shader_library.hpp>
#include <sylva/render/vertex_array.hpp>
#include <sylva/terrain/renderer.hpp>

#include <string>

namespace sylva::terrain::testing {

inline constexpr glm::vec4 kMagenta{1.0f, 0.0f, 1.0f, 1.0f};

struct GlTarget {
  render::Framebuffer target;
  render::LightingUniforms lighting_ubo;
  render::Lighting lighting;
  WindField wind;

  static GlTarget create(int width = 256, int height = 144);
  glm::ivec2 size() const { return target.size(); }
  // Binds the target and lighting, clears to `clear`, runs update + the opaque pass (of the
  // height-field terrain, the general model or any drawable).
  Image render(render::Drawable& terrain, const render::Camera& camera, const glm::vec4& clear);
  Result<Image> depth() const { return render::read_depth(target); }
};

// Draws every cell of a field as two triangles (the RTIN diagonal of each unit cell), flat green,
// for the reference silhouette.
class BruteForceField {
 public:
  static BruteForceField create(const HeightField& field);
  Image render(GlTarget& target, const render::Camera& camera, const glm::vec4& clear);

 private:
  const HeightField* field_ = nullptr;
  render::Program program_;
  render::Buffer vertices_, indices_;
  render::VertexArray vao_;
  std::size_t index_count_ = 0;
  std::vector<glm::vec3> rel_;
};

// Height of the full-resolution surface (each unit cell split along its RTIN diagonal) at grid
// coordinates (x, z), clamped to the field.
double full_resolution_height(const HeightField& field, double x, double z);

// Pixels of exactly `color` (within 1/255 per channel).
bool is_color(const Image& image, int x, int y, const glm::vec4& color);
// `mask` eroded by `radius` pixels (square neighbourhood).
std::vector<std::uint8_t> erode(const std::vector<std::uint8_t>& mask, int width, int height, int radius);

void save_png(const Image& image, const std::string& name);

}  // namespace sylva::terrain::testing
