#include <sylva/scene/module_instance.hpp>
#include <sylva/scene/module_registry.hpp>

namespace sylva::scene {

ModuleInstance::ModuleInstance(std::string module) : module_(std::move(module)) { detail::count_instance(module_, +1); }

ModuleInstance::~ModuleInstance() { detail::count_instance(module_, -1); }

}  // namespace sylva::scene

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace sylva::scene {

Result<SceneMap*> ensure_area_map(const ModuleBuildContext& ctx, const MapSlot& slot, glm::dvec2 min, glm::dvec2 max,
                                  int default_resolution, float fill) {
  const std::string& module = ctx.section->name;
  if (!(max.x > min.x && max.y > min.y)) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("{}: the area of the {} map is empty ({}, {}) .. ({}, {})", module, slot.name, min.x,
                                  min.y, max.x, max.y));
  }
  const std::string id = module + "." + slot.name;
  auto place = [&](MapGrid& grid) {
    grid.texel_size = (max - min) / glm::dvec2(grid.width, grid.height);
    grid.texel_origin = min + 0.5 * grid.texel_size;
  };
  if (auto it = ctx.maps->find(id); it != ctx.maps->end()) {
    place(it->second.grid);
    return &it->second;
  }
  SceneMap map;
  map.module = module;
  map.slot = slot.name;
  map.kind = slot.kind;
  if (auto path = ctx.section->maps.find(slot.name); path != ctx.section->maps.end()) {
    auto grid = read_map_image(ctx.document->resolve(path->second), 1.0f, 0.0f, {0.0, 0.0}, {1.0, 1.0});
    if (!grid.ok()) return make_error(grid.error().code, fmt::format("{}.maps.{}: {}", module, slot.name, grid.error().message));
    map.grid = std::move(*grid);
    map.path = path->second;
  } else {
    const glm::dvec2 extent = max - min;
    const double longer = std::max(extent.x, extent.y);
    const int w = std::max(1, static_cast<int>(std::lround(default_resolution * extent.x / longer)));
    const int h = std::max(1, static_cast<int>(std::lround(default_resolution * extent.y / longer)));
    map.grid = MapGrid(w, h, fill, {0.0, 0.0}, {1.0, 1.0});
  }
  place(map.grid);
  auto [it, inserted] = ctx.maps->emplace(id, std::move(map));
  (void)inserted;
  return &it->second;
}

}  // namespace sylva::scene
