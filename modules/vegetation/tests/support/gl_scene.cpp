#include "support/gl_scene.hpp"

#include <sylva/core/assert.hpp>
#include <sylva/core/log.hpp>
#include <sylva/render/readback.hpp>

#include <epoxy/gl.h>

#include <filesystem>

namespace sylva::vegetation::testing {

GlScene GlScene::create(int width, int height, int samples, GLenum color_format) {
  GlScene s;
  render::FramebufferDesc desc;
  desc.width = width;
  desc.height = height;
  desc.samples = samples;
  desc.color_formats = {color_format};
  Result<render::Framebuffer> fb = render::Framebuffer::create(desc);
  SYLVA_ASSERT(fb.ok(), "framebuffer: {}", fb.error().message);
  s.target = std::move(fb).value();
  s.lighting_ubo = render::LightingUniforms::create();
  s.lighting.fog_density = 0.0f;
  s.camera.set_aspect(width, height);
  s.camera.perspective().near_plane = 0.05f;
  return s;
}

void GlScene::begin(double time) {
  render::apply_reversed_z_state();
  // The shared test state turns multisampling off; a multisampled target wants it on.
  if (target.multisampled()) {
    glEnable(GL_MULTISAMPLE);
  } else {
    glDisable(GL_MULTISAMPLE);
  }
  target.bind();
  target.clear(clear_color, 0.0f);
  lighting_ubo.update(lighting, camera.position().y, time);
  lighting_ubo.bind();
}

Image GlScene::read() const {
  target.resolve();
  return render::read_color(target).value();
}

TreeOnGpu upload_tree(const TreeMesh& mesh, SpeciesPreset textures_of, const TreeAssetOptions& options, int leaf_size) {
  Result<TreeTextureSet> tex = make_texture_set(textures_of, 1, leaf_size, 64);
  SYLVA_ASSERT(tex.ok(), "textures: {}", tex.error().message);
  Result<TreeAsset> asset = TreeAsset::create(mesh, *tex, options);
  SYLVA_ASSERT(asset.ok(), "asset: {}", asset.error().message);
  TreeOnGpu t{mesh, std::move(asset).value(), render::Buffer::dynamic(sizeof(InstanceGpu))};
  return t;
}

void set_instances(TreeOnGpu& tree, const std::vector<InstanceGpu>& instances) {
  tree.instances.upload(std::span<const InstanceGpu>(instances));
}

Image coverage_from_backgrounds(const Image& black, const Image& white) {
  Image out(black.width(), black.height(), 1);
  for (int y = 0; y < black.height(); ++y)
    for (int x = 0; x < black.width(); ++x) {
      float d = 0.0f;
      for (int c = 0; c < 3; ++c) d += white.at(x, y, c) - black.at(x, y, c);
      out.at(x, y) = std::clamp(1.0f - d / 3.0f, 0.0f, 1.0f);
    }
  return out;
}

void save_png(const Image& image, const std::string& name) {
  const std::filesystem::path dir = std::filesystem::current_path() / "vegetation_out";
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  const Status s = write_image(dir / (name + ".png"), image, PixelFormat::kU8);
  if (!s.ok()) log_warn("could not save {}: {}", name, s.error().message);
}

}  // namespace sylva::vegetation::testing
