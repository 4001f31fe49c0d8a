#pragma once
// The GL-free settings of one module section of a scene file: reflected parameters (through the
// section's visit()-based settings struct, DESIGN.md §2) plus the named map slots the module
// paints into (height, density, ...). The scene document owns one ModuleSettings per listed
// module; the editor draws its panels from describe(), the player and sylva-bench set values by
// path ("grass.field.density=120").

#include <sylva/core/params.hpp>
#include <sylva/core/result.hpp>

#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace sylva::scene {

// What the values of a map mean (and how brushes treat them).
enum class MapKind {
  kHeight,  // metres, unbounded (terrain height)
  kUnit,    // a share in [0, 1] (density, height scale)
};

struct MapSlot {
  const char* name;     // "height", "density"; the key under the section's "maps" object
  MapKind kind;
  const char* help;     // one sentence for the editor
};

class ModuleSettings {
 public:
  virtual ~ModuleSettings() = default;

  // Lists the parameters (DESIGN.md §2), so a ModuleSettings is itself Visitable: describe_params,
  // params_from_json/params_to_json and ParamRegistry::add work on it directly. Descriptors
  // point into this object (valid while it lives and is not moved).
  virtual void visit(ParamCollector& collector) = 0;
  virtual std::unique_ptr<ModuleSettings> clone() const = 0;
  // The maps this module paints into (may be empty).
  virtual std::vector<MapSlot> map_slots() const = 0;
  // Checks that span several fields (min <= max and the like), beyond per-parameter ranges.
  // Messages start with "<prefix>.<field>".
  virtual Status check(std::string_view prefix) const {
    (void)prefix;
    return {};
  }
};

// ModuleSettings for any settings struct S with visit(); `Check` adds cross-field checks.
template <Visitable S>
class SettingsOf : public ModuleSettings {
 public:
  using CheckFn = Status (*)(const S&, std::string_view prefix);

  SettingsOf(std::vector<MapSlot> slots, CheckFn check = nullptr) : slots_(std::move(slots)), check_(check) {}

  S value{};

  void visit(ParamCollector& collector) override { value.visit(collector); }
  std::unique_ptr<ModuleSettings> clone() const override { return std::make_unique<SettingsOf>(*this); }
  std::vector<MapSlot> map_slots() const override { return slots_; }
  Status check(std::string_view prefix) const override { return check_ ? check_(value, prefix) : Status{}; }

 private:
  std::vector<MapSlot> slots_;
  CheckFn check_ = nullptr;
};

}  // namespace sylva::scene
