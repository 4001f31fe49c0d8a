#include "plant_preview.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace sylva::voxel::testing {

Image preview_plants(const std::vector<const PlantModel*>& models, int cell) {
  const int w = cell * static_cast<int>(std::max<std::size_t>(models.size(), 1));
  Image img(w, cell * 2, 3);
  for (float& v : img.data()) v = 0.85f;
  std::vector<float> depth(static_cast<std::size_t>(w * cell * 2), std::numeric_limits<float>::lowest());
  const float colours[3][3] = {{0.45f, 0.3f, 0.15f}, {0.2f, 0.6f, 0.2f}, {0.5f, 0.5f, 0.5f}};
  for (std::size_t m = 0; m < models.size(); ++m) {
    const PlantModel& model = *models[m];
    const glm::vec3 ext = model.bounds_max - model.bounds_min;
    const float span = std::max({ext.x, ext.y, ext.z, 1.0f});
    const float scale = (cell - 8) / span;
    const glm::vec3 mid = 0.5f * (model.bounds_min + model.bounds_max);
    for (int view = 0; view < 2; ++view) {
      for (int o = 0; o < kPlantOutputs; ++o) {
        const float* col = colours[std::min(o, 2)];
        for (const PlantPart& p : model.outputs[static_cast<std::size_t>(o)]) {
          // side: screen x = world x, screen up = world y, depth = z. top: x, up = -z, depth = y.
          const float sx = (p.position.x - mid.x) * scale + cell * (static_cast<float>(m) + 0.5f);
          const float sy = view == 0 ? cell * 0.5f - (p.position.y - mid.y) * scale
                                     : cell * 1.5f + (p.position.z - mid.z) * scale;
          const float d = view == 0 ? p.position.z : p.position.y;
          const float shade = 0.6f + 0.4f * std::clamp((d - (view == 0 ? model.bounds_min.z : model.bounds_min.y)) /
                                                           std::max(view == 0 ? ext.z : ext.y, 1e-3f),
                                                       0.0f, 1.0f);
          const float half = std::max(0.5f, 0.5f * p.size * scale);
          const int x0 = static_cast<int>(std::floor(sx - half)), x1 = static_cast<int>(std::ceil(sx + half));
          const int y0 = static_cast<int>(std::floor(sy - half)), y1 = static_cast<int>(std::ceil(sy + half));
          for (int y = std::max(y0, view * cell); y < std::min(y1, (view + 1) * cell); ++y) {
            for (int x = std::max(x0, static_cast<int>(m) * cell); x < std::min(x1, static_cast<int>(m + 1) * cell); ++x) {
              auto& dz = depth[static_cast<std::size_t>(y * w + x)];
              if (d < dz) continue;
              dz = d;
              const bool edge = x == x0 || y == y0 || x == x1 - 1 || y == y1 - 1;
              for (int c = 0; c < 3; ++c) img.at(x, y, c) = col[c] * shade * (edge && half > 2 ? 0.7f : 1.0f);
            }
          }
        }
      }
    }
  }
  return img;
}

void save_preview(const std::filesystem::path& path, const std::vector<const PlantModel*>& models) {
  Image img = preview_plants(models);
  (void)write_image(path, img, PixelFormat::kU8);
}

}  // namespace sylva::voxel::testing
