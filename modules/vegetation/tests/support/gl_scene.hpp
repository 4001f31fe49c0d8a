#pragma once
// GL test support: an off-screen target with the frame's lighting bound, a TreeRenderer and
// helpers to render trees and read the picture back (GL tests only).

#include <sylva/core/image.hpp>
#include <sylva/core/wind.hpp>
#include <sylva/render/buffer.hpp>
#include <sylva/render/camera.hpp>
#include <sylva/render/framebuffer.hpp>
#include <sylva/render/lighting.hpp>
#include <sylva/render/lighting_uniforms.hpp>
#include <sylva/vegetation/tree_renderer.hpp>

#include <string>
#include <vector>

namespace sylva::vegetation::testing {

struct GlScene {
  render::Framebuffer target;
  render::LightingUniforms lighting_ubo;
  render::Lighting lighting;
  render::Camera camera;
  glm::vec4 clear_color{1.0f, 0.0f, 1.0f, 1.0f};

  // samples >= 2 gives a multisampled target (alpha-to-coverage). A float `color_format` for
  // tests that look for NaN in the picture (an 8-bit target stores NaN as a number).
  static GlScene create(int width, int height, int samples = 0, GLenum color_format = GL_RGBA8);
  void begin(double time = 0.0);
  Image read() const;
};

// One tree asset with its instance buffer.
struct TreeOnGpu {
  TreeMesh mesh;
  TreeAsset asset;
  render::Buffer instances;
};

// Builds the asset with small textures (leaf_size px leaves, 64 px bark).
TreeOnGpu upload_tree(const TreeMesh& mesh, SpeciesPreset textures_of, const TreeAssetOptions& options = {},
                      int leaf_size = 64);

// Writes the instance records.
void set_instances(TreeOnGpu& tree, const std::vector<InstanceGpu>& instances);

// Per-pixel coverage of a render over two backgrounds: 1 - (white - black), averaged over rgb.
Image coverage_from_backgrounds(const Image& over_black, const Image& over_white);

// Writes `image` as PNG under vegetation_out/ in the working directory (for a person to look at).
void save_png(const Image& image, const std::string& name);

}  // namespace sylva::vegetation::testing
