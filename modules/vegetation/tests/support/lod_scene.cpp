#include "support/lod_scene.hpp"

#include <sylva/core/assert.hpp>
#include <sylva/core/image_metrics.hpp>

#include "support/models.hpp"

namespace sylva::vegetation::testing {

Forest make_lod_forest(int slice_resolution, SpeciesPreset preset, int leaf_size) {
  ForestSettings settings;
  settings.receive_shadows = false;
  settings.lod.slice_resolution = slice_resolution;
  settings.lod.cache_directory = "";
  Result<Forest> f = Forest::create(settings);
  SYLVA_ASSERT(f.ok(), "forest: {}", f.error().message);
  Forest forest = std::move(f).value();
  Result<TreeTextureSet> tex = make_texture_set(preset, 1, leaf_size, 64);
  SYLVA_ASSERT(tex.ok(), "textures: {}", tex.error().message);
  Result<int> s = forest.add_species(preset_tree(preset), *tex);
  SYLVA_ASSERT(s.ok(), "species: {}", s.error().message);
  SYLVA_ASSERT(forest.set_instances(0, {TreeInstance{}}).ok(), "instances");
  return forest;
}

void force_level(Forest& forest, int level, const LodSettings& natural) {
  LodSettings& l = forest.settings().lod;
  const int resolution = l.slice_resolution;
  l = natural;
  l.slice_resolution = resolution;
  l.cache_directory = "";
  if (level == 0) {
    l.enabled = false;
  } else if (level == 1) {
    l.v1 = 0.0f;
    l.v2 = 1.0e7f;
    l.band = 0.0f;
  } else if (level == 2) {
    l.v1 = 0.0f;
    l.v2 = 0.0f;
    l.band = 0.0f;
  }
  std::vector<TreeInstance> inst = forest.instances(0);
  SYLVA_ASSERT(forest.set_instances(0, std::move(inst)).ok(), "instances");
}

Image render_forest(Forest& forest, GlScene& scene, const WindField& wind, double time) {
  render::FrameContext frame{scene.camera, time, 0.016f, wind, scene.lighting,
                             {scene.target.width(), scene.target.height()}, 1};
  forest.update(frame);
  scene.begin(time);
  render::PassStats stats;
  forest.draw(render::Pass::kOpaque, frame, stats);
  return scene.read();
}

Image foreground(const Image& picture, const glm::vec4& clear) {
  Result<Image> m = mask_from_background(picture, clear, 0.02f);
  SYLVA_ASSERT(m.ok(), "mask: {}", m.error().message);
  return std::move(m).value();
}

double share(const Image& mask) {
  double c = 0.0;
  for (float v : mask.data()) c += v;
  return mask.pixel_count() == 0 ? 0.0 : c / static_cast<double>(mask.pixel_count());
}

}  // namespace sylva::vegetation::testing
