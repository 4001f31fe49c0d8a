#pragma once
// Which content modules this program was built with, and how a scene creates them.
//
// Sylva knows five module sections: "ground" (a plain height-field mesh, always built in, the
// fallback when the terrain module is left out), "terrain", "grass", "vegetation" and "voxel".
// The last four are optional at build time (SYLVA_WITH_<M>=OFF). A scene that asks for one that
// is not built in fails to load with an error naming the module and the CMake option, never by
// silently drawing less.
//
// Instance counters: every module instance a scene creates is counted per module name (live
// and ever created), so tests can prove that a scene without grass creates no grass objects.

#include <sylva/core/result.hpp>
#include <sylva/scene/height_source.hpp>
#include <sylva/scene/module_settings.hpp>

#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace sylva::scene {

class ModuleInstance;
struct ModuleBuildContext;

struct ModuleDescriptor {
  std::string name;          // section name in scene files and prefix of its parameter paths
  std::string description;   // one line for --list-modules and the editor
  bool provides_ground = false;  // builds the scene's ground height field (terrain, ground)
  bool needs_ground = false;     // stands on the ground (grass, vegetation)
  // When create() fails, the scene opens without the section and logs the error (issue 16: a
  // plant file that fails leaves the plants out with a warning); Scene::left_out says so.
  bool left_out_on_failure = false;
  std::function<std::unique_ptr<ModuleSettings>()> make_settings;
  // Ground providers only: the height source their settings describe (the scene builds the one
  // ground HeightField from it and the section's "height" map before creating any module).
  std::function<HeightSourceSettings(const ModuleSettings&)> height_source;
  // Creates the GL side (needs a current GL 4.5 context). Errors name the section.
  std::function<Result<std::unique_ptr<ModuleInstance>>(const ModuleBuildContext&)> create;
};

// Every module section name Sylva defines, built in or not, in the order scenes create them
// (ground providers first, so the others can stand on the ground).
std::span<const std::string_view> known_modules();
bool is_known_module(std::string_view name);

// The module compiled into this program, or null when it was built out (or is unknown).
const ModuleDescriptor* find_module(std::string_view name);
// The content modules compiled in, in creation order.
std::vector<const ModuleDescriptor*> compiled_modules();
// OK when `name` is compiled in; otherwise kNotFound: "<json_path>: this program was built
// without the grass module (configure with -DSYLVA_WITH_GRASS=ON)" or, for an unknown name,
// the list of known modules.
Status require_module(std::string_view name, std::string_view json_path);

// Live / ever-created ModuleInstance objects per module name (see ModuleInstance).
int live_module_instances(std::string_view name);
std::uint64_t created_module_instances(std::string_view name);

namespace detail {
void count_instance(std::string_view name, int delta);

// Tests only: while it lives, the named compiled-in module behaves exactly as if it had been
// built out (find_module returns null, scenes asking for it fail with the built-out message), so
// the full build can test the lean build's error path. Not thread-safe; ground cannot be hidden.
class ScopedBuiltOut {
 public:
  explicit ScopedBuiltOut(std::string name);
  ~ScopedBuiltOut();
  ScopedBuiltOut(const ScopedBuiltOut&) = delete;
  ScopedBuiltOut& operator=(const ScopedBuiltOut&) = delete;

 private:
  std::string name_;
};
}  // namespace detail

}  // namespace sylva::scene
