// L-system grammars (modules/voxel, the .lsys format): text -> systems -> derivation and turtle
// interpretation under small expansion limits, so a growing grammar ends in kLimit quickly.
#include "support/fuzz_support.hpp"

#include <sylva/voxel/lsystem.hpp>
#include <sylva/voxel/plant.hpp>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace sylva::voxel;
  auto systems = parse_lsystems(sylva::fuzz::as_text(data, size), "fuzz.lsys");
  if (!systems.ok()) {
    sylva::fuzz::require_message(systems.error());
    return 0;
  }
  LSystemExecutorSettings settings;
  settings.min_derivations = 0;
  settings.max_derivations = 6;
  settings.limits.max_symbols = std::size_t{1} << 15;
  settings.limits.max_parts = 4096;
  settings.limits.max_depth = 256;
  // A few systems and salts are enough to reach every rule; more only slows each input down.
  const std::size_t count = std::min<std::size_t>(systems->size(), 4);
  for (std::size_t i = 0; i < count; ++i) {
    for (std::uint64_t salt = 0; salt < 2; ++salt) {
      auto plant = generate_plant((*systems)[i], settings, salt);
      if (!plant.ok()) sylva::fuzz::require_message(plant.error());
    }
  }
  return 0;
}
