#pragma once
// The plant preview (issue #16, "Your own plants"): one plant of a voxel grammar, grown with a
// chosen seed, derivation count and angle variation, as the editor's "Plant preview" panel and
// the `preview` script command show it. The plant is a species of the scene's table
// (`voxel.flora.species_file`, or the shipped table when it names none; the table's palette is
// `voxel.blocks.palette_file`'s) with its blocks, or any grammar file (`.lsys`, relative to the
// scene's folder; system `system` of it) with its outputs 0-9 as the blocks. A grammar that does
// not parse, a species the table leaves out or a plant past the limits gives `error` (the file
// and line:column, as the voxel module reports it), never a crash.

#include <sylva/core/params.hpp>
#include <sylva/scene/scene.hpp>

#include <glm/vec3.hpp>

#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace sylva::editor {

struct PlantPreviewSettings {
  std::string species;  // a species name of the scene's table, or a .lsys file
  int system = 0;       // a grammar file's system (0-based)
  std::uint32_t seed = 1;
  int derivations = 3;
  float angle_variation = 0.2f;

  template <class V>
  void visit(V& v) {
    v(species, "species", {.help = "A species of the scene's table, or a .lsys grammar file (relative to the scene)"});
    v(system, "system", {.min = 0, .max = 255, .help = "The system of a grammar file (0-based)"});
    v(seed, "seed", {.help = "Seed of the rule choices and angle jitter"});
    v(derivations, "derivations", {.min = 0, .max = 32, .help = "Derivation steps"});
    v(angle_variation, "angle_variation", {.min = 0.0, .max = 1.0, .help = "Turn jitter as a fraction of the angle"});
  }
  bool operator==(const PlantPreviewSettings&) const = default;
};

struct PreviewBlock {
  glm::vec3 position{0.0f};  // plant space, y up, in blocks
  float size = 1.0f;
  int output = 0;  // 0..9
};

struct PlantPreview {
  std::string title;                       // "pillar (species/pillars.json)"
  std::vector<PreviewBlock> blocks;        // the blocks laid (outputs with a block)
  std::array<std::string, 10> output_blocks;  // block name per output, "" = lays nothing
  std::map<std::string, std::size_t> block_counts;  // by block name
  std::size_t symbols = 0;                 // length of the derived string
  int derivations = 0;
  glm::vec3 bounds_min{0.0f}, bounds_max{0.0f};
  std::string error;  // non-empty: nothing was grown (the message names the file and line:column)

  // "pillar (species/pillars.json): 8 blocks (glowstone 8), 15 symbols, 3 derivations" or
  // "pillar (...): error: <message>".
  std::string summary() const;
};

// The species names of the scene's table in file order (those the table leaves out included);
// empty without a voxel section.
std::vector<std::string> preview_species(scene::Scene& scene);
// Grows the plant `settings` name.
PlantPreview build_plant_preview(scene::Scene& scene, const PlantPreviewSettings& settings);

}  // namespace sylva::editor
