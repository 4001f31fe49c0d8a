#include "hostile_case.hpp"

namespace sylva::hostile {

std::string ground_scene(const std::string& height_map) {
  const std::string maps = height_map.empty() ? "" : R"(, "maps": {"height": ")" + height_map + R"("})";
  return R"({"sylva_scene": 1, "name": "hostile", "ground": {"size": 100.0, "resolution": 33, "height": 10.0)" + maps +
         "}}\n";
}

std::string density_scene(const std::string& module, const std::string& density_map) {
  return R"({"sylva_scene": 1, "name": "hostile", "ground": {"size": 100.0, "resolution": 33, "height": 10.0}, ")" +
         module + R"(": {"maps": {"density": ")" + density_map + R"("}}})" + "\n";
}

}  // namespace sylva::hostile
