#include <sylva/scene/module_registry.hpp>

#include "modules/module_factories.hpp"

#include <sylva/core/assert.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <map>
#include <mutex>

namespace sylva::scene {
namespace {

constexpr std::array<std::string_view, 6> kKnown = {"ground", "terrain", "model_terrain", "grass", "vegetation", "voxel"};

const std::vector<ModuleDescriptor>& table() {
  static const std::vector<ModuleDescriptor> modules = [] {
    std::vector<ModuleDescriptor> m;
    m.push_back(detail::ground_module());
#ifdef SYLVA_HAS_TERRAIN
    m.push_back(detail::terrain_module());
    m.push_back(detail::model_terrain_module());
#endif
#ifdef SYLVA_HAS_GRASS
    m.push_back(detail::grass_module());
#endif
#ifdef SYLVA_HAS_VEGETATION
    m.push_back(detail::vegetation_module());
#endif
#ifdef SYLVA_HAS_VOXEL
    m.push_back(detail::voxel_module());
#endif
    return m;
  }();
  return modules;
}

struct Counters {
  std::mutex mutex;
  std::map<std::string, int, std::less<>> live;
  std::map<std::string, std::uint64_t, std::less<>> created;
};
Counters& counters() {
  static Counters c;
  return c;
}

// Modules a test has hidden (detail::ScopedBuiltOut).
std::vector<std::string>& hidden_modules() {
  static std::vector<std::string> hidden;
  return hidden;
}

}  // namespace

std::span<const std::string_view> known_modules() { return kKnown; }

bool is_known_module(std::string_view name) {
  return std::find(kKnown.begin(), kKnown.end(), name) != kKnown.end();
}

const ModuleDescriptor* find_module(std::string_view name) {
  const std::vector<std::string>& hidden = hidden_modules();
  if (std::find(hidden.begin(), hidden.end(), name) != hidden.end()) return nullptr;
  for (const ModuleDescriptor& d : table()) {
    if (d.name == name) return &d;
  }
  return nullptr;
}

std::vector<const ModuleDescriptor*> compiled_modules() {
  std::vector<const ModuleDescriptor*> out;
  for (std::string_view name : kKnown) {
    if (const ModuleDescriptor* d = find_module(name)) out.push_back(d);
  }
  return out;
}

Status require_module(std::string_view name, std::string_view json_path) {
  if (find_module(name)) return {};
  if (!is_known_module(name)) {
    std::string known;
    for (std::string_view k : kKnown) known += (known.empty() ? "" : ", ") + std::string(k);
    return make_error(ErrorCode::kNotFound, fmt::format("{}: unknown module \"{}\" (known: {})", json_path, name, known));
  }
  // The general model's renderer is part of the terrain module (SYLVA_WITH_TERRAIN).
  std::string upper(name == "model_terrain" ? "terrain" : name);
  std::transform(upper.begin(), upper.end(), upper.begin(), [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
  return make_error(ErrorCode::kNotFound,
                    fmt::format("{}: this program was built without the {} module (configure with -DSYLVA_WITH_{}=ON)",
                                json_path, name, upper));
}

int live_module_instances(std::string_view name) {
  Counters& c = counters();
  std::lock_guard lock(c.mutex);
  auto it = c.live.find(name);
  return it == c.live.end() ? 0 : it->second;
}

std::uint64_t created_module_instances(std::string_view name) {
  Counters& c = counters();
  std::lock_guard lock(c.mutex);
  auto it = c.created.find(name);
  return it == c.created.end() ? 0 : it->second;
}

namespace detail {
void count_instance(std::string_view name, int delta) {
  Counters& c = counters();
  std::lock_guard lock(c.mutex);
  auto it = c.live.find(name);
  if (it == c.live.end()) it = c.live.emplace(std::string(name), 0).first;
  it->second += delta;
  if (delta > 0) {
    auto ct = c.created.find(name);
    if (ct == c.created.end()) ct = c.created.emplace(std::string(name), 0).first;
    ct->second += static_cast<std::uint64_t>(delta);
  }
}
}  // namespace detail

namespace detail {

ScopedBuiltOut::ScopedBuiltOut(std::string name) : name_(std::move(name)) {
  SYLVA_ASSERT(name_ != "ground", "ScopedBuiltOut: the built-in ground cannot be built out");
  hidden_modules().push_back(name_);
}

ScopedBuiltOut::~ScopedBuiltOut() {
  std::vector<std::string>& hidden = hidden_modules();
  if (auto it = std::find(hidden.begin(), hidden.end(), name_); it != hidden.end()) hidden.erase(it);
}

}  // namespace detail
}  // namespace sylva::scene
